// The ROS adapter around a LiveRun (core/run/live_run.h, which holds the logic: pacing, restarts,
// re-acquisition, interpolation at the clock, counters): ship odometry and commands in; cable state, markers,
// vehicle odometry, fin loads, tf and diagnostics out (converted from the run's snapshots, ros/conversions.h).
// Time comes from ros::Time (wall or /clock); the simulation runs `odom_delay` behind it so that the ship's
// motion is interpolated between odometry messages, and extrapolates at most `max_extrapolation` past the
// newest one before it holds.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <std_msgs/Float64.h>

#include "tow_sim/CableParting.h"
#include "tow_sim/CurrentProfile.h"
#include "tow_sim/FinCommand.h"
#include "tow_sim/PlanCableOut.h"
#include "tow_sim/StateFile.h"
#include "tow_sim/TowSimConfig.h"
#include "tow_sim/config/config.h"
#include "tow_sim/config/node_params.h"
#include "tow_sim/core/run/live_run.h"
#include "tow_sim/core/run/tension_limits.h"
#include "tow_sim/core/run/track_trail.h"
#include "tow_sim/ros/survey_publisher.h"

namespace tow_sim
{
class TowSimNode
{
public:
  // Reads and validates every parameter; throws std::invalid_argument naming the full parameter path.
  TowSimNode(ros::NodeHandle nh, ros::NodeHandle pnh);

private:
  void onOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void onFinCommand(const tow_sim::FinCommand::ConstPtr& msg);
  void onCurrent(const geometry_msgs::Vector3Stamped::ConstPtr& msg);
  void onCurrentProfile(const tow_sim::CurrentProfile::ConstPtr& msg);
  void onWinchCommand(const std_msgs::Float64::ConstPtr& msg);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSetPaused(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  // ~plan_cable_out (tow_sim_node_planning.cpp): the towing chart's planner with this node's configuration
  // and current; with `execute`, the winch goes to the planned cable out (LiveRun::driveWinchTo).
  bool onPlanCableOut(tow_sim::PlanCableOut::Request& req, tow_sim::PlanCableOut::Response& res);
  // ~save_state and ~load_state (tow_sim_node_state.cpp): the run's state to a file, and a saved one carried
  // to the ship's pose now (relocate) and continued; a refused file changes nothing.
  bool onSaveState(tow_sim::StateFile::Request& req, tow_sim::StateFile::Response& res);
  bool onLoadState(tow_sim::StateFile::Request& req, tow_sim::StateFile::Response& res);
  // Live settings (tow_sim_node_reconfigure.cpp, cfg/TowSim.cfg): validated like the start-up parameters;
  // a refused change is answered with the old values (c is set back to them).
  void setUpReconfigure();
  tow_sim::TowSimConfig liveConfig() const;
  void onReconfigure(tow_sim::TowSimConfig& c);
  // The current topic changed the current: the server's configuration follows (at the diagnostics' 1 Hz,
  // as each update writes every setting to the parameter server).
  void reportCurrent();
  void publishTick();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  // cable.safe_working_load and cable.breaking_load: checked at each output (a throttled log), the worst
  // since the previous report merged into the diagnostics' summary (WARN, ERROR) with its values.
  void noteTensionLimits(const TowSnapshot& snapshot);
  void diagnoseTensionLimits(diagnostic_updater::DiagnosticStatusWrapper& status);
  // The cable parted (tow_sim_node_state.cpp): said once (ROS_ERROR, the latched cable/parting), and an
  // ERROR in the diagnostics while the run goes on parted.
  void noteParting(const TowSnapshot& snapshot);
  void diagnoseParting(diagnostic_updater::DiagnosticStatusWrapper& status);
  void printStatus();  // the status line (print_status)

  // A notice of the live run, logged at its level; the frequent kinds throttled (2 or 5 s each).
  void say(const LiveNotice& notice);
  void physicsTick();
  // The clock now, and the run's time t [s] as a stamp.
  static int64_t nowNs() { return static_cast<int64_t>(ros::Time::now().toNSec()); }
  ros::Time stamp(double t) const;
  // Subscribes with `callback` guarded: no exception leaves a callback (the node runs on, says why).
  template <class M>
  ros::Subscriber subscribe(const std::string& topic, uint32_t queue,
                            void (TowSimNode::*callback)(const typename M::ConstPtr&));

  ros::NodeHandle nh_, pnh_;
  NodeParams params_;
  // The configuration's keys as loaded (before the node caps max_step or reconfigure changes the load
  // limits): what ~save_state records and ~load_state compares. Declared before config_, which fills it.
  std::map<std::string, std::string> config_keys_;
  SimulationConfig config_;
  LiveRun live_;             // the run, the ship's history, the pacing and the counters (core/run/live_run.h)
  TowSnapshot last_;         // the last published outputs (the status line prints them)
  bool have_last_ = false;   // last_ is of the current run
  uint64_t run_number_ = 0;  // live_'s run the outputs below are of
  std::unique_ptr<TrackTrail> ship_trail_, vehicle_trail_;  // drawn (none when trail_duration is 0)
  std::unique_ptr<SurveyPublisher> survey_;                 // the survey sensors (none without sensors:)
  ros::Time last_tf_stamp_;
  int64_t tf_origin_ns_ = 0;  // live_'s time origin when last_tf_stamp_ was set
  std::array<double, static_cast<size_t>(LiveNotice::Kind::kCount)> said_wall_{};  // [s] each kind last logged
  LiveLoad load_;                    // over the last diagnostics report's interval
  TensionLimitCheck tension_limit_;  // the worst over the outputs since the last diagnostics report

  ros::Subscriber odom_sub_, fin_sub_, current_sub_, current_profile_sub_, winch_sub_;
  ros::Publisher state_pub_, marker_pub_, vehicle_odom_pub_, fin_loads_pub_;
  ros::Publisher ship_force_pub_, vehicle_force_pub_;  // the cable's forces on the ship and the vehicle
  ros::Publisher joint_state_pub_;                     // the fin angles, for robot_state_publisher (URDF)
  ros::Publisher parting_pub_;                         // cable/parting, latched
  std::optional<PartingEvent> parting_;                // the run's, once said
  ros::ServiceServer reset_srv_, pause_srv_, plan_srv_, save_srv_, load_srv_;
  ros::Timer physics_timer_, publish_timer_, status_timer_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  diagnostic_updater::Updater diagnostics_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<tow_sim::TowSimConfig>> reconfigure_;
  Eigen::Vector3d reported_current_ = Eigen::Vector3d::Constant(std::nan(""));  // [m/s] in the server's config
};

}  // namespace tow_sim
