// tow_nav's parameters from a configuration file: its `nav:` section (towNavParams(), tow_nav.h) and the
// node's top-level `tow_point`; and the survey sensors tow_sim_node simulates, its `sensors:` section
// (surveySensorParams(), survey_sensors.h). (Library tow_sim_config.)
#pragma once

#include <yaml-cpp/yaml.h>
#include <string>

#include "tow_sim/core/survey/survey_sensors.h"
#include "tow_sim/core/survey/tow_nav.h"

namespace tow_sim
{
// Throws std::invalid_argument naming the key (under `prefix`), the value and the range.
TowNavParams loadNavParams(const YAML::Node& root, const std::string& prefix = "");
// The `sensors:` section (enabled unless it says enabled: false); without one, sensors disabled.
SurveySensorParams loadSensorParams(const YAML::Node& root, const std::string& prefix = "");

}  // namespace tow_sim
