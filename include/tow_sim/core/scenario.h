// Batch scenarios (tow_sim_batch): the configuration plus a scripted ship, a command schedule, the
// initial state and the run's timing, read from YAML and written back with every default filled in.
#pragma once

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "tow_sim/core/config.h"
#include "tow_sim/core/depth_autopilot.h"
#include "tow_sim/core/ship_track.h"

namespace tow_sim
{
struct Manoeuvre
{
  enum class Type
  {
    kStraight,     // speed [m/s] for duration [s]
    kSpeedChange,  // to_speed [m/s] over duration [s], linearly
    kTurn,         // at speed, radius [m], through angle [rad], direction +1 port / -1 starboard
    kZigzag,       // at speed and radius, heading swings +-angle about the heading at its start, `legs` times
    kWaypoints     // at speed, turning no tighter than radius, through points [x, y] reached within acceptance
  };
  Type type = Type::kStraight;
  double speed = 2.0;
  double duration = 60.0;
  double to_speed = 1.0;
  double radius = 200.0;
  double angle = 3.14159265358979323846;
  int direction = 1;
  int legs = 4;
  double acceptance = 30.0;
  std::vector<Eigen::Vector2d> points;
};

struct CommandEvent
{
  double t = 0.0;            // [s]
  double rudder = 0.0;       // [rad]
  double elevator = 0.0;     // [rad]
  double thrust = 0.0;       // [N]
  double payout_rate = 0.0;  // [m/s] winch, positive pays out (needs winch.enabled)
};

// The depth autopilot in the loop (tow_sim_batch): its gains, its rate and a setpoint schedule.
struct AutopilotSetpoint
{
  double t = 0.0;         // [s] from this time on
  bool altitude = false;  // false: `value` is a depth [m, positive down]; true: an altitude above the seabed [m]
  double value = 0.0;     // [m]
};
struct AutopilotScenario
{
  bool enabled = false;
  DepthAutopilotParams params;
  double rate = 10.0;                        // [Hz] fin commands, [0.1, 1000]
  std::vector<AutopilotSetpoint> setpoints;  // sorted by time; none: hold the first depth
};

struct Scenario
{
  SimulationConfig config;
  Eigen::Vector3d tow_point_S = Eigen::Vector3d(-20.0, 0.0, 0.0);  // [m] ship frame (FLU)
  Eigen::Vector2d start_position = Eigen::Vector2d::Zero();        // [m] ship, world
  double start_heading = 0.0;                                      // [rad] ENU, from +x counter-clockwise
  std::vector<Manoeuvre> manoeuvres;                               // one after the other
  std::vector<CommandEvent> commands;                              // sorted by time
  AutopilotScenario autopilot;                                     // drives the fins when enabled
  enum class Start
  {
    kEquilibrium,
    kLine,
    kPoints
  } start = Start::kEquilibrium;
  Eigen::Vector3d line_direction_S = Eigen::Vector3d(-1.0, 0.0, -0.5);  // ship frame, for `line`
  Eigen::Matrix3Xd points;                                              // joints x_2 .. x_{nu+2}, for `points`
  double duration = 600.0;                                              // [s]
  double output_interval = 1.0;                                         // [s] timeseries.csv
  double shape_interval = 60.0;                                         // [s] shapes.csv
};

// Reads a scenario; throws std::invalid_argument naming the key, the value and the allowed range.
Scenario loadScenario(const YAML::Node& root, const std::string& base_dir = "");
Scenario loadScenarioFile(const std::string& path);
YAML::Node toYaml(const Scenario& scenario);

// The ship's reference point moved through the manoeuvres, sampled every `dt` up to `duration`: speed
// slews at most 0.1 m/s^2 and the yaw rate follows its target with a 2 s lag, so the track (and the tow
// point built from it) has continuous acceleration.
struct ShipPath
{
  ShipTrack tow_point;                // tow point, world
  std::vector<double> t;              // [s] sample times
  std::vector<Eigen::Vector3d> pose;  // x [m], y [m], heading [rad] of the ship
  std::vector<double> speed;          // [m/s]
  // Ship pose at time t (linear between samples).
  Eigen::Vector3d poseAt(double time) const;
  double speedAt(double time) const;
};
ShipPath buildShipPath(const Scenario& scenario, double dt = 0.05);

}  // namespace tow_sim
