// A YAML mapping with its key path, for the configuration and scenario loaders (private to the core).
#pragma once

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace tow_sim
{
namespace detail
{
[[noreturn]] inline void fail(const std::string& path, const std::string& what)
{
  throw std::invalid_argument(path + ": " + what);
}

// The known key nearest to a misspelt one (edit distance, at most a third of its length and at least 2),
// or "" when none is that near.
inline std::string closestKey(const std::string& key, const std::set<std::string>& known)
{
  std::string best;
  size_t best_distance = std::max<size_t>(2, key.size() / 3) + 1;
  for (const std::string& candidate : known)
  {
    std::vector<size_t> row(candidate.size() + 1);
    for (size_t j = 0; j <= candidate.size(); ++j)
      row[j] = j;
    for (size_t i = 1; i <= key.size(); ++i)
    {
      size_t diagonal = row[0];
      row[0] = i;
      for (size_t j = 1; j <= candidate.size(); ++j)
      {
        const size_t above = row[j];
        row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (key[i - 1] == candidate[j - 1] ? 0 : 1) });
        diagonal = above;
      }
    }
    if (row.back() < best_distance)
    {
      best_distance = row.back();
      best = candidate;
    }
  }
  return best;
}

// One YAML mapping with its key path; remembers which keys were read so that unknown ones (typos)
// are reported instead of silently ignored.
class Section
{
public:
  Section(const YAML::Node& node, std::string path) : node_(node), path_(std::move(path))
  {
    if (node_ && !node_.IsNull() && !node_.IsMap())
      fail(path_, "must be a mapping of keys to values");
  }

  const std::string& name() const { return path_; }
  std::string path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const std::string& key)
  {
    known_.insert(key);
    return node_ && node_.IsMap() && node_[key] && !node_[key].IsNull();
  }

  void read(const std::string& key, double& value)
  {
    if (has(key))
      value = number(node_[key], path(key));
  }
  void read(const std::string& key, std::optional<double>& value)
  {
    if (has(key))
      value = number(node_[key], path(key));
  }
  void read(const std::string& key, int& value)
  {
    if (!has(key))
      return;
    const double v = number(node_[key], path(key));
    if (v != std::floor(v) || std::abs(v) > 1e9)
      fail(path(key), "must be a whole number, got " + node_[key].as<std::string>());
    value = static_cast<int>(v);
  }
  void read(const std::string& key, bool& value)
  {
    if (!has(key))
      return;
    try
    {
      value = node_[key].as<bool>();
    }
    catch (const YAML::Exception&)
    {
      fail(path(key), "must be true or false");
    }
  }
  std::string text(const std::string& key, const std::string& fallback)
  {
    if (!has(key))
      return fallback;
    if (!node_[key].IsScalar())
      fail(path(key), "must be a string");
    return node_[key].as<std::string>();
  }
  // True when the key is set to a plain value (not a list or mapping).
  bool isScalar(const std::string& key) { return has(key) && node_[key].IsScalar(); }
  std::vector<double> list(const std::string& key)
  {
    std::vector<double> out;
    if (!has(key))
      return out;
    const YAML::Node n = node_[key];
    if (!n.IsSequence())
      fail(path(key), "must be a list of numbers");
    for (size_t i = 0; i < n.size(); ++i)
      out.push_back(number(n[i], path(key) + "[" + std::to_string(i) + "]"));
    return out;
  }
  void read(const std::string& key, Eigen::Vector3d& value)
  {
    if (!has(key))
      return;
    const std::vector<double> v = list(key);
    if (v.size() != 3)
      fail(path(key), "must be a list of 3 numbers [x, y, z], got " + std::to_string(v.size()));
    value = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  // A list of mappings, each a Section named key[i].
  std::vector<Section> items(const std::string& key)
  {
    std::vector<Section> out;
    if (!has(key))
      return out;
    const YAML::Node n = node_[key];
    if (!n.IsSequence())
      fail(path(key), "must be a list");
    for (size_t i = 0; i < n.size(); ++i)
      out.emplace_back(n[i], path(key) + "[" + std::to_string(i) + "]");
    return out;
  }
  Section child(const std::string& key)
  {
    has(key);
    return Section(node_ && node_.IsMap() ? node_[key] : YAML::Node(), path(key));
  }

  // Marks keys as known that another reader takes (finish() leaves them alone).
  void allow(const std::vector<std::string>& keys) { known_.insert(keys.begin(), keys.end()); }

  // Throws for any key that no read asked for, naming the nearest known one.
  void finish() const
  {
    if (!node_ || !node_.IsMap())
      return;
    for (const auto& entry : node_)
    {
      if (!entry.first.IsScalar())
        fail(path_, "has a key that is not a plain name (a list or mapping used as a key)");
      const std::string key = entry.first.as<std::string>();
      if (known_.count(key))
        continue;
      std::ostringstream os;
      os << "unknown key";
      const std::string near = closestKey(key, known_);
      if (!near.empty())
        os << "; did you mean '" << near << "'?";
      os << " (known keys:";
      for (const std::string& k : known_)
        os << " " << k;
      os << ")";
      fail(path(key), os.str());
    }
  }

private:
  static double number(const YAML::Node& n, const std::string& where)
  {
    if (!n.IsScalar())
      fail(where, "must be a number");
    const std::string text = n.as<std::string>();
    try
    {
      return n.as<double>();
    }
    catch (const YAML::Exception&)
    {
      fail(where, "must be a number, got '" + text + "'");
    }
  }

  YAML::Node node_;
  std::string path_;
  std::set<std::string> known_;
};

}  // namespace detail
}  // namespace tow_sim
