#include "tow_sim/scenario/param_docs.h"

#include "tow_sim/core/survey/survey_sensors.h"
#include "tow_sim/core/survey/tow_nav.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

#include "tow_sim/config/config.h"
#include "tow_sim/config/node_params.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/seabed.h"
#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/survey/survey_sensors.h"
#include "tow_sim/core/survey/tow_nav.h"
#include "tow_sim/core/vehicle/vehicle.h"
#include "tow_sim/scenario/scenario_tables.h"

namespace tow_sim
{
namespace
{

// Numbers as the documentation writes them: 1e5 for large powers of ten, π/2, plain otherwise.
std::string number(double x, bool markdown)
{
  const std::string minus = markdown ? "−" : "-";
  if (x == 0.0)
    return "0";
  if (std::abs(std::abs(x) - kHalfPi) < 1e-12)
    return (x < 0 ? minus : "") + std::string(markdown ? "π/2" : "pi/2");
  const double exponent = std::log10(std::abs(x));
  std::ostringstream os;
  if (std::abs(x) >= 1e4 && std::abs(exponent - std::round(exponent)) < 1e-12)
    os << (x < 0 ? minus : "") << "1e" << static_cast<int>(std::round(exponent));
  else
  {
    os.precision(10);
    os << std::abs(x);
    std::string s = os.str();
    const size_t e = s.find("e-0");
    if (e != std::string::npos)
      s.erase(e + 2, 1);  // 1e-07 -> 1e-7
    return (x < 0 ? minus : "") + s;
  }
  return os.str();
}

std::string unitText(const std::string& unit, bool markdown)
{
  if (unit.empty() || unit == "-")
    return markdown ? "–" : "-";
  if (!markdown)
    return unit;
  std::string u = unit;
  for (const auto& [from, to] : std::map<std::string, std::string>{ { "^2", "²" }, { "^3", "³" } })
    for (size_t i = u.find(from); i != std::string::npos; i = u.find(from))
      u.replace(i, from.size(), to);
  return u;
}

template <class S>
std::string rangeText(const ParamSpec<S>& p, bool markdown)
{
  auto interval = [&]
  { return (p.lo_open ? "(" : "[") + number(p.lo, markdown) + ", " + number(p.hi, markdown) + "]"; };
  switch (p.kind)
  {
    case ParamKind::kNumber:
    case ParamKind::kInteger:
      return p.bounds ? p.range_text : interval();
    case ParamKind::kVector3:
      return "each " + interval();
    case ParamKind::kBool:
      return "bool";
    case ParamKind::kChoice:
    {
      std::string out;
      for (size_t i = 0; i < p.choices.size(); ++i)
        out += (i ? ", " : "") + (markdown ? "`" + p.choices[i] + "`" : p.choices[i]);
      return out;
    }
    case ParamKind::kText:
    case ParamKind::kCustom:
      return p.range_text;
  }
  return "";
}

template <class S>
std::string defaultText(const ParamSpec<S>& p, const S& d, bool markdown)
{
  const std::string quote = markdown ? "`" : "";
  if (!p.default_text.empty() && (p.kind == ParamKind::kCustom || !p.get_number || !p.get_number(d)))
    return p.default_text;
  switch (p.kind)
  {
    case ParamKind::kNumber:
      return number(*p.get_number(d), markdown);
    case ParamKind::kInteger:
      return std::to_string(static_cast<int>(*p.get_number(d)));
    case ParamKind::kBool:
      return p.get_bool(d) ? "true" : "false";
    case ParamKind::kChoice:
      return quote + p.get_text(d) + quote;
    case ParamKind::kText:
      return p.get_text(d).empty() ? "\"\"" : quote + p.get_text(d) + quote;
    case ParamKind::kVector3:
    {
      const Eigen::Vector3d v = p.get_vector(d);
      return "[" + number(v.x(), markdown) + ", " + number(v.y(), markdown) + ", " + number(v.z(), markdown) + "]";
    }
    case ParamKind::kCustom:
      return p.default_text;
  }
  return "";
}

std::string escaped(std::string text)
{
  for (size_t i = text.find('|'); i != std::string::npos; i = text.find('|', i + 2))
    text.replace(i, 1, "\\|");
  return text;
}

template <class S>
std::string markdown(const ParamTable<S>& table, const S& defaults)
{
  std::ostringstream os;
  os << "| key | unit | default | range | meaning |\n|---|---|---|---|---|\n";
  for (const ParamSpec<S>& p : table.specs())
    os << "| `" << p.key << "` | " << escaped(unitText(p.unit, true)) << " | "
       << escaped(defaultText(p, defaults, true)) << " | " << escaped(rangeText(p, true)) << " | " << escaped(p.meaning)
       << " |\n";
  return os.str();
}

// config/tow_sim.yaml: a value as YAML reads it back exactly.
std::string yamlValue(double x)
{
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

template <class S>
std::string yamlValue(const ParamSpec<S>& p, const S& d)
{
  switch (p.kind)
  {
    case ParamKind::kNumber:
      return yamlValue(*p.get_number(d));
    case ParamKind::kInteger:
      return std::to_string(static_cast<int>(*p.get_number(d)));
    case ParamKind::kBool:
      return p.get_bool(d) ? "true" : "false";
    case ParamKind::kChoice:
    case ParamKind::kText:
      return p.get_text(d).empty() ? "\"\"" : p.get_text(d);
    case ParamKind::kVector3:
    {
      const Eigen::Vector3d v = p.get_vector(d);
      return "[" + yamlValue(v.x()) + ", " + yamlValue(v.y()) + ", " + yamlValue(v.z()) + "]";
    }
    case ParamKind::kCustom:
      break;
  }
  return "";
}

// A YAML tree with its numbers written to 10 significant digits (the writer keeps every digit of a double).
YAML::Node rounded(const YAML::Node& node)
{
  if (node.IsSequence() || node.IsMap())
  {
    YAML::Node out(node.Type());
    for (auto it = node.begin(); it != node.end(); ++it)
    {
      if (node.IsMap())
        out[it->first] = rounded(it->second);
      else
        out.push_back(rounded(*it));
    }
    return out;
  }
  double value = 0.0;
  if (node.IsScalar() && YAML::convert<double>::decode(node, value))
    return YAML::Node(yamlValue(value));
  return node;
}

// One section's keys: nested keys under their parents, a comment with unit, range and meaning on each line;
// custom keys with the value the configuration writer gives them (or, where it gives none, as a comment).
template <class S>
void writeSection(std::ostringstream& os, const ParamTable<S>& table, const S& defaults, const YAML::Node& written)
{
  std::vector<std::string> open;  // the nested mappings open now
  for (const ParamSpec<S>& p : table.specs())
  {
    std::vector<std::string> parts;
    std::stringstream ss(p.key);
    for (std::string part; std::getline(ss, part, '.');)
      parts.push_back(part);
    const std::vector<std::string> parents(parts.begin(), parts.end() - 1);
    size_t common = 0;
    while (common < open.size() && common < parents.size() && open[common] == parents[common])
      ++common;
    open.resize(common);
    for (size_t i = common; i < parents.size(); ++i)
    {
      os << std::string(2 * (i + 1), ' ') << parents[i] << ":\n";
      open.push_back(parents[i]);
    }
    YAML::Node node = YAML::Clone(written);
    for (const std::string& part : parts)
      node.reset(node && node.IsMap() ? node[part] : YAML::Node());
    std::string line = std::string(2 * parts.size(), ' ');
    if (p.kind == ParamKind::kCustom && (!node || node.IsNull()))
      line += "# " + parts.back() + ": " + p.default_text;
    else if (p.kind == ParamKind::kCustom)
    {
      YAML::Emitter e;
      e.SetDoublePrecision(10);
      e << YAML::Flow << rounded(node);
      line += parts.back() + ": " + e.c_str();
    }
    else if (p.optional && !p.get_number(defaults))
      line += "# " + parts.back() + ": " + p.default_text;
    else
      line += parts.back() + ": " + yamlValue(p, defaults);
    const std::string unit = p.unit.empty() ? "" : "[" + unitText(p.unit, false) + "] ";
    const std::string range = rangeText(p, false);
    const std::string comment = "# " + unit + (range.empty() ? "" : range + "; ") + p.meaning;
    if (line.size() > 39)  // a long value: the comment goes above it
      os << std::string(2 * parts.size(), ' ') << comment << "\n" << line << "\n";
    else
      os << line << std::string(40 - line.size(), ' ') << comment << "\n";
  }
}

const std::map<std::string, std::function<std::string()>>& tables()
{
  static const std::map<std::string, std::function<std::string()>> all = {
    { "cable", [] { return markdown(cableParams(), CableParams()); } },
    { "depressor", [] { return markdown(depressorParams(), DepressorParams()); } },
    { "vehicle", [] { return markdown(vehicleParams(), VehicleParams()); } },
    { "environment", [] { return markdown(environmentParams(), Environment()); } },
    { "winch", [] { return markdown(winchParams(), WinchParams()); } },
    { "seabed", [] { return markdown(seabedParams(), SeabedParams()); } },
    { "numerics", [] { return markdown(numericsParams(), NumericsParams()); } },
    { "node", [] { return markdown(nodeParams(), NodeParams()); } },
    { "autopilot_node", [] { return markdown(autopilotNodeParams(), AutopilotNodeParams()); } },
    { "replay_node", [] { return markdown(replayParams(), ReplayParams()); } },
    { "ship_motion_node", [] { return markdown(shipMotionParams(), ShipMotionParams()); } },
    { "gnss_ship_node", [] { return markdown(gnssShipParams(), GnssShipParams()); } },
    { "tow_nav_node", [] { return markdown(towNavNodeParams(), TowNavNodeParams()); } },
    { "ship", [] { return markdown(shipParams(), Scenario()); } },
    { "manoeuvres", [] { return markdown(manoeuvreParams(), Manoeuvre()); } },
    { "commands", [] { return markdown(commandParams(), CommandEvent()); } },
    { "autopilot", [] { return markdown(autopilotLoopParams(), AutopilotLoop()); } },
    { "initial_state", [] { return markdown(initialStateParams(), InitialShape()); } },
    { "simulation", [] { return markdown(simulationParams(), Scenario()); } },
    { "sensors", [] { return markdown(surveySensorParams(), SurveySensorParams()); } },
    { "nav", [] { return markdown(towNavParams(), TowNavParams()); } },
  };
  return all;
}
}  // namespace

std::vector<std::string> documentedTables()
{
  std::vector<std::string> names;
  for (const auto& entry : tables())
    names.push_back(entry.first);
  return names;
}

std::string markdownTable(const std::string& name)
{
  const auto found = tables().find(name);
  if (found == tables().end())
    throw std::invalid_argument("no parameter table named '" + name + "'");
  return found->second();
}

std::string withCurrentTables(const std::string& text)
{
  const std::string open = "<!-- params:", close = "<!-- /params -->";
  std::string out;
  size_t at = 0;
  for (size_t start = text.find(open); start != std::string::npos; start = text.find(open, at))
  {
    const size_t name_end = text.find(" -->", start);
    const size_t end = text.find(close, start);
    if (name_end == std::string::npos || end == std::string::npos)
      throw std::invalid_argument("an unterminated <!-- params: ... --> block");
    const std::string name = text.substr(start + open.size(), name_end - start - open.size());
    out += text.substr(at, name_end + 4 - at) + "\n" + markdownTable(name);
    at = end;
  }
  return out + text.substr(at);
}

std::string configFile()
{
  const SimulationConfig d;
  const YAML::Node written = toYaml(d);
  std::ostringstream os;
  os << "# tow_sim configuration: the cable, the towed vehicle, the water, the winch, the seabed and the numerics.\n"
        "# SI units and radians; world frame ENU (z up, depth = -z); vehicle body frame FLU with zero roll.\n"
        "# Every key is optional: a missing key takes the value shown here (the built-in defaults). Unknown keys\n"
        "# and out-of-range values are errors that name the key, the value and the allowed range.\n"
        "# Generated from the parameter tables by tow_sim_param_docs (make docs): edit the tables, not this file.\n";
  auto section = [&](const char* name, const char* about) -> std::ostringstream&
  {
    os << "\n# " << about << "\n" << name << ":\n";
    return os;
  };
  writeSection(section("cable", "The towing cable: nu rigid segments."), cableParams(), d.cable, written["cable"]);
  writeSection(section("environment", "The water."), environmentParams(), d.environment, written["environment"]);
  writeSection(section("winch",
                       "The winch at the tow point: the first segment changes length; segments are split "
                       "off or merged into it."),
               winchParams(), d.winch, written["winch"]);
  writeSection(section("seabed", "The sea floor and the contact of cable joints and the vehicle's hull ends with it."),
               seabedParams(), d.seabed, written["seabed"]);
  writeSection(section("numerics", "The integration."), numericsParams(), d.numerics, written["numerics"]);
  writeSection(section("vehicle",
                       "The example vehicle: 2 m long, 0.3 m diameter, tail fins. Distances along its "
                       "axis from the bail, aft; the nose forward."),
               vehicleParams(), d.vehicle, written["vehicle"]);
  return os.str();
}

}  // namespace tow_sim
