// The cable left on the ship after a parting aft of the tow point (Simulator::part, docs/solver.md §10),
// through the run, against closed forms: hanging at rest in vacuum it stays where it was and the ship
// carries its weight while the vehicle side falls at g; towed in water without tangential drag it settles
// straight at the critical angle phi, (w - b) cos(phi) = 1/2 rho C_n d U^2 sin^2(phi), with the ship
// carrying the net weight's component along it, T_1 = (w - b) l sin(phi) for the l metres left on it; an
// elastic one hanging in still water settles stretched, the ship carrying its net weight.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/chain_fixtures.h"

#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{

TEST(ShipSide, HangingInVacuumItStaysAndTheShipCarriesItsWeight)
{
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 10;
  Environment vacuum;
  vacuum.water_density = 0.0;
  auto model = test::makeModel(cable, EndElementParams(), vacuum);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  sim.reset(0.0,
            straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, -1.0), Eigen::Vector3d::Zero()));
  const Eigen::Matrix3Xd hung = sim.jointPositions();
  sim.part(3);  // at joint 4: three segments stay on the ship
  EXPECT_TRUE(sim.parted());
  EXPECT_EQ(sim.geometry().segments, 7);
  sim.advanceTo(2.0);
  const double g = vacuum.gravity, w = cable.mass_per_length * 10.0 * g;  // one segment's weight
  const Eigen::Matrix3Xd ship_side = sim.shipSideJoints();
  ASSERT_EQ(ship_side.cols(), 4);
  EXPECT_LT((ship_side - hung.leftCols(4)).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(sim.shipTension(), 3.0 * w, 1e-9 * w);
  ASSERT_EQ(sim.shipSideTensions().cols(), 3);
  EXPECT_NEAR(sim.shipSideTensions().col(2).norm(), w, 1e-9 * w);  // the last carries itself alone
  const Eigen::Matrix3Xd fallen = sim.jointPositions();            // the free end first
  for (Eigen::Index j = 0; j < fallen.cols() - 1; ++j)
    EXPECT_LT((fallen.col(j) - hung.col(j + 3) - Eigen::Vector3d(0.0, 0.0, -0.5 * g * 4.0)).norm(), 1e-6)
        << "joint " << j;
  EXPECT_LT(sim.lengthError(), 1e-9);
}

// Parted while the winch pays out, the cable left on the ship stops paying out: its first segment keeps
// its length, so its first joint no longer moves away from the tow point. A restored whole cable has no
// ship side left over.
TEST(ShipSide, PartedDuringAPayoutItKeepsItsLengthsAndARestoreClearsIt)
{
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 10;
  Environment vacuum;
  vacuum.water_density = 0.0;
  auto model = test::makeModel(cable, EndElementParams(), vacuum);
  WinchParams winch;
  winch.enabled = true;
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), winch);
  sim.reset(0.0,
            straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, -1.0), Eigen::Vector3d::Zero()));
  const SimulatorState whole = sim.saveState();
  sim.setWinchCommand(1.0);
  sim.advanceTo(3.0);
  ASSERT_GT(sim.payoutRate(), 0.5);
  sim.part(3);
  const Eigen::Matrix3Xd x = sim.shipSideJoints();
  ASSERT_EQ(x.cols(), 4);
  EXPECT_LT(sim.lengthError(), 1e-12);
  EXPECT_LT(sim.advanceTo(4.0).max_length_error, 1e-6);               // each step's, before the projection
  EXPECT_LT((sim.shipSideJoints() - x).cwiseAbs().maxCoeff(), 1e-9);  // hanging still, at rest
  const double w = cable.mass_per_length * vacuum.gravity;
  EXPECT_NEAR(sim.shipTension(), w * (x(2, 0) - x(2, 3)), 1e-9 * sim.shipTension());  // its whole weight

  sim.restoreState(whole);
  EXPECT_FALSE(sim.parted());
  EXPECT_EQ(sim.shipSideJoints().cols(), 0);
  EXPECT_EQ(sim.shipSideTensions().cols(), 0);
  EXPECT_DOUBLE_EQ(sim.shipTension(), sim.tensions().col(0).norm());
}

