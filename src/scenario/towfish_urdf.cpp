#include "tow_sim/scenario/towfish_urdf.h"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "tow_sim/config/node_params.h"
#include "tow_sim/config/param_yaml.h"
#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{

Eigen::Vector3d readVector(const YAML::Node& node, const std::string& name, double limit, const char* unit)
{
  if (!node || !node.IsSequence() || node.size() != 3)
    throw std::invalid_argument(name + ": must be a list of 3 numbers " + unit);
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i)
  {
    try
    {
      v[i] = node[i].as<double>();
    }
    catch (const YAML::Exception&)
    {
      throw std::invalid_argument(name + "[" + std::to_string(i) + "]: must be a number " + unit);
    }
    requireInRange(name + "[" + std::to_string(i) + "]", v[i], -limit, limit, unit);
  }
  return v;
}

SensorFrame readSensor(const YAML::Node& node, const std::string& name)
{
  if (!node.IsMap())
    throw std::invalid_argument(name + ": must be a mapping {name: NAME, xyz: [x, y, z], rpy: [r, p, y]}");
  for (const auto& entry : node)
  {
    const std::string key = entry.first.as<std::string>();
    if (key != "name" && key != "xyz" && key != "rpy")
      throw std::invalid_argument(name + "." + key + ": unknown key (known keys: name, rpy, xyz)");
  }
  SensorFrame s;
  s.name = node["name"] ? node["name"].as<std::string>() : "";
  const bool word = !s.name.empty() && s.name.find_first_not_of(
                                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                           "0123456789_") == std::string::npos;
  if (!word)
    throw std::invalid_argument(name + ".name = '" + s.name + "': must be letters, digits and '_', not empty");
  s.xyz = readVector(node["xyz"], name + ".xyz", 100.0, "[m]");
  s.rpy = node["rpy"] ? readVector(node["rpy"], name + ".rpy", 2.0 * kPi, "[rad]") : Eigen::Vector3d::Zero();
  return s;
}

void link(std::ostream& os, const std::string& name, const std::string& visuals = "")
{
  if (visuals.empty())
    os << "  <link name=\"" << name << "\"/>\n";
  else
    os << "  <link name=\"" << name << "\">\n" << visuals << "  </link>\n";
}

std::string vec(const Eigen::Vector3d& v)
{
  std::ostringstream os;
  os.precision(9);
  os << v.x() + 0.0 << ' ' << v.y() + 0.0 << ' ' << v.z() + 0.0;  // + 0.0: no "-0"
  return os.str();
}

std::string box(const Eigen::Vector3d& at, const Eigen::Vector3d& size, const char* material)
{
  return "    <visual>\n      <origin xyz=\"" + vec(at) + "\" rpy=\"0 0 0\"/>\n      <geometry><box size=\"" +
         vec(size) + "\"/></geometry>\n      <material name=\"" + material + "\"/>\n    </visual>\n";
}

void joint(std::ostream& os, const std::string& name, const char* type, const std::string& parent,
           const std::string& child, const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy,
           const std::string& extra = "")
{
  os << "  <joint name=\"" << name << "\" type=\"" << type << "\">\n    <parent link=\"" << parent
     << "\"/>\n    <child link=\"" << child << "\"/>\n    <origin xyz=\"" << vec(xyz) << "\" rpy=\"" << vec(rpy)
     << "\"/>\n"
     << extra << "  </joint>\n";
}

std::string finLimits(const FinPairParams& fin, const Eigen::Vector3d& axis)
{
  std::ostringstream os;
  os.precision(9);
  os << "    <axis xyz=\"" << vec(axis) << "\"/>\n    <limit lower=\"" << -fin.max_deflection << "\" upper=\""
     << fin.max_deflection << "\" effort=\"0\" velocity=\"" << fin.max_rate << "\"/>\n";
  return os.str();
}
}  // namespace

std::vector<SensorFrame> defaultSensorFrames(double hull_diameter)
{
  const double r = 0.5 * hull_diameter, down = kPi / 6.0;
  return { { "sidescan_port", Eigen::Vector3d(0.0, r, 0.0), Eigen::Vector3d(0.0, down, 0.5 * kPi) },
           { "sidescan_starboard", Eigen::Vector3d(0.0, -r, 0.0), Eigen::Vector3d(0.0, down, -0.5 * kPi) },
           { "altimeter", Eigen::Vector3d(0.0, 0.0, -r), Eigen::Vector3d(0.0, 0.5 * kPi, 0.0) } };
}

TowfishDescription readTowfishDescription(const YAML::Node& root)
{
  NodeParams node;
  detail::ParamReader reader(detail::Section(root, ""));
  reader.read(nodeParams(), node);
  validate(node, "");
  TowfishDescription d;
  d.vehicle_frame = node.vehicle_frame;
  d.hull_diameter = node.vehicle_diameter;
  const YAML::Node sensors = root && root.IsMap() ? root["sensor_frames"] : YAML::Node();
  if (!sensors || sensors.IsNull())
  {
    d.sensors = defaultSensorFrames(d.hull_diameter);
    return d;
  }
  if (!sensors.IsSequence())
    throw std::invalid_argument("sensor_frames: must be a list of {name, xyz, rpy}");
  std::set<std::string> names;
  for (size_t i = 0; i < sensors.size(); ++i)
  {
    const std::string name = "sensor_frames[" + std::to_string(i) + "]";
    d.sensors.push_back(readSensor(sensors[i], name));
    if (!names.insert(d.sensors.back().name).second)
      throw std::invalid_argument(name + ".name = '" + d.sensors.back().name + "': used twice");
  }
  return d;
}

