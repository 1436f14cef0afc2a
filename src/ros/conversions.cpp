#include "tow_sim/ros/conversions.h"

#include <algorithm>
#include <sstream>

#include "tow_sim/scenario/towfish_urdf.h"

namespace tow_sim
{
namespace ros_conv
{
YAML::Node toYaml(XmlRpc::XmlRpcValue& value)
{
  switch (value.getType())
  {
    case XmlRpc::XmlRpcValue::TypeStruct:
    {
      YAML::Node node(YAML::NodeType::Map);
      for (auto& entry : value)
        node[entry.first] = toYaml(entry.second);
      return node;
    }
    case XmlRpc::XmlRpcValue::TypeArray:
    {
      YAML::Node node(YAML::NodeType::Sequence);
      for (int i = 0; i < value.size(); ++i)
        node.push_back(toYaml(value[i]));
      return node;
    }
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return YAML::Node(static_cast<bool>(value));
    case XmlRpc::XmlRpcValue::TypeInt:
      return YAML::Node(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeDouble:
    {
      std::ostringstream os;
      os.precision(17);
      os << static_cast<double>(value);
      return YAML::Node(os.str());
    }
    case XmlRpc::XmlRpcValue::TypeString:
      return YAML::Node(static_cast<std::string>(value));
    default:
      return YAML::Node();
  }
}

YAML::Node privateParameters(const ros::NodeHandle& pnh)
{
  XmlRpc::XmlRpcValue tree;
  return pnh.getParam(pnh.getNamespace(), tree) ? toYaml(tree) : YAML::Node();
}

std::invalid_argument withSlashes(const std::invalid_argument& e)
{
  std::string message = e.what();
  const size_t end = message.find_first_of(" :");
  for (size_t i = 0; i < end && i < message.size(); ++i)
    if (message[i] == '.')
      message[i] = '/';
  return std::invalid_argument(message);
}

OdometryInput toOdometryInput(const nav_msgs::Odometry& msg)
{
  const auto& pose = msg.pose.pose;
  OdometryInput in;
  in.frame_id = msg.header.frame_id;
  in.p_W = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  in.q_wxyz = Eigen::Vector4d(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z);
  in.v_S = toEigen(msg.twist.twist.linear);
  in.w_S = toEigen(msg.twist.twist.angular);
  return in;
}

Eigen::Vector3d toEigen(const geometry_msgs::Vector3& v)
{
  return Eigen::Vector3d(v.x, v.y, v.z);
}

geometry_msgs::Point toPoint(const Eigen::Vector3d& v)
{
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

geometry_msgs::Vector3 toVector3(const Eigen::Vector3d& v)
{
  geometry_msgs::Vector3 p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

geometry_msgs::Quaternion toQuaternion(const Eigen::Quaterniond& q)
{
  geometry_msgs::Quaternion m;
  m.w = q.w();
  m.x = q.x();
  m.y = q.y();
  m.z = q.z();
  return m;
}

std_msgs::ColorRGBA tensionColor(double tension, double full_scale, bool slack)
{
  std_msgs::ColorRGBA c;
  c.a = 1.0;
  if (slack)
  {
    c.r = 1.0;
    c.b = 1.0;
    return c;
  }
  const double x = std::clamp(tension / full_scale, 0.0, 1.0);
  if (x < 0.5)
  {
    c.g = 2.0 * x;
    c.b = 1.0 - 2.0 * x;
  }
  else
  {
    c.r = 2.0 * x - 1.0;
    c.g = 2.0 - 2.0 * x;
  }
  return c;
}

tow_sim::CableState toCableState(const TowSnapshot& s, const std_msgs::Header& header)
{
  tow_sim::CableState state;
  state.header = header;
  for (Eigen::Index j = 0; j < s.joints.cols(); ++j)
    state.joints.push_back(toPoint(s.joints.col(j)));
  for (Eigen::Index j = 0; j < s.tensions.cols(); ++j)
  {
    state.tension.push_back(s.tensions.col(j).norm());
    state.tension_vector.push_back(toVector3(s.tensions.col(j)));
  }
  state.slack.assign(s.slack.begin(), s.slack.end());
  state.tension_ship = s.tension_ship;
  state.tension_vehicle = s.tension_vehicle;
  state.vehicle_depth = s.depth;
  state.layback = s.layback;
  state.diversion = s.diversion.offset;
  state.diversion_rate = s.diversion.rate;
  state.cable_length = s.cable_length;
  state.payout_rate = s.payout_rate;
  state.snap_count = static_cast<uint32_t>(std::min<long>(s.snap_count, 4294967295L));
  state.max_strain = s.max_strain;
  state.seabed_present = s.seabed_present;
  state.seabed_contact.assign(s.joint_contact.begin(), s.joint_contact.end());
  if (s.seabed_present)
    state.vehicle_altitude = s.vehicle_altitude;
  state.vehicle_on_seabed = s.vehicle_on_seabed;
  state.max_length_error = s.max_length_error;
  for (int section : s.segment_section)
    state.section.push_back(static_cast<uint16_t>(section));
  for (const BodyOutput& b : s.bodies)
  {
    state.body_joint.push_back(b.joint);
    state.body_tension_above.push_back(b.joint >= 0 ? b.tension_above.norm() : 0.0);
  }
  return state;
}

nav_msgs::Odometry toVehicleOdometry(const TowSnapshot& s, const std_msgs::Header& header,
                                     const std::string& child_frame)
{
  const Eigen::Matrix3d R = s.attitude.toRotationMatrix();
  nav_msgs::Odometry odom;
  odom.header = header;
  odom.child_frame_id = child_frame;
  odom.pose.pose.position = toPoint(s.vehicle.p_cg_W);
  odom.pose.pose.orientation = toQuaternion(s.attitude);
  odom.twist.twist.linear = toVector3(R.transpose() * s.vehicle.v_cg_W);
  odom.twist.twist.angular = toVector3(R.transpose() * s.vehicle.omega_W);
  return odom;
}

geometry_msgs::TransformStamped toVehicleTransform(const TowSnapshot& s, const std_msgs::Header& header,
                                                   const std::string& child_frame)
{
  geometry_msgs::TransformStamped tf;
  tf.header = header;
  tf.child_frame_id = child_frame;
  tf.transform.translation = toVector3(s.vehicle.p_cg_W);
  tf.transform.rotation = toQuaternion(s.attitude);
  return tf;
}

geometry_msgs::TransformStamped toViewTransform(const TowSnapshot& s, const std_msgs::Header& header,
                                                const std::string& child_frame)
{
  geometry_msgs::TransformStamped tf;
  tf.header = header;
  tf.child_frame_id = child_frame;
  tf.transform.translation = toVector3(0.5 * (s.tow_point.p_W + s.vehicle.p_cg_W));
  tf.transform.rotation.w = 1.0;  // world-aligned: a view that follows it does not swing with the ship
  return tf;
}

sensor_msgs::JointState toJointState(const TowSnapshot& s, const std_msgs::Header& header,
                                     const std::string& vehicle_frame)
{
  sensor_msgs::JointState joints;
  joints.header.stamp = header.stamp;  // no frame: joint states have none
  joints.name = { rudderJointName(vehicle_frame), elevatorJointName(vehicle_frame),
                  differentialJointName(vehicle_frame) };
  joints.position = { s.vehicle.rudder, s.vehicle.elevator, s.vehicle.differential };
  return joints;
}

tow_sim::FinLoads toFinLoads(const TowSnapshot& s, const std_msgs::Header& header, const std::string& vehicle_frame)
{
  const VehicleOutputs& o = s.vehicle;
  tow_sim::FinLoads loads;
  loads.header = header;
  loads.header.frame_id = vehicle_frame;
  loads.rudder_angle = o.rudder;
  loads.elevator_angle = o.elevator;
  loads.elevator_differential = o.differential;
  loads.thrust = o.thrust;
  loads.rudder_angle_of_attack = o.rudder_loads.angle_of_attack;
  loads.elevator_angle_of_attack = o.elevator_loads.angle_of_attack;
  loads.rudder_lift = toVector3(o.rudder_loads.lift_B);
  loads.rudder_drag = toVector3(o.rudder_loads.drag_B);
  loads.rudder_moment = toVector3(o.rudder_loads.moment_cg_B);
  loads.rudder_hinge_moment = o.rudder_loads.hinge_moment;
  loads.elevator_lift = toVector3(o.elevator_loads.lift_B);
  loads.elevator_drag = toVector3(o.elevator_loads.drag_B);
  loads.elevator_moment = toVector3(o.elevator_loads.moment_cg_B);
  loads.elevator_hinge_moment = o.elevator_loads.hinge_moment;
  return loads;
}

geometry_msgs::WrenchStamped toShipTowForce(const TowSnapshot& s, const std_msgs::Header& header)
{
  geometry_msgs::WrenchStamped w;
  w.header = header;
  w.wrench.force = toVector3(-shipPull(s));
  w.wrench.torque = toVector3(Eigen::Vector3d::Zero());
  return w;
}

geometry_msgs::WrenchStamped toVehicleTowForce(const TowSnapshot& s, const std_msgs::Header& header,
                                               const std::string& vehicle_frame)
{
  const Eigen::Matrix3d R = s.attitude.toRotationMatrix();  // vehicle frame to world
  const Eigen::Vector3d force_W = s.tensions.col(s.segments);
  const Eigen::Vector3d arm_W = s.joints.col(s.segments) - s.vehicle.p_cg_W;  // CG to the bail
  geometry_msgs::WrenchStamped w;
  w.header = header;
  w.header.frame_id = vehicle_frame;
  w.wrench.force = toVector3(R.transpose() * force_W);
  w.wrench.torque = toVector3(R.transpose() * arm_W.cross(force_W));
  return w;
}

}  // namespace ros_conv
}  // namespace tow_sim
