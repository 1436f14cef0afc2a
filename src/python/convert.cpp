#include "convert.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tow_sim/scenario/batch_run.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace tow_sim::python
{
namespace
{
std::string numberText(double x)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);  // every double read back exactly
  return text;
}

bool isSequence(const py::handle& value)
{
  return py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) || py::isinstance<py::array>(value);
}
}  // namespace

YAML::Node toYamlNode(const py::handle& value, const std::string& path)
{
  if (value.is_none())
    return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::dict>(value))
  {
    YAML::Node node(YAML::NodeType::Map);
    for (const auto& item : value.cast<py::dict>())
    {
      if (!py::isinstance<py::str>(item.first))
        throw std::invalid_argument((path.empty() ? "a" : path + ": a") + std::string(" key is not a str: ") +
                                    py::repr(item.first).cast<std::string>());
      const std::string key = item.first.cast<std::string>();
      node[key] = toYamlNode(item.second, path.empty() ? key : path + "." + key);
    }
    return node;
  }
  if (py::isinstance<py::str>(value))
    return YAML::Node(value.cast<std::string>());
  if (py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_")))
    return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (isSequence(value))
  {
    YAML::Node node(YAML::NodeType::Sequence);
    size_t i = 0;
    for (const auto& item : value)
      node.push_back(toYamlNode(item, path + "[" + std::to_string(i++) + "]"));
    return node;
  }
  if (py::hasattr(value, "__index__"))  // int and NumPy's integers
    return YAML::Node(py::int_(py::reinterpret_borrow<py::object>(value)).cast<long long>());
  if (py::hasattr(value, "__float__"))  // float and NumPy's floats
    return YAML::Node(numberText(py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>()));
  throw std::invalid_argument(path + " = " + py::repr(value).cast<std::string>() +
                              ": not a value a configuration holds (dict, list, str, bool, int, float or None)");
}

