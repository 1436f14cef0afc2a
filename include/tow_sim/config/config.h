// Loading the simulator's configuration (cable, vehicle, environment, numerics, winch, seabed) from YAML, as written
// in config/tow_sim.yaml. The same loader serves the offline tools (a file) and the ROS node (its
// private parameters, converted to YAML), so every key is read, defaulted and checked in one place.
#pragma once

#include <yaml-cpp/yaml.h>
#include <map>
#include <string>
#include <vector>

#include "tow_sim/core/run/simulation_config.h"

namespace tow_sim
{
// Reads the sections `cable`, `vehicle`, `environment`, `numerics`, `winch` and `seabed` of `root`
// (other top-level keys are the caller's to check: requireKnownKeys; a relative seabed.grid_file is taken from
// `base_dir` when given; every section and key is optional and defaults to the documented value). Throws
// std::invalid_argument naming the full key path (prefixed by `prefix`, e.g. "/tow_sim/") for an
// unknown key, a wrong type, or a value out of its range.
SimulationConfig loadConfig(const YAML::Node& root, const std::string& prefix = "", const std::string& base_dir = "");
// A configuration file: loadConfig, grid files relative to the file's directory, and every top-level key one
// of configurationFileKeys().
SimulationConfig loadConfigFile(const std::string& path);

// The top-level keys a configuration file may hold, so that a misspelt one is refused: the six sections,
// tow_sim_node's own parameters (NodeParams: the file is loaded into its private namespace) and
// tow_sim_urdf's sensor_frames, tow_sim_nav's nav and the survey sensors. One file serves the node, the ship,
// the chart, the URDF and the towfish estimator.
std::vector<std::string> configurationFileKeys();
// Refuses a top-level key of `root` outside `known`, naming it under `prefix` ("" or "/node/") with the
// nearest known key (std::invalid_argument).
void requireKnownKeys(const YAML::Node& root, const std::string& prefix, const std::vector<std::string>& known);

// The directory part of a path ("" for a bare file name), with a trailing slash.
std::string directoryOf(const std::string& path);
// A file named in a configuration, relative to `base_dir` unless absolute, made absolute (so that a
// configuration written back, e.g. the batch runner's scenario.yaml in another folder, names the same file).
std::string resolvePath(const std::string& file, const std::string& base_dir);

// Writes a configuration back as YAML (every key, defaults filled in).
YAML::Node toYaml(const SimulationConfig& config);

// The configuration's keys and values as text, flattened from toYaml: `cable.length` "500", a list's items as
// `cable.sections[0].length`, an empty list "[]". What a saved state records (RunState::configuration).
std::map<std::string, std::string> configurationKeys(const SimulationConfig& config);
// Throws std::invalid_argument when a saved state's configuration (not empty: recorded) differs from
// `config`'s keys, naming the keys that differ (up to 8) with their saved and current values, then `hint`
// (how to load it all the same). A key the state lacks (added to tow_sim after it was saved) differs only when
// its value now is not its default.
void requireSameConfiguration(const std::map<std::string, std::string>& saved, const SimulationConfig& config,
                              const std::string& hint);
// The same against keys already flattened (configurationKeys).
void requireSameConfiguration(const std::map<std::string, std::string>& saved,
                              const std::map<std::string, std::string>& now, const std::string& hint);

// Reads a bathymetry grid file: YAML {origin: [x, y], spacing: [dx, dy], depth: [[row at y0], [row at y0+dy],
// ...]}. Throws std::invalid_argument naming the file and the key.
BathymetryGrid loadBathymetryFile(const std::string& path);

}  // namespace tow_sim
