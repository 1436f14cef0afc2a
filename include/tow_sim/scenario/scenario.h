// Batch scenarios (tow_sim_batch): the configuration plus a scripted ship, a command schedule, the
// initial state and the run's timing, read from YAML and written back with every default filled in.
// (Library tow_sim_scenario.)
#pragma once

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "tow_sim/config/config.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/ship_response.h"
#include "tow_sim/core/run/depth_autopilot.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/core/survey/survey_sensors.h"

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
  double angle = kPi;
  int direction = 1;
  int legs = 4;
  double acceptance = 30.0;
  std::vector<Eigen::Vector2d> points;
};

// One row of a measured ship motion file (ship.motion_file): the ship's reference point and attitude,
// world ENU, REP-103.
struct ShipMotionSample
{
  double t = 0.0;                             // [s]
  double x = 0.0, y = 0.0, z = 0.0;           // [m]
  double roll = 0.0, pitch = 0.0, yaw = 0.0;  // [rad]
};

// Reads a CSV with the columns t, x, y, z, roll, pitch, yaw (a header line first; # comments): at least two
// rows, times strictly increasing, every value finite. Throws std::invalid_argument naming the file and line.
std::vector<ShipMotionSample> loadShipMotionFile(const std::string& path);

struct Scenario
{
  SimulationConfig config;
  Eigen::Vector3d tow_point_S = Eigen::Vector3d(-20.0, 0.0, 0.0);  // [m] ship frame (FLU)
  Eigen::Vector2d start_position = Eigen::Vector2d::Zero();        // [m] ship, world
  double start_heading = 0.0;                                      // [rad] ENU, from +x counter-clockwise
  std::vector<Manoeuvre> manoeuvres;                               // one after the other
  // In waves the scripted ship heaves, rolls and pitches by its RAOs (rao_file, or the generic vessel's).
  bool wave_response = true;
  std::string rao_file;                  // CSV (RaoTable::fromCsvFile), absolute once loaded; "": the generic vessel
  std::shared_ptr<const RaoTable> rao;   // loaded from rao_file
  std::string motion_file;               // measured ship motion replayed instead of manoeuvres ("": none)
  std::vector<ShipMotionSample> motion;  // loaded from motion_file
  std::vector<CommandEvent> commands;    // sorted by time
  AutopilotLoop autopilot;  // the depth autopilot in the loop: gains, rate, setpoints; drives the fins when enabled
  InitialShape initial;     // equilibrium (default), line (direction in the ship frame) or points (world)
  double duration = 600.0;  // [s]
  double output_interval = 1.0;       // [s] timeseries.csv
  double shape_interval = 60.0;       // [s] shapes.csv
  std::vector<double> save_state_at;  // [s] output times at which the run's state is saved (sorted)
  SurveySensorParams sensors;         // survey sensors simulated into measurements.csv (sensors.enabled)
};

// Reads a scenario; throws std::invalid_argument naming the key, the value and the allowed range.
Scenario loadScenario(const YAML::Node& root, const std::string& base_dir = "");
Scenario loadScenarioFile(const std::string& path);
YAML::Node toYaml(const Scenario& scenario);

}  // namespace tow_sim