Eigen::Vector3d vector3(const py::handle& value, const std::string& name)
{
  std::vector<double> v;
  try
  {
    v = value.cast<std::vector<double>>();
  }
  catch (const py::cast_error&)
  {
  }
  if (v.size() != 3)
    throw std::invalid_argument(name + " = " + py::repr(value).cast<std::string>() +
                                ": must be three numbers [x, y, z]");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

namespace
{
std::vector<std::string> columnNames(const std::string& header)
{
  std::vector<std::string> names;
  std::istringstream columns(header);
  for (std::string name; std::getline(columns, name, ',');)
    names.push_back(name);
  return names;
}
}  // namespace

double number(const py::handle& value, const std::string& name)
{
  double v = std::numeric_limits<double>::quiet_NaN();
  if (!py::isinstance<py::str>(value) && py::hasattr(value, "__float__"))
    v = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  if (!std::isfinite(v))
    throw std::invalid_argument(name + " = " + py::repr(value).cast<std::string>() + ": must be a finite number");
  return v;
}

std::vector<CommandEvent> commandList(const py::handle& commands)
{
  std::vector<CommandEvent> out;
  if (commands.is_none())
    return out;
  for (const auto& item : commands)
  {
    const std::string name = "commands[" + std::to_string(out.size()) + "]";
    if (!py::isinstance<py::dict>(item))
      throw std::invalid_argument(name + ": a dict {t, rudder, elevator, thrust, payout_rate, differential}");
    const py::dict d = item.cast<py::dict>();
    CommandEvent e;
    for (const auto& kv : d)
    {
      const std::string key = py::str(kv.first).cast<std::string>();
      const double v = number(kv.second, name + "." + key);
      double* field = key == "t"              ? &e.t
                      : key == "rudder"       ? &e.rudder
                      : key == "elevator"     ? &e.elevator
                      : key == "thrust"       ? &e.thrust
                      : key == "payout_rate"  ? &e.payout_rate
                      : key == "differential" ? &e.differential
                                              : nullptr;
      if (!field)
        throw std::invalid_argument(name + "." + key +
                                    ": unknown key (t, rudder, elevator, thrust, payout_rate, differential)");
      *field = v;
    }
    out.push_back(e);
  }
  return out;
}

py::dict seriesDict(const std::string& header, const std::vector<std::vector<double>>& rows)
{
  const std::vector<std::string> names = columnNames(header);
  py::dict out;
  for (size_t c = 0; c < names.size(); ++c)
  {
    py::array_t<double> column(static_cast<py::ssize_t>(rows.size()));
    auto data = column.mutable_unchecked<1>();
    for (size_t r = 0; r < rows.size(); ++r)
      data(static_cast<py::ssize_t>(r)) = rows[r].at(c);
    out[py::str(names[c])] = column;
  }
  return out;
}

namespace
{
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

py::dict rowDict(const TowSnapshot& s)
{
  const std::vector<std::string> names = columnNames(timeseriesHeader(s.bodies.size()));
  const std::vector<double> values = timeseriesValues(s);
  py::dict row;
  for (size_t c = 0; c < names.size(); ++c)
    row[py::str(names[c])] = values.at(c);
  return row;
}

py::list bodyList(const TowSnapshot& s)
{
  py::list bodies;
  for (const BodyOutput& b : s.bodies)
  {
    py::dict d;
    d["joint"] = b.joint;  // its row of joints; -1: a parting took it off the vehicle side
    d["position"] = Eigen::Vector3d(b.p_W);
    d["depth"] = b.depth;
    d["tension_above"] = Eigen::Vector3d(b.tension_above);
    d["tension_below"] = Eigen::Vector3d(b.tension_below);
    bodies.append(d);
  }
  return bodies;
}

void bindSnapshotCable(py::class_<TowSnapshot>& c)
{
  c.def_property_readonly(
       "joints", [](const TowSnapshot& s) { return RowMatrix(s.joints.transpose()); },
       "[m] (n, 3) joints x_1 .. x_{nu+2}, world ENU, the tow point first")
      .def_property_readonly(
          "tensions", [](const TowSnapshot& s) { return RowMatrix(s.tensions.transpose()); },
          "[N] (nu + 1, 3) T_1 .. T_{nu+1}: the pull toward the ship on each element's forward joint")
      .def_property_readonly(
          "tension_magnitudes",
          [](const TowSnapshot& s) { return Eigen::VectorXd(s.tensions.colwise().norm().transpose()); },
          "[N] |T_1| .. |T_{nu+1}|")
      .def_readonly("segments", &TowSnapshot::segments, "nu, the cable's segments (the winch changes it)")
      .def_readonly("slack", &TowSnapshot::slack)
      .def_readonly("segment_section", &TowSnapshot::segment_section)
      .def_readonly("cable_length", &TowSnapshot::cable_length, "[m]")
      .def_readonly("payout_rate", &TowSnapshot::payout_rate, "[m/s]")
      .def_readonly("tension_ship", &TowSnapshot::tension_ship, "[N] |T_1|")
      .def_readonly("tension_vehicle", &TowSnapshot::tension_vehicle, "[N] |T_{nu+1}|")
      .def_readonly("max_length_error", &TowSnapshot::max_length_error)
      .def_readonly("parted", &TowSnapshot::parted)
      .def_property_readonly("bodies", &bodyList, "cable.bodies: a dict each (joint, position, depth, tensions)");
}
}  // namespace

void bindSnapshot(py::module_& m)
{
  py::class_<TowSnapshot> c(m, "Snapshot", "Every output of a run at one instant: SI units, world ENU frame.");
  c.def_readonly("t", &TowSnapshot::t, "[s]")
      .def_property_readonly(
          "vehicle_position", [](const TowSnapshot& s) { return Eigen::Vector3d(s.vehicle.p_cg_W); },
          "[m] the vehicle's CG, world")
      .def_property_readonly(
          "vehicle_velocity", [](const TowSnapshot& s) { return Eigen::Vector3d(s.vehicle.v_cg_W); },
          "[m/s] the CG's velocity over ground, world")
      .def_property_readonly(
          "vehicle_attitude", [](const TowSnapshot& s) { return Eigen::Vector4d(s.attitude.coeffs()); },
          "the vehicle's attitude as published: quaternion (x, y, z, w), body FLU to world")
      .def_readonly("pitch", &TowSnapshot::pitch, "[rad] positive nose down")
      .def_readonly("yaw", &TowSnapshot::yaw, "[rad] from +x, counter-clockwise")
      .def_readonly("depth", &TowSnapshot::depth, "[m] of the CG")
      .def_readonly("layback", &TowSnapshot::layback, "[m] of the CG behind the tow point, along the heading")
      .def_property_readonly(
          "diversion", [](const TowSnapshot& s) { return s.diversion.offset; },
          "[m] of the CG from the ship's track, positive to port")
      .def_property_readonly(
          "diversion_rate", [](const TowSnapshot& s) { return s.diversion.rate; }, "[m/s]")
      .def_property_readonly(
          "fins",
          [](const TowSnapshot& s) {
            return py::dict("rudder"_a = s.vehicle.rudder, "elevator"_a = s.vehicle.elevator,
                            "thrust"_a = s.vehicle.thrust);
          },
          "the actual rudder and elevator [rad] and thrust [N]")
      .def_property_readonly(
          "ship",
          [](const TowSnapshot& s)
          {
            return py::dict("x"_a = s.ship.x, "y"_a = s.ship.y, "z"_a = s.ship.z, "heading"_a = s.ship.heading,
                            "speed"_a = s.ship.speed);
          },
          "the ship's reference point [m], heading [rad] and speed [m/s]")
      .def_property_readonly("row", &rowDict, "timeseries.csv's row: a dict of the columns (NaN for a blank cell)");
  bindSnapshotCable(c);
}

}  // namespace tow_sim::python
