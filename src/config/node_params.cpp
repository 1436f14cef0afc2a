#include "tow_sim/config/node_params.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "tow_sim/config/param_yaml.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/run/depth_autopilot.h"

namespace tow_sim
{
namespace
{
// A node's world frame and its child frame (`child_key`): non-empty and different.
void requireDistinctFrames(const std::string& world, const std::string& child, const std::string& child_key,
                           const std::string& prefix)
{
  if (world.empty() || child.empty() || world == child)
    throw std::invalid_argument(prefix + child_key + ": world_frame and " + child_key +
                                " must be non-empty and different");
}

}  // namespace

const ParamTable<NodeParams>& nodeParams()
{
  using N = NodeParams;
  static const ParamTable<N> table =
      ParamTable<N>()
          .text("world_frame", &N::world_frame, "non-empty", "frame of ship/odom, current and every output")
          .text("vehicle_frame", &N::vehicle_frame, "≠ world_frame", "tf child frame of the vehicle CG")
          .vector3("tow_point", &N::tow_point_S, "m", -1000.0, 1000.0, "tow point in the ship frame (FLU)")
          .number("physics_rate", &N::physics_rate, "Hz", 1.0, 1000.0, kClosed,
                  "integration ticks: dopri5 and rk4 end a step at each, the implicit steppers take their own")
          .number("publish_rate", &N::publish_rate, "Hz", 0.1, 100.0, kClosed,
                  "state, markers, odometry, fin loads, tf")
          .number("odom_delay", &N::odom_delay, "s", 0.0, 10.0, kClosed,
                  "the simulation runs this far behind the clock, to interpolate between odometry messages")
          .number("max_command_lag", &N::max_command_lag, "s", 0.001, 10.0, kClosed,
                  "the adaptive implicit stepper's steps are capped at this (and numerics.max_step): a "
                  "command from another node acts from the end of the step under way")
          .number("max_tick_wall", &N::max_tick_wall, "s", 0.001, 10.0, kClosed,
                  "a physics tick integrates at most 0.5 s of simulated time and, judged by the previous "
                  "ticks' cost, about this much wall time (at least one step): callbacks never wait long")
          .number("max_extrapolation", &N::max_extrapolation, "s", 0.0, 60.0, kClosed,
                  "past the newest odometry; then the simulation holds")
          .number("max_ship_speed", &N::max_ship_speed, "m/s", 0.0, 1000.0, kOpen,
                  "odometry faster than this, or jumping farther, is rejected; a velocity taken from the "
                  "positions (the twist contradicted) is clamped to it")
          .integer("reacquire_after", &N::reacquire_after, "messages", 2, 1000,
                   "odometry refused as a jump this many times in a row, consistent among itself, is the ship: "
                   "the cable is laid out again there (a GPS's (0, 0, 0) before its fix)")
          .number("max_odom_age", &N::max_odom_age, "s", 0.0, 1e6, kOpen,
                  "odometry stamped more than this before the clock is rejected (a publisher on another clock)")
          .choice("initial_shape", &N::initial_shape,
                  { { "equilibrium", "equilibrium" }, { "line", "line" }, { "hanging", "hanging" } },
                  "the steady tow at the ship's velocity (a line if none is found), straight astern at "
                  "initial_angle, or straight down")
          .number("initial_angle", &N::initial_angle, "rad", 0.0, kHalfPi, kClosed, "below the horizontal, for line")
          .number("tension_color_max", &N::tension_color_max, "N", 0.0, 1e9, kOpen, "red end of the colour scale")
          .number("force_arrow_scale", &N::force_arrow_scale, "m/N", 0.0, 10.0, kOpen, "tow-force arrow per newton")
          .number("cable_marker_width", &N::cable_marker_width, "m", 0.0, 100.0, kOpen, "drawn cable width")
          .number("vehicle_diameter", &N::vehicle_diameter, "m", 0.0, 100.0, kOpen, "drawn hull diameter")
          .number("ship_length", &N::ship_length, "m", 0.0, 1000.0, kOpen,
                  "drawn ship hull outline, centred on the odometry's reference point")
          .number("ship_beam", &N::ship_beam, "m", 0.0, 200.0, kOpen, "drawn ship hull width")
          .number("vehicle_marker_scale", &N::vehicle_marker_scale, "-", 1.0, 1000.0, kClosed,
                  "the vehicle's markers drawn this many times their size about its centre, half transparent "
                  "above 1 (a 2 m towfish is a few pixels in a view of the whole tow); its label says so")
          .number("label_height", &N::label_height, "m", 0.0, 1000.0, kOpen,
                  "text height of the ship's tension label (the vehicle's: half of it)")
          .text("view_frame", &N::view_frame, "a frame name or empty",
                "tf child frame of world_frame midway between the tow point and the vehicle, world-aligned: "
                "rviz's default view of the whole tow follows it (empty: not published)")
          .number("trail_duration", &N::trail_duration, "s", 0.0, 86400.0, kClosed,
                  "drawn tracks of the ship and the vehicle over this time (0: none)")
          .boolean("print_status", &N::print_status, "a status line each second (the launch file sets it)");
  return table;
}

void validate(const NodeParams& p, const std::string& prefix)
{
  validateParams(nodeParams(), p, prefix);
  requireDistinctFrames(p.world_frame, p.vehicle_frame, "vehicle_frame", prefix);
  if (!p.view_frame.empty() && (p.view_frame == p.world_frame || p.view_frame == p.vehicle_frame))
    throw std::invalid_argument(prefix + "view_frame = '" + p.view_frame +
                                "' must differ from world_frame and vehicle_frame (or be empty: none)");
}

const ParamTable<AutopilotNodeParams>& autopilotNodeParams()
{
  using A = AutopilotNodeParams;
  static const ParamTable<A> table = ParamTable<A>()
                                         .number("rate", &A::rate, "Hz", 0.1, 1000.0, kClosed, "fins/command")
                                         .nest("", &A::controller, autopilotParams())
                                         .text("world_frame", &A::world_frame, "non-empty", "frame of both odometries")
                                         .text("plan_service", &A::plan_service, "a service name, or empty",
                                               "tow_sim_node's ~plan_cable_out (relative to the node's namespace), "
                                               "asked for the winch's feed-forward at each depth setpoint; empty: "
                                               "none, the cable out at the first cable/state stands in")
                                         .boolean("setpoint_marker", &A::setpoint_marker,
                                                  "an interactive marker (~setpoint_marker) at the vehicle to drag "
                                                  "the depth setpoint in rviz");
  return table;
}

void validate(const AutopilotNodeParams& p, const std::string& prefix)
{
  validateParams(autopilotNodeParams(), p, prefix);
  if (p.world_frame.empty())
    throw std::invalid_argument(prefix + "world_frame: must be a non-empty string");
}

const ParamTable<ShipMotionParams>& shipMotionParams()
{
  using S = ShipMotionParams;
  static const ParamTable<S> table =
      ParamTable<S>()
          .text("manoeuvre", &S::manoeuvre, "straight, turn, zigzag, speed_change or waypoints",
                "the preset: turn after turn_start for good, zigzag from turn_start, speed_change at change_time, "
                "waypoints in order (straight on after the last)")
          .number("speed", &S::speed, "m/s", -15.0, 15.0, kClosed, "through the water (negative: astern)")
          .number("speed_2", &S::speed_2, "m/s", -15.0, 15.0, kClosed, "speed_change: the speed after it")
          .number("change_time", &S::change_time, "s", 0.0, 1e6, kClosed, "speed_change: when it begins")
          .number("change_duration", &S::change_duration, "s", 0.0, 1e6, kOpen, "speed_change: over this time")
          .number("turn_radius", &S::turn_radius, "m", -1e5, 1e5, kClosed,
                  "turn, zigzag, waypoints: positive to port, magnitude at least 10 (zigzag: the swing's rate is "
                  "speed / turn_radius, its amplitude that times zigzag_period / 4)")
          .number("turn_start", &S::turn_start, "s", 0.0, 1e6, kClosed, "turn, zigzag: straight until then")
          .number("zigzag_period", &S::zigzag_period, "s", 0.0, 1e6, kOpen, "zigzag: one full swing")
          .number("waypoint_radius", &S::waypoint_radius, "m", 1.0, 1e4, kClosed, "waypoints: reached within this")
          .custom("waypoints", "m", "[]", "x, y pairs", "waypoints: [x1, y1, x2, y2, …] world")
          .number("heading", &S::heading, "rad", -10.0, 10.0, kClosed, "at the start, from +x toward +y")
          .number("rate", &S::rate, "Hz", 1.0, 1000.0, kClosed, "ship/odom and tf")
          .text("world_frame", &S::world_frame, "non-empty", "frame of ship/odom")
          .text("ship_frame", &S::ship_frame, "≠ world_frame", "child frame of ship/odom and the tf")
          .boolean("wave_response", &S::wave_response,
                   "heave, roll and pitch by the RAOs in the configuration's environment.waves (false: level)")
          .text("rao_file", &S::rao_file, "a CSV file, or empty", "the ship's RAOs (empty: the generic vessel's)");
  return table;
}

void validate(const ShipMotionParams& p, const std::string& prefix)
{
  validateParams(shipMotionParams(), p, prefix);
  const std::vector<std::string> known = { "straight", "turn", "zigzag", "speed_change", "waypoints" };
  if (std::find(known.begin(), known.end(), p.manoeuvre) == known.end())
    throw std::invalid_argument(prefix + "manoeuvre = '" + p.manoeuvre +
                                "' must be straight, turn, zigzag, speed_change or waypoints");
  if (!(std::abs(p.turn_radius) >= 10.0))
  {
    std::ostringstream why;
    why << prefix << "turn_radius = " << p.turn_radius << " must have a magnitude in [10, 1e5] [m]";
    throw std::invalid_argument(why.str());
  }
  if (p.manoeuvre == "waypoints" && p.waypoints.empty())
    throw std::invalid_argument(prefix + "waypoints: the waypoints manoeuvre needs at least one [x, y] pair");
  requireDistinctFrames(p.world_frame, p.ship_frame, "ship_frame", prefix);
}

ShipMotionParams readShipMotionParams(const YAML::Node& params, const std::string& name)
{
  ShipMotionParams p;
  detail::ParamReader reader(detail::Section(params, name));
  reader.read(shipMotionParams(), p);
  const std::vector<double> points = reader.at("").list("waypoints");
  if (points.size() % 2 != 0)
    throw std::invalid_argument(name + ".waypoints must hold x, y pairs [m]: an even count of numbers, got " +
                                std::to_string(points.size()));
  for (size_t i = 0; i + 1 < points.size(); i += 2)
    p.waypoints.emplace_back(points[i], points[i + 1]);
  validate(p, name + ".");
  return p;
}

// The keys of a geodetic origin, for the nodes that take GNSS fixes (S has the four members).
template <class S>
ParamTable<S> withGeodeticOrigin(ParamTable<S> table)
{
  table
      .boolean("origin_from_first_fix", &S::origin_from_first_fix,
               "the first good fix is the ENU origin (else origin_latitude, _longitude, _altitude)")
      .number("origin_latitude", &S::origin_latitude, "deg", -90.0, 90.0, kClosed, "WGS84, north positive")
      .number("origin_longitude", &S::origin_longitude, "deg", -180.0, 180.0, kClosed, "WGS84, east positive")
      .number("origin_altitude", &S::origin_altitude, "m", -1e4, 1e4, kClosed, "above the WGS84 ellipsoid");
  return table;
}

const ParamTable<GnssShipParams>& gnssShipParams()
{
  using G = GnssShipParams;
  static const ParamTable<G> table =
      withGeodeticOrigin(ParamTable<G>())
          .vector3("antenna", &G::antenna_S, "m", -1000.0, 1000.0, "the GNSS antenna in the ship frame (FLU)")
          .number("smoothing_time", &G::smoothing_time, "s", 0.0, 600.0, kClosed,
                  "time constant of the alpha-beta tracker that smooths the fixes and gives the velocity (0: none)")
          .boolean("use_altitude", &G::use_altitude, "the ship's z from the fixes' altitude (else z = 0)")
          .choice("heading_convention", &G::heading_convention, { { "enu", "enu" }, { "compass", "compass" } },
                  "ship/heading's yaw: enu from east toward north (REP-103), compass from north clockwise")
          .number("max_heading_age", &G::max_heading_age, "s", 0.0, 60.0, kOpen,
                  "a fix is used with the newest heading if their stamps are at most this far apart")
          .text("world_frame", &G::world_frame, "non-empty", "frame of ship/odom (ENU about the origin)")
          .text("ship_frame", &G::ship_frame, "≠ world_frame", "child frame of ship/odom and the tf")
          .boolean("publish_tf", &G::publish_tf, "the tf world_frame -> ship_frame");
  return table;
}

void validate(const GnssShipParams& p, const std::string& prefix)
{
  validateParams(gnssShipParams(), p, prefix);
  requireDistinctFrames(p.world_frame, p.ship_frame, "ship_frame", prefix);
}

const ParamTable<TowNavNodeParams>& towNavNodeParams()
{
  using N = TowNavNodeParams;
  static const ParamTable<N> table =
      withGeodeticOrigin(ParamTable<N>())
          .choice("heading_convention", &N::heading_convention, { { "enu", "enu" }, { "compass", "compass" } },
                  "survey/ship/heading's yaw: enu from east toward north (REP-103), compass from north clockwise")
          .choice("depth_source", &N::depth_source, { { "depth", "depth" }, { "pressure", "pressure" } },
                  "the fish's depth from survey/fish/depth, or from survey/fish/pressure (absolute)")
          .number("atmospheric_pressure", &N::atmospheric_pressure, "Pa", 0.0, 2e5, kClosed,
                  "taken off survey/fish/pressure before dividing by the water's density times g")
          .number("hold", &N::hold, "s", 0.0, 30.0, kClosed,
                  "a measurement waits this long for the others of its instant (more than the sensors' transport "
                  "delay; the estimate is this much behind the clock)")
          .number(
              "max_ship_gap", &N::max_ship_gap, "s", 0.0, 60.0, kOpen,
              "a USBL fix is placed between the ship's fixes (and headings) on both sides of its stamp, at most twice "
              "this apart; without them it is refused")
          .number("rate", &N::rate, "Hz", 0.1, 100.0, kClosed, "the estimate's updates and outputs")
          .text("world_frame", &N::world_frame, "non-empty", "the estimate's frame (ENU about the origin)")
          .text("ship_frame", &N::ship_frame, "≠ world_frame", "the frame_id survey/usbl's fixes must have")
          .text("fish_frame", &N::fish_frame, "≠ world_frame", "child frame of the estimate's tf")
          .boolean("publish_tf", &N::publish_tf, "the tf world_frame -> fish_frame");
  return table;
}

void validate(const TowNavNodeParams& p, const std::string& prefix)
{
  validateParams(towNavNodeParams(), p, prefix);
  requireDistinctFrames(p.world_frame, p.ship_frame, "ship_frame", prefix);
  requireDistinctFrames(p.world_frame, p.fish_frame, "fish_frame", prefix);
}

TowNavNodeParams readTowNavNodeParams(const YAML::Node& params, const std::string& name)
{
  TowNavNodeParams p;
  detail::ParamReader reader(detail::Section(params, name));
  reader.read(towNavNodeParams(), p);
  reader.finish();
  validate(p, name + ".");
  return p;
}

const ParamTable<ReplayParams>& replayParams()
{
  using R = ReplayParams;
  static const ParamTable<R> table =
      ParamTable<R>()
          .text("run", &R::run, "a folder with shapes.csv", "the tow_sim_batch run to replay (required)")
          .number("speed", &R::speed, "-", 0.0, 1e4, kOpen, "simulated seconds per wall second")
          .number("publish_rate", &R::publish_rate, "Hz", 0.1, 100.0, kClosed, "wall time: /clock and cable/markers")
          .boolean("loop", &R::loop, "start again after the last shape (else hold it)")
          .text("world_frame", &R::world_frame, "non-empty", "frame of the markers")
          .text("vehicle_frame", &R::vehicle_frame, "≠ world_frame",
                "tf child frame at the vehicle's element (bail to tail midpoint, x forward): the close-up view's")
          .text("view_frame", &R::view_frame, "a frame name or empty",
                "tf child frame midway between the tow point and the vehicle, world-aligned: the view of the whole "
                "tow follows it (empty: not published)")
          .number("tension_color_max", &R::tension_color_max, "N", 0.0, 1e9, kOpen, "red end of the colour scale")
          .number("cable_marker_width", &R::cable_marker_width, "m", 0.0, 100.0, kOpen, "drawn cable width");
  return table;
}

void validate(const ReplayParams& p, const std::string& prefix)
{
  validateParams(replayParams(), p, prefix);
  if (p.run.empty())
    throw std::invalid_argument(prefix + "run: must name a tow_sim_batch output folder (with shapes.csv)");
  requireDistinctFrames(p.world_frame, p.vehicle_frame, "vehicle_frame", prefix);
}

}  // namespace tow_sim
