// The ROS adapter around the core DepthAutopilot: vehicle/odom, ship/odom and autopilot/depth_setpoint in;
// fins/command out at ~rate, and winch/command when ~actuator is winch or both (the cable out from
// cable/state, the feed-forward from tow_sim_node's ~plan_cable_out). Parameters, topics and signs:
// docs/nodes.md ("depth_autopilot_node").
#pragma once

#include <dynamic_reconfigure/server.h>
#include <interactive_markers/interactive_marker_server.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include <future>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "tow_sim/CableState.h"
#include "tow_sim/DepthAutopilotConfig.h"
#include "tow_sim/PlanCableOut.h"
#include "tow_sim/config/node_params.h"
#include "tow_sim/core/run/depth_autopilot.h"

namespace tow_sim
{
class DepthAutopilotNode
{
public:
  // Reads and validates every parameter; throws std::invalid_argument naming the full parameter path,
  // the value and the range.
  DepthAutopilotNode(ros::NodeHandle nh, ros::NodeHandle pnh);

private:
  void onVehicleOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void onShipOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void onSetpoint(const std_msgs::Float64::ConstPtr& msg);
  void onAltitudeSetpoint(const std_msgs::Float64::ConstPtr& msg);
  // A depth setpoint from the topic or the marker: validated, planned for the winch, the marker moved.
  void applyDepthSetpoint(double depth, const std::string& source);
  // ~setpoint_marker: dragged along z in rviz, it sets the depth setpoint where it is let go; it follows
  // the vehicle horizontally and shows the setpoint's depth.
  void setUpMarker();
  void onMarkerFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback);
  void moveMarker();
  void followWithMarker();  // moveMarker when the vehicle has gone 2 m or the setpoint changed
  void onCableState(const tow_sim::CableState::ConstPtr& msg);
  void tick(const ros::TimerEvent& event);
  bool frameOk(const nav_msgs::Odometry& msg, const char* topic);
  void askForPlan(double now);
  // Live gains and limits (cfg/DepthAutopilot.cfg), validated like the start-up parameters; a refused
  // change is answered with the old values.
  tow_sim::DepthAutopilotConfig liveConfig() const;
  void onReconfigure(tow_sim::DepthAutopilotConfig& c);
  void takePlan(double now);

  ros::NodeHandle nh_, pnh_;
  AutopilotNodeParams node_params_;  // the controller's gains, the rate and the world frame
  DepthAutopilot autopilot_;
  bool announced_hold_ = false;
  ros::Subscriber vehicle_sub_, ship_sub_, setpoint_sub_, altitude_setpoint_sub_, state_sub_;
  // The newest cable/state with a seabed: the vehicle's altitude and depth, and their stamp.
  bool have_altitude_ = false;
  double altitude_ = 0.0, altitude_depth_ = 0.0, altitude_stamp_ = 0.0;  // [m], [m], [s]
  // The newest cable/state's cable out and its stamp (the winch actuator's measurement).
  bool have_cable_out_ = false;
  double cable_out_ = 0.0, cable_out_stamp_ = 0.0;  // [m], [s]
  bool drives_winch_ = false;                       // ~actuator winch or both
  // The winch's feed-forward: the depth setpoint still to be planned (NaN: none), the call under way (on
  // its own thread, so the ticks go on) and when to ask again after tow_sim_node did not answer.
  double plan_depth_ = std::numeric_limits<double>::quiet_NaN();  // [m]
  std::future<std::pair<bool, tow_sim::PlanCableOut::Response>> plan_call_;
  double plan_depth_asked_ = 0.0, plan_retry_at_ = 0.0;  // [m], [s]
  ros::Publisher fin_pub_, winch_pub_;
  ros::Timer timer_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<tow_sim::DepthAutopilotConfig>> reconfigure_;
  std::unique_ptr<interactive_markers::InteractiveMarkerServer> marker_server_;
  double marker_x_ = 0.0, marker_y_ = 0.0, marker_z_ = 0.0;  // [m] where the marker was last put
};

}  // namespace tow_sim
