// The scripted ship of a scenario (ScriptedShip, scripted_ship.h) sampled every `dt` up to the scenario's
// duration into a ShipHistory: the tow point's motion and the ship's pose. Speed and yaw rate change
// smoothly, so the tow point's acceleration is continuous. (Library tow_sim_scenario.)
#pragma once

#include <memory>

#include "tow_sim/core/run/ship_track.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
ShipHistory buildShipPath(const Scenario& scenario, double dt = 0.05);

// A ship on a straight course at `speed` [m/s] along +x, at the origin at t = 0, heading 0, sampled every `dt` [s]
// from `from` to `to` [s]; its reference point is the tow point (the towing chart's steady tow, tests).
std::shared_ptr<ShipHistory> straightShip(double speed, double from, double to, double dt = 1.0);

}  // namespace tow_sim
