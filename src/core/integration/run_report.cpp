#include "tow_sim/core/integration/run_report.h"

#include <Eigen/Geometry>

#include "tow_sim/core/chain/chain_state.h"

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

void countSnaps(const ChainGeometry& geometry, const Eigen::Matrix3Xd& joints, const std::vector<double>& multipliers,
                std::vector<char>& slack, StepReport& report)
{
  const size_t n = static_cast<size_t>(geometry.segments);
  const bool first = slack.size() != n;  // after a reset: no step to compare with
  slack.resize(n);
  const std::vector<double> strain = segmentStrains(geometry, joints);
  for (size_t e = 0; e < n; ++e)
  {
    const bool taut = multipliers[e] < 0.0;
    if (first)
      slack[e] = !taut && strain[e] < 0.0;
    else if (slack[e] && taut)
    {
      ++report.snaps;
      slack[e] = false;
    }
    else if (!taut && strain[e] <= 0.0)
      slack[e] = true;
    report.max_strain = std::max(report.max_strain, strain[e]);
  }
}

}  // namespace tow_sim
