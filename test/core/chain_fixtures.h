// Helpers shared by the core tests: building models and the mechanical energy of a chain.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/integration/simulator.h"
#include "tow_sim/core/run/ship_track.h"
#include "tow_sim/core/run/simulation_config.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace test
{
// The numerics of the suites that run once per stepper (Winch, Seabed, CurrentProfile, VehicleTow): the
// defaults, with the stepper TOW_SIM_TEST_STEPPER names (dopri5, rk4, implicit, implicit_fixed) when
// set. CTest and catkin run those suites a second time with it set to implicit.
NumericsParams suiteNumerics();

// A ship steaming at 2 m/s along `heading` [rad, ENU] from `start` [m], sampled each second for `seconds` s.
std::shared_ptr<ShipHistory> steamingShip(const Eigen::Vector2d& start, double heading, int seconds);

// A vehicle's chain in a Simulator, for the tests that drive the simulator directly.
struct VehicleTow
{
  std::shared_ptr<Vehicle> vehicle;
  std::shared_ptr<ChainModel> model;
  std::unique_ptr<Simulator> sim;

  VehicleOutputs out() const;  // the vehicle's outputs at the simulator's state
  double bailTension() const;  // [N] |T| at the bail
};

inline std::shared_ptr<ChainModel> makeModel(const CableParams& cable, const EndElementParams& end,
                                             const Environment& env, const NumericsParams& num = NumericsParams(),
                                             std::shared_ptr<const Seabed> seabed = nullptr)
{
  return std::make_shared<ChainModel>(cable, std::make_shared<RigidEndElement>(end, num), env, num, seabed);
}

// 200 m of the default cable in 40 segments behind the default vehicle, dopri5 at 1e-9: a short tow for runs
// checked to many digits (test_modes, test_motion_response).
inline SimulationConfig shortTightTow()
{
  SimulationConfig config;
  config.cable.length = 200.0;
  config.cable.segments = 40;
  config.numerics.stepper = StepperType::kDopri5;
  config.numerics.abs_tol = config.numerics.rel_tol = 1e-9;
  return config;
}

// A small two-part tow (config YAML): 200 m of cable in 20 segments, a winged depressor with a clump at its aft
// attachment, then 128 m of light tether in 16 segments with a float on it.
inline constexpr const char* kSmallTwoPartTow = R"(
cable:
  length: 330.0
  sections:
    - {length: 200.0, segments: 20}
    - {depressor: {length: 2.0, mass: 400.0, wing_area: 0.5, lift_coefficient: 0.8}}
    - {length: 128.0, segments: 16, diameter: 0.02, mass_per_length: 0.35}
  bodies:
    - {at: 202.0, mass: 300.0, displaced_volume: 0.05, drag_area: 0.3, added_mass: 40.0}
    - {at: 266.0, mass: 20.0, displaced_volume: 0.05, drag_area: 0.15, added_mass: 50.0})";

// An end element that is one more cable segment: same length, mass, diameter and coefficients.
inline EndElementParams endLikeSegment(const CableParams& cable)
{
  EndElementParams e;
  const double d = cable.segmentLength();
  const double area = 0.25 * kPi * cable.diameter * cable.diameter;
  e.length = d;
  e.mass = cable.mass_per_length * d;
  e.displaced_volume = area * d;
  e.cg_from_bail = 0.5 * d;
  e.cb_from_bail = 0.5 * d;
  e.transverse_inertia = e.mass * d * d / 12.0;
  e.diameter = cable.diameter;
  e.normal_drag_coefficient = cable.normal_drag_coefficient;
  e.tangential_drag_coefficient = cable.tangential_drag_coefficient;
  e.added_mass_coefficient = cable.added_mass_coefficient;
  return e;
}

// Kinetic plus potential energy of the rigid elements in vacuum, from positions and velocities only:
// sum of 1/2 m |v_G|^2 + 1/2 I_t |w|^2 + m g z_G, w = s x ds/dt, I_t about the CG.
double chainEnergy(const ChainModel& model, const CableParams& cable, const EndElementParams& end, double gravity,
                   const ShipEndState& ship, const ChainState& state);

}  // namespace test
}  // namespace tow_sim
