#include "tow_sim/scenario/scenario.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tow_sim/config/yaml_section.h"

namespace tow_sim
{
namespace
{
using detail::fail;
using detail::Section;
constexpr double kPi = 3.14159265358979323846;

const char* typeName(Manoeuvre::Type t)
{
  switch (t)
  {
    case Manoeuvre::Type::kStraight:
      return "straight";
    case Manoeuvre::Type::kSpeedChange:
      return "speed_change";
    case Manoeuvre::Type::kTurn:
      return "turn";
    case Manoeuvre::Type::kZigzag:
      return "zigzag";
    case Manoeuvre::Type::kWaypoints:
      return "waypoints";
  }
  return "straight";
}

Manoeuvre readManoeuvre(Section s, double previous_speed)
{
  Manoeuvre m;
  m.speed = previous_speed;
  const std::string type = s.text("type", "straight");
  const Manoeuvre::Type types[] = { Manoeuvre::Type::kStraight, Manoeuvre::Type::kSpeedChange, Manoeuvre::Type::kTurn,
                                    Manoeuvre::Type::kZigzag, Manoeuvre::Type::kWaypoints };
  bool known = false;
  for (Manoeuvre::Type t : types)
    if (type == typeName(t))
    {
      m.type = t;
      known = true;
    }
  if (!known)
    fail(s.path("type"), "= '" + type + "' must be straight, speed_change, turn, zigzag or waypoints");
  s.read("speed", m.speed);
  s.read("duration", m.duration);
  s.read("to_speed", m.to_speed);
  s.read("radius", m.radius);
  s.read("angle", m.angle);
  std::string direction = s.text("direction", "port");
  if (direction != "port" && direction != "starboard")
    fail(s.path("direction"), "= '" + direction + "' must be port or starboard");
  m.direction = direction == "port" ? 1 : -1;
  s.read("legs", m.legs);
  s.read("acceptance", m.acceptance);
  const std::vector<double> points = s.list("points");
  if (points.size() % 2 != 0)
    fail(s.path("points"), "must hold x, y pairs [m]: an even count of numbers");
  for (size_t i = 0; i + 1 < points.size(); i += 2)
    m.points.emplace_back(points[i], points[i + 1]);
  s.finish();
  requireInRange(s.path("speed"), m.speed, -15.0, 15.0, "[m/s]");
  requireInRange(s.path("duration"), m.duration, 0.0, 1e6, "[s]", true);
  requireInRange(s.path("to_speed"), m.to_speed, -15.0, 15.0, "[m/s]");
  requireInRange(s.path("radius"), m.radius, 10.0, 1e5, "[m]");
  requireInRange(s.path("angle"), m.angle, 0.0, 100.0, "[rad]", true);
  requireInRange(s.path("legs"), m.legs, 1.0, 1000.0, "[-]");
  requireInRange(s.path("acceptance"), m.acceptance, 1.0, 1e4, "[m]");
  if (m.type == Manoeuvre::Type::kWaypoints && m.points.empty())
    fail(s.path("points"), "the waypoints manoeuvre needs at least one [x, y] pair");
  return m;
}
}  // namespace

Scenario loadScenarioUnguarded(const YAML::Node& root, const std::string& base_dir);

Scenario loadScenario(const YAML::Node& root, const std::string& base_dir)
{
  try
  {
    return loadScenarioUnguarded(root, base_dir);
  }
  catch (const YAML::Exception& e)  // a shape the checks did not foresee: still a clear refusal
  {
    throw std::invalid_argument(std::string("scenario: ") + e.what());
  }
}

Scenario loadScenarioUnguarded(const YAML::Node& root, const std::string& base_dir)
{
  Scenario sc;
  sc.config = loadConfig(root, "", base_dir);
  Section top(root, "scenario");
  for (const char* section : { "cable", "vehicle", "environment", "numerics", "winch", "seabed" })
    top.has(section);

  Section ship = top.child("ship");
  ship.read("tow_point", sc.tow_point_S);
  std::vector<double> start = ship.list("start_position");
  if (!start.empty())
  {
    if (start.size() != 2)
      fail(ship.path("start_position"), "must be [x, y] [m]");
    sc.start_position = Eigen::Vector2d(start[0], start[1]);
  }
  ship.read("start_heading", sc.start_heading);
  double speed = 2.0;
  for (Section m : ship.items("manoeuvres"))
  {
    sc.manoeuvres.push_back(readManoeuvre(m, speed));
    const Manoeuvre& last = sc.manoeuvres.back();
    speed = last.type == Manoeuvre::Type::kSpeedChange ? last.to_speed : last.speed;
  }
  ship.finish();
  for (int i = 0; i < 3; ++i)
    requireInRange(ship.path("tow_point") + "[" + std::to_string(i) + "]", sc.tow_point_S[i], -1000.0, 1000.0, "[m]");
  requireInRange(ship.path("start_heading"), sc.start_heading, -100.0, 100.0, "[rad]");
  if (sc.manoeuvres.empty())
    sc.manoeuvres.push_back(Manoeuvre());

  for (Section c : top.items("commands"))
  {
    CommandEvent e;
    c.read("t", e.t);
    c.read("rudder", e.rudder);
    c.read("elevator", e.elevator);
    c.read("thrust", e.thrust);
    c.read("payout_rate", e.payout_rate);
    c.finish();
    requireInRange(c.path("payout_rate"), e.payout_rate, -20.0, 20.0, "[m/s]");
    if (e.payout_rate != 0.0 && !sc.config.winch.enabled)
      fail(c.path("payout_rate"), "needs the winch: winch.enabled is false");
    requireInRange(c.path("t"), e.t, 0.0, 1e7, "[s]");
    requireInRange(c.path("rudder"), e.rudder, -kPi / 2, kPi / 2, "[rad]");
    requireInRange(c.path("elevator"), e.elevator, -kPi / 2, kPi / 2, "[rad]");
    requireInRange(c.path("thrust"), e.thrust, -1e6, 1e6, "[N]");
    sc.commands.push_back(e);
  }
  std::stable_sort(sc.commands.begin(), sc.commands.end(),
                   [](const CommandEvent& a, const CommandEvent& b) { return a.t < b.t; });

  if (top.has("autopilot"))
  {
    Section a = top.child("autopilot");
    AutopilotScenario& ap = sc.autopilot;
    ap.enabled = true;
    DepthAutopilotParams& p = ap.params;
    a.read("rate", ap.rate);
    a.read("kp", p.kp);
    a.read("ki", p.ki);
    a.read("kd", p.kd);
    a.read("max_elevator", p.max_elevator);
    a.read("track_keeping", p.track_keeping);
    a.read("rudder_kp", p.rudder_kp);
    a.read("rudder_kd", p.rudder_kd);
    a.read("max_rudder", p.max_rudder);
    a.read("track_spacing", p.track_spacing);
    a.read("track_length", p.track_length);
    a.read("thrust", p.thrust);
    a.read("odom_timeout", p.odom_timeout);
    a.read("max_depth", p.max_depth);
    requireInRange(a.path("rate"), ap.rate, 0.1, 1000.0, "[Hz]");
    p.validate(a.name() + ".");  // before the setpoints, which are checked against max_depth
    for (Section item : a.items("setpoints"))
    {
      AutopilotSetpoint sp;
      item.read("t", sp.t);
      const bool has_depth = item.has("depth"), has_altitude = item.has("altitude");
      if (has_depth == has_altitude)
        fail(item.name(), "needs exactly one of depth [m] and altitude [m]");
      sp.altitude = has_altitude;
      item.read(has_altitude ? "altitude" : "depth", sp.value);
      item.finish();
      requireInRange(item.path("t"), sp.t, 0.0, 1e7, "[s]");
      requireInRange(item.path(has_altitude ? "altitude" : "depth"), sp.value, 0.0, p.max_depth, "[m]");
      if (sp.altitude && sc.config.seabed.type == SeabedParams::Type::kNone)
        fail(item.path("altitude"), "needs a seabed: seabed.type is none");
      ap.setpoints.push_back(sp);
    }
    a.finish();
    std::stable_sort(ap.setpoints.begin(), ap.setpoints.end(),
                     [](const AutopilotSetpoint& x, const AutopilotSetpoint& y) { return x.t < y.t; });
    for (std::size_t i = 0; i < sc.commands.size(); ++i)
    {
      const CommandEvent& c = sc.commands[i];
      if (c.rudder != 0.0 || c.elevator != 0.0 || c.thrust != 0.0)
        fail("commands[" + std::to_string(i) + "]",
             "rudder, elevator and thrust belong to the autopilot when there "
             "is one (payout_rate alone is allowed)");
    }
  }

  if (top.has("initial_state"))
  {
    Section init = top.child("initial_state");
    const std::string type = init.text("type", "equilibrium");
    if (type == "equilibrium")
      sc.initial.type = InitialShape::Type::kEquilibrium;
    else if (type == "line")
      sc.initial.type = InitialShape::Type::kLine;
    else if (type == "points")
      sc.initial.type = InitialShape::Type::kPoints;
    else
      fail(init.path("type"), "= '" + type + "' must be equilibrium, line or points");
    init.read("direction", sc.initial.line_direction_S);
    const std::vector<double> p = init.list("points");
    init.finish();
    if (sc.initial.line_direction_S.norm() < 1e-9 || !sc.initial.line_direction_S.allFinite())
      fail(init.path("direction"), "must be a finite, non-zero [x, y, z] in the ship frame");
    const size_t joints = static_cast<size_t>(sc.config.cable.segments) + 1;
    if (sc.initial.type == InitialShape::Type::kPoints)
    {
      if (p.size() != 3 * joints)
        fail(init.path("points"), "must hold 3 (nu + 1) = " + std::to_string(3 * joints) +
                                      " numbers (joints x_2 .. x_{nu+2}, world, x y z each); got " +
                                      std::to_string(p.size()));
      sc.initial.points = Eigen::Map<const Eigen::Matrix3Xd>(p.data(), 3, static_cast<Eigen::Index>(joints));
    }
  }

  Section sim = top.child("simulation");
  sim.read("duration", sc.duration);
  sim.read("output_interval", sc.output_interval);
  sim.read("shape_interval", sc.shape_interval);
  sim.finish();
  requireInRange(sim.path("duration"), sc.duration, 0.0, 1e7, "[s]", true);
  requireInRange(sim.path("output_interval"), sc.output_interval, 1e-3, 1e5, "[s]");
  requireInRange(sim.path("shape_interval"), sc.shape_interval, 1e-3, 1e7, "[s]");
  top.finish();
  return sc;
}

Scenario loadScenarioFile(const std::string& path)
{
  YAML::Node root;
  try
  {
    root = YAML::LoadFile(path);
  }
  catch (const YAML::Exception& e)
  {
    throw std::invalid_argument(path + ": cannot read the scenario: " + e.what());
  }
  return loadScenario(root, directoryOf(path));
}

YAML::Node toYaml(const Scenario& sc)
{
  YAML::Node root = toYaml(sc.config);
  YAML::Node ship = root["ship"];
  ship["tow_point"] = std::vector<double>{ sc.tow_point_S.x(), sc.tow_point_S.y(), sc.tow_point_S.z() };
  ship["start_position"] = std::vector<double>{ sc.start_position.x(), sc.start_position.y() };
  ship["start_heading"] = sc.start_heading;
  for (const Manoeuvre& m : sc.manoeuvres)
  {
    YAML::Node n;
    n["type"] = typeName(m.type);
    n["speed"] = m.speed;
    n["duration"] = m.duration;
    n["to_speed"] = m.to_speed;
    n["radius"] = m.radius;
    n["angle"] = m.angle;
    n["direction"] = m.direction > 0 ? "port" : "starboard";
    n["legs"] = m.legs;
    n["acceptance"] = m.acceptance;
    std::vector<double> points;
    for (const Eigen::Vector2d& p : m.points)
    {
      points.push_back(p.x());
      points.push_back(p.y());
    }
    n["points"] = points;
    ship["manoeuvres"].push_back(n);
  }
  for (const CommandEvent& e : sc.commands)
  {
    YAML::Node n;
    n["t"] = e.t;
    n["rudder"] = e.rudder;
    n["elevator"] = e.elevator;
    n["thrust"] = e.thrust;
    n["payout_rate"] = e.payout_rate;
    root["commands"].push_back(n);
  }
  if (sc.autopilot.enabled)
  {
    const AutopilotScenario& ap = sc.autopilot;
    const DepthAutopilotParams& p = ap.params;
    YAML::Node a = root["autopilot"];
    a["rate"] = ap.rate;
    a["kp"] = p.kp;
    a["ki"] = p.ki;
    a["kd"] = p.kd;
    a["max_elevator"] = p.max_elevator;
    a["track_keeping"] = p.track_keeping;
    a["rudder_kp"] = p.rudder_kp;
    a["rudder_kd"] = p.rudder_kd;
    a["max_rudder"] = p.max_rudder;
    a["track_spacing"] = p.track_spacing;
    a["track_length"] = p.track_length;
    a["thrust"] = p.thrust;
    a["odom_timeout"] = p.odom_timeout;
    a["max_depth"] = p.max_depth;
    a["setpoints"] = YAML::Node(YAML::NodeType::Sequence);
    for (const AutopilotSetpoint& sp : ap.setpoints)
    {
      YAML::Node n;
      n["t"] = sp.t;
      n[sp.altitude ? "altitude" : "depth"] = sp.value;
      a["setpoints"].push_back(n);
    }
  }
  YAML::Node init = root["initial_state"];
  const InitialShape& initial = sc.initial;
  init["type"] = initial.type == InitialShape::Type::kEquilibrium ? "equilibrium"
                 : initial.type == InitialShape::Type::kLine      ? "line"
                                                                  : "points";
  const Eigen::Vector3d& d = initial.line_direction_S;
  init["direction"] = std::vector<double>{ d.x(), d.y(), d.z() };
  if (initial.type == InitialShape::Type::kPoints)
    init["points"] = std::vector<double>(initial.points.data(), initial.points.data() + initial.points.size());
  root["simulation"]["duration"] = sc.duration;
  root["simulation"]["output_interval"] = sc.output_interval;
  root["simulation"]["shape_interval"] = sc.shape_interval;
  return root;
}

}  // namespace tow_sim
