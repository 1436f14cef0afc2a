// tow_sim_node's saved states (~save_state writes the run's state, saved_state.h; ~load_state carries a
// saved one to the ship's pose now and goes on from it) and the cable parting's report.
#include <cstdio>
#include <exception>
#include <string>

#include "tow_sim/config/config.h"
#include "tow_sim/core/io/saved_state.h"
#include "tow_sim/ros/tow_sim_node.h"

namespace tow_sim
{
namespace
{
std::string timeText(double t)
{
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.3f", t);
  return buffer;
}
}  // namespace

bool TowSimNode::onSaveState(tow_sim::StateFile::Request& req, tow_sim::StateFile::Response& res)
{
  res.success = false;
  if (req.path.empty())
    res.message = "path: must name the file to write";
  else if (!live_.started())
    res.message = "no run to save yet (no ship odometry)";
  else
  {
    try
    {
      RunState state = live_.run().saveState();
      state.configuration = config_keys_;
      writeRunState(req.path, state);
      res.success = true;
      res.message = "saved the state at t = " + timeText(stamp(live_.run().time()).toSec()) + " s to " + req.path;
      ROS_INFO("tow_sim: %s", res.message.c_str());
    }
    catch (const std::exception& e)
    {
      res.message = e.what();
    }
  }
  if (!res.success)
    ROS_WARN("tow_sim: ~save_state refused: %s", res.message.c_str());
  return true;
}

bool TowSimNode::onLoadState(tow_sim::StateFile::Request& req, tow_sim::StateFile::Response& res)
{
  res.success = false;
  if (req.path.empty())
    res.message = "path: must name a saved state file";
  else if (!live_.shipKnown())
    res.message = "no ship odometry yet: a state is placed at the ship";
  else
  {
    try
    {
      const RunState saved = readRunState(req.path);
      if (!req.any_configuration)
        requireSameConfiguration(saved.configuration, config_keys_, "any_configuration: true loads it");
      live_.load(saved);  // refused: nothing changed
      const double t = live_.run().time();
      res.success = true;
      res.message = "loaded " + req.path + " (saved at run time " + timeText(saved.sim.t) +
                    " s) at t = " + timeText(stamp(t).toSec()) + " s, placed at the ship's pose now";
      ROS_INFO("tow_sim: %s", res.message.c_str());
    }
    catch (const std::exception& e)
    {
      res.message = e.what();
    }
  }
  if (!res.success)
    ROS_WARN("tow_sim: ~load_state refused: %s", res.message.c_str());
  return true;
}

void TowSimNode::noteParting(const TowSnapshot& snapshot)
{
  if (!snapshot.parting)
  {
    parting_.reset();  // a restart joined the cable again
    return;
  }
  if (parting_ && parting_->t == snapshot.parting->t)
    return;
  parting_ = snapshot.parting;
  tow_sim::CableParting msg;
  msg.header.stamp = stamp(parting_->t);
  msg.header.frame_id = params_.world_frame;
  msg.joint = static_cast<uint32_t>(parting_->joint);
  msg.tension = parting_->tension;
  msg.breaking_load = config_.cable.breaking_load.value_or(0.0);
  parting_pub_.publish(msg);
  ROS_ERROR(
      "tow_sim: the cable PARTED at joint %d (1: the tow point) under %.0f N, above the breaking load %.0f N "
      "(t = %.3f s); the vehicle side goes on with a free end, ~reset joins the cable again",
      parting_->joint, parting_->tension, msg.breaking_load, msg.header.stamp.toSec());
}

void TowSimNode::diagnoseParting(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  using diagnostic_msgs::DiagnosticStatus;
  if (parting_)
    status.mergeSummaryf(DiagnosticStatus::ERROR, "the cable parted at joint %d under %.0f N", parting_->joint,
                         parting_->tension);
  status.add("parted", parting_ ? "yes" : "no");
}

}  // namespace tow_sim
