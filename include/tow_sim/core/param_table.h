// Parameter tables: each key of a parameter struct described once (its path, the member it sets, its unit,
// its range, its default, which is the struct's own, and a one-line meaning). A table drives the
// validation of the struct (validateParams, here), reading it from YAML and the ROS parameter server and
// writing it back (tow_sim_config), and the parameter tables of docs/parameters.md and config/tow_sim.yaml
// (tow_sim_param_docs writes them; a test checks they are current).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace tow_sim
{
// The lower end of a number's range: open, (lo, hi], or closed, [lo, hi].
inline constexpr bool kOpen = true;
inline constexpr bool kClosed = false;

enum class ParamKind
{
  kNumber,  // double; kInteger: int; both within [lo, hi] (or (lo, hi]); may be optional (unset)
  kInteger,
  kBool,
  kChoice,   // one of `choices` (an enum)
  kVector3,  // [x, y, z], each within [lo, hi]
  kText,     // a string (range_text says what it may be)
  kCustom    // read, written and checked by the loader's own code (lists, tables, matrices); documented here
};

template <class S>
struct ParamSpec
{
  std::string key;  // path inside its section, dots for nesting ("inertia.xx", "rudder.lift_constant")
  ParamKind kind = ParamKind::kNumber;
  std::string unit;     // "m", "kg/m", "-" (none); empty for bools, choices, text
  std::string meaning;  // one line
  // Numbers and vector components: [lo, hi], (lo, hi] when lo_open; `bounds`, when set, gives them from the
  // struct's other keys, and range_text then documents them (also the allowed values of text and custom).
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  std::function<std::pair<double, double>(const S&)> bounds;
  std::string range_text;
  bool optional = false;     // a number that may be unset (the struct then computes it)
  std::string default_text;  // documented default where the struct's value says too little
  std::function<std::optional<double>(const S&)> get_number;
  std::function<void(S&, std::optional<double>)> set_number;
  std::function<bool(const S&)> get_bool;
  std::function<void(S&, bool)> set_bool;
  std::vector<std::string> choices;  // kChoice
  std::function<std::string(const S&)> get_text;
  std::function<void(S&, const std::string&)> set_text;  // throws std::invalid_argument for a bad choice
  std::function<Eigen::Vector3d(const S&)> get_vector;
  std::function<void(S&, const Eigen::Vector3d&)> set_vector;
};

template <class S>
class ParamTable
{
public:
  using Spec = ParamSpec<S>;

  ParamTable& number(const std::string& key, double S::*member, const std::string& unit, double lo, double hi,
                     bool lo_open, const std::string& meaning)
  {
    return numberAt(
        key, [member](const S& s) { return s.*member; }, [member](S& s, double v) { s.*member = v; }, unit, lo, hi,
        lo_open, meaning);
  }
  // A number held elsewhere in the struct (a matrix entry), read and written through get and set.
  ParamTable& numberAt(const std::string& key, std::function<double(const S&)> get, std::function<void(S&, double)> set,
                       const std::string& unit, double lo, double hi, bool lo_open, const std::string& meaning)
  {
    Spec p = base(key, ParamKind::kNumber, unit, meaning);
    p.lo = lo;
    p.hi = hi;
    p.lo_open = lo_open;
    p.get_number = [get](const S& s) -> std::optional<double> { return get(s); };
    p.set_number = [set](S& s, std::optional<double> v) { set(s, *v); };
    return add(std::move(p));
  }
  // A number whose range depends on the struct's other keys; range_text documents it.
  ParamTable& bounded(const std::string& key, double S::*member, const std::string& unit,
                      std::function<std::pair<double, double>(const S&)> bounds, const std::string& range_text,
                      const std::string& meaning)
  {
    number(key, member, unit, 0.0, 0.0, false, meaning);
    specs_.back().bounds = std::move(bounds);
    specs_.back().range_text = range_text;
    return *this;
  }
  ParamTable& integer(const std::string& key, int S::*member, const std::string& unit, double lo, double hi,
                      const std::string& meaning)
  {
    Spec p = base(key, ParamKind::kInteger, unit, meaning);
    p.lo = lo;
    p.hi = hi;
    p.get_number = [member](const S& s) -> std::optional<double> { return s.*member; };
    p.set_number = [member](S& s, std::optional<double> v) { s.*member = static_cast<int>(*v); };
    return add(std::move(p));
  }
  ParamTable& optionalNumber(const std::string& key, std::optional<double> S::*member, const std::string& unit,
                             double lo, double hi, bool lo_open, const std::string& default_text,
                             const std::string& meaning)
  {
    Spec p = base(key, ParamKind::kNumber, unit, meaning);
    p.lo = lo;
    p.hi = hi;
    p.lo_open = lo_open;
    p.optional = true;
    p.default_text = default_text;
    p.get_number = [member](const S& s) { return s.*member; };
    p.set_number = [member](S& s, std::optional<double> v) { s.*member = v; };
    return add(std::move(p));
  }
  ParamTable& boolean(const std::string& key, bool S::*member, const std::string& meaning)
  {
    Spec p = base(key, ParamKind::kBool, "", meaning);
    p.get_bool = [member](const S& s) { return s.*member; };
    p.set_bool = [member](S& s, bool v) { s.*member = v; };
    return add(std::move(p));
  }
  template <class E>
  ParamTable& choice(const std::string& key, E S::*member, const std::vector<std::pair<std::string, E>>& names,
                     const std::string& meaning)
  {
    Spec p = base(key, ParamKind::kChoice, "", meaning);
    for (const auto& n : names)
      p.choices.push_back(n.first);
    p.get_text = [member, names](const S& s)
    {
      for (const auto& n : names)
        if (n.second == s.*member)
          return n.first;
      return names.front().first;
    };
    const std::string allowed = choiceList(p.choices);
    p.set_text = [member, names, allowed](S& s, const std::string& v)
    {
      for (const auto& n : names)
        if (n.first == v)
        {
          s.*member = n.second;
          return;
        }
      throw std::invalid_argument("'" + v + "' must be " + allowed);
    };
    return add(std::move(p));
  }
  ParamTable& vector3(const std::string& key, Eigen::Vector3d S::*member, const std::string& unit, double lo, double hi,
                      const std::string& meaning)
  {
    Spec p = base(key, ParamKind::kVector3, unit, meaning);
    p.lo = lo;
    p.hi = hi;
    p.get_vector = [member](const S& s) { return s.*member; };
    p.set_vector = [member](S& s, const Eigen::Vector3d& v) { s.*member = v; };
    return add(std::move(p));
  }
  ParamTable& text(const std::string& key, std::string S::*member, const std::string& range_text,
                   const std::string& meaning)
  {
    Spec p = base(key, ParamKind::kText, "", meaning);
    p.range_text = range_text;
    p.get_text = [member](const S& s) { return s.*member; };
    p.set_text = [member](S& s, const std::string& v) { s.*member = v; };
    return add(std::move(p));
  }
  ParamTable& custom(const std::string& key, const std::string& unit, const std::string& default_text,
                     const std::string& range_text, const std::string& meaning)
  {
    Spec p = base(key, ParamKind::kCustom, unit, meaning);
    p.default_text = default_text;
    p.range_text = range_text;
    return add(std::move(p));
  }
  // The keys of another table, for a struct held in member, under "prefix." (or at this level for "").
  template <class T>
  ParamTable& nest(const std::string& prefix, T S::*member, const ParamTable<T>& inner);

  const std::vector<Spec>& specs() const { return specs_; }
  const Spec* find(const std::string& key) const
  {
    for (const Spec& p : specs_)
      if (p.key == key)
        return &p;
    return nullptr;
  }

  static std::string choiceList(const std::vector<std::string>& names)
  {
    std::string out;
    for (size_t i = 0; i < names.size(); ++i)
      out += (i == 0 ? "" : (i + 1 == names.size() ? " or " : ", ")) + ("'" + names[i] + "'");
    return out;
  }

private:
  static Spec base(const std::string& key, ParamKind kind, const std::string& unit, const std::string& meaning)
  {
    Spec p;
    p.key = key;
    p.kind = kind;
    p.unit = unit;
    p.meaning = meaning;
    return p;
  }
  ParamTable& add(Spec p)
  {
    specs_.push_back(std::move(p));
    return *this;
  }
  std::vector<Spec> specs_;
};

template <class S>
template <class T>
ParamTable<S>& ParamTable<S>::nest(const std::string& prefix, T S::*member, const ParamTable<T>& inner)
{
  for (const ParamSpec<T>& q : inner.specs())
  {
    Spec p;
    p.key = prefix.empty() ? q.key : prefix + "." + q.key;
    p.kind = q.kind;
    p.unit = q.unit;
    p.meaning = q.meaning;
    p.lo = q.lo;
    p.hi = q.hi;
    p.lo_open = q.lo_open;
    p.range_text = q.range_text;
    p.optional = q.optional;
    p.default_text = q.default_text;
    p.choices = q.choices;
    if (q.bounds)
      p.bounds = [member, f = q.bounds](const S& s) { return f(s.*member); };
    if (q.get_number)
    {
      p.get_number = [member, f = q.get_number](const S& s) { return f(s.*member); };
      p.set_number = [member, f = q.set_number](S& s, std::optional<double> v) { f(s.*member, v); };
    }
    if (q.get_bool)
    {
      p.get_bool = [member, f = q.get_bool](const S& s) { return f(s.*member); };
      p.set_bool = [member, f = q.set_bool](S& s, bool v) { f(s.*member, v); };
    }
    if (q.get_text)
    {
      p.get_text = [member, f = q.get_text](const S& s) { return f(s.*member); };
      p.set_text = [member, f = q.set_text](S& s, const std::string& v) { f(s.*member, v); };
    }
    if (q.get_vector)
    {
      p.get_vector = [member, f = q.get_vector](const S& s) { return f(s.*member); };
      p.set_vector = [member, f = q.set_vector](S& s, const Eigen::Vector3d& v) { f(s.*member, v); };
    }
    specs_.push_back(std::move(p));
  }
  return *this;
}

// Throws std::invalid_argument unless lo <= value <= hi (or lo < value where lo_open) and finite.
void requireInRange(const std::string& name, double value, double lo, double hi, const char* unit,
                    bool lo_open = false);

// A key's full name under a prefix: "<prefix>.<key>", or "<prefix><key>" when the prefix is empty or ends
// in '.' or '/' (a ROS namespace).
inline std::string paramName(const std::string& prefix, const std::string& key)
{
  const bool joined = prefix.empty() || prefix.back() == '.' || prefix.back() == '/';
  return prefix + (joined ? "" : ".") + key;
}

// Checks every number, integer and vector component of `s` against its range; throws
// std::invalid_argument naming "<prefix>.<key>", the value and the range.
template <class S>
void validateParams(const ParamTable<S>& table, const S& s, const std::string& prefix)
{
  for (const ParamSpec<S>& p : table.specs())
  {
    const std::string name = paramName(prefix, p.key);
    const std::string unit = "[" + p.unit + "]" + (p.bounds ? " (" + p.range_text + ")" : "");
    double lo = p.lo, hi = p.hi;
    if (p.bounds)
      std::tie(lo, hi) = p.bounds(s);
    if (p.kind == ParamKind::kNumber || p.kind == ParamKind::kInteger)
    {
      const std::optional<double> v = p.get_number(s);
      if (v)
        requireInRange(name, *v, lo, hi, unit.c_str(), p.lo_open);
    }
    else if (p.kind == ParamKind::kVector3)
    {
      const Eigen::Vector3d v = p.get_vector(s);
      for (int i = 0; i < 3; ++i)
        requireInRange(name + "[" + std::to_string(i) + "]", v[i], lo, hi, unit.c_str(), p.lo_open);
    }
  }
}

}  // namespace tow_sim
