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
  const std::string refused = refusal(req, live_.shipKnown(), config_.winch.enabled);
  if (!refused.empty())
  {
    res.message = refused;
    return true;
  }
  // The chart tows along +x from a tow point at the surface: the current (now: the topics may have changed
  // it) turned into the ship's heading, and the target measured from the tow point's height.
  SimulationConfig c = config_;
  const Environment& now = live_.started() ? live_.run().simulator().data().environment : config_.environment;
  const double heading = live_.newestShipPose().heading;
  const Eigen::Matrix3d to_ship = Eigen::AngleAxisd(-heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  c.environment.current_W = to_ship * now.current_W;
  c.environment.current_profile = now.current_profile;
  for (CurrentSample& sample : c.environment.current_profile)
    sample.velocity_W = to_ship * sample.velocity_W;
  const double height = params_.tow_point_S.z();
  std::ostringstream what;
  if (req.depth_min != 0.0 || req.depth_max != 0.0)
  {
    speedWindowAnswer(c, live_.started() ? live_.run().simulator().cableLength() : c.cable.length, height, req, res,
                      what);
    if (req.depth == 0.0)
    {
      res.message = what.str();
      ROS_INFO("tow_sim: plan_cable_out: %s", res.message.c_str());
      return true;
    }
    what << "; ";
  }
  const double speed = req.speed > 0.0 ? req.speed : live_.newestShipPose().speed;
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
  if (req.execute)
  {
    const std::string refused_now = live_.driveWinchTo(plan.cable_out);
    res.executing = refused_now.empty();
    what << (res.executing ? "; the winch is on its way" : "; not executed: " + refused_now);
  }
  res.message = what.str();
  ROS_INFO("tow_sim: plan_cable_out: %s", res.message.c_str());
  return true;
}

}  // namespace tow_sim
