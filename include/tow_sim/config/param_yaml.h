// Reading and writing a parameter table's keys in YAML (the configuration files, scenarios, and the ROS
// parameter server converted to YAML), with the key path of every error. Used by the libraries and the
// ROS edge (ros/conversions.h); not part of the core's API.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "tow_sim/config/yaml_section.h"
#include "tow_sim/core/param_table.h"

namespace tow_sim
{
namespace detail
{
// One YAML mapping and its sub-mappings, read key by key: every read marks its key known, and finish()
// reports any key no table and no custom code asked for (a typo) in any of them.
class ParamReader
{
public:
  explicit ParamReader(const Section& root) { sections_.emplace("", root); }

  // The mapping at a dotted path below the root ("" is the root itself), for custom keys.
  Section& at(const std::string& path)
  {
    auto found = sections_.find(path);
    if (found != sections_.end())
      return found->second;
    const size_t dot = path.rfind('.');
    Section& parent = at(dot == std::string::npos ? "" : path.substr(0, dot));
    return sections_.emplace(path, parent.child(dot == std::string::npos ? path : path.substr(dot + 1))).first->second;
  }

  // Every key of the table but the custom ones, which it only marks known for the caller to read.
  template <class S>
  void read(const ParamTable<S>& table, S& out)
  {
    for (const ParamSpec<S>& p : table.specs())
    {
      const size_t dot = p.key.rfind('.');
      Section& s = at(dot == std::string::npos ? "" : p.key.substr(0, dot));
      readOne(s, dot == std::string::npos ? p.key : p.key.substr(dot + 1), p, out);
    }
  }

  void finish() const
  {
    for (const auto& entry : sections_)
      entry.second.finish();
  }

private:
  template <class S>
  static void readOne(Section& s, const std::string& key, const ParamSpec<S>& p, S& out)
  {
    switch (p.kind)
    {
      case ParamKind::kNumber:
      {
        std::optional<double> value = p.get_number(out);
        if (p.optional)
          s.read(key, value);
        else
          s.read(key, *value);
        p.set_number(out, value);
        return;
      }
      case ParamKind::kInteger:
      {
        int value = static_cast<int>(*p.get_number(out));
        s.read(key, value);
        p.set_number(out, value);
        return;
      }
      case ParamKind::kBool:
      {
        bool value = p.get_bool(out);
        s.read(key, value);
        p.set_bool(out, value);
        return;
      }
      case ParamKind::kChoice:
      case ParamKind::kText:
      {
        const std::string value = s.text(key, p.get_text(out));
        try
        {
          p.set_text(out, value);
        }
        catch (const std::invalid_argument& e)
        {
          fail(s.path(key), e.what());
        }
        return;
      }
      case ParamKind::kVector3:
      {
        Eigen::Vector3d value = p.get_vector(out);
        s.read(key, value);
        p.set_vector(out, value);
        return;
      }
      case ParamKind::kCustom:
        s.has(key);  // the caller reads it
        return;
    }
  }

  std::map<std::string, Section> sections_;
};

// Writes every key of the table but the custom ones (and unset optional numbers) into `node`.
template <class S>
void writeParams(YAML::Node node, const ParamTable<S>& table, const S& in)
{
  for (const ParamSpec<S>& p : table.specs())
  {
    YAML::Node target = node;
    std::string key = p.key;
    for (size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.'))
    {
      target.reset(target[key.substr(0, dot)]);  // rebind (assignment would overwrite the node)
      key = key.substr(dot + 1);
    }
    switch (p.kind)
    {
      case ParamKind::kNumber:
        if (const std::optional<double> v = p.get_number(in))
          target[key] = *v;
        break;
      case ParamKind::kInteger:
        target[key] = static_cast<int>(*p.get_number(in));
        break;
      case ParamKind::kBool:
        target[key] = p.get_bool(in);
        break;
      case ParamKind::kChoice:
      case ParamKind::kText:
        target[key] = p.get_text(in);
        break;
      case ParamKind::kVector3:
      {
        const Eigen::Vector3d v = p.get_vector(in);
        target[key] = std::vector<double>{ v.x(), v.y(), v.z() };
        break;
      }
      case ParamKind::kCustom:
        break;
    }
  }
}

}  // namespace detail

// The top-level names of a table's keys ("winch.max_rate" -> "winch"), each once, in the table's order.
template <class S>
std::vector<std::string> topLevelKeys(const ParamTable<S>& table)
{
  std::vector<std::string> keys;
  for (const ParamSpec<S>& p : table.specs())
  {
    const std::string top = p.key.substr(0, p.key.find('.'));
    if (std::find(keys.begin(), keys.end(), top) == keys.end())
      keys.push_back(top);
  }
  return keys;
}

}  // namespace tow_sim
