#include "tow_sim/core/io/saved_state.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tow_sim
{
namespace
{
const char* const kMagic = "tow_sim_state";
const int kFormat = 2;  // written; 1 (without the configuration) is still read
const char* const kConfigPrefix = "config.";
const char* const kConfigHash = "config_hash";

class Writer
{
public:
  void put(const std::string& key, const std::vector<double>& values)
  {
    out_ << key;
    char buffer[40];
    for (double v : values)
    {
      std::snprintf(buffer, sizeof buffer, " %.17g", v);
      out_ << buffer;
    }
    out_ << '\n';
  }
  void put(const std::string& key, double value) { put(key, std::vector<double>{ value }); }
  void put(const std::string& key, const Eigen::Vector3d& v) { put(key, std::vector<double>{ v.x(), v.y(), v.z() }); }
  void put(const std::string& key, const FinServo::State& s)
  {
    put(key, std::vector<double>{ s.t0, s.angle0, s.target });
  }
  void put(const std::string& key, const ValueRange& r) { put(key, std::vector<double>{ r.min, r.max }); }
  std::string text() const { return out_.str(); }

private:
  std::ostringstream out_;
};

// The fields of a state's text by key; each taken once, and none left over at the end.
class Fields
{
public:
  explicit Fields(const std::string& source) : source_(source) {}

  void add(const std::string& key, std::vector<double> values, int line)
  {
    if (!fields_.emplace(key, std::move(values)).second)
      fail("line " + std::to_string(line) + ": " + key + " is given twice");
  }
  bool has(const std::string& key) const { return fields_.count(key) != 0; }
  std::vector<double> take(const std::string& key, std::size_t count = 0, bool any_count = false)
  {
    auto it = fields_.find(key);
    if (it == fields_.end())
      fail(key + " is missing");
    std::vector<double> values = std::move(it->second);
    fields_.erase(it);
    if (!any_count && values.size() != count)
      fail(key + " has " + std::to_string(values.size()) + " values, expected " + std::to_string(count));
    return values;
  }
  double number(const std::string& key) { return take(key, 1)[0]; }
  long integer(const std::string& key, long lo, long hi)
  {
    const double v = number(key);
    if (!(v >= static_cast<double>(lo) && v <= static_cast<double>(hi)) || v != std::floor(v))
      fail(key + " must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
           std::to_string(v));
    return static_cast<long>(v);
  }
  bool flag(const std::string& key) { return integer(key, 0, 1) == 1; }
  Eigen::Vector3d vector3(const std::string& key)
  {
    const std::vector<double> v = take(key, 3);
    return { v[0], v[1], v[2] };
  }
  FinServo::State servo(const std::string& key)
  {
    const std::vector<double> v = take(key, 3);
    return { v[0], v[1], v[2] };
  }
  ValueRange range(const std::string& key)
  {
    const std::vector<double> v = take(key, 2);
    ValueRange r;
    r.min = v[0];
    r.max = v[1];
    return r;
  }
  void finish() const
  {
    if (!fields_.empty())
      fail(fields_.begin()->first + " is not a field of a tow_sim state");
  }
  [[noreturn]] void fail(const std::string& what) const
  {
    throw std::invalid_argument("saved state " + source_ + ": " + what);
  }

private:
  std::string source_;
  std::map<std::string, std::vector<double>> fields_;
};

void putAutopilot(Writer& w, const DepthAutopilotState& a)
{
  w.put("autopilot.setpoint", std::vector<double>{ a.has_setpoint ? 1.0 : 0.0, a.setpoint });
  w.put("autopilot.altitude_setpoint", std::vector<double>{ a.altitude_mode ? 1.0 : 0.0, a.altitude_setpoint });
  const VehicleMeasurement& m = a.vehicle;
  w.put("autopilot.vehicle",
        std::vector<double>{ a.has_vehicle ? 1.0 : 0.0, m.t, m.p_W.x(), m.p_W.y(), m.p_W.z(), m.v_W.x(), m.v_W.y(),
                             m.v_W.z(), m.altitude, m.cable_out, m.received, m.roll, m.roll_rate });
  w.put("autopilot.integral", std::vector<double>{ a.integrated ? 1.0 : 0.0, a.integrated_until, a.integral });
  w.put("autopilot.winch", std::vector<double>{ a.feed_forward ? 1.0 : 0.0, a.cable_out_base, a.winch_integral });
  std::vector<double> track;
  for (const Eigen::Vector2d& p : a.track)
  {
    track.push_back(p.x());
    track.push_back(p.y());
  }
  w.put("autopilot.track", track);
}

DepthAutopilotState takeAutopilot(Fields& f)
{
  DepthAutopilotState a;
  auto flag = [&f](const std::string& key, double v)
  {
    if (v != 0.0 && v != 1.0)
      f.fail(key + ": its first value must be 0 or 1");
    return v == 1.0;
  };
  std::vector<double> v = f.take("autopilot.setpoint", 2);
  a.has_setpoint = flag("autopilot.setpoint", v[0]);
  a.setpoint = v[1];
  v = f.take("autopilot.altitude_setpoint", 2);
  a.altitude_mode = flag("autopilot.altitude_setpoint", v[0]);
  a.altitude_setpoint = v[1];
  v = f.take("autopilot.vehicle", 0, true);
  if (v.size() == 11)  // saved before the roll: unknown
    v.insert(v.end(), 2, std::numeric_limits<double>::quiet_NaN());
  if (v.size() != 13)
    f.fail("autopilot.vehicle has " + std::to_string(v.size()) + " values, expected 13 (11 before the roll)");
  a.has_vehicle = flag("autopilot.vehicle", v[0]);
  VehicleMeasurement& m = a.vehicle;
  m.t = v[1];
  m.p_W = Eigen::Vector3d(v[2], v[3], v[4]);
  m.v_W = Eigen::Vector3d(v[5], v[6], v[7]);
  m.altitude = v[8];
  m.cable_out = v[9];
  m.received = v[10];
  m.roll = v[11];
  m.roll_rate = v[12];
  v = f.take("autopilot.integral", 3);
  a.integrated = flag("autopilot.integral", v[0]);
  a.integrated_until = v[1];
  a.integral = v[2];
  v = f.take("autopilot.winch", 3);
  a.feed_forward = flag("autopilot.winch", v[0]);
  a.cable_out_base = v[1];
  a.winch_integral = v[2];
  v = f.take("autopilot.track", 0, true);
  if (v.size() % 2 != 0)
    f.fail("autopilot.track must have x y pairs, got " + std::to_string(v.size()) + " values");
  for (std::size_t i = 0; i < v.size(); i += 2)
    a.track.emplace_back(v[i], v[i + 1]);
  return a;
}

std::vector<double> parseNumbers(std::istringstream& in, const Fields& f, int line)
{
  std::vector<double> values;
  std::string token;
  while (in >> token)
  {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    // ERANGE also flags a subnormal, which %.17g writes and strtod reads back exactly: only an overflow
    // (a number beyond the doubles) is refused.
    if (end == token.c_str() || *end != '\0' || (errno == ERANGE && std::isinf(v)))
      f.fail("line " + std::to_string(line) + ": '" + token + "' is not a number");
    values.push_back(v);
  }
  return values;
}

// The lines of a state's text: its numeric fields into f, the configuration's text lines apart.
void readFields(const std::string& text, Fields& f, std::map<std::string, std::string>& configuration,
                std::string& hash)
{
  std::istringstream lines(text);
  std::string line;
  for (int n = 1; std::getline(lines, line); ++n)
  {
    std::istringstream in(line);
    std::string key;
    if (!(in >> key) || key[0] == '#')
      continue;
    if (!f.has(kMagic) && key != kMagic)
      f.fail("line " + std::to_string(n) + ": not a tow_sim state (it must begin with '" + kMagic + " " +
             std::to_string(kFormat) + "')");
    if (key == kConfigHash || key.rfind(kConfigPrefix, 0) == 0)  // text: the rest of the line
    {
      std::string value;
      std::getline(in >> std::ws, value);
      if (key == kConfigHash)
        hash = value;
      else if (!configuration.emplace(key.substr(std::string(kConfigPrefix).size()), value).second)
        f.fail("line " + std::to_string(n) + ": " + key + " is given twice");
      continue;
    }
    f.add(key, parseNumbers(in, f, n), n);
  }
}

// The format version, and a configuration that matches its hash (format 2; none in format 1).
void checkConfiguration(const Fields& f, long format, const std::map<std::string, std::string>& configuration,
                        const std::string& hash)
{
  if (format != 1 && format != kFormat)
    f.fail(std::string(kMagic) + ": format versions other than 1 and " + std::to_string(kFormat) + " are not read");
  if (format == 1 && (!configuration.empty() || !hash.empty()))
    f.fail("format 1 has no configuration lines");
  if (configuration.empty() != hash.empty())
    f.fail(hash.empty() ? "config_hash is missing" : "config_hash without the configuration's config. lines");
  if (!hash.empty() && hash != configurationHash(configuration))
    f.fail("config_hash " + hash + " does not match the config. lines (" + configurationHash(configuration) +
           "): the file was edited or damaged");
}
}  // namespace

std::string runStateText(const RunState& s)
{
  Writer w;
  w.put(kMagic, kFormat);
  const SimulatorState& sim = s.sim;
  w.put("t", sim.t);
  w.put("reached", s.reached);
  w.put("dt", sim.dt);
  w.put("segments", sim.segments);
  w.put("y", sim.y);
  w.put("rudder", sim.rudder);
  w.put("elevator", sim.elevator);
  w.put("differential", sim.differential);
  w.put("thrust", sim.thrust);
  w.put("winch_command", sim.winch_command);
  w.put("slack", std::vector<double>(sim.slack.begin(), sim.slack.end()));
  w.put("tow_point.p", s.tow_point.p_W);
  w.put("tow_point.v", s.tow_point.v_W);
  w.put("tow_point.a", s.tow_point.a_W);
  w.put("heading", s.heading);
  w.put("ticks", static_cast<double>(s.ticks));
  w.put("snap_count", static_cast<double>(s.snap_count));
  w.put("max_strain", s.max_strain);
  w.put("max_length_error", s.max_length_error);
  w.put("tension_ship_range", s.tension_ship_range);
  w.put("tension_vehicle_range", s.tension_vehicle_range);
  w.put("attitude_heading", s.attitude_heading);
  w.put("autopilot", s.autopilot ? 1.0 : 0.0);
  if (s.autopilot)
    putAutopilot(w, *s.autopilot);
  std::string config;
  if (!s.configuration.empty())
  {
    config = std::string(kConfigHash) + " " + configurationHash(s.configuration) + "\n";
    for (const auto& [key, value] : s.configuration)
      config += kConfigPrefix + key + " " + value + "\n";
  }
  return "# tow_sim saved state (docs/nodes.md, Saved states): the cable, the actuators, the run's counters, the "
         "autopilot, the configuration\n" +
         w.text() + config;
}

std::string configurationHash(const std::map<std::string, std::string>& configuration)
{
  std::uint64_t h = 14695981039346656037ULL;
  for (const auto& [key, value] : configuration)
    for (const std::string& part : { key, std::string("="), value, std::string("\n") })
      for (unsigned char c : part)
      {
        h ^= c;
        h *= 1099511628211ULL;
      }
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

RunState parseRunState(const std::string& text, const std::string& source)
{
  Fields f(source);
  std::map<std::string, std::string> configuration;
  std::string hash;
  readFields(text, f, configuration, hash);
  if (!f.has(kMagic))
    f.fail("empty: not a tow_sim state");
  checkConfiguration(f, f.integer(kMagic, 0, 1000000), configuration, hash);
  RunState s;
  SimulatorState& sim = s.sim;
  sim.t = f.number("t");
  s.reached = f.number("reached");
  sim.dt = f.number("dt");
  sim.segments = static_cast<int>(f.integer("segments", 1, 100000));
  const std::size_t plain = 6 * static_cast<std::size_t>(sim.segments + 1) + 2;
  sim.y = f.take("y", 0, true);
  if (sim.y.size() != plain && sim.y.size() != plain + 2)  // + a rolling vehicle's roll angle and spin
    f.fail("y has " + std::to_string(sim.y.size()) + " values, expected " + std::to_string(plain) + " (" +
           std::to_string(plain + 2) + " with vehicle.roll: free)");
  sim.rudder = f.servo("rudder");
  sim.elevator = f.servo("elevator");
  if (f.has("differential"))  // states saved before the differential elevator have none
    sim.differential = f.servo("differential");
  sim.thrust = f.number("thrust");
  sim.winch_command = f.number("winch_command");
  for (double v : f.take("slack", 0, true))
  {
    if (v != 0.0 && v != 1.0)
      f.fail("slack: each flag must be 0 or 1");
    sim.slack.push_back(v == 1.0 ? 1 : 0);
  }
  s.tow_point.p_W = f.vector3("tow_point.p");
  s.tow_point.v_W = f.vector3("tow_point.v");
  s.tow_point.a_W = f.vector3("tow_point.a");
  s.heading = f.number("heading");
  s.ticks = f.integer("ticks", 0, 1L << 52);
  s.snap_count = f.integer("snap_count", 0, 1L << 52);
  s.max_strain = f.number("max_strain");
  s.max_length_error = f.number("max_length_error");
  s.tension_ship_range = f.range("tension_ship_range");
  s.tension_vehicle_range = f.range("tension_vehicle_range");
  s.attitude_heading = f.number("attitude_heading");
  if (f.flag("autopilot"))
    s.autopilot = takeAutopilot(f);
  f.finish();
  s.configuration = std::move(configuration);
  if (!s.tow_point.p_W.allFinite() || !s.tow_point.v_W.allFinite() || !s.tow_point.a_W.allFinite() ||
      !std::isfinite(s.heading))
    f.fail("tow_point and heading must be finite");
  return s;
}

void writeRunState(const std::string& path, const RunState& state)
{
  // Written beside and renamed over: a failed write leaves an older state whole.
  const std::string text = runStateText(state), partial = path + ".partial";
  {
    std::ofstream out(partial);
    if (!(out << text) || !out.flush())
    {
      std::remove(partial.c_str());
      throw std::runtime_error("cannot write the saved state " + path);
    }
  }
  if (std::rename(partial.c_str(), path.c_str()) != 0)
  {
    std::remove(partial.c_str());
    throw std::runtime_error("cannot write the saved state " + path);
  }
}

RunState readRunState(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("cannot read the saved state " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return parseRunState(text.str(), path);
}

}  // namespace tow_sim
