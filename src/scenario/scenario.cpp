#include "tow_sim/scenario/scenario.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "tow_sim/config/param_yaml.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/run/depth_autopilot.h"
#include "tow_sim/scenario/scenario_tables.h"

namespace tow_sim
{
namespace
{
using detail::fail;
using detail::ParamReader;
using detail::Section;
}  // namespace

const ParamTable<Scenario>& shipParams()
{
  using S = Scenario;
  static const ParamTable<S> table =
      ParamTable<S>()
          .vector3("tow_point", &S::tow_point_S, "m", -1000.0, 1000.0, "tow point in the ship frame (FLU)")
          .custom("start_position", "m", "[0, 0]", "[x, y]", "the ship's start, world")
          .number("start_heading", &S::start_heading, "rad", -100.0, 100.0, kClosed,
                  "ENU, counter-clockwise from +x (east)")
          .custom("manoeuvres", "", "[straight at 2 m/s for 60 s]", "a list (keys below)",
                  "one after the other; the speed carries over when omitted; straight on after the last")
          .boolean("wave_response", &S::wave_response,
                   "in environment.waves the scripted ship heaves, rolls and pitches by its RAOs (the tow point "
                   "with it)")
          .text("rao_file", &S::rao_file, "a readable CSV file, or empty",
                "the ship's RAOs (see The ship in waves); empty: the generic 60 m vessel; relative to the scenario")
          .text("motion_file", &S::motion_file, "a readable CSV file, or empty",
                "measured motion t, x, y, z, roll, pitch, yaw [s, m, rad] replayed instead of manoeuvres; relative "
                "to the scenario");
  return table;
}

const ParamTable<Manoeuvre>& manoeuvreParams()
{
  using M = Manoeuvre;
  static const ParamTable<M> table =
      ParamTable<M>()
          .choice("type", &M::type,
                  { { "straight", M::Type::kStraight },
                    { "speed_change", M::Type::kSpeedChange },
                    { "turn", M::Type::kTurn },
                    { "zigzag", M::Type::kZigzag },
                    { "waypoints", M::Type::kWaypoints } },
                  "see The scripted ship")
          .number("speed", &M::speed, "m/s", -15.0, 15.0, kClosed, "ship speed (the previous one when omitted)")
          .number("duration", &M::duration, "s", 0.0, 1e6, kOpen, "straight, speed_change")
          .number("to_speed", &M::to_speed, "m/s", -15.0, 15.0, kClosed, "speed_change: linear over duration")
          .number("radius", &M::radius, "m", 10.0, 1e5, kClosed, "turn, zigzag, waypoints: the tightest turn")
          .number("angle", &M::angle, "rad", 0.0, 100.0, kOpen, "turn: through this; zigzag: ± this about the course")
          .choice("direction", &M::direction, { { "port", 1 }, { "starboard", -1 } },
                  "turn, zigzag: first to this side")
          .integer("legs", &M::legs, "-", 1, 1000, "zigzag: swings")
          .number("acceptance", &M::acceptance, "m", 1.0, 1e4, kClosed, "waypoints: reached within this")
          .custom("points", "m", "[]", "x, y pairs", "waypoints: [x1, y1, x2, y2, …] world");
  return table;
}

const ParamTable<CommandEvent>& commandParams()
{
  using C = CommandEvent;
  static const ParamTable<C> table =
      ParamTable<C>()
          .number("t", &C::t, "s", 0.0, 1e7, kClosed, "from this time on")
          .number("rudder", &C::rudder, "rad", -kHalfPi, kHalfPi, kClosed, "then saturated by the vehicle's limits")
          .number("elevator", &C::elevator, "rad", -kHalfPi, kHalfPi, kClosed, "likewise")
          .number("thrust", &C::thrust, "N", -1e6, 1e6, kClosed, "likewise")
          .number("payout_rate", &C::payout_rate, "m/s", -20.0, 20.0, kClosed,
                  "winch (needs winch.enabled; saturated at winch.max_rate); omitted: 0")
          .number("differential", &C::differential, "rad", -kHalfPi, kHalfPi, kClosed,
                  "the elevator's differential, starboard fin +, port fin −: rolls a vehicle with roll: free to "
                  "port (saturated like the elevator); omitted: 0");
  return table;
}

const ParamTable<AutopilotLoop>& autopilotLoopParams()
{
  using A = AutopilotLoop;
  static const ParamTable<A> table =
      ParamTable<A>()
          .number("rate", &A::rate, "Hz", 0.1, 1000.0, kClosed, "fin commands")
          .nest("", &A::params, autopilotParams())
          .custom("setpoints", "s, m", "[] (hold the first depth)", "depth or altitude in [0, max_depth]",
                  "[{t: 100, depth: 221.8}, {t: 600, altitude: 25}]: each from its time on; altitude needs a seabed");
  return table;
}

const ParamTable<InitialShape>& initialStateParams()
{
  using I = InitialShape;
  static const ParamTable<I> table =
      ParamTable<I>()
          .choice("type", &I::type,
                  { { "equilibrium", I::Type::kEquilibrium },
                    { "line", I::Type::kLine },
                    { "hanging", I::Type::kHanging },
                    { "points", I::Type::kPoints },
                    { "file", I::Type::kFile } },
                  "the steady tow (a line if none is found), a line along direction, straight down, points, or a "
                  "saved state")
          .vector3("direction", &I::line_direction_S, "-", -1e6, 1e6,
                   "ship frame (FLU), not zero: the line's direction")
          .custom("points", "m", "[]", "3 (ν + 1) numbers", "joints x_2 … x_{ν+2}, world, x y z each")
          .text("path", &I::path, "a readable state file, for file",
                "a state saved by save_state_at or the node's ~save_state; relative to the scenario")
          .boolean("any_configuration", &I::any_configuration,
                   "for file: load a state saved under another configuration (else refused, naming the keys "
                   "that differ)");
  return table;
}

const ParamTable<Scenario>& simulationParams()
{
  using S = Scenario;
  static const ParamTable<S> table =
      ParamTable<S>()
          .number("duration", &S::duration, "s", 0.0, 1e7, kOpen, "simulated time")
          .number("output_interval", &S::output_interval, "s", 1e-3, 1e5, kClosed, "timeseries.csv rows")
          .number("shape_interval", &S::shape_interval, "s", 1e-3, 1e7, kClosed, "shapes.csv")
          .custom("save_state_at", "s", "[]", "output times in [0, duration]",
                  "the run's state is written at each (state_<t>.txt beside the CSVs; initial_state type file)");
  return table;
}

namespace
{
void readShipFiles(Section& ship, Scenario& sc, const std::string& base_dir)
{
  try
  {
    if (!sc.rao_file.empty())
    {
      sc.rao_file = resolvePath(sc.rao_file, base_dir);
      sc.rao = std::make_shared<const RaoTable>(RaoTable::fromCsvFile(sc.rao_file));
    }
    else if (sc.config.environment.waves.type != WaveParams::Type::kNone)  // (waves need gravity > 0)
      sc.rao = std::make_shared<const RaoTable>(RaoTable::genericVessel(sc.config.environment.gravity));
  }
  catch (const std::invalid_argument& e)
  {
    fail(ship.path("rao_file"), e.what());
  }
  if (sc.motion_file.empty())
    return;
  if (ship.has("manoeuvres"))
    fail(ship.path("motion_file"), "replaces the manoeuvres: give one or the other");
  try
  {
    sc.motion_file = resolvePath(sc.motion_file, base_dir);
    sc.motion = loadShipMotionFile(sc.motion_file);
  }
  catch (const std::invalid_argument& e)
  {
    fail(ship.path("motion_file"), e.what());
  }
}

void readShip(ParamReader r, Scenario& sc, const std::string& base_dir)
{
  r.read(shipParams(), sc);
  Section& ship = r.at("");
  readShipFiles(ship, sc, base_dir);
  const std::vector<double> start = ship.list("start_position");
  if (!start.empty() && start.size() != 2)
    fail(ship.path("start_position"), "must be [x, y] [m]");
  if (!start.empty())
    sc.start_position = Eigen::Vector2d(start[0], start[1]);
  double speed = 2.0;
  for (Section item : ship.items("manoeuvres"))
  {
    Manoeuvre m;
    m.speed = speed;
    ParamReader mr(item);
    mr.read(manoeuvreParams(), m);
    const std::vector<double> points = mr.at("").list("points");
    if (points.size() % 2 != 0)
      fail(item.path("points"), "must hold x, y pairs [m]: an even count of numbers");
    for (size_t i = 0; i + 1 < points.size(); i += 2)
      m.points.emplace_back(points[i], points[i + 1]);
    mr.finish();
    validateParams(manoeuvreParams(), m, item.name());
    if (m.type == Manoeuvre::Type::kWaypoints && m.points.empty())
      fail(item.path("points"), "the waypoints manoeuvre needs at least one [x, y] pair");
    sc.manoeuvres.push_back(m);
    speed = m.type == Manoeuvre::Type::kSpeedChange ? m.to_speed : m.speed;
  }
  r.finish();
  validateParams(shipParams(), sc, ship.name());
  if (sc.manoeuvres.empty())
    sc.manoeuvres.push_back(Manoeuvre());
}

void readCommands(Section& top, Scenario& sc)
{
  for (Section item : top.items("commands"))
  {
    CommandEvent e;
    ParamReader r(item);
    r.read(commandParams(), e);
    r.finish();
    if (e.payout_rate != 0.0 && !sc.config.winch.enabled)
      fail(item.path("payout_rate"), "needs the winch: winch.enabled is false");
    validateParams(commandParams(), e, item.name());
    sc.commands.push_back(e);
  }
  std::stable_sort(sc.commands.begin(), sc.commands.end(),
                   [](const CommandEvent& a, const CommandEvent& b) { return a.t < b.t; });
}

void readSetpoints(Section& a, const Scenario& sc, AutopilotLoop& ap)
{
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
    requireInRange(item.path(has_altitude ? "altitude" : "depth"), sp.value, 0.0, ap.params.max_depth, "[m]");
    if (sp.altitude && sc.config.seabed.type == SeabedParams::Type::kNone)
      fail(item.path("altitude"), "needs a seabed: seabed.type is none");
    ap.setpoints.push_back(sp);
  }
  std::stable_sort(ap.setpoints.begin(), ap.setpoints.end(),
                   [](const AutopilotSetpoint& x, const AutopilotSetpoint& y) { return x.t < y.t; });
}

void readAutopilot(Section& top, Scenario& sc)
{
  if (!top.has("autopilot"))
    return;
  AutopilotLoop& ap = sc.autopilot;
  ap.enabled = true;
  ParamReader r(top.child("autopilot"));
  r.read(autopilotLoopParams(), ap);
  validateParams(autopilotLoopParams(), ap, r.at("").name());  // before the setpoints, checked against max_depth
  readSetpoints(r.at(""), sc, ap);
  r.finish();
  for (std::size_t i = 0; i < sc.commands.size(); ++i)
  {
    const CommandEvent& c = sc.commands[i];
    if (c.rudder != 0.0 || c.elevator != 0.0 || c.thrust != 0.0)
      fail("commands[" + std::to_string(i) + "]",
           "rudder, elevator and thrust belong to the autopilot when there is one (payout_rate alone is allowed)");
  }
}

void readInitialState(Section& top, Scenario& sc, const std::string& base_dir)
{
  if (!top.has("initial_state"))
    return;
  ParamReader r(top.child("initial_state"));
  InitialShape& init = sc.initial;
  r.read(initialStateParams(), init);
  Section& s = r.at("");
  const std::vector<double> p = s.list("points");
  r.finish();
  validateParams(initialStateParams(), init, s.name());
  if (init.line_direction_S.norm() < 1e-9 || !init.line_direction_S.allFinite())
    fail(s.path("direction"), "must be a finite, non-zero [x, y, z] in the ship frame");
  if ((init.type == InitialShape::Type::kFile) != !init.path.empty())
    fail(s.path("path"), "is the saved state of type: file, and only of it");
  if (init.type == InitialShape::Type::kFile)
  {
    init.path = resolvePath(init.path, base_dir);
    std::ifstream probe(init.path);
    if (!probe)
      fail(s.path("path"), "cannot read " + init.path);
  }
  const size_t joints = static_cast<size_t>(sc.config.cable.segments) + 1;
  if (init.type != InitialShape::Type::kPoints)
    return;
  if (p.size() != 3 * joints)
    fail(s.path("points"), "must hold 3 (nu + 1) = " + std::to_string(3 * joints) +
                               " numbers (joints x_2 .. x_{nu+2}, world, x y z each); got " + std::to_string(p.size()));
  init.points = Eigen::Map<const Eigen::Matrix3Xd>(p.data(), 3, static_cast<Eigen::Index>(joints));
}

// Each save time an output time within the run (the state is saved where a row is written).
void checkSaveTimes(Scenario& sc, const std::string& key)
{
  for (double t : sc.save_state_at)
  {
    const double k = t / sc.output_interval;
    if (!(t >= 0.0 && t <= sc.duration) || std::abs(k - std::round(k)) > 1e-9 * std::max(1.0, k))
      fail(key, "must list output times (multiples of output_interval = " + std::to_string(sc.output_interval) +
                    " s) in [0, duration = " + std::to_string(sc.duration) + " s]; got " + std::to_string(t));
  }
  std::sort(sc.save_state_at.begin(), sc.save_state_at.end());  // after the check: no NaN to sort
}

Scenario loadScenarioUnguarded(const YAML::Node& root, const std::string& base_dir)
{
  if (!root || root.IsNull() || !root.IsMap())
    fail("scenario",
         "must be a mapping of sections (ship, commands, simulation, ...): the file is empty or not a "
         "mapping");
  Scenario sc;
  sc.config = loadConfig(root, "", base_dir);
  Section top(root, "scenario");
  for (const char* section : { "cable", "vehicle", "environment", "numerics", "winch", "seabed" })
    top.has(section);
  readShip(ParamReader(top.child("ship")), sc, base_dir);
  readCommands(top, sc);
  readAutopilot(top, sc);
  readInitialState(top, sc, base_dir);
  if (top.has("sensors"))
  {
    ParamReader sensors(top.child("sensors"));
    sc.sensors.enabled = true;
    sensors.read(surveySensorParams(), sc.sensors);
    sensors.finish();
    validate(sc.sensors, sensors.at("").name());
  }
  ParamReader simulation(top.child("simulation"));
  simulation.read(simulationParams(), sc);
  sc.save_state_at = simulation.at("").list("save_state_at");
  simulation.finish();
  validateParams(simulationParams(), sc, simulation.at("").name());
  checkSaveTimes(sc, simulation.at("").path("save_state_at"));
  top.finish();
  if (!sc.motion.empty() && (sc.motion.front().t > 0.0 || sc.motion.back().t < sc.duration))
    fail("ship.motion_file", "covers t = " + std::to_string(sc.motion.front().t) + " .. " +
                                 std::to_string(sc.motion.back().t) +
                                 " s; the run needs 0 .. simulation.duration = " + std::to_string(sc.duration) + " s");
  return sc;
}
}  // namespace

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
  try
  {
    return loadScenario(root, directoryOf(path));
  }
  catch (const std::invalid_argument& e)
  {
    if (!root || root.IsNull() || !root.IsMap())
      throw std::invalid_argument(path + ": " + e.what());
    throw;
  }
}

