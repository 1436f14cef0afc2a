#include "tow_sim/config/node_params.h"

#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/run/depth_autopilot.h"

namespace tow_sim
{
namespace
{
// The node's and tow_sim_replay's world and vehicle frames: non-empty and different.
void requireDistinctFrames(const std::string& world, const std::string& vehicle, const std::string& prefix)
{
  if (world.empty() || vehicle.empty() || world == vehicle)
    throw std::invalid_argument(prefix +
                                "vehicle_frame: world_frame and vehicle_frame must be non-empty and different");
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
          .number("trail_duration", &N::trail_duration, "s", 0.0, 86400.0, kClosed,
                  "drawn tracks of the ship and the vehicle over this time (0: none)")
          .boolean("print_status", &N::print_status, "a status line each second (the launch file sets it)");
  return table;
}

void validate(const NodeParams& p, const std::string& prefix)
{
  validateParams(nodeParams(), p, prefix);
  requireDistinctFrames(p.world_frame, p.vehicle_frame, prefix);
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
                "tf child frame at the vehicle's element (bail to tail midpoint, x forward): rviz's view follows it")
          .number("tension_color_max", &R::tension_color_max, "N", 0.0, 1e9, kOpen, "red end of the colour scale")
          .number("cable_marker_width", &R::cable_marker_width, "m", 0.0, 100.0, kOpen, "drawn cable width");
  return table;
}

void validate(const ReplayParams& p, const std::string& prefix)
{
  validateParams(replayParams(), p, prefix);
  if (p.run.empty())
    throw std::invalid_argument(prefix + "run: must name a tow_sim_batch output folder (with shapes.csv)");
  requireDistinctFrames(p.world_frame, p.vehicle_frame, prefix);
}

}  // namespace tow_sim
