// tow_nav_node: where the towfish is, live, from a survey vessel's sensor topics and the cable model (tow_nav.h,
// docs/survey.md "tow_nav_node"). Subscribes the topics tow_sim_node's simulated sensors publish (a real
// vessel's drivers remapped onto them): survey/ship/fix, survey/ship/heading, survey/cable_out,
// survey/tension, survey/fish/depth or survey/fish/pressure, survey/fish/imu, survey/usbl. Publishes, at ~rate
// once the model has started:
//
//   nav/fish/pose         geometry_msgs/PoseWithCovarianceStamped  the fish's CG in ~world_frame, its covariance
//   nav/fish/fix          sensor_msgs/NavSatFix                    the same as latitude, longitude, altitude
//   nav/layback           tow_sim/SensorValue                      [m] behind the tow point along the heading
//   nav/cross_track       tow_sim/SensorValue                      [m] off the tow point's line, positive to port
//   tf ~world_frame -> ~fish_frame, and /diagnostics (what was refused, and why, counted).
//
// The estimate is ~hold behind the clock (a row waits for the measurements of its instant) and stamped at its
// instant. A message with a bad field is refused with a throttled warning naming the field and counted; the
// estimate carries on.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <map>
#include <memory>
#include <string>

#include "tow_sim/config/node_params.h"
#include "tow_sim/core/survey/tow_nav.h"
#include "tow_sim/ros/survey_rows.h"

namespace tow_sim
{
class TowNavNode
{
public:
  // Reads and validates the towing configuration, its nav: section and the node's keys; throws
  // std::invalid_argument naming the full parameter path.
  TowNavNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~TowNavNode();

private:
  TowNavNode(ros::NodeHandle nh, ros::NodeHandle pnh, const SimulationConfig& config);
  template <class M>
  ros::Subscriber subscribe(const std::string& topic, std::string (SurveyRows::*take)(const M&));
  void tick(const ros::TimerEvent&);
  void restart(const ros::Time& now);
  void warnRefused(const std::string& topic, const std::string& why);
  void publish(const TowNavEstimate& e);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  ros::NodeHandle nh_;
  TowNavNodeParams params_;
  TowNavParams nav_params_;
  SimulationConfig config_;
  std::unique_ptr<SurveyRows> rows_;
  std::unique_ptr<TowNav> nav_;
  TowNavEstimate last_;
  // The AHRS's latest (the pose's orientation) and its t.
  double fish_yaw_ = NAN, fish_pitch_ = NAN, fish_roll_ = NAN, fish_t_ = NAN;
  ros::Time last_now_;                           // the clock at the previous tick
  std::map<std::string, ros::WallTime> warned_;  // when each topic's refusal was last logged
  long restarts_ = 0;                            // after the clock went back
  long rows_taken_ = 0;
  double cpu_ = 0.0, cpu_since_ = 0.0;  // [s] the ticks' thread CPU time, and the wall time it was reset at
  ros::Publisher pose_pub_, fix_pub_, layback_pub_, cross_track_pub_;
  std::vector<ros::Subscriber> subs_;
  ros::Timer timer_;
  diagnostic_updater::Updater diagnostics_;
  tf2_ros::TransformBroadcaster broadcaster_;
};

}  // namespace tow_sim
