// The model is constant and the right-hand side has no side effects: evaluating it at other states and
// times (an integrator's trial stages) changes nothing that a later evaluation at the same (t, y) sees,
// to the bit; the running chain's data changes only through its own calls (commands, currents, the winch).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/integration/simulator.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
bool sameBits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(ModelAndData, RightHandSideHasNoSideEffects)
{
  CableParams cable;
  cable.length = 200.0;
  cable.segments = 30;
  WinchParams winch;
  winch.enabled = true;
  winch.min_length = 100.0;
  winch.max_length = 400.0;
  SeabedParams bottom;
  bottom.type = SeabedParams::Type::kFlat;
  bottom.depth = 90.0;
  Environment env;
  env.current_profile = { CurrentSample{ 0.0, Eigen::Vector3d(0.1, 0.0, 0.0) },
                          CurrentSample{ 200.0, Eigen::Vector3d(0.0, 0.4, 0.0) } };
  const auto model = std::make_shared<const ChainModel>(cable, std::make_shared<Vehicle>(VehicleParams()), env,
                                                        NumericsParams(), std::make_shared<Seabed>(bottom));
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), u), winch);
  sim.reset(0.0, steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), u).state);
  sim.command(0.1, -0.2, 50.0);
  sim.setWinchCommand(1.5);
  sim.advanceTo(12.0);  // paying out: the first segment changes length at a rate, the fins are moving

  const Simulator::StateVector y = sim.stateVector();
  const double t = sim.time();
  const ChainGeometry geometry_before = sim.geometry();
  const double length_error_before = sim.lengthError();
  Simulator::StateVector first(y.size()), again(y.size()), trial(y.size());
  sim.derivative(t, y, first);

  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int i = 0; i < 20; ++i)
  {
    Simulator::StateVector other = y;
    for (double& value : other)
      value += 0.5 * noise(rng);  // other positions, velocities, cable out and payout rate
    sim.derivative(t + 3.0 * noise(rng), other, trial);
  }
  // Nothing the simulator shows moved (the old model kept the last trial's first segment).
  EXPECT_TRUE(sameBits(y, sim.stateVector()));
  const ChainGeometry& geometry_after = sim.geometry();
  for (auto field : { &ChainGeometry::nominal_length, &ChainGeometry::first_length, &ChainGeometry::first_rate,
                      &ChainGeometry::first_acceleration, &ChainGeometry::end_length })
    EXPECT_EQ(std::memcmp(&(geometry_before.*field), &(geometry_after.*field), sizeof(double)), 0);
  EXPECT_EQ(geometry_before.segments, geometry_after.segments);
  EXPECT_EQ(geometry_before.end_body, geometry_after.end_body);
  EXPECT_EQ(geometry_before.aft_sections, geometry_after.aft_sections);
  EXPECT_EQ(geometry_before.aft_segments, geometry_after.aft_segments);
  EXPECT_EQ(sim.lengthError(), length_error_before);
  sim.derivative(t, y, again);
  EXPECT_TRUE(sameBits(first, again)) << "the right-hand side at the same (t, y) changed after trial evaluations";
  // And what the step left: the derivative at the current state is the one the simulator reports.
  const StateLayout layout{ sim.geometry().jointCount() };
  EXPECT_TRUE(layout.velocities(first).isApprox(sim.accelerations(), 1e-15));
}

TEST(ModelAndData, TheModelOutlivesItsRunsUnchanged)
{
  // Two simulators on one model: commands, currents and the winch of one never reach the other.
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 20;
  WinchParams winch;
  winch.enabled = true;
  winch.min_length = 60.0;
  winch.max_length = 200.0;
  const auto model = std::make_shared<const ChainModel>(cable, std::make_shared<Vehicle>(VehicleParams()),
                                                        Environment(), NumericsParams());
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  Simulator a(model, constantVelocityShip(Eigen::Vector3d::Zero(), u), winch);
  Simulator b(model, constantVelocityShip(Eigen::Vector3d::Zero(), u), winch);
  const ChainState start = steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), u).state;
  a.reset(0.0, start);
  b.reset(0.0, start);
  a.command(0.3, 0.3, 100.0);
  a.setCurrent(Eigen::Vector3d(0.0, 0.5, 0.0));
  a.setWinchCommand(1.0);
  a.advanceTo(30.0);
  b.advanceTo(30.0);
  EXPECT_GT(a.geometry().segments, b.geometry().segments);  // a paid out and re-meshed, b did not
  EXPECT_EQ(b.geometry().segments, 20);
  EXPECT_EQ(b.data().environment.current_W, Eigen::Vector3d::Zero());
  EXPECT_EQ(b.data().actuators.thrust, 0.0);
  EXPECT_EQ(model->segments(), 20);
  EXPECT_EQ(model->environment().current_W, Eigen::Vector3d::Zero());
  // b equals a fresh run on the same model.
  Simulator c(model, constantVelocityShip(Eigen::Vector3d::Zero(), u), winch);
  c.reset(0.0, start);
  c.advanceTo(30.0);
  EXPECT_TRUE(sameBits(b.stateVector(), c.stateVector()));
}

}  // namespace
}  // namespace tow_sim
