// Conversions at the ROS edge: parameter trees to YAML (so the core's loader reads them), Eigen to
// messages, and the tension colour scale.
#pragma once

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Vector3.h>
#include <std_msgs/ColorRGBA.h>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>
#include <Eigen/Geometry>

namespace tow_sim
{
namespace ros_conv
{
// A parameter-server subtree as YAML (structs -> maps, arrays -> sequences, scalars -> scalars).
YAML::Node toYaml(XmlRpc::XmlRpcValue& value);

geometry_msgs::Point toPoint(const Eigen::Vector3d& v);
geometry_msgs::Vector3 toVector3(const Eigen::Vector3d& v);
geometry_msgs::Quaternion toQuaternion(const Eigen::Quaterniond& q);

// Tension colour scale of the cable marker: blue at 0 N, green at half of full_scale, red at and above
// full_scale; magenta for a joint in compression (slack).
std_msgs::ColorRGBA tensionColor(double tension, double full_scale, bool slack);

}  // namespace ros_conv
}  // namespace tow_sim
