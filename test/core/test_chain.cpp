// One chain of the simulation (Chain, core/chain/chain.h): its block of a shared state vector. A chain's
// right-hand side must not depend on where its block sits or on the blocks beside it: the vehicle side of a
// parted cable (a free first joint) and the cable left on the ship (a free last joint), laid one after the
// other, give each the derivative it gives alone at offset 0, bit for bit, and neither writes into the
// other's block. Its projection restores every kept length along the current directions (closed form:
// the geometry's lengths), and a free first joint is read from its block.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "chain_fixtures.h"
#include "tow_sim/core/chain/chain.h"

namespace tow_sim
{
namespace
{
struct TwoChains
{
  std::shared_ptr<ChainModel> model;
  ChainData data;
  ChainGeometry vehicle, ship_side;
};

TwoChains partedAtJoint5()
{
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 10;
  TwoChains c;
  c.model = test::makeModel(cable, EndElementParams(), Environment());
  c.data = c.model->initialData();
  c.vehicle = c.ship_side = c.model->initialGeometry();
  c.vehicle.segments = 6;
  c.ship_side.segments = 4;
  c.ship_side.end_body = false;
  c.ship_side.aft_segments = 6;
  return c;
}

// A bent, moving chain in a block: joint k of `chain` at a wavy line from `from`, moving across it.
void fillBlock(const Chain& chain, const Eigen::Vector3d& from, std::vector<double>& y)
{
  const StateLayout& L = chain.layout();
  Eigen::Vector3d x = from;
  for (int e = 0; e < L.joints; ++e)
  {
    const double angle = 0.3 * std::sin(0.7 * e + from.x());
    x += chain.geometry().elementLength(e) * Eigen::Vector3d(-std::cos(angle), 0.2, -std::sin(angle)).normalized();
    L.positions(y).col(e) = x;
    L.velocities(y).col(e) = Eigen::Vector3d(2.0, 0.1 * e, -0.05 * e);
  }
  if (L.free)
  {
    L.freePosition(y) = from;
    L.freeVelocity(y) = Eigen::Vector3d(1.5, -0.2, 0.3);
  }
}

TEST(Chain, ABlockBesideAnotherGivesTheDerivativeItGivesAlone)
{
  const TwoChains c = partedAtJoint5();
  ShipEndState ship;
  ship.v_W = Eigen::Vector3d(2.0, 0.0, 0.0);
  const Chain vehicle(c.vehicle, StateLayout{ 0, true });
  const Chain ship_side(c.ship_side, StateLayout{ 0, false, vehicle.layout().end(), false });
  ASSERT_EQ(vehicle.layout().size(), 6u * 7u + 2u + 6u);
  ASSERT_EQ(ship_side.layout().size(), 6u * 4u);
  std::vector<double> y(ship_side.layout().end()), dydt(y.size(), std::numeric_limits<double>::quiet_NaN());
  fillBlock(vehicle, Eigen::Vector3d(-40.0, 0.0, -20.0), y);
  fillBlock(ship_side, ship.p_W, y);
  vehicle.derivative(*c.model, c.vehicle, c.data, 0.3, ship, y, dydt);
  // The vehicle side wrote its joints and its free end, not the cable-out slots (the simulator's) nor the
  // ship side's block.
  for (std::size_t i = vehicle.layout().end(); i < dydt.size(); ++i)
    EXPECT_TRUE(std::isnan(dydt[i])) << "value " << i;
  ship_side.derivative(*c.model, c.ship_side, c.data, 0.3, ship, y, dydt);

  const Chain vehicle_alone(c.vehicle, StateLayout{ 0, true });
  const Chain ship_side_alone(c.ship_side, StateLayout{ 0, false, 0, false });
  std::vector<double> y_vehicle(y.begin(), y.begin() + static_cast<long>(vehicle.layout().end()));
  std::vector<double> y_ship(y.begin() + static_cast<long>(vehicle.layout().end()), y.end());
  std::vector<double> d_vehicle(y_vehicle.size(), 0.0), d_ship(y_ship.size(), 0.0);
  vehicle_alone.derivative(*c.model, c.vehicle, c.data, 0.3, ship, y_vehicle, d_vehicle);
  ship_side_alone.derivative(*c.model, c.ship_side, c.data, 0.3, ship, y_ship, d_ship);
  const StateLayout& V = vehicle.layout();
  EXPECT_EQ(Eigen::Matrix3Xd(V.velocities(dydt)), Eigen::Matrix3Xd(V.velocities(d_vehicle)));
  EXPECT_EQ(Eigen::Vector3d(V.freeVelocity(dydt)), Eigen::Vector3d(V.freeVelocity(d_vehicle)));
  EXPECT_EQ(Eigen::Vector3d(V.freePosition(dydt)), Eigen::Vector3d(1.5, -0.2, 0.3));  // the free end's velocity
  for (std::size_t i = 0; i < d_ship.size(); ++i)
    EXPECT_EQ(dydt[vehicle.layout().end() + i], d_ship[i]) << "ship side value " << i;
  // Something moved: the accelerations are not all zero.
  EXPECT_GT(V.velocities(dydt).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(Chain, ProjectionRestoresTheLengthsFromItsFreeFirstJoint)
{
  const TwoChains c = partedAtJoint5();
  const Chain vehicle(c.vehicle, StateLayout{ 0, true, 5 });  // 5 values of something else first
  std::vector<double> y(vehicle.layout().end(), 0.0);
  fillBlock(vehicle, Eigen::Vector3d(-40.0, 0.0, -20.0), y);
  const StateLayout& L = vehicle.layout();
  L.positions(y) *= 1.01;   // every element stretched: lengths off by about a percent
  const ShipEndState ship;  // the tow point, far from the free end: the chain must not hang from it
  ASSERT_GT(vehicle.lengthError(*c.model, ship, y), 1e-3);
  vehicle.project(*c.model, ship, y);
  Eigen::Vector3d x_f = L.freePosition(y);
  for (int e = 0; e < L.joints; ++e)
  {
    const Eigen::Vector3d x = L.positions(y).col(e);
    EXPECT_NEAR((x - x_f).norm(), c.vehicle.elementLength(e), 1e-12 * c.vehicle.elementLength(e)) << "element " << e;
    // No velocity along the element relative to its forward joint.
    const Eigen::Vector3d v_f =
        e == 0 ? Eigen::Vector3d(L.freeVelocity(y)) : Eigen::Vector3d(L.velocities(y).col(e - 1));
    EXPECT_NEAR((x - x_f).normalized().dot(L.velocities(y).col(e) - v_f), 0.0, 1e-12) << "element " << e;
    x_f = x;
  }
  EXPECT_LT(vehicle.lengthError(*c.model, ship, y), 1e-14);
  EXPECT_EQ(vehicle.jointPositions(ship, y).col(0), Eigen::Vector3d(L.freePosition(y)));
}

}  // namespace
}  // namespace tow_sim
