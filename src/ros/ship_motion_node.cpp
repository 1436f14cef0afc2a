#include "tow_sim/ros/ship_motion_node.h"

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "tow_sim/config/config.h"
#include "tow_sim/core/attitude.h"
#include "tow_sim/ros/conversions.h"

namespace tow_sim
{
namespace
{
// Its own parameters and, as tow_sim.launch loads the towing configuration here too (for the waves), a
// configuration file's keys: any other private parameter is a typo.
ShipMotionParams readParams(const ros::NodeHandle& pnh)
{
  try
  {
    ros_conv::requireConfigurationOrOwnKeys(pnh, shipMotionParams());
    return readShipMotionParams(ros_conv::privateParameters(pnh), pnh.getNamespace());
  }
  catch (const std::invalid_argument& e)
  {
    throw ros_conv::withSlashes(e);
  }
}
}  // namespace

ShipMotionNode::ShipMotionNode(ros::NodeHandle nh, ros::NodeHandle pnh) : params_(readParams(pnh))
{
  ship_ = std::make_unique<ScriptedShip>(presetManoeuvres(params_), 0.0, 0.0, params_.heading);
  readWaves(pnh);
  odom_pub_ = nh.advertise<nav_msgs::Odometry>("ship/odom", 20);
  cmd_sub_ = nh.subscribe("cmd_vel", 5, &ShipMotionNode::onCmdVel, this);
  timer_ = nh.createTimer(ros::Duration(1.0 / params_.rate), [this](const ros::TimerEvent&) { tick(); });
}

void ShipMotionNode::readWaves(const ros::NodeHandle& pnh)
{
  const bool respond = params_.wave_response;
  const std::string& rao_file = params_.rao_file;
  const SimulationConfig config = loadConfig(ros_conv::privateParameters(pnh), pnh.getNamespace() + "/");
  const Environment& env = config.environment;
  if (!respond || env.waves.type == WaveParams::Type::kNone)
    return;
  waves_ = std::make_unique<WaveField>(env.waves, env.gravity);
  try
  {
    rao_ = std::make_unique<RaoTable>(rao_file.empty() ? RaoTable::genericVessel(env.gravity)
                                                       : RaoTable::fromCsvFile(rao_file));
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(pnh.resolveName("rao_file") + ": " + e.what());
  }
  ROS_INFO("ship_motion: heaving, rolling and pitching in %s waves (%s)",
           env.waves.type == WaveParams::Type::kRegular ? "regular" : "JONSWAP",
           rao_file.empty() ? "the generic vessel's RAOs" : rao_file.c_str());
}

void ShipMotionNode::onCmdVel(const geometry_msgs::Twist::ConstPtr& msg)
{
  if (!std::isfinite(msg->linear.x) || !std::isfinite(msg->angular.z))
  {
    ROS_WARN_THROTTLE(2.0, "ship_motion: rejected cmd_vel: linear.x and angular.z must be finite");
    return;
  }
  teleop_.speed = std::clamp(msg->linear.x, -15.0, 15.0);
  teleop_.yaw_rate = std::clamp(msg->angular.z, -0.5, 0.5);
  last_cmd_ = ros::Time::now();
}

void ShipMotionNode::tick()
{
  const ros::Time now = ros::Time::now();
  if (last_.isZero() || now < last_)
    last_ = now;  // the first tick, or the clock jumped back
  const double dt = (now - last_).toSec();
  last_ = now;
  const bool teleop = !last_cmd_.isZero() && (now - last_cmd_).toSec() < 1.0;
  if (dt > 0.0)
    ship_->step(dt, teleop ? &teleop_ : nullptr);
  publish(now);
}

void ShipMotionNode::publish(const ros::Time& now)
{
  const ShipRigidMotion m = scriptedShipMotion(now.toSec(), ship_->x(), ship_->y(), ship_->heading(), ship_->speed(),
                                               ship_->yawRate(), waves_.get(), rao_.get());
  const Eigen::Matrix3d R = rotationFromEuler(m.roll, m.pitch, m.yaw);
  const Eigen::Quaterniond q(R);
  const Eigen::Vector3d v_S = R.transpose() * m.v_W, w_S = R.transpose() * shipAngularVelocity(m);
  nav_msgs::Odometry odom;
  odom.header.stamp = now;
  odom.header.frame_id = params_.world_frame;
  odom.child_frame_id = params_.ship_frame;
  odom.pose.pose.position.x = m.p_W.x();
  odom.pose.pose.position.y = m.p_W.y();
  odom.pose.pose.position.z = m.p_W.z();
  odom.pose.pose.orientation.x = q.x();
  odom.pose.pose.orientation.y = q.y();
  odom.pose.pose.orientation.z = q.z();
  odom.pose.pose.orientation.w = q.w();
  odom.twist.twist.linear.x = v_S.x();  // REP-105: twist in the ship frame
  odom.twist.twist.linear.y = v_S.y();
  odom.twist.twist.linear.z = v_S.z();
  odom.twist.twist.angular.x = w_S.x();
  odom.twist.twist.angular.y = w_S.y();
  odom.twist.twist.angular.z = w_S.z();
  odom_pub_.publish(odom);

  geometry_msgs::TransformStamped tf;
  tf.header = odom.header;
  tf.child_frame_id = params_.ship_frame;
  tf.transform.translation.x = m.p_W.x();
  tf.transform.translation.y = m.p_W.y();
  tf.transform.translation.z = m.p_W.z();
  tf.transform.rotation = odom.pose.pose.orientation;
  broadcaster_.sendTransform(tf);
}

}  // namespace tow_sim
