// The scripted ship of a scenario: its reference point moved through the manoeuvres and sampled every `dt`
// up to the scenario's duration, as a ShipHistory (the tow point's motion and the ship's pose). Speed slews
// at most 0.1 m/s^2 and the yaw rate follows its target with a 2 s lag, so the track (and the tow point
// built from it) has continuous acceleration. (Library tow_sim_scenario.)
#pragma once

#include "tow_sim/core/ship_track.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
ShipHistory buildShipPath(const Scenario& scenario, double dt = 0.05);

}  // namespace tow_sim
