// Conversions between Python objects and the core's inputs and outputs for the Python module (tow_sim._core,
// docs/python.md): dicts to YAML nodes, so that a dict is read by the very loader a file is, and snapshots to
// NumPy arrays and dicts.
#pragma once

#include <pybind11/pybind11.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tow_sim/core/run/tow_run.h"

namespace tow_sim::python
{
// A dict (nested dicts, lists, tuples, NumPy arrays, str, bool, int, float, None) as the YAML node a file with
// the same content would give. Throws std::invalid_argument naming `path` and the key for any other value.
YAML::Node toYamlNode(const pybind11::handle& value, const std::string& path);

// A finite number (int, float, NumPy's); std::invalid_argument naming `name` otherwise.
double number(const pybind11::handle& value, const std::string& name);

// A 3-vector from a sequence of three numbers; std::invalid_argument naming `name` otherwise.
Eigen::Vector3d vector3(const pybind11::handle& value, const std::string& name);

// A list of dicts {t, rudder, elevator, thrust, payout_rate} as commands (CommandEvent); None: none.
// std::invalid_argument naming commands[i].key for an unknown key or a value that is not finite.
std::vector<CommandEvent> commandList(const pybind11::handle& commands);

// The columns of timeseries.csv (batch_run.h) as a dict of NumPy arrays from rows of timeseriesValues.
pybind11::dict seriesDict(const std::string& header, const std::vector<std::vector<double>>& rows);

// Registers the Snapshot class (a TowSnapshot's outputs as properties and NumPy arrays).
void bindSnapshot(pybind11::module_& m);

}  // namespace tow_sim::python
