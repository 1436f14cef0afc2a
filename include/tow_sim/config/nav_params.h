// tow_nav's parameters from a configuration file: its `nav:` section (towNavParams(), tow_nav.h) and the
// node's top-level `tow_point`. (Library tow_sim_config.)
#pragma once

#include <yaml-cpp/yaml.h>
#include <string>

#include "tow_sim/core/survey/tow_nav.h"

namespace tow_sim
{
// Throws std::invalid_argument naming the key (under `prefix`), the value and the range.
TowNavParams loadNavParams(const YAML::Node& root, const std::string& prefix = "");

}  // namespace tow_sim
