#include "tow_sim/ros/conversions.h"

#include <algorithm>
#include <sstream>

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

}  // namespace ros_conv
}  // namespace tow_sim
