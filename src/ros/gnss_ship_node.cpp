#include "tow_sim/ros/gnss_ship_node.h"

#include <nav_msgs/Odometry.h>
#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/ros/conversions.h"

namespace tow_sim
{
namespace ros_conv
{
std::string fixProblem(const sensor_msgs::NavSatFix& fix)
{
  std::ostringstream why;
  if (fix.status.status < sensor_msgs::NavSatStatus::STATUS_FIX)
    why << "status.status = " << int(fix.status.status) << " (no fix): a fix needs status >= 0";
  else if (!(std::isfinite(fix.latitude) && std::abs(fix.latitude) <= 90.0))
    why << "latitude = " << fix.latitude << " must be finite, in [-90, 90] [deg]";
  else if (!(std::isfinite(fix.longitude) && std::abs(fix.longitude) <= 180.0))
    why << "longitude = " << fix.longitude << " must be finite, in [-180, 180] [deg]";
  else if (!(std::isfinite(fix.altitude) && std::abs(fix.altitude) <= 1e4))
    why << "altitude = " << fix.altitude << " must be finite, in [-1e4, 1e4] [m]";
  return why.str();
}

double headingYaw(const geometry_msgs::QuaternionStamped& heading, const std::string& convention)
{
  const auto& q = heading.quaternion;
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!(std::isfinite(n) && std::abs(n - 1.0) < 0.01))
  {
    std::ostringstream why;
    why << "quaternion: |q| = " << n << " must be 1 within 0.01 (finite x, y, z, w)";
    throw std::invalid_argument(why.str());
  }
  const double yaw = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
  return convention == "compass" ? std::remainder(kHalfPi - yaw, 2.0 * kPi) : yaw;
}
}  // namespace ros_conv

namespace
{
// Its own parameters; the towing configuration's keys are allowed beside them (tow_sim.launch loads it
// here too, for its world_frame).
GnssShipParams readParams(const ros::NodeHandle& pnh)
{
  ros_conv::requireConfigurationOrOwnKeys(pnh, gnssShipParams());
  return ros_conv::readPrivateParams(pnh, gnssShipParams(), validate);
}

GnssTrackParams trackParams(const GnssShipParams& p)
{
  GnssTrackParams t;
  t.antenna_S = p.antenna_S;
  t.smoothing_time = p.smoothing_time;
  t.use_altitude = p.use_altitude;
  return t;
}
}  // namespace

GnssShipNode::GnssShipNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : params_(readParams(pnh)), track_(trackParams(params_))
{
  if (!params_.origin_from_first_fix)
    origin_ = std::make_unique<GeographicLib::LocalCartesian>(params_.origin_latitude, params_.origin_longitude,
                                                              params_.origin_altitude);
  odom_pub_ = nh.advertise<nav_msgs::Odometry>("ship/odom", 20);
  fix_sub_ = nh.subscribe("ship/fix", 20, &GnssShipNode::onFix, this);
  heading_sub_ = nh.subscribe("ship/heading", 20, &GnssShipNode::onHeading, this);
  ROS_INFO("gnss_ship: %s + %s -> %s in '%s' about %s", fix_sub_.getTopic().c_str(), heading_sub_.getTopic().c_str(),
           odom_pub_.getTopic().c_str(), params_.world_frame.c_str(),
           origin_ ? "the configured origin" : "the first good fix");
}

GnssShipNode::~GnssShipNode() = default;

void GnssShipNode::onHeading(const geometry_msgs::QuaternionStamped::ConstPtr& msg)
{
  try
  {
    yaw_ = ros_conv::headingYaw(*msg, params_.heading_convention);
    heading_stamp_ = msg->header.stamp;
  }
  catch (const std::invalid_argument& e)
  {
    ROS_WARN_THROTTLE(2.0, "gnss_ship: rejected %s: %s", heading_sub_.getTopic().c_str(), e.what());
  }
}

void GnssShipNode::onFix(const sensor_msgs::NavSatFix::ConstPtr& msg)
{
  const std::string problem = ros_conv::fixProblem(*msg);
  if (!problem.empty())
  {
    ROS_WARN_THROTTLE(2.0, "gnss_ship: rejected %s: %s", fix_sub_.getTopic().c_str(), problem.c_str());
    return;
  }
  if (heading_stamp_.isZero() || std::abs((msg->header.stamp - heading_stamp_).toSec()) > params_.max_heading_age)
  {
    ROS_WARN_THROTTLE(2.0, "gnss_ship: fix at %.3f s dropped: no %s within ~max_heading_age = %g s of it",
                      msg->header.stamp.toSec(), heading_sub_.getTopic().c_str(), params_.max_heading_age);
    return;
  }
  if (!origin_)
  {
    origin_ = std::make_unique<GeographicLib::LocalCartesian>(msg->latitude, msg->longitude, msg->altitude);
    ROS_INFO("gnss_ship: origin of '%s' at the first fix: %.8f deg N, %.8f deg E, %.2f m", params_.world_frame.c_str(),
             msg->latitude, msg->longitude, msg->altitude);
  }
  GnssFix fix;
  fix.t = msg->header.stamp.toSec();
  fix.yaw = yaw_;
  origin_->Forward(msg->latitude, msg->longitude, msg->altitude, fix.antenna_W.x(), fix.antenna_W.y(),
                   fix.antenna_W.z());
  try
  {
    publish(msg->header.stamp, track_.update(fix));
  }
  catch (const std::invalid_argument& e)
  {
    ROS_WARN_THROTTLE(2.0, "gnss_ship: rejected %s: header.stamp: %s", fix_sub_.getTopic().c_str(), e.what());
  }
}

void GnssShipNode::publish(const ros::Time& stamp, const ShipEstimate& e)
{
  nav_msgs::Odometry odom;
  odom.header.stamp = stamp;
  odom.header.frame_id = params_.world_frame;
  odom.child_frame_id = params_.ship_frame;
  odom.pose.pose.position = ros_conv::toPoint(e.p_W);
  odom.pose.pose.orientation =
      ros_conv::toQuaternion(Eigen::Quaterniond(Eigen::AngleAxisd(e.yaw, Eigen::Vector3d::UnitZ())));
  odom.twist.twist.linear = ros_conv::toVector3(e.v_S);  // REP-105: in the ship frame
  odom.twist.twist.angular.z = e.yaw_rate;
  odom_pub_.publish(odom);
  if (!params_.publish_tf)
    return;
  geometry_msgs::TransformStamped tf;
  tf.header = odom.header;
  tf.child_frame_id = params_.ship_frame;
  tf.transform.translation = ros_conv::toVector3(e.p_W);
  tf.transform.rotation = odom.pose.pose.orientation;
  broadcaster_.sendTransform(tf);
}

}  // namespace tow_sim
