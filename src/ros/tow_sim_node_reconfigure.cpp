// tow_sim_node's live settings (dynamic_reconfigure, cfg/TowSim.cfg): the uniform current, the publish
// rate, the drawing's scales and the cable's load limits. A change is validated exactly as the start-up
// parameters are (the same tables, the same messages) and acts from the next tick; a refused change keeps
// every old value and is reported back to the client as the old configuration.
#include <cmath>
#include <stdexcept>
#include <string>

#include "tow_sim/core/param_table.h"
#include "tow_sim/ros/conversions.h"
#include "tow_sim/ros/tow_sim_node.h"

namespace tow_sim
{
namespace
{
std::optional<double> unsetAtZero(double v)
{
  return v == 0.0 ? std::nullopt : std::optional<double>(v);
}
}  // namespace

void TowSimNode::setUpReconfigure()
{
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<tow_sim::TowSimConfig>>(reconfigure_mutex_, pnh_);
  reported_current_ = live_.run().simulator().data().environment.current_W;
  reconfigure_->updateConfig(liveConfig());  // the start-up values, not the generator's defaults
  reconfigure_->setCallback([this](tow_sim::TowSimConfig& c, uint32_t) { onReconfigure(c); });
}

tow_sim::TowSimConfig TowSimNode::liveConfig() const
{
  tow_sim::TowSimConfig c;
  const Eigen::Vector3d current = live_.run().simulator().data().environment.current_W;
  c.current_x = current.x();
  c.current_y = current.y();
  c.current_z = current.z();
  c.publish_rate = params_.publish_rate;
  c.tension_color_max = params_.tension_color_max;
  c.force_arrow_scale = params_.force_arrow_scale;
  c.cable_marker_width = params_.cable_marker_width;
  c.vehicle_diameter = params_.vehicle_diameter;
  c.ship_length = params_.ship_length;
  c.ship_beam = params_.ship_beam;
  c.safe_working_load = config_.cable.safe_working_load.value_or(0.0);
  c.breaking_load = config_.cable.breaking_load.value_or(0.0);
  return c;
}

void TowSimNode::onReconfigure(tow_sim::TowSimConfig& c)
{
  const std::string prefix = pnh_.getNamespace() + "/";
  try
  {
    NodeParams params = params_;
    params.publish_rate = c.publish_rate;
    params.tension_color_max = c.tension_color_max;
    params.force_arrow_scale = c.force_arrow_scale;
    params.cable_marker_width = c.cable_marker_width;
    params.vehicle_diameter = c.vehicle_diameter;
    params.ship_length = c.ship_length;
    params.ship_beam = c.ship_beam;
    validate(params, prefix);
    CableParams cable = config_.cable;
    cable.safe_working_load = unsetAtZero(c.safe_working_load);
    cable.breaking_load = unsetAtZero(c.breaking_load);
    validate(cable, prefix);
    const Eigen::Vector3d current(c.current_x, c.current_y, c.current_z);
    const char* axes[] = { "current_x", "current_y", "current_z" };
    for (int i = 0; i < 3; ++i)
      requireInRange(prefix + axes[i], current[i], -20.0, 20.0, "[m/s]");
    // Valid: everything at once.
    std::string why;
    if (!live_.setCurrent(current, &why))  // counted there
    {
      ROS_ERROR("tow_sim: reconfigure refused: %s; every setting keeps its previous value", why.c_str());
      c = liveConfig();
      return;
    }
    reported_current_ = current;
    if (params.publish_rate != params_.publish_rate)
      publish_timer_.setPeriod(ros::Duration(1.0 / params.publish_rate));
    params_ = params;
    config_.cable = cable;
    ROS_INFO(
        "tow_sim: reconfigured: current [%g, %g, %g] m/s, publish_rate %g Hz, tension_color_max %g N, "
        "safe_working_load %g N, breaking_load %g N (0: unset)",
        current.x(), current.y(), current.z(), params_.publish_rate, params_.tension_color_max, c.safe_working_load,
        c.breaking_load);
  }
  catch (const std::invalid_argument& e)
  {
    live_.countRejected();
    ROS_ERROR("tow_sim: reconfigure refused: %s; every setting keeps its previous value",
              ros_conv::withSlashes(e).what());
    c = liveConfig();
  }
}

void TowSimNode::reportCurrent()
{
  const Eigen::Vector3d current = live_.run().simulator().data().environment.current_W;
  if (!reconfigure_ || current == reported_current_)
    return;
  reported_current_ = current;
  reconfigure_->updateConfig(liveConfig());
}

}  // namespace tow_sim
