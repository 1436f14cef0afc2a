// The parameter tables of a scenario file's own keys (param_table.h); the configuration sections are the
// core's tables. (Library tow_sim_scenario.)
#pragma once

#include "tow_sim/core/param_table.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
const ParamTable<Scenario>& shipParams();                // ship: tow_point, start_position, start_heading, manoeuvres
const ParamTable<Manoeuvre>& manoeuvreParams();          // ship.manoeuvres[i]
const ParamTable<CommandEvent>& commandParams();         // commands[i]
const ParamTable<AutopilotLoop>& autopilotLoopParams();  // autopilot: rate, the controller's keys, setpoints
const ParamTable<InitialShape>& initialStateParams();    // initial_state
const ParamTable<Scenario>& simulationParams();          // simulation

}  // namespace tow_sim
