#include "tow_sim/core/integration/run_report.h"

#include <Eigen/Geometry>

namespace tow_sim
{
Diversion lateralDiversion(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, const ShipEndState& ship,
                           const Eigen::Vector3d& track_direction_W)
{
  const Eigen::Vector3d port = Eigen::Vector3d::UnitZ().cross(track_direction_W).normalized();
  Diversion d;
  d.offset = port.dot(p_W - ship.p_W);
  d.rate = port.dot(v_W - ship.v_W);
  return d;
}

}  // namespace tow_sim
