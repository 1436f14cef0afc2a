// The O(nu) sweep must reproduce the dense Newton-Euler solve (physics.md §8) for random states.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "core/chain_fixtures.h"
#include "core/dense_reference.h"
#include "core/random_chain.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
using test::EndKind;
using test::makeRandomCase;
using test::RandomCase;

double relativeError(const Eigen::Matrix3Xd& value, const Eigen::Matrix3Xd& reference)
{
  return (value - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

TEST(SolverVsDense, RandomStatesMatchToOnePartInABillion)
{
  std::mt19937 rng(12345);
  for (int segments = 1; segments <= 30; ++segments)
  {
    for (int trial = 0; trial < 5; ++trial)
    {
      const RandomCase c = makeRandomCase(segments, rng);
      ChainSolver solver;
      Eigen::Matrix3Xd a(3, c.model->jointCount()), tensions(3, c.model->jointCount());
      solver.solve(*c.model, c.geometry, c.data, 0.0, c.ship, c.x, c.v, a, &tensions);
      const test::DenseSolution ref = test::solveDense(*c.model, c.geometry, c.data, 0.0, c.ship, c.x, c.v);
      EXPECT_LT(relativeError(a, ref.accelerations), 1e-9) << "nu = " << segments << ", trial " << trial;
      EXPECT_LT(relativeError(tensions, ref.tensions), 1e-9) << "nu = " << segments << ", trial " << trial;
    }
  }
}

TEST(SolverVsDense, WithTheWinchPayingOutTheFirstSegment)
{
  std::mt19937 rng(4242);
  for (EndKind kind : { EndKind::kRigid, EndKind::kVehicleA })
  {
    for (int segments = 1; segments <= 20; ++segments)
    {
      const RandomCase c = makeRandomCase(segments, rng, kind, true);
      ChainSolver solver;
      Eigen::Matrix3Xd a(3, c.model->jointCount()), tensions(3, c.model->jointCount());
      solver.solve(*c.model, c.geometry, c.data, 0.2, c.ship, c.x, c.v, a, &tensions);
      const test::DenseSolution ref = test::solveDense(*c.model, c.geometry, c.data, 0.2, c.ship, c.x, c.v);
      EXPECT_LT(relativeError(a, ref.accelerations), 1e-9) << "nu = " << segments;
      EXPECT_LT(relativeError(tensions, ref.tensions), 1e-9) << "nu = " << segments;
    }
  }
}

TEST(SolverVsDense, WithTheFullVehicleInBothApproaches)
{
  std::mt19937 rng(777);
  for (EndKind kind : { EndKind::kVehicleA, EndKind::kVehicleB, EndKind::kVehicleBMunk })
  {
    for (int segments = 1; segments <= 30; ++segments)
    {
      for (int trial = 0; trial < 3; ++trial)
      {
        const RandomCase c = makeRandomCase(segments, rng, kind);
        ChainSolver solver;
        Eigen::Matrix3Xd a(3, c.model->jointCount()), tensions(3, c.model->jointCount());
        const double t = 0.4;  // fins part-way through their travel
        solver.solve(*c.model, c.geometry, c.data, t, c.ship, c.x, c.v, a, &tensions);
        const test::DenseSolution ref = test::solveDense(*c.model, c.geometry, c.data, t, c.ship, c.x, c.v);
        const int k = static_cast<int>(kind);
        EXPECT_LT(relativeError(a, ref.accelerations), 1e-9) << "kind " << k << ", nu = " << segments;
        EXPECT_LT(relativeError(tensions, ref.tensions), 1e-9) << "kind " << k << ", nu = " << segments;
      }
    }
  }
}

TEST(SolverVsDense, DenseReferenceSatisfiesHandCheckedPendulum)
{
  // One massless-cable-free check of the reference itself: a single end rod hanging at rest in vacuum
  // from a fixed point carries its weight; its tail does not accelerate.
  CableParams cable;
  cable.segments = 1;
  cable.length = 1.0;
  cable.mass_per_length = 2.0;
  EndElementParams end = test::endLikeSegment(cable);
  Environment env;
  env.water_density = 0.0;
  auto model = test::makeModel(cable, end, env);
  ShipEndState ship;
  Eigen::Matrix3Xd x(3, 2), v = Eigen::Matrix3Xd::Zero(3, 2);
  x << 0, 0, 0, 0, -1, -2;
  const test::DenseSolution ref = test::solveDense(*model, 0.0, ship, x, v);
  EXPECT_NEAR(ref.tensions(2, 0), 2.0 * 2.0 * env.gravity, 1e-9);  // both rods, 2 kg each
  EXPECT_NEAR(ref.tensions(2, 1), 2.0 * env.gravity, 1e-9);
  EXPECT_LT(ref.accelerations.norm(), 1e-9);
}

}  // namespace
}  // namespace tow_sim
