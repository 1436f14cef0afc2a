// The steady tow in an irregular sea, in the frequency domain (issue 31, item 3; docs/physics.md §12, (P53a)):
// each wave component of a scenario's sea (the very components its run draws) moves the ship by its response
// amplitude operators (read at the wave's frequency, zero-speed ones) and the ship meets it at the encounter
// frequency; the ship's heave, roll and pitch move the tow point, and the tow answers at the encounter frequency
// by its response to the tow point's motion (modes.h, motionResponse). The outputs' variances are
// the sums over the components of half their squared amplitudes. (Library tow_sim_scenario.)
#pragma once

#include <complex>
#include <optional>
#include <vector>

#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
// The outputs, in the order of SeaStateResponse::names.
constexpr int kSeaStateOutputs = 7;

struct SeaStateComponent
{
  double frequency = 0.0;            // [rad/s] omega of the wave
  double encounter_frequency = 0.0;  // [rad/s] omega - k . v_ship (negative: the ship overtakes the wave)
  double direction = 0.0;            // [rad] the wave travels toward, relative to the ship's heading (0: following)
  double amplitude = 0.0;            // [m] a
  // Per metre of wave amplitude, complex (phase relative to the wave's elevation at the ship's reference point):
  // the tow point's heave [m], the vehicle CG's heave, surge, sway [m] and pitch [rad] (REP-103), the tensions
  // at the ship and the vehicle [N].
  std::complex<double> outputs[kSeaStateOutputs];
};

struct SeaStateResponse
{
  static constexpr const char* names[kSeaStateOutputs] = { "tow_point_heave", "vehicle_heave", "vehicle_surge",
                                                           "vehicle_sway",    "vehicle_pitch", "tension_ship",
                                                           "tension_vehicle" };
  double speed = 0.0;                                // [m/s] the ship's, along its heading
  std::vector<SeaStateComponent> components;         // the sea's, in its order
  double standard_deviation[kSeaStateOutputs] = {};  // sqrt(sum 1/2 a^2 |H|^2), units as the outputs
};

// The scenario's sea (environment.waves: regular or jonswap) about the steady tow at the scenario's initial
// speed and heading with cable_out [m] (default the configuration's), the ship moving by its RAOs (the
// scenario's rao_file or the generic vessel; none with ship.wave_response false) and the tow point at
// tow_point_S; currents turned into the ship's frame. Throws std::invalid_argument for calm water, a ship that
// replays a motion file or starts at rest (speed <= 0), and as steadyTow.
SeaStateResponse seaStateResponse(const Scenario& scenario, std::optional<double> cable_out = std::nullopt);

}  // namespace tow_sim
