// ship_motion_node: a scripted ship for demos and tests. Publishes nav_msgs/Odometry on ship/odom and the
// tf world -> ship; follows geometry_msgs/Twist on cmd_vel (surge speed, yaw rate) while it keeps coming.
// The ship moves by the scenarios' manoeuvre law (ScriptedShip, tow_sim_scenario) from a preset
// (ShipMotionParams, config/node_params.h: its table gives the parameters, their units and ranges). In
// waves (~environment/waves, the towing configuration's section loaded here too) the ship heaves, rolls and
// pitches by its RAOs, the sea running on ROS time like tow_sim_node's.
#pragma once

#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>

#include "tow_sim/config/node_params.h"
#include "tow_sim/core/environment/ship_response.h"
#include "tow_sim/core/environment/waves.h"
#include "tow_sim/scenario/scripted_ship.h"

namespace tow_sim
{
class ShipMotionNode
{
public:
  // Reads and validates every parameter; throws std::invalid_argument naming the full parameter path.
  ShipMotionNode(ros::NodeHandle nh, ros::NodeHandle pnh);

private:
  void readWaves(const ros::NodeHandle& pnh);
  void onCmdVel(const geometry_msgs::Twist::ConstPtr& msg);
  void tick();
  void publish(const ros::Time& now);

  ShipMotionParams params_;
  std::unique_ptr<ScriptedShip> ship_;
  std::unique_ptr<WaveField> waves_;  // none: a level ship
  std::unique_ptr<RaoTable> rao_;
  ScriptedShip::Teleop teleop_;
  ros::Time last_, last_cmd_;
  ros::Publisher odom_pub_;
  ros::Subscriber cmd_sub_;
  ros::Timer timer_;
  tf2_ros::TransformBroadcaster broadcaster_;
};

}  // namespace tow_sim
