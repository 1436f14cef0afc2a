// The scripted ship of a scenario (ScriptedShip, scripted_ship.h) sampled every `dt` up to the scenario's
// duration into a ShipHistory: the tow point's motion and the ship's pose. Speed and yaw rate change
// smoothly, so the tow point's acceleration is continuous. (Library tow_sim_scenario.)
#pragma once

#include "tow_sim/core/run/ship_track.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
ShipHistory buildShipPath(const Scenario& scenario, double dt = 0.05);

}  // namespace tow_sim
