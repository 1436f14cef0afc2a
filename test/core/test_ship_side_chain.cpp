// The ship side of a parted cable (ChainGeometry::end_body false, docs/solver.md §10): segments from the
// ship whose last joint nothing pulls on, against closed forms. Hanging at rest in vacuum: no acceleration,
// and each joint carries the weight below it. One segment is a uniform rod of mass m and length L on a
// pivot: released level at rest its tail starts falling at 3g/2 and the pivot carries mg/4; hanging and
// swinging through the bottom at angular rate w, the pivot carries mg + m w^2 L/2.
#include <gtest/gtest.h>

#include <cmath>

#include "chain_fixtures.h"
#include "tow_sim/core/chain/chain_solver.h"

namespace tow_sim
{
namespace
{
struct ShipSide
{
  std::shared_ptr<ChainModel> model;
  ChainGeometry geometry;
  ChainData data;
  double segment_mass = 0.0;  // [kg]
};

ShipSide shipSide(int segments)
{
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 10;
  Environment vacuum;
  vacuum.water_density = 0.0;
  ShipSide r;
  r.model = test::makeModel(cable, EndElementParams(), vacuum);
  r.data = r.model->initialData();
  r.geometry = r.model->initialGeometry();
  r.geometry.segments = segments;  // those forward of the break
  r.geometry.end_body = false;
  r.segment_mass = cable.mass_per_length * r.geometry.nominal_length;
  return r;
}

TEST(ShipSideChain, HangingAtRestInVacuumEachJointCarriesTheWeightBelowIt)
{
  const ShipSide r = shipSide(4);
  ASSERT_EQ(r.geometry.elementCount(), 4);
  ShipEndState ship;
  ship.p_W = Eigen::Vector3d(5.0, 1.0, 0.0);
  Eigen::Matrix3Xd x(3, 4), v = Eigen::Matrix3Xd::Zero(3, 4), a(3, 4), T;
  for (int j = 0; j < 4; ++j)
    x.col(j) = ship.p_W - Eigen::Vector3d(0.0, 0.0, (j + 1) * r.geometry.nominal_length);
  ChainSolver solver;
  solver.solve(*r.model, r.geometry, r.data, 0.0, ship, x, v, a, &T);
  const double g = 9.81, w = r.segment_mass * g;
  EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-10);
  ASSERT_EQ(T.cols(), 4);
  for (int k = 0; k < 4; ++k)  // T_k: the force on element k at its forward joint, up
    EXPECT_LT((T.col(k) - Eigen::Vector3d(0.0, 0.0, (4 - k) * w)).norm(), 1e-9 * w) << "joint " << k + 1;
}

TEST(ShipSideChain, OneSegmentReleasedLevelIsARodOnAPivot)
{
  const ShipSide r = shipSide(1);
  const double L = r.geometry.nominal_length, m = r.segment_mass, g = 9.81;
  ShipEndState ship;
  Eigen::Matrix3Xd x(3, 1), v = Eigen::Matrix3Xd::Zero(3, 1), a(3, 1), T;
  x.col(0) = Eigen::Vector3d(-L, 0.0, 0.0);
  ChainSolver solver;
  solver.solve(*r.model, r.geometry, r.data, 0.0, ship, x, v, a, &T);
  EXPECT_LT((a.col(0) - Eigen::Vector3d(0.0, 0.0, -1.5 * g)).norm(), 1e-10);
  EXPECT_LT((T.col(0) - Eigen::Vector3d(0.0, 0.0, 0.25 * m * g)).norm(), 1e-9 * m * g);
}

TEST(ShipSideChain, OneSegmentSwingingThroughTheBottomCarriesItsCentripetalLoad)
{
  const ShipSide r = shipSide(1);
  const double L = r.geometry.nominal_length, m = r.segment_mass, g = 9.81, omega = 0.7;
  ShipEndState ship;
  Eigen::Matrix3Xd x(3, 1), v(3, 1), a(3, 1), T;
  x.col(0) = Eigen::Vector3d(0.0, 0.0, -L);
  v.col(0) = Eigen::Vector3d(omega * L, 0.0, 0.0);
  ChainSolver solver;
  solver.solve(*r.model, r.geometry, r.data, 0.0, ship, x, v, a, &T);
  EXPECT_LT((a.col(0) - Eigen::Vector3d(0.0, 0.0, omega * omega * L)).norm(), 1e-10);  // toward the pivot
  EXPECT_LT((T.col(0) - Eigen::Vector3d(0.0, 0.0, m * g + 0.5 * m * omega * omega * L)).norm(), 1e-9 * m * g);
}

}  // namespace
}  // namespace tow_sim
