// Loading the simulator's configuration (cable, vehicle, environment, numerics) from YAML, as written
// in config/tow_sim.yaml. The same loader serves the offline tools (a file) and the ROS node (its
// private parameters, converted to YAML), so every key is read, defaulted and checked in one place.
#pragma once

#include <string>
#include <yaml-cpp/yaml.h>

#include "tow_sim/core/params.h"
#include "tow_sim/core/vehicle.h"

namespace tow_sim
{
struct SimulationConfig
{
  CableParams cable;
  VehicleParams vehicle;
  Environment environment;
  NumericsParams numerics;
};

// Reads the sections `cable`, `vehicle`, `environment` and `numerics` of `root` (others are ignored;
// every section and key is optional and defaults to the documented value). Throws
// std::invalid_argument naming the full key path (prefixed by `prefix`, e.g. "/tow_sim/") for an
// unknown key, a wrong type, or a value out of its range.
SimulationConfig loadConfig(const YAML::Node& root, const std::string& prefix = "");
SimulationConfig loadConfigFile(const std::string& path);

// Writes a configuration back as YAML (every key, defaults filled in).
YAML::Node toYaml(const SimulationConfig& config);

}  // namespace tow_sim