std::string rudderJointName(const std::string& vehicle_frame)
{
  return vehicle_frame + "_rudder_joint";
}
std::string elevatorJointName(const std::string& vehicle_frame)
{
  return vehicle_frame + "_elevator_joint";
}
std::string differentialJointName(const std::string& vehicle_frame)
{
  return vehicle_frame + "_elevator_differential_joint";
}

std::string towfishUrdf(const VehicleParams& v, const TowfishDescription& d)
{
  // Body x of a point `from_bail` aft of the bail: the bail lies cg_from_bail ahead of the CG.
  auto x = [&](double from_bail) { return v.cg_from_bail - from_bail; };
  const std::string& f = d.vehicle_frame;
  const double length = v.nose_from_bail + v.tail_from_bail, r = 0.5 * d.hull_diameter;
  const double span = 0.8 * d.hull_diameter, chord = 0.12 * length;  // as tow_sim_node's markers
  std::ostringstream os;
  os.precision(9);
  os << "<?xml version=\"1.0\"?>\n<!-- Generated by tow_sim_urdf from the vehicle configuration. -->\n"
     << "<robot name=\"" << f << "\">\n"
     << "  <material name=\"hull\"><color rgba=\"0.85 0.85 0.85 1\"/></material>\n"
     << "  <material name=\"fin\"><color rgba=\"1 0.55 0 1\"/></material>\n";
  link(os, f);  // the CG, body axes FLU
  std::ostringstream hull_visual;
  hull_visual.precision(9);
  hull_visual << "    <visual>\n      <origin xyz=\"0 0 0\" rpy=\"0 " << 0.5 * kPi << " 0\"/>\n"
              << "      <geometry><cylinder radius=\"" << r << "\" length=\"" << length << "\"/></geometry>\n"
              << "      <material name=\"hull\"/>\n    </visual>\n";
  joint(os, f + "_hull_joint", "fixed", f, f + "_hull",
        Eigen::Vector3d(x(0.5 * (v.tail_from_bail - v.nose_from_bail)), 0, 0), Eigen::Vector3d::Zero());
  link(os, f + "_hull", hull_visual.str());
  // Positive rudder turns the leading edge to port: about +z; positive elevator lifts it: about -y.
  const double out = r + 0.5 * span;
  joint(os, rudderJointName(f), "revolute", f, f + "_rudder", Eigen::Vector3d(x(v.vertical_fin_from_bail), 0, 0),
        Eigen::Vector3d::Zero(), finLimits(v.rudder, Eigen::Vector3d::UnitZ()));
  link(os, f + "_rudder",
       box(Eigen::Vector3d(0, 0, out), Eigen::Vector3d(chord, 0.02, span), "fin") +
           box(Eigen::Vector3d(0, 0, -out), Eigen::Vector3d(chord, 0.02, span), "fin"));
  joint(os, elevatorJointName(f), "revolute", f, f + "_elevator", Eigen::Vector3d(x(v.horizontal_fin_from_bail), 0, 0),
        Eigen::Vector3d::Zero(), finLimits(v.elevator, -Eigen::Vector3d::UnitY()));
  link(os, f + "_elevator");
  // Each elevator fin turns from the pair by the differential (physics.md (P57a)): the starboard one by it, the
  // port one by its opposite (a mimic joint).
  joint(os, differentialJointName(f), "revolute", f + "_elevator", f + "_elevator_starboard", Eigen::Vector3d::Zero(),
        Eigen::Vector3d::Zero(), finLimits(v.elevator, -Eigen::Vector3d::UnitY()));
  link(os, f + "_elevator_starboard", box(Eigen::Vector3d(0, -out, 0), Eigen::Vector3d(chord, span, 0.02), "fin"));
  joint(os, f + "_elevator_port_joint", "revolute", f + "_elevator", f + "_elevator_port", Eigen::Vector3d::Zero(),
        Eigen::Vector3d::Zero(),
        finLimits(v.elevator, -Eigen::Vector3d::UnitY()) + "    <mimic joint=\"" + differentialJointName(f) +
            "\" multiplier=\"-1\"/>\n");
  link(os, f + "_elevator_port", box(Eigen::Vector3d(0, out, 0), Eigen::Vector3d(chord, span, 0.02), "fin"));
  joint(os, f + "_bail_joint", "fixed", f, f + "_bail", Eigen::Vector3d(x(0.0), 0, 0), Eigen::Vector3d::Zero());
  link(os, f + "_bail");
  for (const SensorFrame& s : d.sensors)
  {
    joint(os, f + "_" + s.name + "_joint", "fixed", f, f + "_" + s.name, s.xyz, s.rpy);
    link(os, f + "_" + s.name);
  }
  os << "</robot>\n";
  return os.str();
}

}  // namespace tow_sim