namespace
{
void writeShip(YAML::Node ship, const Scenario& sc)
{
  detail::writeParams(ship, shipParams(), sc);
  ship["start_position"] = std::vector<double>{ sc.start_position.x(), sc.start_position.y() };
  if (!sc.motion_file.empty())
    return;  // the motion file replaces the manoeuvres
  for (const Manoeuvre& m : sc.manoeuvres)
  {
    YAML::Node n(YAML::NodeType::Map);  // a map already: writeParams fills a copy of the handle
    detail::writeParams(n, manoeuvreParams(), m);
    std::vector<double> points;
    for (const Eigen::Vector2d& p : m.points)
    {
      points.push_back(p.x());
      points.push_back(p.y());
    }
    n["points"] = points;
    ship["manoeuvres"].push_back(n);
  }
}

void writeAutopilot(YAML::Node a, const AutopilotLoop& ap)
{
  detail::writeParams(a, autopilotLoopParams(), ap);
  a["setpoints"] = YAML::Node(YAML::NodeType::Sequence);
  for (const AutopilotSetpoint& sp : ap.setpoints)
  {
    YAML::Node n;
    n["t"] = sp.t;
    n[sp.altitude ? "altitude" : "depth"] = sp.value;
    a["setpoints"].push_back(n);
  }
}
}  // namespace

YAML::Node toYaml(const Scenario& sc)
{
  YAML::Node root = toYaml(sc.config);
  writeShip(root["ship"], sc);
  for (const CommandEvent& e : sc.commands)
  {
    YAML::Node n(YAML::NodeType::Map);
    detail::writeParams(n, commandParams(), e);
    root["commands"].push_back(n);
  }
  if (sc.autopilot.enabled)
    writeAutopilot(root["autopilot"], sc.autopilot);
  YAML::Node init = root["initial_state"];
  detail::writeParams(init, initialStateParams(), sc.initial);
  if (sc.initial.type == InitialShape::Type::kPoints)
    init["points"] = std::vector<double>(sc.initial.points.data(), sc.initial.points.data() + sc.initial.points.size());
  if (sc.sensors.enabled)
    detail::writeParams(root["sensors"], surveySensorParams(), sc.sensors);
  detail::writeParams(root["simulation"], simulationParams(), sc);
  if (!sc.save_state_at.empty())
    root["simulation"]["save_state_at"] = sc.save_state_at;
  return root;
}

}  // namespace tow_sim
