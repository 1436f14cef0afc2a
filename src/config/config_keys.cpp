// A configuration as flat keys and values (what a saved state records) and the check that a saved state's
// configuration is the run's (docs/nodes.md, "Saved states").
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "tow_sim/config/config.h"
#include "tow_sim/core/io/saved_state.h"

namespace tow_sim
{
namespace
{
// A number as its shortest text that reads back as the same double ("0.1", not yaml-cpp's
// "0.10000000000000001"); any other scalar as it is.
std::string shortest(const std::string& scalar)
{
  char* end = nullptr;
  const double v = std::strtod(scalar.c_str(), &end);
  if (scalar.empty() || *end != '\0' || !std::isfinite(v))
    return scalar;
  char buffer[40];
  for (int digits = 1; digits <= 17; ++digits)
  {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    const bool exponent = std::string(buffer).find('e') != std::string::npos;
    if (std::strtod(buffer, nullptr) == v && (!exponent || scalar.find_first_of("eE") != std::string::npos))
      break;
  }
  return buffer;
}

void flatten(const YAML::Node& node, const std::string& path, std::map<std::string, std::string>& out)
{
  if (node.IsMap())
  {
    for (const auto& entry : node)
      flatten(entry.second, path.empty() ? entry.first.as<std::string>() : path + "." + entry.first.as<std::string>(),
              out);
  }
  else if (node.IsSequence() && node.size() == 0)
    out[path] = "[]";
  else if (node.IsSequence())
  {
    for (size_t i = 0; i < node.size(); ++i)
      flatten(node[i], path + "[" + std::to_string(i) + "]", out);
  }
  else if (node.IsScalar())
    out[path] = shortest(node.Scalar());
  else
    out[path] = "~";
}
}  // namespace

std::map<std::string, std::string> configurationKeys(const SimulationConfig& config)
{
  std::map<std::string, std::string> keys;
  flatten(toYaml(config), "", keys);
  // The bathymetry by its content, not by where its file is (the node and the batch resolve a relative
  // grid_file against different folders; an edited grid in the same file is another seabed).
  keys.erase("seabed.grid_file");
  if (config.seabed.type == SeabedParams::Type::kGrid)
  {
    const BathymetryGrid& g = config.seabed.grid;
    std::map<std::string, std::string> values;
    char buffer[128];  // four %.17g numbers take up to 4 x 24 + 3 characters: none may be cut off the hash
    for (Eigen::Index k = 0; k < g.depth.size(); ++k)
    {
      std::snprintf(buffer, sizeof buffer, "%.17g", g.depth.data()[k]);
      values[std::to_string(k)] = buffer;
    }
    std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g %.17g", g.origin.x(), g.origin.y(), g.spacing.x(),
                  g.spacing.y());
    values["origin, spacing"] = buffer;
    keys["seabed.grid"] = std::to_string(g.depth.cols()) + " x " + std::to_string(g.depth.rows()) + " depths, FNV-1a " +
                          configurationHash(values);
  }
  return keys;
}

void requireSameConfiguration(const std::map<std::string, std::string>& saved, const SimulationConfig& config,
                              const std::string& hint)
{
  if (!saved.empty())
    requireSameConfiguration(saved, configurationKeys(config), hint);
}

void requireSameConfiguration(const std::map<std::string, std::string>& saved,
                              const std::map<std::string, std::string>& now, const std::string& hint)
{
  if (saved.empty())
    return;
  std::vector<std::string> differ;
  auto value = [](const std::map<std::string, std::string>& m, const std::string& key)
  {
    const auto it = m.find(key);
    return it == m.end() ? std::string("(none)") : it->second;
  };
  // A key the saved state does not have came after it was saved: the state ran as that key's default (each new
  // option defaults to the model before it), so only a value other than the default differs.
  static const std::map<std::string, std::string> defaults = configurationKeys(SimulationConfig());
  std::set<std::string> keys;
  for (const auto& entry : saved)
    keys.insert(entry.first);
  for (const auto& entry : now)
    keys.insert(entry.first);
  for (const std::string& key : keys)
    if (value(saved, key) != value(now, key) &&
        !(!saved.count(key) && defaults.count(key) && value(defaults, key) == value(now, key)))
      differ.push_back(key);
  if (differ.empty())
    return;
  std::ostringstream os;
  os << "saved under another configuration: " << differ.size()
     << (differ.size() == 1 ? " key differs:" : " keys differ:");
  for (size_t i = 0; i < differ.size() && i < 8; ++i)
    os << (i ? "," : "") << " " << differ[i] << " (saved " << value(saved, differ[i]) << ", now "
       << value(now, differ[i]) << ")";
  if (differ.size() > 8)
    os << ", …";
  os << "; " << hint;
  throw std::invalid_argument(os.str());
}

}  // namespace tow_sim
