#include "tow_sim/scenario/sea_state.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/ship_response.h"
#include "tow_sim/scenario/scripted_ship.h"
#include "tow_sim/scenario/towing_chart.h"

namespace tow_sim
{
namespace
{
// The tow point's complex translation [m] per metre of wave amplitude (ship frame, FLU) from the ship's heave,
// roll and pitch RAOs (P43) to first order in the angles, (P32): heave z + roll x x r + pitch y x r.
Eigen::Vector3cd towPointMotion(const RaoValue& r, const Eigen::Vector3d& tow_point_S)
{
  const Eigen::Vector3d by_roll = Eigen::Vector3d::UnitX().cross(tow_point_S);
  const Eigen::Vector3d by_pitch = Eigen::Vector3d::UnitY().cross(tow_point_S);
  Eigen::Vector3cd d = r.roll * by_roll.cast<std::complex<double>>() + r.pitch * by_pitch.cast<std::complex<double>>();
  d.z() += r.heave;
  return d;
}

std::complex<double> MotionResponse::*const kFields[kSeaStateOutputs - 1] = {
  &MotionResponse::heave, &MotionResponse::surge,        &MotionResponse::sway,
  &MotionResponse::pitch, &MotionResponse::tension_ship, &MotionResponse::tension_vehicle
};
// The steady tow runs along +x, the ship frame: the currents, world, turned into it.
SimulationConfig inShipFrame(const SimulationConfig& world, double heading)
{
  const Eigen::AngleAxisd to_ship(-heading, Eigen::Vector3d::UnitZ());
  SimulationConfig config = world;
  config.environment.current_W = to_ship * config.environment.current_W;
  for (CurrentSample& sample : config.environment.current_profile)
    sample.velocity_W = to_ship * sample.velocity_W;
  return config;
}
}  // namespace

SeaStateResponse seaStateResponse(const Scenario& scenario, std::optional<double> cable_out)
{
  if (scenario.config.environment.waves.type == WaveParams::Type::kNone)
    throw std::invalid_argument("sea state: environment.waves.type is none: a sea state needs waves");
  if (!scenario.motion_file.empty())
    throw std::invalid_argument(
        "sea state: ship.motion_file replays measured motion; a sea state needs the ship's "
        "manoeuvres and RAOs");
  const ScriptedShip ship(scenario.manoeuvres, scenario.start_position.x(), scenario.start_position.y(),
                          scenario.start_heading);
  SeaStateResponse out;
  out.speed = ship.speed();
  if (!(out.speed > 0.0))
    throw std::invalid_argument("sea state: the ship's initial speed " + std::to_string(out.speed) +
                                " m/s must be > 0 (at rest the linearised drag has no flow to damp the response)");
  const double heading = scenario.start_heading;
  const SimulationConfig config = inShipFrame(scenario.config, heading);
  const WaveField sea(config.environment.waves, config.environment.gravity);
  const Eigen::Vector2d v_W = out.speed * Eigen::Vector2d(std::cos(heading), std::sin(heading));
  // Each component at |encounter frequency|, the ship's motion conjugated where it overtakes the wave (so that
  // every input is Re(D e^{+i |omega_e| t})).
  std::vector<double> periods;
  for (const WaveComponent& c : sea.components())
  {
    SeaStateComponent s;
    s.frequency = c.omega;
    s.encounter_frequency = c.omega - (c.kx * v_W.x() + c.ky * v_W.y());
    s.direction = std::remainder(c.direction - heading, 2.0 * kPi);
    s.amplitude = c.amplitude;
    out.components.push_back(s);
    periods.push_back(std::min(2.0 * kPi / std::max(std::abs(s.encounter_frequency), 1e-12), 1e5));
  }
  const double length = cable_out.value_or(config.cable.length);
  // The tow's response to the tow point moving along x, y, z (ship frame): one steady tow, one linearisation.
  const std::vector<std::vector<MotionResponse>> axis =
      steadyTowResponses(config, out.speed, length, config.environment.current_W,
                         { Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ() }, periods);
  for (size_t i = 0; i < out.components.size(); ++i)
  {
    SeaStateComponent& s = out.components[i];
    const WaveComponent& c = sea.components()[i];
    Eigen::Vector3cd d = Eigen::Vector3cd::Zero();
    if (scenario.wave_response && scenario.rao)
      d = towPointMotion(scenario.rao->at(c.omega, c.direction - heading), scenario.tow_point_S);
    if (s.encounter_frequency < 0.0)
      d = d.conjugate();
    s.outputs[0] = d.z();
    for (int j = 0; j < kSeaStateOutputs - 1; ++j)
      for (int k = 0; k < 3; ++k)
        s.outputs[j + 1] += axis[k][i].*kFields[j] * d(k);
    for (int j = 0; j < kSeaStateOutputs; ++j)
      out.standard_deviation[j] += 0.5 * std::norm(s.outputs[j]) * s.amplitude * s.amplitude;
  }
  for (double& v : out.standard_deviation)
    v = std::sqrt(v);
  return out;
}

}  // namespace tow_sim
