// The winch: the first segment changes length at the commanded rate, segments are split off or merged
// at the ship, and the chain's mass and the rest of its shape are kept. Checked against the equilibrium
// of the longer cable, against the start (pay out and haul back), against the limits, and against the
// length constraint before projection (which holds only if the winch's acceleration term is right).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/chain_fixtures.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/integration/simulator.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
using Tow = test::VehicleTow;

WinchParams testWinch()
{
  WinchParams w;
  w.enabled = true;
  w.min_length = 100.0;
  w.max_length = 400.0;
  w.max_rate = 1.0;
  w.max_acceleration = 0.2;
  w.response_time = 1.0;
  return w;
}

Tow makeTow(double length, int segments, const Eigen::Vector3d& ship_velocity, const WinchParams& winch)
{
  CableParams cable;
  cable.length = length;
  cable.segments = segments;
  Tow tow;
  tow.vehicle = std::make_shared<Vehicle>(VehicleParams());
  tow.model = std::make_shared<ChainModel>(cable, tow.vehicle, Environment(), test::suiteNumerics());
  tow.sim = std::make_unique<Simulator>(tow.model, constantVelocityShip(Eigen::Vector3d::Zero(), ship_velocity), winch);
  const EquilibriumResult eq = steadyTowEquilibrium(*tow.model, 0.0, Eigen::Vector3d::Zero(), ship_velocity);
  tow.sim->reset(0.0, eq.state);
  return tow;
}

double vehicleDepth(const Simulator& sim)
{
  return -sim.jointPositions().rightCols<1>().z();
}

// Sum of the element lengths along the chain, and what the cable's layout says.
void expectBookkeeping(const Simulator& sim)
{
  const ChainModel& m = sim.model();
  const ChainGeometry& g = sim.geometry();
  const Eigen::Matrix3Xd p = sim.jointPositions();
  double along = 0.0;
  for (int e = 0; e < g.segments; ++e)
    along += (p.col(e + 1) - p.col(e)).norm();
  EXPECT_NEAR(along, sim.cableLength(), 1e-9 * sim.cableLength());
  EXPECT_NEAR(g.cableLength(), sim.cableLength(), 1e-9 * sim.cableLength());
  // Mass per length is the cable's: the chain's mass is the cable out times it.
  double mass = 0.0;
  for (int e = 0; e < g.segments; ++e)
    mass += e == 0 ? m.firstSegment(g).mass : m.segment().mass;
  EXPECT_NEAR(mass, m.cable().mass_per_length * sim.cableLength(), 1e-9 * mass);
  const double d = m.nominalSegmentLength();
  EXPECT_GE(g.first_length, sim.winch().segment_min_fraction * d - 1e-9);
  EXPECT_LE(g.first_length, sim.winch().segment_max_fraction * d + 1e-9);
}

TEST(Winch, IsOffByDefaultAndValidated)
{
  Tow tow = makeTow(300.0, 60, Eigen::Vector3d(2.0, 0.0, 0.0), WinchParams());
  EXPECT_THROW(tow.sim->setWinchCommand(0.5), std::invalid_argument);
  WinchParams w = testWinch();
  w.max_length = 250.0;  // below the cable's 300 m
  try
  {
    Simulator sim(tow.model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), w);
    FAIL() << "a cable longer than winch.max_length accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("cable.length = 300"), std::string::npos) << e.what();
  }
  w = testWinch();
  w.segment_max_fraction = 1.2;  // a split would leave a piece below the band
  EXPECT_THROW(validate(w, tow.model->cable()), std::invalid_argument);
  CableParams fine = tow.model->cable();
  fine.length = 300.0;
  fine.segments = 30000;  // 1 cm segments: 1 km out would be 100000 of them, 1 km + 1 cm one too many
  w = testWinch();
  w.max_length = 1000.0;
  EXPECT_NO_THROW(validate(w, fine));
  w.max_length = 1000.01 + 1e-9;
  try
  {
    validate(w, fine);
    FAIL() << "a winch that could lay out more than 100000 segments accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("winch.max_length = 1000.01 is out of range"), std::string::npos) << e.what();
  }
  w = testWinch();
  Simulator on(tow.model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), w);
  EXPECT_THROW(on.setWinchCommand(NAN), std::invalid_argument);
  EXPECT_DOUBLE_EQ(on.setWinchCommand(5.0), 1.0);  // saturated at max_rate
}

