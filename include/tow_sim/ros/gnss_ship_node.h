// gnss_ship_node: a survey vessel's GNSS as the ship odometry tow_sim_node follows (docs/own_ship.md).
// Subscribes sensor_msgs/NavSatFix on ship/fix and geometry_msgs/QuaternionStamped on ship/heading (the
// ship's yaw; ~heading_convention says from east or from north); publishes nav_msgs/Odometry on ship/odom
// (~world_frame: ENU about the geodetic origin, GeographicLib's LocalCartesian; child ~ship_frame, twist
// in the ship frame) and the tf world -> ship. The antenna's lever arm is taken out with the heading and
// the track smoothed by an alpha-beta tracker (GnssTrack, tow_sim_core). Parameters: GnssShipParams
// (config/node_params.h). A fix without a fix (status < 0), with non-finite fields, stamped no later than
// the previous one or without a heading within ~max_heading_age is dropped with a throttled warning
// naming the field; the node keeps its track.
#pragma once

#include <geometry_msgs/QuaternionStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/NavSatFix.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>
#include <string>

#include "tow_sim/config/node_params.h"
#include "tow_sim/core/run/gnss_track.h"

namespace GeographicLib
{
class LocalCartesian;
}

namespace tow_sim
{
namespace ros_conv
{
// Why a fix cannot be used ("" if it can): names the message field and the allowed range.
std::string fixProblem(const sensor_msgs::NavSatFix& fix);
// The ship's yaw [rad] from +x (east) toward +y (north) out of ship/heading; throws std::invalid_argument
// naming the field if the quaternion is not finite or far from unit length.
double headingYaw(const geometry_msgs::QuaternionStamped& heading, const std::string& convention);
}  // namespace ros_conv

class GnssShipNode
{
public:
  // Reads and validates every parameter; throws std::invalid_argument naming the full parameter path.
  GnssShipNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~GnssShipNode();

private:
  void onFix(const sensor_msgs::NavSatFix::ConstPtr& msg);
  void onHeading(const geometry_msgs::QuaternionStamped::ConstPtr& msg);
  void publish(const ros::Time& stamp, const ShipEstimate& e);

  GnssShipParams params_;
  GnssTrack track_;
  std::unique_ptr<GeographicLib::LocalCartesian> origin_;  // none until the first good fix (or configured)
  double yaw_ = 0.0;
  ros::Time heading_stamp_;  // zero: no heading yet
  ros::Publisher odom_pub_;
  ros::Subscriber fix_sub_, heading_sub_;
  tf2_ros::TransformBroadcaster broadcaster_;
};

}  // namespace tow_sim
