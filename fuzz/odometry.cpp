// libFuzzer target: arbitrary odometry and fin commands. Every accepted sample keeps the ship track
// finite; commands are applied or refused; the vehicle's loads stay finite. Any violation aborts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "tow_sim/core/run/odometry_check.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace
{
double take(const uint8_t*& data, size_t& size)
{
  double v = 0.0;
  if (size >= sizeof(double))
  {
    std::memcpy(&v, data, sizeof(double));
    data += sizeof(double);
    size -= sizeof(double);
  }
  else
    size = 0;
  return v;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  tow_sim::ShipTrack track(1.0, 64);
  const tow_sim::OdometryLimits limits;
  static const tow_sim::Vehicle vehicle{ tow_sim::VehicleParams() };
  tow_sim::Actuators actuators = vehicle.restingActuators(0.0);
  double now = 0.0;
  while (size >= 14 * sizeof(double))
  {
    tow_sim::OdometryInput in;
    in.frame_id = take(data, size) > 0.0 ? "odom" : "map";
    in.t = take(data, size);
    in.p_W = Eigen::Vector3d(take(data, size), take(data, size), take(data, size));
    in.q_wxyz = Eigen::Vector4d(take(data, size), take(data, size), take(data, size), take(data, size));
    in.v_S = Eigen::Vector3d(take(data, size), take(data, size), 0.0);
    in.w_S = Eigen::Vector3d(0.0, 0.0, take(data, size));
    now = std::isfinite(in.t) ? in.t : now;
    const tow_sim::OdometryResult r = tow_sim::checkOdometry(in, limits, track, now);
    if (r.accepted)
    {
      if (!r.tow_p_W.allFinite() || !r.tow_v_W.allFinite() || !track.add(in.t, r.tow_p_W, r.tow_v_W))
        std::abort();
      const tow_sim::ShipEndState s = track(in.t - 0.05);
      if (!s.p_W.allFinite() || !s.v_W.allFinite() || !s.a_W.allFinite())
        std::abort();
    }
    const double rudder = take(data, size), elevator = take(data, size);
    try
    {
      vehicle.command(actuators, 0.0, rudder, elevator, 0.0);
    }
    catch (const std::invalid_argument&)
    {
      if (std::isfinite(rudder) && std::isfinite(elevator))
        std::abort();  // a finite command must be taken (saturated)
    }
  }
  // The vehicle's loads at its commanded fin angles, towed level at 2 m/s, stay finite.
  const tow_sim::ElementKinematics k = tow_sim::ElementKinematics::fromJoints(
      Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.2, 0, 0), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(2, 0, 0));
  tow_sim::BodyDynamics body;
  vehicle.dynamics(10.0, k, tow_sim::Environment(), actuators, body);
  if (!body.wrench.allFinite() || !body.mass.allFinite())
    std::abort();
  return 0;
}