TEST(Winch, LimitsOnRateAccelerationAndLengthHold)
{
  WinchParams w = testWinch();
  w.min_length = 280.0;
  w.max_length = 320.0;
  Tow tow = makeTow(300.0, 60, Eigen::Vector3d(2.0, 0.0, 0.0), w);
  double worst_rate = 0.0, worst_accel = 0.0, longest = 0.0, shortest = 1e9;
  double previous_rate = tow.sim->payoutRate();
  const double dt = 0.05;
  for (int i = 1; i <= 3000; ++i)
  {
    // Out to the upper limit and beyond, then in to the lower limit and beyond, commands past the limit.
    if (i == 1)
      tow.sim->setWinchCommand(5.0);
    if (i == 1000)
      tow.sim->setWinchCommand(-5.0);
    tow.sim->advanceTo(i * dt);
    const double rate = tow.sim->payoutRate();
    worst_rate = std::max(worst_rate, std::abs(rate));
    worst_accel = std::max(worst_accel, std::abs(rate - previous_rate) / dt);
    previous_rate = rate;
    longest = std::max(longest, tow.sim->cableLength());
    shortest = std::min(shortest, tow.sim->cableLength());
    if (i % 100 == 0)
      expectBookkeeping(*tow.sim);
  }
  std::printf(
      "winch limits: |rate| <= %.6f m/s (1), |accel| <= %.6f m/s^2 (0.2), length %.6f .. %.6f m "
      "(280 .. 320), %d segments at the end\n",
      worst_rate, worst_accel, shortest, longest, tow.sim->geometry().segments);
  EXPECT_LE(worst_rate, 1.0 + 1e-9);
  EXPECT_GT(worst_rate, 0.99);  // it did reach full speed
  EXPECT_LE(worst_accel, 0.2 * (1.0 + 1e-3));
  EXPECT_LE(longest, 320.0 + 1e-9);
  EXPECT_GE(shortest, 280.0 - 1e-9);
  EXPECT_GT(longest, 319.9);  // it did reach both limits
  EXPECT_LT(shortest, 280.1);
}

TEST(Winch, PayingOutDeepensTowardTheLongerCablesEquilibrium)
{
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  WinchParams w = testWinch();
  Tow tow = makeTow(300.0, 60, u, w);
  const double start_depth = vehicleDepth(*tow.sim);
  // The longer cable's own equilibrium, same segment length.
  Tow longer = makeTow(400.0, 80, u, WinchParams());
  const double target_depth = vehicleDepth(*longer.sim);

  tow.sim->setWinchCommand(1.0);  // to max_length = 400 m
  double previous = start_depth, deepest = start_depth;
  bool deepening = true;
  double worst_error = 0.0;
  for (int i = 1; i <= 150; ++i)
  {
    const bool paying_out = tow.sim->payoutRate() > 0.99;  // at full rate
    const StepReport r = tow.sim->advanceTo(i * 1.0);
    worst_error = std::max(worst_error, r.max_length_error);
    // While cable goes out at full rate the vehicle only sinks. (It sinks below the new equilibrium: the cable near
    // the ship moves slower through the water while it is paid out; then it rises back to it.)
    if (paying_out && vehicleDepth(*tow.sim) < previous - 1e-6)
      deepening = false;
    previous = vehicleDepth(*tow.sim);
    deepest = std::max(deepest, previous);
    expectBookkeeping(*tow.sim);
  }
  EXPECT_NEAR(tow.sim->cableLength(), 400.0, 1e-3);
  EXPECT_EQ(tow.sim->geometry().segments, 80);
  tow.sim->advanceTo(1200.0);
  const double end_depth = vehicleDepth(*tow.sim);
  std::printf(
      "paying out 100 m at 1 m/s: depth %.2f m -> %.2f m (deepest %.2f m); equilibrium of the 400 m cable "
      "%.2f m; largest length error before projection %.1e\n",
      start_depth, end_depth, deepest, target_depth, worst_error);
  EXPECT_TRUE(deepening);
  EXPECT_NEAR(end_depth, target_depth, 0.01);
  EXPECT_GT(target_depth - start_depth, 10.0);  // a real change to follow
  // The shape, not only the depth: every joint where the longer cable's equilibrium has it.
  const Eigen::Matrix3Xd a = tow.sim->jointPositions().colwise() - tow.sim->shipEnd().p_W;
  const Eigen::Matrix3Xd b = longer.sim->jointPositions().colwise() - longer.sim->shipEnd().p_W;
  ASSERT_EQ(a.cols(), b.cols());
  EXPECT_LT((a - b).colwise().norm().maxCoeff(), 0.02);
  // The length constraint holds through the steps by the dynamics, not only by the projection: to the
  // integration's accuracy (dopri5 at 1e-7: measured 2e-8; implicit at 2e-5: measured 7e-6).
  const bool implicit = test::suiteNumerics().stepper == StepperType::kImplicit;
  EXPECT_LT(worst_error, implicit ? 3e-5 : 1e-7);
}

