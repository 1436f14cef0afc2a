#include "tow_sim/core/run/depth_autopilot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/params.h"

namespace tow_sim
{
namespace
{

const DepthAutopilotParams& validated(const DepthAutopilotParams& p)
{
  p.validate();
  return p;
}
}  // namespace

void DepthAutopilotParams::validate(const std::string& prefix) const
{
  validateParams(autopilotParams(), *this, prefix);
}

PastTrack::PastTrack(double spacing, double length)
    : spacing_(spacing), max_points_(std::max<size_t>(2, static_cast<size_t>(std::ceil(length / spacing)) + 1))
{
}

void PastTrack::add(const Eigen::Vector2d& p_W)
{
  if (!p_W.allFinite())
    return;
  if (!points_.empty() && (p_W - points_.back()).norm() < spacing_)
    return;
  points_.push_back(p_W);
  while (points_.size() > max_points_)
    points_.pop_front();
}

void PastTrack::restore(const std::vector<Eigen::Vector2d>& points)
{
  points_.clear();
  for (const Eigen::Vector2d& p : points)
    if (p.allFinite())
    {
      points_.push_back(p);
      if (points_.size() > max_points_)
        points_.pop_front();
    }
}

PastTrack::Offset PastTrack::offset(const Eigen::Vector2d& p_W, const Eigen::Vector2d& v_W) const
{
  Offset best;
  double best_distance2 = std::numeric_limits<double>::infinity();
  const size_t last = points_.size() - 2;
  for (size_t i = 0; i + 1 < points_.size(); ++i)
  {
    const Eigen::Vector2d& a = points_[i];
    const Eigen::Vector2d d = points_[i + 1] - a;
    double s = (p_W - a).dot(d) / d.squaredNorm();  // d is at least `spacing` long
    if (i > 0)
      s = std::max(s, 0.0);  // the oldest segment extends astern as a line
    if (i < last)
      s = std::min(s, 1.0);  // the newest extends ahead
    const double distance2 = (p_W - (a + s * d)).squaredNorm();
    if (distance2 < best_distance2)
    {
      best_distance2 = distance2;
      const Eigen::Vector2d port(-d.y() / d.norm(), d.x() / d.norm());  // left of the direction of travel
      best.offset = (p_W - a).dot(port);
      best.rate = v_W.dot(port);
      best.segment = i;
    }
  }
  return best;
}

DepthAutopilot::DepthAutopilot(const DepthAutopilotParams& params)
    : p_(validated(params)), track_(params.track_spacing, params.track_length)
{
}

void DepthAutopilot::setTuning(const DepthAutopilotParams& params, const std::string& prefix)
{
  DepthAutopilotParams p = params;
  p.actuator = p_.actuator;
  p.track_spacing = p_.track_spacing;
  p.track_length = p_.track_length;
  p.validate(prefix);
  p_ = p;
  integral_ = std::clamp(integral_, -p_.max_elevator, p_.max_elevator);
}

void DepthAutopilot::setSetpoint(double depth)
{
  requireInRange("depth setpoint", depth, 0.0, p_.max_depth, "[m] (positive down)");
  setpoint_ = depth;
  has_setpoint_ = true;
  altitude_mode_ = false;
}

void DepthAutopilot::setAltitudeSetpoint(double altitude)
{
  requireInRange("altitude setpoint", altitude, 0.0, p_.max_depth, "[m] (above the seabed)");
  altitude_setpoint_ = altitude;
  altitude_mode_ = true;
  if (has_vehicle_ && std::isfinite(vehicle_.altitude))
  {
    setpoint_ = std::max(0.0, -vehicle_.p_W.z() + vehicle_.altitude - altitude_setpoint_);
    has_setpoint_ = true;
  }
}

void DepthAutopilot::setCableOutFeedForward(double cable_out)
{
  if (std::isnan(cable_out))
  {
    feed_forward_ = false;
    cable_out_base_ = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  requireInRange("cable out feed-forward", cable_out, 0.0, 1e5, "[m]", true);
  cable_out_base_ = cable_out;
  feed_forward_ = true;
}

bool DepthAutopilot::addVehicle(const VehicleMeasurement& m)
{
  if (!std::isfinite(m.t) || !m.p_W.allFinite() || !m.v_W.allFinite() || std::isinf(m.altitude) ||
      std::isinf(m.cable_out) || std::isinf(m.roll) || std::isinf(m.roll_rate))
    throw std::invalid_argument("vehicle odometry: the stamp, position and velocity must be finite");
  if (has_vehicle_ && m.t <= vehicle_.t)
    return false;
  vehicle_ = m;
  has_vehicle_ = true;
  if (altitude_mode_ && std::isfinite(m.altitude))
  {
    setpoint_ = std::max(0.0, -m.p_W.z() + m.altitude - altitude_setpoint_);
    has_setpoint_ = true;
  }
  if (!has_setpoint_)
  {
    setpoint_ = std::max(0.0, -m.p_W.z());
    has_setpoint_ = true;
  }
  return true;
}

void DepthAutopilot::addShip(const Eigen::Vector2d& p_W)
{
  if (!p_W.allFinite())
    throw std::invalid_argument("ship position must be finite");
  track_.add(p_W);
}

double DepthAutopilot::elevator(double error, double v_up, double dt, AutopilotCommand& out)
{
  const double max = p_.max_elevator;
  const double pd = -p_.kp * error - p_.kd * v_up;
  if (dt > 0.0)
  {
    // Conditional integration: while the output is saturated, integrate only back out of saturation.
    const double step = -p_.ki * error * dt;
    const double candidate = std::clamp(integral_ + step, -max, max);
    const double u = pd + candidate;
    const bool winding_up = std::abs(u) > max && step * u > 0.0;
    if (!winding_up)
      integral_ = candidate;
  }
  const double u = pd + integral_;
  out.elevator_saturated = std::abs(u) > max;
  out.integral = integral_;
  return std::clamp(u, -max, max);
}

AutopilotCommand DepthAutopilot::update(double now)
{
  AutopilotCommand out;
  if (!has_vehicle_)
    return out;
  const double arrived = std::isfinite(vehicle_.received) ? vehicle_.received : vehicle_.t;
  if (now - arrived > p_.odom_timeout)
  {
    out.status = AutopilotCommand::Status::kStale;
    return out;
  }
  out.status = AutopilotCommand::Status::kActive;
  out.thrust = p_.thrust;
  // Integrate over the time since the last integrated measurement, never across a stale gap.
  double dt = 0.0;
  if (integrated_ && vehicle_.t - integrated_until_ <= p_.odom_timeout)
    dt = vehicle_.t - integrated_until_;
  integrated_until_ = vehicle_.t;
  integrated_ = true;
  const double depth = -vehicle_.p_W.z();
  out.depth_error = setpoint_ - depth;
  if (p_.actuator != DepthAutopilotParams::Actuator::kWinch)
    out.elevator = elevator(out.depth_error, vehicle_.v_W.z(), dt, out);
  if (p_.actuator != DepthAutopilotParams::Actuator::kElevator)
    winch(out.depth_error, dt, out);

  if (p_.track_keeping && track_.usable())
  {
    const PastTrack::Offset o = track_.offset(vehicle_.p_W.head<2>(), vehicle_.v_W.head<2>());
    out.tracking = true;
    out.track_offset = o.offset;
    out.track_offset_rate = o.rate;
    out.rudder = std::clamp(-p_.rudder_kp * o.offset - p_.rudder_kd * o.rate, -p_.max_rudder, p_.max_rudder);
  }
  if (p_.roll_hold && std::isfinite(vehicle_.roll))  // a positive differential rolls it to port
    out.differential = std::clamp(
        p_.roll_kp * vehicle_.roll + p_.roll_kd * (std::isfinite(vehicle_.roll_rate) ? vehicle_.roll_rate : 0.0),
        -p_.max_differential, p_.max_differential);
  return out;
}

void DepthAutopilot::winch(double error, double dt, AutopilotCommand& out)
{
  const double L = vehicle_.cable_out;
  if (!std::isfinite(L))
    return;  // no winch command without the cable out
  if (!std::isfinite(cable_out_base_))
    cable_out_base_ = L;  // no plan: hold what is out, the feedback does the rest
  const double max = p_.max_payout_rate;
  const double tau = p_.winch_time_constant;
  auto rate = [&](double integral) { return (cable_out_base_ + p_.winch_kp * error + integral - L) / tau; };
  if (dt > 0.0)
  {
    // Conditional integration, as the elevator's: not further into a saturated rate.
    const double step = p_.winch_ki * error * dt;
    const double u = rate(winch_integral_ + step);
    if (!(std::abs(u) > max && step * u > 0.0))
      winch_integral_ += step;
  }
  out.winch = true;
  out.winch_integral = winch_integral_;
  out.cable_out_target = cable_out_base_ + p_.winch_kp * error + winch_integral_;
  out.payout_rate = std::clamp(rate(winch_integral_), -max, max);
}

void DepthAutopilot::reset()
{
  track_.clear();
  has_setpoint_ = false;
  altitude_mode_ = false;
  has_vehicle_ = false;
  integrated_ = false;
  integral_ = 0.0;
  winch_integral_ = 0.0;
  if (!feed_forward_)
    cable_out_base_ = std::numeric_limits<double>::quiet_NaN();
}

DepthAutopilotState DepthAutopilot::state() const
{
  DepthAutopilotState s;
  s.has_setpoint = has_setpoint_;
  s.setpoint = setpoint_;
  s.altitude_mode = altitude_mode_;
  s.altitude_setpoint = altitude_setpoint_;
  s.has_vehicle = has_vehicle_;
  s.vehicle = vehicle_;
  s.integrated_until = integrated_until_;
  s.integrated = integrated_;
  s.integral = integral_;
  s.cable_out_base = cable_out_base_;
  s.feed_forward = feed_forward_;
  s.winch_integral = winch_integral_;
  s.track = track_.points();
  return s;
}

void DepthAutopilot::restore(const DepthAutopilotState& s)
{
  has_setpoint_ = s.has_setpoint;
  setpoint_ = s.setpoint;
  altitude_mode_ = s.altitude_mode;
  altitude_setpoint_ = s.altitude_setpoint;
  has_vehicle_ = s.has_vehicle;
  vehicle_ = s.vehicle;
  integrated_until_ = s.integrated_until;
  integrated_ = s.integrated;
  integral_ = s.integral;
  cable_out_base_ = s.cable_out_base;
  feed_forward_ = s.feed_forward;
  winch_integral_ = s.winch_integral;
  track_.restore(s.track);
}

const ParamTable<DepthAutopilotParams>& autopilotParams()
{
  using A = DepthAutopilotParams;
  static const ParamTable<A> table =
      ParamTable<A>()
          .number("kp", &A::kp, "rad/m", 0.0, 10.0, kClosed, "elevator per metre of depth error")
          .number("ki", &A::ki, "rad/(m s)", 0.0, 10.0, kClosed, "elevator per metre-second of integrated error")
          .number("kd", &A::kd, "rad/(m/s)", 0.0, 100.0, kClosed, "elevator per m/s of vertical velocity (world, up)")
          .number("max_elevator", &A::max_elevator, "rad", 0.0, kHalfPi, kOpen,
                  "elevator limit (the default vehicle's max_deflection)")
          .boolean("track_keeping", &A::track_keeping, "steer on the ship's track; false: rudder 0")
          .number("rudder_kp", &A::rudder_kp, "rad/m", 0.0, 10.0, kClosed, "rudder per metre of lateral offset")
          .number("rudder_kd", &A::rudder_kd, "rad/(m/s)", 0.0, 100.0, kClosed, "rudder per m/s of offset rate")
          .number("max_rudder", &A::max_rudder, "rad", 0.0, kHalfPi, kOpen, "rudder limit")
          .number("track_spacing", &A::track_spacing, "m", 0.01, 1000.0, kClosed,
                  "a ship position is stored each time the ship has moved this far")
          .bounded(
              "track_length", &A::track_length, "m",
              [](const A& a) { return std::make_pair(std::max(10.0, 2.0 * a.track_spacing), 1e6); },
              "at least 10 m and two track_spacing", "past track kept (older points dropped)")
          .number("thrust", &A::thrust, "N", -1e6, 1e6, kClosed, "constant thrust command")
          .number("odom_timeout", &A::odom_timeout, "s", 0.0, 3600.0, kOpen,
                  "no new vehicle odometry for this long (since it arrived): fins centred")
          .number("max_depth", &A::max_depth, "m", 0.0, 1e5, kOpen, "setpoints above it are rejected")
          .choice("actuator", &A::actuator,
                  { { "elevator", A::Actuator::kElevator },
                    { "winch", A::Actuator::kWinch },
                    { "both", A::Actuator::kBoth } },
                  "what holds the depth: the elevator (PID above), the winch (payout rate; needs winch.enabled), "
                  "or both")
          .number("winch_kp", &A::winch_kp, "m/m", 0.0, 1000.0, kClosed,
                  "winch: cable out aimed at per metre of depth error, on top of the planner's steady cable out")
          .number("winch_ki", &A::winch_ki, "m/(m s)", 0.0, 100.0, kClosed,
                  "winch: cable out per metre-second of integrated depth error")
          .number("winch_time_constant", &A::winch_time_constant, "s", 0.0, 1000.0, kOpen,
                  "winch: payout rate = (cable out aimed at − cable out) / this")
          .number("max_payout_rate", &A::max_payout_rate, "m/s", 0.0, 100.0, kOpen, "winch: payout command limit")
          .boolean("roll_hold", &A::roll_hold,
                   "hold a rolling vehicle (vehicle.roll: free) level with the elevator's differential")
          .number("roll_kp", &A::roll_kp, "rad/rad", 0.0, 100.0, kClosed, "differential per radian of roll")
          .number("roll_kd", &A::roll_kd, "rad/(rad/s)", 0.0, 100.0, kClosed, "differential per rad/s of roll rate")
          .number("max_differential", &A::max_differential, "rad", 0.0, kHalfPi, kOpen, "differential limit");
  return table;
}

}  // namespace tow_sim
