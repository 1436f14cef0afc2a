// Loading the simulator's configuration (cable, vehicle, environment, numerics, winch, seabed) from YAML, as written
// in config/tow_sim.yaml. The same loader serves the offline tools (a file) and the ROS node (its
// private parameters, converted to YAML), so every key is read, defaulted and checked in one place.
#pragma once

#include <yaml-cpp/yaml.h>
#include <string>

#include "tow_sim/core/run/simulation_config.h"

namespace tow_sim
{
// Reads the sections `cable`, `vehicle`, `environment`, `numerics`, `winch` and `seabed` of `root`
// (others are ignored; a relative seabed.grid_file is taken from `base_dir` when given;
// every section and key is optional and defaults to the documented value). Throws
// std::invalid_argument naming the full key path (prefixed by `prefix`, e.g. "/tow_sim/") for an
// unknown key, a wrong type, or a value out of its range.
SimulationConfig loadConfig(const YAML::Node& root, const std::string& prefix = "", const std::string& base_dir = "");
SimulationConfig loadConfigFile(const std::string& path);  // grid files relative to the file's directory

// The directory part of a path ("" for a bare file name), with a trailing slash.
std::string directoryOf(const std::string& path);
// A file named in a configuration, relative to `base_dir` unless absolute, made absolute (so that a
// configuration written back, e.g. the batch runner's scenario.yaml in another folder, names the same file).
std::string resolvePath(const std::string& file, const std::string& base_dir);

// Writes a configuration back as YAML (every key, defaults filled in).
YAML::Node toYaml(const SimulationConfig& config);

// Reads a bathymetry grid file: YAML {origin: [x, y], spacing: [dx, dy], depth: [[row at y0], [row at y0+dy],
// ...]}. Throws std::invalid_argument naming the file and the key.
BathymetryGrid loadBathymetryFile(const std::string& path);

}  // namespace tow_sim