// Hauling in stops at min_length = the starting 300 m, so the way back ends exactly where it began.
TEST(Winch, PayingOutAndHaulingBackAtRestReturnsTheSameShape)
{
  WinchParams w = testWinch();
  w.min_length = 300.0;
  w.max_length = 500.0;
  Tow tow = makeTow(300.0, 60, Eigen::Vector3d::Zero(), w);  // hanging straight down
  const Eigen::Matrix3Xd start = tow.sim->jointPositions();
  tow.sim->setWinchCommand(1.0);
  tow.sim->advanceTo(55.0);
  tow.sim->setWinchCommand(0.0);
  tow.sim->advanceTo(80.0);
  const double paid = tow.sim->cableLength() - 300.0;
  const int segments_out = tow.sim->geometry().segments;
  tow.sim->setWinchCommand(-1.0);
  tow.sim->advanceTo(200.0);
  tow.sim->setWinchCommand(0.0);
  tow.sim->advanceTo(300.0);
  const Eigen::Matrix3Xd end = tow.sim->jointPositions();
  std::printf(
      "at rest: paid out %.2f m (%d segments), hauled back to %.6f m (%d segments); largest joint offset "
      "from the start %.2e m\n",
      paid, segments_out, tow.sim->cableLength(), tow.sim->geometry().segments,
      end.cols() == start.cols() ? (end - start).cwiseAbs().maxCoeff() : -1.0);
  EXPECT_GT(paid, 40.0);
  EXPECT_GT(segments_out, 67);
  EXPECT_NEAR(tow.sim->cableLength(), 300.0, 1e-6);
  ASSERT_EQ(tow.sim->geometry().segments, 60);
  EXPECT_LT((end - start).cwiseAbs().maxCoeff(), 1e-8);  // measured 4e-13 m
}

TEST(Winch, PayingOutAndHaulingBackUnderwayReturnsToTheSteadyTow)
{
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  WinchParams w = testWinch();
  w.min_length = 300.0;
  Tow tow = makeTow(300.0, 60, u, w);
  const Eigen::Matrix3Xd start = tow.sim->jointPositions().colwise() - tow.sim->shipEnd().p_W;
  tow.sim->setWinchCommand(1.0);
  tow.sim->advanceTo(60.0);
  const double depth_out = vehicleDepth(*tow.sim);
  tow.sim->setWinchCommand(-1.0);
  tow.sim->advanceTo(200.0);
  tow.sim->advanceTo(1100.0);
  const Eigen::Matrix3Xd end = tow.sim->jointPositions().colwise() - tow.sim->shipEnd().p_W;
  std::printf(
      "underway: depth %.2f m -> %.2f m with 50 m more -> back to %.6f m, %d segments; largest joint offset "
      "from the start after settling %.2e m\n",
      -start(2, start.cols() - 1), depth_out, tow.sim->cableLength(), tow.sim->geometry().segments,
      end.cols() == start.cols() ? (end - start).colwise().norm().maxCoeff() : -1.0);
  EXPECT_GT(depth_out + start(2, start.cols() - 1), 3.0);  // it went deeper on the way out
  EXPECT_NEAR(tow.sim->cableLength(), 300.0, 1e-6);
  ASSERT_EQ(end.cols(), start.cols());
  EXPECT_LT((end - start).colwise().norm().maxCoeff(), 1e-6);  // measured 2e-9 m
}

// Review findings, kept as regressions.
TEST(Winch, ADisabledWinchDoesNotConstrainTheCable)
{
  CableParams cable;
  cable.length = 1000.0;
  cable.segments = 4;  // 250 m segments: beyond the enabled winch's default min_length band
  EXPECT_NO_THROW(validate(WinchParams(), cable));
  auto model = std::make_shared<ChainModel>(cable, std::make_shared<Vehicle>(VehicleParams()), Environment(),
                                            test::suiteNumerics());
  EXPECT_NO_THROW(Simulator(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero())));
}

// A first segment parked within rounding of both band edges (max = min + 1) must not split and merge
// for ever.
TEST(Winch, ReMeshingTerminatesOnTheBandEdge)
{
  CableParams cable;
  cable.length = 10.0;
  cable.segments = 25;  // d = 0.4 m
  WinchParams w;
  w.enabled = true;
  w.min_length = 5.0;
  w.max_length = 40.0;
  auto vehicle = std::make_shared<Vehicle>(VehicleParams());
  auto model = std::make_shared<ChainModel>(cable, vehicle, Environment(), test::suiteNumerics());
  const double d = model->nominalSegmentLength();
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), w);
  sim.restoreLayout(87, (35.0 - 86 * d) + 86 * d);  // 35 m out, the first segment a few ulps past 1.5 d
  sim.reset(0.0,
            straightChain(sim.geometry(), Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()));
  sim.advanceTo(0.5);
  EXPECT_GE(sim.geometry().segments, 87);
  EXPECT_LE(sim.geometry().segments, 88);
  expectBookkeeping(sim);
}

