// The parameter documentation, generated from the parameter tables: the key tables of docs/parameters.md (between
// <!-- params:NAME --> and <!-- /params --> markers) and the whole of config/tow_sim.yaml. tow_sim_param_docs
// writes them (`make docs`); Docs.* tests that the files in the repository are current. (Library
// tow_sim_scenario, which sees every table.)
#pragma once

#include <string>
#include <vector>

namespace tow_sim
{
// The names of the documented tables: cable, vehicle, environment, winch, seabed, numerics, node,
// autopilot_node, ship, manoeuvres, commands, autopilot, initial_state, simulation.
std::vector<std::string> documentedTables();
// One table as markdown: | key | unit | default | range | meaning |. Throws std::invalid_argument for an
// unknown name.
std::string markdownTable(const std::string& name);
// `text` with every marked block replaced by its current table. Throws std::invalid_argument for an unknown
// or unterminated block.
std::string withCurrentTables(const std::string& text);
// config/tow_sim.yaml: every configuration key with its default, unit, range and meaning.
std::string configFile();

}  // namespace tow_sim
