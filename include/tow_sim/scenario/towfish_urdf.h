// The towed vehicle as a URDF (robot_description) for robot_state_publisher and rviz's RobotModel: the
// vehicle frame at the CG (body axes FLU, the frame tow_sim_node publishes on tf), the hull, the rudder and
// elevator pairs as revolute joints at their documented positions (their angles come from tow_sim_node's
// joint_states), the bail, and sensor frames for users' own sensor models. ROS-free: tow_sim_urdf prints it.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
// A sensor's frame on the vehicle: a fixed joint from the vehicle frame.
struct SensorFrame
{
  std::string name;                               // the frame is <vehicle_frame>_<name>
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // [m] from the CG, body axes FLU
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();  // [rad] fixed-axis roll, pitch, yaw (URDF)
};

struct TowfishDescription
{
  std::string vehicle_frame = "tow_vehicle";  // the node's ~vehicle_frame
  double hull_diameter = 0.3;                 // [m] the node's ~vehicle_diameter (drawn)
  std::vector<SensorFrame> sensors;           // defaultSensorFrames unless the configuration gives them
};

// A side-scan transducer on each side of the hull at the CG's station (x axis looking out and 30 degrees
// down) and an altimeter under the CG (x axis looking down).
std::vector<SensorFrame> defaultSensorFrames(double hull_diameter);

// From a configuration in the node's YAML format: the node's `vehicle_frame` and `vehicle_diameter`, and
// `sensor_frames: [{name: NAME, xyz: [x, y, z], rpy: [r, p, y]}, ...]` (names: letters, digits, '_';
// distinct; |xyz| <= 100 m; |rpy| <= 2 pi). Throws std::invalid_argument naming the key.
TowfishDescription readTowfishDescription(const YAML::Node& root);

// The joints tow_sim_node's joint_states names (positions: the actual fin angles [rad], the simulation's
// senses: a positive rudder turns the leading edge to port, a positive elevator lifts it; the elevator's
// differential lifts the starboard fin's leading edge by it and, its mimic, the port fin's by its opposite).
std::string rudderJointName(const std::string& vehicle_frame);
std::string elevatorJointName(const std::string& vehicle_frame);
std::string differentialJointName(const std::string& vehicle_frame);

// The URDF document.
std::string towfishUrdf(const VehicleParams& vehicle, const TowfishDescription& description);

}  // namespace tow_sim