TEST(Winch, ResetStartsTheWinchFromRest)
{
  Tow tow = makeTow(300.0, 60, Eigen::Vector3d(2.0, 0.0, 0.0), testWinch());
  tow.sim->setWinchCommand(1.0);
  tow.sim->advanceTo(10.0);
  ASSERT_GT(tow.sim->payoutRate(), 0.5);
  const double out = tow.sim->cableLength();
  tow.sim->reset(10.0, tow.sim->state());
  EXPECT_EQ(tow.sim->payoutRate(), 0.0);
  EXPECT_EQ(tow.sim->cableLength(), out);
  // The command is cleared with the fins' (a restart after divergence must not pay out on its own).
  tow.sim->advanceTo(20.0);
  EXPECT_EQ(tow.sim->payoutRate(), 0.0);
  EXPECT_EQ(tow.sim->cableLength(), out);
}

TEST(Winch, PaidOutCableDragsAtItsOwnSpeedThroughTheWater)
{
  // A cable hanging straight down from a ship at rest, paid out at a steady 1 m/s: all of it sinks at
  // 1 m/s, the first segment's cable too (only its geometric midpoint moves at 0.5 m/s). Its tension
  // drop is its weight in water less the Pode drag of cable moving along itself at 1 m/s,
  // C1 L0 (1 m/s)^2 with C1 = rho C_dt pi D / 2, nothing accelerating.
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 20;
  WinchParams w = testWinch();
  w.min_length = 50.0;
  w.max_acceleration = 1.0;
  auto vehicle = std::make_shared<Vehicle>(VehicleParams());
  const Environment env;
  auto model = std::make_shared<ChainModel>(cable, vehicle, env, test::suiteNumerics());
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), w);
  sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()));
  sim.advanceTo(60.0);  // the hanging vehicle settles
  sim.setWinchCommand(1.0);
  sim.advanceTo(80.0);
  ASSERT_NEAR(sim.payoutRate(), 1.0, 1e-6);
  const double L0 = sim.geometry().first_length;
  const double area = kPi * cable.diameter * cable.diameter / 4.0;
  const double net_weight = (cable.mass_per_length - env.water_density * area) * env.gravity * L0;
  const double c1 = 0.5 * env.water_density * cable.tangential_drag_coefficient * kPi * cable.diameter;
  const double drop = sim.tensions().col(0).z() - sim.tensions().col(1).z();
  std::printf(
      "first segment %.3f m paid out at 1 m/s: tension drop %.4f N = weight %.4f N - drag %.4f N (at the "
      "midpoint's 0.5 m/s: %.4f N)\n",
      L0, drop, net_weight, net_weight - drop, c1 * L0 * 0.25);
  EXPECT_NEAR(net_weight - drop, c1 * L0, 0.02 * c1 * L0);
}

TEST(Winch, FastHaulInWithFixedStepsNeverCollapsesTheFirstSegment)
{
  // 20 m/s against a band whose lower edge is 0.1 m: an RK4 step of 0.02 s would take 0.4 m off the
  // first segment, past zero (the step then leaves joints 1e8 lengths off before the projection); the
  // simulator shortens its steps while the winch runs instead.
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 100;  // d = 1 m
  NumericsParams num = test::suiteNumerics();
  num.stepper = StepperType::kRk4;
  num.fixed_step = 0.02;
  WinchParams w;
  w.enabled = true;
  w.min_length = 50.0;
  w.max_length = 200.0;
  w.max_rate = 20.0;
  w.max_acceleration = 100.0;
  w.response_time = 0.01;
  w.segment_min_fraction = 0.1;
  w.segment_max_fraction = 1.1;
  auto vehicle = std::make_shared<Vehicle>(VehicleParams(), num);
  auto model = std::make_shared<ChainModel>(cable, vehicle, Environment(), num);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), w);
  sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()));
  sim.setWinchCommand(-20.0);
  double before_projection = 0.0;
  for (double t = 0.1; t <= 5.0 + 1e-9; t += 0.1)
  {
    StepReport report;
    ASSERT_NO_THROW(report = sim.advanceTo(t)) << "at t = " << t << " s";
    before_projection = std::max(before_projection, report.max_length_error);
  }
  std::printf("hauled in 50 m at 20 m/s with rk4: largest length error before projection %.1e\n", before_projection);
  EXPECT_LT(before_projection, 1e-9);
  EXPECT_NEAR(sim.cableLength(), 50.0, 1e-3);
  EXPECT_EQ(sim.geometry().segments, 50);
  EXPECT_LT(sim.lengthError(), 1e-9);
  expectBookkeeping(sim);
}

}  // namespace
}  // namespace tow_sim
