// interpolate(TowSnapshot, TowSnapshot, t): the outputs between two snapshots of a run (tow_run.h).
#include <algorithm>
#include <cmath>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"

namespace tow_sim
{
namespace
{
template <class T>
T lerp(const T& a, const T& b, double w)
{
  return a + w * (b - a);
}

double lerpAngle(double a, double b, double w)  // [rad] the short way round
{
  return a + w * std::remainder(b - a, 2.0 * kPi);
}

FinPairLoads lerp(const FinPairLoads& a, const FinPairLoads& b, double w)
{
  FinPairLoads out;
  out.angle = lerp(a.angle, b.angle, w);
  out.angle_of_attack = lerp(a.angle_of_attack, b.angle_of_attack, w);
  out.inflow_angle = lerp(a.inflow_angle, b.inflow_angle, w);
  out.lift_W = lerp(a.lift_W, b.lift_W, w);
  out.drag_W = lerp(a.drag_W, b.drag_W, w);
  out.moment_cg_W = lerp(a.moment_cg_W, b.moment_cg_W, w);
  out.lift_B = lerp(a.lift_B, b.lift_B, w);
  out.drag_B = lerp(a.drag_B, b.drag_B, w);
  out.moment_cg_B = lerp(a.moment_cg_B, b.moment_cg_B, w);
  return out;
}

VehicleOutputs lerp(const VehicleOutputs& a, const VehicleOutputs& b, double w)
{
  VehicleOutputs out = w < 0.5 ? a : b;
  out.p_cg_W = lerp(a.p_cg_W, b.p_cg_W, w);
  out.q_WB = a.q_WB.slerp(w, b.q_WB);
  out.v_cg_W = lerp(a.v_cg_W, b.v_cg_W, w);
  out.v_cg_B = lerp(a.v_cg_B, b.v_cg_B, w);
  out.omega_W = lerp(a.omega_W, b.omega_W, w);
  out.omega_B = lerp(a.omega_B, b.omega_B, w);
  out.depth = lerp(a.depth, b.depth, w);
  out.pitch = lerp(a.pitch, b.pitch, w);
  out.yaw = lerpAngle(a.yaw, b.yaw, w);
  out.roll = lerpAngle(a.roll, b.roll, w);
  out.rudder = lerp(a.rudder, b.rudder, w);
  out.elevator = lerp(a.elevator, b.elevator, w);
  out.thrust = lerp(a.thrust, b.thrust, w);
  out.rudder_loads = lerp(a.rudder_loads, b.rudder_loads, w);
  out.elevator_loads = lerp(a.elevator_loads, b.elevator_loads, w);
  return out;
}
}  // namespace

TowSnapshot interpolate(const TowSnapshot& a, const TowSnapshot& b, double t)
{
  const double span = b.t - a.t;
  const double w = span > 0.0 ? std::clamp((t - a.t) / span, 0.0, 1.0) : 1.0;
  TowSnapshot out = w < 0.5 ? a : b;  // the discrete outputs, and the whole across a change of layout
  out.max_length_error = std::max(a.max_length_error, b.max_length_error);
  out.max_strain = std::max(a.max_strain, b.max_strain);
  out.tension_ship_range = b.tension_ship_range;  // the extremes of the interval that ends at b
  out.tension_vehicle_range = b.tension_vehicle_range;
  if (a.joints.cols() != b.joints.cols() || a.tensions.cols() != b.tensions.cols() || a.parted != b.parted ||
      a.ship_side.cols() != b.ship_side.cols() || a.ship_side_tensions.cols() != b.ship_side_tensions.cols())
    return out;
  out.t = lerp(a.t, b.t, w);
  out.ship.x = lerp(a.ship.x, b.ship.x, w);
  out.ship.y = lerp(a.ship.y, b.ship.y, w);
  out.ship.heading = lerpAngle(a.ship.heading, b.ship.heading, w);
  out.ship.speed = lerp(a.ship.speed, b.ship.speed, w);
  out.tow_point.p_W = lerp(a.tow_point.p_W, b.tow_point.p_W, w);
  out.tow_point.v_W = lerp(a.tow_point.v_W, b.tow_point.v_W, w);
  out.tow_point.a_W = lerp(a.tow_point.a_W, b.tow_point.a_W, w);
  out.joints = lerp(a.joints, b.joints, w);
  out.tensions = lerp(a.tensions, b.tensions, w);
  out.ship_side = lerp(a.ship_side, b.ship_side, w);
  out.ship_side_tensions = lerp(a.ship_side_tensions, b.ship_side_tensions, w);
  out.tension_ship = lerp(a.tension_ship, b.tension_ship, w);
  out.tension_vehicle = lerp(a.tension_vehicle, b.tension_vehicle, w);
  out.cable_length = lerp(a.cable_length, b.cable_length, w);
  out.payout_rate = lerp(a.payout_rate, b.payout_rate, w);
  out.vehicle = lerp(a.vehicle, b.vehicle, w);
  out.attitude = a.attitude.slerp(w, b.attitude);
  out.pitch = lerp(a.pitch, b.pitch, w);
  out.yaw = lerpAngle(a.yaw, b.yaw, w);
  out.roll = lerpAngle(a.roll, b.roll, w);
  out.depth = lerp(a.depth, b.depth, w);
  out.layback = lerp(a.layback, b.layback, w);
  out.diversion.offset = lerp(a.diversion.offset, b.diversion.offset, w);
  out.diversion.rate = lerp(a.diversion.rate, b.diversion.rate, w);
  out.vehicle_altitude = lerp(a.vehicle_altitude, b.vehicle_altitude, w);
  return out;
}

}  // namespace tow_sim
