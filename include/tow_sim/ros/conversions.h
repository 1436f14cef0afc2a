// Conversions at the ROS edge: parameter trees to YAML (so the configuration loader reads them), Eigen
// to messages, a tow run's snapshot to the node's messages, and the tension colour scale. Stateless; all
// but the parameter-server readers (which need a NodeHandle) are tested without roscore.
#pragma once

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Vector3.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/ColorRGBA.h>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <stdexcept>

#include "tow_sim/CableState.h"
#include "tow_sim/FinLoads.h"
#include "tow_sim/config/config.h"
#include "tow_sim/config/param_yaml.h"
#include "tow_sim/core/run/odometry_check.h"
#include "tow_sim/core/run/tow_run.h"

namespace tow_sim
{
namespace ros_conv
{
// A parameter-server subtree as YAML (structs -> maps, arrays -> sequences, scalars -> scalars).
YAML::Node toYaml(XmlRpc::XmlRpcValue& value);
// The node's private namespace as YAML (null when it holds nothing).
YAML::Node privateParameters(const ros::NodeHandle& pnh);
// The loaders name keys "section.key"; on the parameter server they are "section/key".
std::invalid_argument withSlashes(const std::invalid_argument& e);

// A table's keys from the node's private namespace (unknown keys there are left alone: they may belong to
// other readers), then validate(params, "<namespace>/"); errors name the full parameter path.
template <class S>
S readPrivateParams(const ros::NodeHandle& pnh, const ParamTable<S>& table,
                    void (*validate)(const S&, const std::string&))
{
  S params;
  try
  {
    detail::ParamReader reader(detail::Section(privateParameters(pnh), pnh.getNamespace()));
    reader.read(table, params);
    validate(params, pnh.getNamespace() + "/");
  }
  catch (const std::invalid_argument& e)
  {
    throw withSlashes(e);
  }
  return params;
}

// Ship odometry as the live run's input (its time, t, is the live run's to set from the stamp).
OdometryInput toOdometryInput(const nav_msgs::Odometry& msg);
Eigen::Vector3d toEigen(const geometry_msgs::Vector3& v);

// As readPrivateParams, for a node whose private namespace holds only this table's keys: any other is a
// typo, refused naming it and the nearest known key.
template <class S>
S readOwnPrivateParams(const ros::NodeHandle& pnh, const ParamTable<S>& table,
                       void (*validate)(const S&, const std::string&))
{
  S params = readPrivateParams(pnh, table, validate);
  try
  {
    requireKnownKeys(privateParameters(pnh), pnh.getNamespace() + "/", topLevelKeys(table));
  }
  catch (const std::invalid_argument& e)
  {
    throw withSlashes(e);
  }
  return params;
}

// For a node that tow_sim.launch also loads the towing configuration into (ship_motion_node for the waves,
// gnss_ship_node for the world frame): a private key neither a configuration file's nor this table's is
// a typo, refused naming it and the nearest known key.
template <class S>
void requireConfigurationOrOwnKeys(const ros::NodeHandle& pnh, const ParamTable<S>& table)
{
  std::vector<std::string> known = configurationFileKeys();
  for (const std::string& key : topLevelKeys(table))
    known.push_back(key);
  try
  {
    requireKnownKeys(privateParameters(pnh), pnh.getNamespace() + "/", known);
  }
  catch (const std::invalid_argument& e)
  {
    throw withSlashes(e);
  }
}

geometry_msgs::Point toPoint(const Eigen::Vector3d& v);
geometry_msgs::Vector3 toVector3(const Eigen::Vector3d& v);
geometry_msgs::Quaternion toQuaternion(const Eigen::Quaterniond& q);

// Tension colour scale of the cable marker: blue at 0 N, green at half of full_scale, red at and above
// full_scale; magenta for a joint in compression (slack).
std_msgs::ColorRGBA tensionColor(double tension, double full_scale, bool slack);

// A snapshot as cable/state, vehicle/odom (CG pose in header.frame_id, twist in the vehicle frame
// child_frame: the published attitude), the tf to the vehicle, and vehicle/fin_loads (body axes).
tow_sim::CableState toCableState(const TowSnapshot& s, const std_msgs::Header& header);
nav_msgs::Odometry toVehicleOdometry(const TowSnapshot& s, const std_msgs::Header& header,
                                     const std::string& child_frame);
geometry_msgs::TransformStamped toVehicleTransform(const TowSnapshot& s, const std_msgs::Header& header,
                                                   const std::string& child_frame);
// The tf to the frame midway between the tow point and the vehicle's CG, with the world's axes (rviz's view
// of the whole tow follows it).
geometry_msgs::TransformStamped toViewTransform(const TowSnapshot& s, const std_msgs::Header& header,
                                                const std::string& child_frame);
tow_sim::FinLoads toFinLoads(const TowSnapshot& s, const std_msgs::Header& header, const std::string& vehicle_frame);
// The cable's force on the ship, -T_1, applied at the tow point: in the world frame of `header`, torque
// zero (the moment about the tow point; a ship simulator adds its own lever arm).
geometry_msgs::WrenchStamped toShipTowForce(const TowSnapshot& s, const std_msgs::Header& header);
// The cable's pull on the vehicle, T_{nu+1} at the bail, in the vehicle frame (the CG, body axes as
// published on tf): the force and its moment about the CG.
// The fins' actual angles as joint states of the URDF towfish (tow_sim_urdf): rudder and elevator joints.
sensor_msgs::JointState toJointState(const TowSnapshot& s, const std_msgs::Header& header,
                                     const std::string& vehicle_frame);
geometry_msgs::WrenchStamped toVehicleTowForce(const TowSnapshot& s, const std_msgs::Header& header,
                                               const std::string& vehicle_frame);

}  // namespace ros_conv
}  // namespace tow_sim