TEST(ShipSide, TowedWithoutTangentialDragItLiesAtTheCriticalAngle)
{
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 10;
  cable.diameter = 0.02;
  cable.mass_per_length = 1.0;
  cable.normal_drag_coefficient = 1.2;
  cable.tangential_drag_coefficient = 0.0;  // the closed form has none
  const Environment env;
  auto model = test::makeModel(cable, EndElementParams(), env);
  const double speed = 2.0;
  const Eigen::Vector3d ship_velocity(speed, 0.0, 0.0);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), ship_velocity));
  sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -0.3), ship_velocity));
  sim.part(6);  // 60 m stay on the ship
  sim.advanceTo(300.0);

  const double net = (cable.mass_per_length - env.water_density * kPi * 0.25 * cable.diameter * cable.diameter) *
                     env.gravity;  // [N/m]
  const double drag = 0.5 * env.water_density * cable.normal_drag_coefficient * cable.diameter * speed * speed;
  const double cos_phi = (-net + std::sqrt(net * net + 4.0 * drag * drag)) / (2.0 * drag);
  const double phi = std::acos(cos_phi), expected = net * 60.0 * std::sin(phi);
  const Eigen::Matrix3Xd x = sim.shipSideJoints();
  ASSERT_EQ(x.cols(), 7);
  double worst = 0.0;
  for (Eigen::Index e = 0; e < 6; ++e)
  {
    const Eigen::Vector3d s = x.col(e + 1) - x.col(e);
    worst = std::max(worst, std::abs(std::atan2(-s.z(), s.head<2>().norm()) - phi));
  }
  std::printf(
      "ship side: critical angle %.4f deg, worst segment off by %.1e deg; ship tension %.4f N (closed form "
      "%.4f N)\n",
      phi * 180.0 / kPi, worst * 180.0 / kPi, sim.shipTension(), expected);
  EXPECT_LT(worst * 180.0 / kPi, 0.01);
  EXPECT_NEAR(sim.shipTension(), expected, 1e-6 * expected);
  EXPECT_LT(x.row(1).cwiseAbs().maxCoeff(), 1e-6);  // astern, in the plane of the tow
}

TEST(ShipSide, ElasticHangingInWaterSettlesUnderItsNetWeight)
{
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 10;
  cable.axial_stiffness = 2e4;  // [N] 1.3 % strain at the top under the 30 m left on the ship
  cable.axial_damping = 2e3;    // [N s] critically damps the hanging segments' stretch
  const Environment env;
  auto model = test::makeModel(cable, EndElementParams(), env);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  sim.reset(0.0,
            straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, -1.0), Eigen::Vector3d::Zero()));
  sim.part(3);
  sim.advanceTo(60.0);
  const double area = 0.25 * kPi * cable.diameter * cable.diameter;
  const double net = (cable.mass_per_length - env.water_density * area) * env.gravity * 30.0;  // [N]
  const Eigen::Matrix3Xd x = sim.shipSideJoints();
  ASSERT_EQ(x.cols(), 4);
  // Each segment stretched by its mean tension, which falls linearly to 0 at the free end: a continuous
  // hanging rod's net w l^2 / (2 EA).
  const double hangs = 30.0 + net * 30.0 / (2.0 * *cable.axial_stiffness);
  std::printf("elastic ship side: ship tension %.6f N (net weight %.6f N), hangs %.6f m (closed form %.6f m)\n",
              sim.shipTension(), net, -x(2, 3), hangs);
  EXPECT_NEAR(sim.shipTension(), net, 1e-6 * net);
  EXPECT_NEAR(-x(2, 3), hangs, 1e-6);
  EXPECT_LT(x.topRows(2).cwiseAbs().maxCoeff(), 1e-9);  // straight down
}

}  // namespace
}  // namespace tow_sim
