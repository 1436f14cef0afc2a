// The O(nu) sweep must reproduce the dense Newton-Euler solve (physics.md §8) for random states.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "core/chain_fixtures.h"
#include "core/dense_reference.h"
#include "tow_sim/core/chain_solver.h"
#include "tow_sim/core/vehicle.h"

namespace tow_sim
{
namespace
{
struct RandomCase
{
  std::shared_ptr<ChainModel> model;
  ChainData data;  // the actuators commanded, the first segment paid out
  ShipEndState ship;
  Eigen::Matrix3Xd x, v;
};

Eigen::Vector3d randomVector(std::mt19937& rng, double scale)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Eigen::Vector3d(u(rng), u(rng), u(rng));
}

enum class EndKind
{
  kRigid,
  kVehicleA,
  kVehicleB,
  kVehicleBMunk
};

// A vehicle with random geometry, inertia with products, fins mid-travel and thrust.
std::shared_ptr<Vehicle> makeRandomVehicle(EndKind kind, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  VehicleParams p;
  p.tail_from_bail = 0.5 + 2.5 * u(rng);
  p.nose_from_bail = u(rng);
  auto along = [&] { return -p.nose_from_bail + (p.nose_from_bail + p.tail_from_bail) * u(rng); };
  p.cg_from_bail = along();
  p.cb_from_bail = along();
  p.horizontal_fin_from_bail = along();
  p.vertical_fin_from_bail = along();
  p.mass = 20.0 + 300.0 * u(rng);
  p.displaced_volume = 0.3 * u(rng);
  const Eigen::Matrix3d a = Eigen::Matrix3d::Random();
  p.inertia_B = a * a.transpose() + Eigen::Vector3d(1.0, 20.0, 20.0).asDiagonal().toDenseMatrix();
  p.c1 = 50.0 * u(rng);
  p.c2 = 400.0 * u(rng);
  p.added_mass_a = 200.0 * u(rng);
  const Matrix6d b = Matrix6d::Random();
  p.added_mass_b = 30.0 * b * b.transpose();
  p.added_mass_approach = kind == EndKind::kVehicleA ? AddedMassApproach::kA : AddedMassApproach::kB;
  p.munk_terms = kind == EndKind::kVehicleBMunk;
  p.thrust_offset_z = u(rng) - 0.5;
  p.rudder.center_of_pressure_offset = 0.05;
  return std::make_shared<Vehicle>(p);
}

// winch: the first segment is paid out (random length, rate and acceleration) while the rest is not.
RandomCase makeRandomCase(int segments, std::mt19937& rng, EndKind kind = EndKind::kRigid, bool winch = false)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  CableParams cable;
  cable.segments = segments;
  cable.length = 20.0 + 480.0 * u(rng);
  cable.diameter = 0.005 + 0.05 * u(rng);
  cable.mass_per_length = 0.1 + 3.0 * u(rng);
  cable.normal_drag_coefficient = 2.0 * u(rng);
  cable.tangential_drag_coefficient = 0.05 * u(rng);
  cable.added_mass_coefficient = 1.5 * u(rng);
  cable.tangential_drag_model = u(rng) < 0.5 ? TangentialDragModel::kPode : TangentialDragModel::kQuadratic;
  EndElementParams end;
  end.length = 0.5 + 4.0 * u(rng);
  end.mass = 10.0 + 500.0 * u(rng);
  end.displaced_volume = 0.3 * u(rng);
  end.cg_from_bail = end.length * u(rng);
  end.cb_from_bail = end.length * u(rng);
  end.diameter = 0.1 + 0.5 * u(rng);
  Environment env;
  env.current_W = randomVector(rng, 1.5);

  RandomCase c;
  if (kind == EndKind::kRigid)
    c.model = test::makeModel(cable, end, env);
  else
    c.model = std::make_shared<ChainModel>(cable, makeRandomVehicle(kind, rng), env, NumericsParams());
  c.ship.p_W = randomVector(rng, 100.0);
  c.ship.v_W = randomVector(rng, 3.0);
  c.ship.a_W = randomVector(rng, 0.5);
  c.data = c.model->initialData(0.0);
  if (kind != EndKind::kRigid)
    c.model->endBody().command(c.data.actuators, 0.0, 0.6 * (u(rng) - 0.5), 0.6 * (u(rng) - 0.5),
                               400.0 * (u(rng) - 0.5));
  double payout_rate = 0.0;
  if (winch)
  {
    payout_rate = 4.0 * (u(rng) - 0.5);
    c.data.geometry.first_length = (0.5 + u(rng)) * c.model->nominalSegmentLength();
    c.data.geometry.first_rate = payout_rate;
    c.data.geometry.first_acceleration = 2.0 * (u(rng) - 0.5);
  }
  const int n = c.model->jointCount();
  c.x.resize(3, n);
  c.v.resize(3, n);
  Eigen::Vector3d x_f = c.ship.p_W, v_f = c.ship.v_W;
  for (int e = 0; e < n; ++e)
  {
    const Eigen::Vector3d s = randomVector(rng, 1.0).normalized();
    const Eigen::Vector3d omega = randomVector(rng, 0.3);
    const double d = c.data.geometry.elementLength(e);
    c.x.col(e) = x_f + d * s;
    c.v.col(e) = v_f + d * omega.cross(s);  // consistent with the length constraint
    if (e == 0)
      c.v.col(e) += payout_rate * s;  // ... and the winch's rate
    x_f = c.x.col(e);
    v_f = c.v.col(e);
  }
  return c;
}

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
      solver.solve(*c.model, c.data.geometry, c.data, 0.0, c.ship, c.x, c.v, a, &tensions);
      const test::DenseSolution ref = test::solveDense(*c.model, c.data.geometry, c.data, 0.0, c.ship, c.x, c.v);
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
      solver.solve(*c.model, c.data.geometry, c.data, 0.2, c.ship, c.x, c.v, a, &tensions);
      const test::DenseSolution ref = test::solveDense(*c.model, c.data.geometry, c.data, 0.2, c.ship, c.x, c.v);
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
        solver.solve(*c.model, c.data.geometry, c.data, t, c.ship, c.x, c.v, a, &tensions);
        const test::DenseSolution ref = test::solveDense(*c.model, c.data.geometry, c.data, t, c.ship, c.x, c.v);
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
