#include <sys/stat.h>
#include <yaml-cpp/yaml.h>

#include <stdexcept>
#include <string>

#include "tow_sim/config/config.h"

namespace tow_sim
{
BathymetryGrid loadBathymetryFile(const std::string& path)
{
  // Only a regular file of sane size (not a device, pipe or directory that would block or never end).
  struct stat st;
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    throw std::invalid_argument(path + ": cannot read the bathymetry grid: not a readable regular file");
  if (st.st_size > 200L * 1024 * 1024)
    throw std::invalid_argument(path + ": the bathymetry grid file is larger than 200 MB");
  try
  {
    const YAML::Node root = YAML::LoadFile(path);
    if (!root.IsMap())
      throw std::invalid_argument(path + ": must be a mapping with origin, spacing and depth");
    for (const auto& entry : root)
    {
      const std::string key = entry.first.as<std::string>();
      if (key != "origin" && key != "spacing" && key != "depth")
        throw std::invalid_argument(path + ": " + key + ": unknown key (known keys: depth, origin, spacing)");
    }
    BathymetryGrid g;
    auto pair = [&](const char* key)
    {
      const YAML::Node n = root[key];
      if (!n || !n.IsSequence() || n.size() != 2)
        throw std::invalid_argument(path + ": " + key + " must be a list of 2 numbers [m]");
      return Eigen::Vector2d(n[0].as<double>(), n[1].as<double>());
    };
    g.origin = pair("origin");
    g.spacing = pair("spacing");
    const YAML::Node rows = root["depth"];
    if (!rows || !rows.IsSequence() || rows.size() == 0 || !rows[0].IsSequence())
      throw std::invalid_argument(path + ": depth must be a list of rows (lists of depths [m])");
    g.depth.resize(rows.size(), rows[0].size());
    for (std::size_t j = 0; j < rows.size(); ++j)
    {
      if (!rows[j].IsSequence() || rows[j].size() != rows[0].size())
        throw std::invalid_argument(path + ": depth[" + std::to_string(j) + "] must be a list of " +
                                    std::to_string(rows[0].size()) + " depths, like depth[0]");
      for (std::size_t i = 0; i < rows[j].size(); ++i)
        g.depth(j, i) = rows[j][i].as<double>();
    }
    return g;
  }
  catch (const YAML::Exception& e)
  {
    throw std::invalid_argument(path + ": cannot read the bathymetry grid: " + e.what());
  }
}

}  // namespace tow_sim
