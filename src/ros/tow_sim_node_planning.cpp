// TowSimNode's ~plan_cable_out service and the winch driven to a planned cable out.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "tow_sim/ros/tow_sim_node.h"
#include "tow_sim/scenario/towing_chart.h"

namespace tow_sim
{
namespace
{
constexpr double kArrived = 0.05;  // [m] the winch is there within this of the planned cable out
}  // namespace

namespace
{
// Why a request cannot be answered ("" when it can).
std::string refusal(const tow_sim::PlanCableOut::Request& req, bool ship_known, bool winch_enabled)
{
  std::ostringstream why;
  const bool window = req.depth_min != 0.0 || req.depth_max != 0.0;
  if (!(std::isfinite(req.depth) && req.depth >= 0.0 && req.depth <= 12000.0))
    why << "depth = " << req.depth << " must be in (0, 12000] [m] (0: a window only)";
  else if (req.depth == 0.0 && !window)
    why << "depth = 0 asks for no plan: give a depth, or depth_min and depth_max for a speed window";
  else if (window && !(std::isfinite(req.depth_min) && std::isfinite(req.depth_max) && req.depth_min >= 0.0 &&
                       req.depth_max > req.depth_min && req.depth_max <= 12000.0))
    why << "depth_min = " << req.depth_min << ", depth_max = " << req.depth_max
        << " must satisfy 0 <= depth_min < depth_max <= 12000 [m]";
  else if (window &&
           !(std::isfinite(req.window_cable_out) && req.window_cable_out >= 0.0 && req.window_cable_out <= 1e5))
    why << "window_cable_out = " << req.window_cable_out << " must be in (0, 1e5] [m] (0: the cable out now)";
  else if (!(std::isfinite(req.speed) && req.speed >= 0.0 && req.speed <= 15.0))
    why << "speed = " << req.speed << " must be in [0, 15] [m/s] (0: the ship's present speed)";
  else if (req.depth > 0.0 && req.speed == 0.0 && !ship_known)
    why << "speed 0 asks for the ship's present speed: no ship odometry yet";
  else if (req.execute && !winch_enabled)
    why << "execute needs the winch: winch.enabled is false";
  return why.str();
}

// The speed window of a request (tow_sim_chart --cable-out --depth-band) into res and `what`, depths from
// the tow point `height` [m] above the surface, on the request's cable out or `out_now` [m].
void speedWindowAnswer(const SimulationConfig& c, double out_now, double height,
                       const tow_sim::PlanCableOut::Request& req, tow_sim::PlanCableOut::Response& res,
                       std::ostream& what)
{
  const double out = req.window_cable_out > 0.0 ? req.window_cable_out : out_now;
  const SpeedWindow w = speedWindow(c, out, req.depth_min + height, req.depth_max + height, c.environment.current_W);
  res.window_found = w.found;
  res.slowest = w.slowest;
  res.fastest = w.fastest;
  if (w.found)
    what << "with " << out << " m out the vehicle stays between " << req.depth_min << " and " << req.depth_max
         << " m from " << w.slowest << " to " << w.fastest << " m/s";
  else
    what << w.reason;
}
}  // namespace

bool TowSimNode::onPlanCableOut(tow_sim::PlanCableOut::Request& req, tow_sim::PlanCableOut::Response& res)
{
  res.reachable = res.executing = res.window_found = false;
  const std::string refused = refusal(req, !ship_->empty(), config_.winch.enabled);
  if (!refused.empty())
  {
    res.message = refused;
    return true;
  }
  // The chart tows along +x from a tow point at the surface: the current (now: the topics may have changed
  // it) turned into the ship's heading, and the target measured from the tow point's height.
  SimulationConfig c = config_;
  const Environment& now = started_ ? run_.simulator().data().environment : config_.environment;
  const double heading = ship_->empty() ? 0.0 : ship_->pose(ship_->newestTime()).heading;
  const Eigen::Matrix3d to_ship = Eigen::AngleAxisd(-heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  c.environment.current_W = to_ship * now.current_W;
  c.environment.current_profile = now.current_profile;
  for (CurrentSample& sample : c.environment.current_profile)
    sample.velocity_W = to_ship * sample.velocity_W;
  const double height = params_.tow_point_S.z();
  std::ostringstream what;
  if (req.depth_min != 0.0 || req.depth_max != 0.0)
  {
    speedWindowAnswer(c, started_ ? run_.simulator().cableLength() : c.cable.length, height, req, res, what);
    if (req.depth == 0.0)
    {
      res.message = what.str();
      ROS_INFO("tow_sim: plan_cable_out: %s", res.message.c_str());
      return true;
    }
    what << "; ";
  }
  const double speed = req.speed > 0.0 ? req.speed : ship_->pose(ship_->newestTime()).speed;
  const CableOutPlan plan = planCableOut(c, req.depth + height, speed, c.environment.current_W,
                                         config_.winch.min_length, config_.winch.max_length);
  res.reachable = plan.reachable;
  if (!plan.reachable)
  {
    res.message = what.str() + plan.reason;
    return true;
  }
  res.cable_out = plan.cable_out;
  res.depth = plan.point.depth - height;
  res.tension_ship = plan.point.tension_ship;
  res.tension_vehicle = plan.point.tension_vehicle;
  what << plan.cable_out << " m out puts the vehicle at " << res.depth << " m at " << speed << " m/s";
  if (req.execute && !started_)
    what << "; not executed: no ship odometry yet";
  else if (req.execute && run_.simulator().parted())
    what << "; not executed: the cable has parted (~reset joins it again)";
  else if (req.execute)
  {
    winch_target_ = plan.cable_out;
    res.executing = true;
    what << "; the winch is on its way";
  }
  res.message = what.str();
  ROS_INFO("tow_sim: plan_cable_out: %s", res.message.c_str());
  return true;
}

void TowSimNode::driveWinch()
{
  if (!winch_target_ || !config_.winch.enabled)
    return;
  if (run_.simulator().parted())  // the winch stopped with the parting: nothing to drive
  {
    winch_target_.reset();
    ROS_WARN("tow_sim: the planned cable out is given up: the cable has parted");
    return;
  }
  const double remaining = *winch_target_ - run_.simulator().cableLength();
  if (std::abs(remaining) <= kArrived)
  {
    winch_target_.reset();
    run_.setWinchCommand(0.0);
    ROS_INFO("tow_sim: the winch has reached the planned cable out");
    return;
  }
  // Payout rate = remaining length / (4 x the winch's response time), within max_rate: with the winch's own
  // first-order lag the approach is critically damped. The command holds for a physics tick, so the time
  // constant is at least two ticks (else the loop would hunt).
  const double limit = config_.winch.max_rate;
  const double time_constant = std::max(4.0 * config_.winch.response_time, 2.0 / params_.physics_rate);
  run_.setWinchCommand(std::clamp(remaining / time_constant, -limit, limit));
}

}  // namespace tow_sim
