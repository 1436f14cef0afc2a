// Loading the simulator's configuration (cable, vehicle, environment, numerics) from YAML, as written
// in config/tow_sim.yaml. The same loader serves the offline tools (a file) and the ROS node (its
// private parameters, converted to YAML), so every key is read, defaulted and checked in one place.
#pragma once

#include <yaml-cpp/yaml.h>
#include <string>

#include "tow_sim/core/params.h"
#include "tow_sim/core/seabed.h"
#include "tow_sim/core/vehicle.h"

namespace tow_sim
{
struct SimulationConfig
{
  CableParams cable;
  VehicleParams vehicle;
  Environment environment;
  NumericsParams numerics;
  WinchParams winch;
  SeabedParams seabed;  // its grid already read from seabed.grid_file
};

// Reads the sections `cable`, `vehicle`, `environment`, `numerics`, `winch` and `seabed` of `root`
// (others are ignored; a relative seabed.grid_file is taken from `base_dir` when given;
// every section and key is optional and defaults to the documented value). Throws
// std::invalid_argument naming the full key path (prefixed by `prefix`, e.g. "/tow_sim/") for an
// unknown key, a wrong type, or a value out of its range.
SimulationConfig loadConfig(const YAML::Node& root, const std::string& prefix = "", const std::string& base_dir = "");
SimulationConfig loadConfigFile(const std::string& path);  // grid files relative to the file's directory

// The directory part of a path ("" for a bare file name), with a trailing slash.
std::string directoryOf(const std::string& path);

// Writes a configuration back as YAML (every key, defaults filled in).
YAML::Node toYaml(const SimulationConfig& config);

}  // namespace tow_sim
