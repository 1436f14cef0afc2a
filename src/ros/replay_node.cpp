#include "tow_sim/ros/replay_node.h"

#include <rosgraph_msgs/Clock.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>

#include "tow_sim/ros/conversions.h"
#include "tow_sim/ros/markers.h"

namespace tow_sim
{
ReplayNode::ReplayNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh),
      pnh_(pnh),
      params_(ros_conv::readOwnPrivateParams<ReplayParams>(pnh, replayParams(), validate)),
      frames_(readShapes(params_.run + "/shapes.csv"))
{
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("cable/markers", 2);
  started_ = ros::WallTime::now();
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / params_.publish_rate), &ReplayNode::tick, this);
  ROS_INFO("tow_sim_replay: %zu shapes from %.1f s to %.1f s of %s at %g x real time%s", frames_.size(),
           frames_.front().t, frames_.back().t, params_.run.c_str(), params_.speed, params_.loop ? ", looping" : "");
}

void ReplayNode::tick(const ros::WallTimerEvent&)
{
  double t = frames_.front().t + params_.speed * (ros::WallTime::now() - started_).toSec();
  if (t > frames_.back().t && params_.loop)
  {
    started_ = ros::WallTime::now();
    t = frames_.front().t;
  }
  publish(std::min(t, frames_.back().t));
}

void ReplayNode::publish(double t)
{
  const ShapeFrame s = shapeAt(frames_, t);
  rosgraph_msgs::Clock clock;
  clock.clock.fromSec(std::max(t, 1e-9));  // the run's time (ros::Time zero means "unset")
  clock_pub_.publish(clock);

  std_msgs::Header header;
  header.stamp = clock.clock;
  header.frame_id = params_.world_frame;
  visualization_msgs::MarkerArray array;
  array.markers.push_back(
      tensionLine(header, s.joints, s.tension, s.slack, params_.cable_marker_width, params_.tension_color_max));

  // The vehicle: the last element, bail to tail point.
  const Eigen::Index n = s.joints.cols();
  if (n >= 2)
  {
    const Eigen::Vector3d bail = s.joints.col(n - 2), tail = s.joints.col(n - 1);
    visualization_msgs::Marker hull = baseMarker(header, "vehicle", 0, visualization_msgs::Marker::SPHERE);
    hull.pose.position = ros_conv::toPoint(0.5 * (bail + tail));
    hull.pose.orientation = ros_conv::toQuaternion(
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), (bail - tail).normalized()));
    hull.scale.x = std::max((bail - tail).norm(), 0.1);
    hull.scale.y = hull.scale.z = 0.25 * hull.scale.x;
    hull.color.r = hull.color.g = hull.color.b = 0.85;
    array.markers.push_back(hull);
    geometry_msgs::TransformStamped tf;
    tf.header = header;
    tf.child_frame_id = params_.vehicle_frame;
    tf.transform.translation.x = hull.pose.position.x;
    tf.transform.translation.y = hull.pose.position.y;
    tf.transform.translation.z = hull.pose.position.z;
    tf.transform.rotation = hull.pose.orientation;
    if (t != last_tf_t_)  // holding at the end: no repeated stamps for tf listeners
    {
      tf_broadcaster_.sendTransform(tf);
      if (!params_.view_frame.empty())
      {
        tf.child_frame_id = params_.view_frame;  // midway from the tow point, with the world's axes
        tf.transform.translation = ros_conv::toVector3(0.5 * (s.joints.col(0) + 0.5 * (bail + tail)));
        tf.transform.rotation = geometry_msgs::Quaternion();
        tf.transform.rotation.w = 1.0;
        tf_broadcaster_.sendTransform(tf);
      }
    }
    last_tf_t_ = t;
  }
  visualization_msgs::Marker label = baseMarker(header, "labels", 0, visualization_msgs::Marker::TEXT_VIEW_FACING);
  label.pose.position = ros_conv::toPoint(s.joints.col(0) + Eigen::Vector3d(0, 0, 15));
  label.scale.z = 8.0;
  label.color.r = label.color.g = label.color.b = 1.0;
  char text[96];
  std::snprintf(text, sizeof(text), "replay t = %.1f s, T ship %.0f N", t, s.tension.front());
  label.text = text;
  array.markers.push_back(label);
  marker_pub_.publish(array);
}

}  // namespace tow_sim
