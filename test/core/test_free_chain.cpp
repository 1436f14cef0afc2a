// A chain with a free first joint (ChainSolver::solveFree, docs/solver.md §9: the vehicle side of a parted
// cable) against closed forms: in vacuum every joint of a chain moving as a whole falls at g with no
// tension, and a spinning chain's centre of mass still falls at g (its momentum changes by its weight
// alone); in water a free simple body lying level starts sinking at (W - B)/(m + m_a) and settles at its
// terminal velocity sqrt((W - B) / (1/2 rho C_n D L)); and a free solve agrees with the prescribed solve
// driven by the acceleration it found (the tension there is then zero).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <vector>

#include "chain_fixtures.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{

struct FreeChain
{
  std::shared_ptr<ChainModel> model;
  ChainGeometry geometry;
  ChainData data;
};

FreeChain freeChain(const CableParams& cable, const EndElementParams& end, const Environment& env, int segments)
{
  FreeChain c;
  c.model = test::makeModel(cable, end, env);
  c.data = c.model->initialData();
  c.geometry = c.model->initialGeometry();
  c.geometry.segments = segments;  // those aft of the break (0: the end body alone)
  return c;
}

// A bent chain: joints x_2 .. x_{nu+2} from `first` turning by 0.4 rad per element in a tilted plane.
Eigen::Matrix3Xd bentJoints(const ChainGeometry& g, const Eigen::Vector3d& first)
{
  Eigen::Matrix3Xd x(3, g.elementCount());
  Eigen::Vector3d p = first;
  for (int e = 0; e < g.elementCount(); ++e)
  {
    const double angle = 0.4 * e;
    p += g.elementLength(e) * Eigen::Vector3d(-std::cos(angle), 0.3 * std::sin(angle), -std::sin(angle)).normalized();
    x.col(e) = p;
  }
  return x;
}

TEST(FreeChain, InVacuumAChainMovingAsAWholeFallsAtGWithNoTension)
{
  CableParams cable;
  cable.length = 50.0;
  cable.segments = 5;
  Environment vacuum;
  vacuum.water_density = 0.0;
  const FreeChain c = freeChain(cable, EndElementParams(), vacuum, 5);
  ShipEndState first;
  first.p_W = Eigen::Vector3d(3.0, -2.0, -10.0);
  first.v_W = Eigen::Vector3d(1.0, -2.0, 0.5);
  const Eigen::Matrix3Xd x = bentJoints(c.geometry, first.p_W);
  Eigen::Matrix3Xd v(3, x.cols()), a(3, x.cols()), T;
  v.colwise() = first.v_W;
  ChainSolver solver;
  const Eigen::Vector3d a_first = solver.solveFree(*c.model, c.geometry, c.data, 0.0, first, x, v, a, &T);
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  EXPECT_LT((a_first - g).norm(), 1e-10);
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    EXPECT_LT((a.col(j) - g).norm(), 1e-10) << "joint " << j;
  EXPECT_LT(T.cwiseAbs().maxCoeff(), 1e-9 * 200.0 * 9.81);
}

TEST(FreeChain, InVacuumASpinningChainsCentreOfMassFallsAtG)
{
  CableParams cable;
  cable.length = 40.0;
  cable.segments = 4;
  Environment vacuum;
  vacuum.water_density = 0.0;
  const EndElementParams end;
  const FreeChain c = freeChain(cable, end, vacuum, 4);
  ShipEndState first;
  first.p_W = Eigen::Vector3d(0.0, 0.0, -20.0);
  first.v_W = Eigen::Vector3d(0.5, 0.0, 0.0);
  const Eigen::Matrix3Xd x = bentJoints(c.geometry, first.p_W);
  // Velocities with each element turning about its forward joint (s . (v_a - v_f) = 0: rigid).
  Eigen::Matrix3Xd v(3, x.cols()), a(3, x.cols()), T;
  Eigen::Vector3d x_f = first.p_W, v_f = first.v_W;
  for (Eigen::Index e = 0; e < x.cols(); ++e)
  {
    const Eigen::Vector3d w(0.1 * (e + 1), -0.2, 0.3 * (e % 2 ? 1 : -1));
    v.col(e) = v_f + w.cross(x.col(e) - x_f);
    x_f = x.col(e);
    v_f = v.col(e);
  }
  ChainSolver solver;
  const Eigen::Vector3d a_first = solver.solveFree(*c.model, c.geometry, c.data, 0.0, first, x, v, a, &T);
  // The centre of mass: each element's at its CG fraction between its joints (linear in them).
  Eigen::Vector3d momentum_rate = Eigen::Vector3d::Zero();
  double mass = 0.0;
  Eigen::Vector3d a_f = a_first;
  for (Eigen::Index e = 0; e < a.cols(); ++e)
  {
    const bool segment = e < c.geometry.segments;
    const double m = segment ? cable.mass_per_length * c.geometry.elementLength(static_cast<int>(e)) : end.mass;
    const double gamma = segment ? 0.5 : end.cg_from_bail / end.length;
    momentum_rate += m * ((1.0 - gamma) * a_f + gamma * a.col(e));
    mass += m;
    a_f = a.col(e);
  }
  EXPECT_LT((momentum_rate / mass - Eigen::Vector3d(0.0, 0.0, -9.81)).norm(), 1e-9);
  EXPECT_GT(T.cwiseAbs().maxCoeff(), 1.0);  // the spin does pull on the joints: not the trivial case
  EXPECT_LT(T.col(0).norm(), 1e-9);         // but nothing on the free end
}

// The simple body alone (no segment), level, CG and CB at its middle.
struct LevelBody
{
  EndElementParams end;
  Environment water;
  FreeChain chain;
  LevelBody() : chain(freeChain(CableParams(), end, water, 0)) {}
  double netWeight() const { return (end.mass - water.water_density * end.displaced_volume) * water.gravity; }
};

TEST(FreeChain, AFreeSimpleBodyStartsSinkingAtItsNetWeightOverMassAndAddedMass)
{
  const LevelBody b;
  EXPECT_EQ(b.chain.geometry.elementLength(0), b.end.length);  // no segment: element 0 is the body
  ShipEndState bail;
  bail.p_W = Eigen::Vector3d(0.0, 0.0, -50.0);
  Eigen::Matrix3Xd x(3, 1), v = Eigen::Matrix3Xd::Zero(3, 1), a(3, 1);
  x.col(0) = bail.p_W - Eigen::Vector3d(b.end.length, 0.0, 0.0);
  ChainSolver solver;
  const Eigen::Vector3d a_bail = solver.solveFree(*b.chain.model, b.chain.geometry, b.chain.data, 0.0, bail, x, v, a);
  const double added = b.end.added_mass_coefficient * b.water.water_density * 0.25 * kPi * b.end.diameter *
                       b.end.diameter * b.end.length;
  const double expected = -b.netWeight() / (b.end.mass + added);
  EXPECT_NEAR(a_bail.z(), expected, 1e-12 * std::abs(expected));
  EXPECT_NEAR(a(2, 0), expected, 1e-12 * std::abs(expected));
  EXPECT_LT(a_bail.head<2>().norm() + a.col(0).head<2>().norm(), 1e-12);
}

TEST(FreeChain, AFreeSimpleBodySettlesAtItsTerminalVelocity)
{
  // Integrated here (classical RK4, 10 ms) from rest for 20 s: the time constant is about 0.4 s.
  const LevelBody b;
  ChainSolver solver;
  Eigen::Matrix<double, 12, 1> y;  // bail and tail positions, then their velocities
  y << 0.0, 0.0, -50.0, -b.end.length, 0.0, -50.0, 0, 0, 0, 0, 0, 0;
  auto f = [&](const Eigen::Matrix<double, 12, 1>& s)
  {
    ShipEndState bail;
    bail.p_W = s.segment<3>(0);
    bail.v_W = s.segment<3>(6);
    Eigen::Matrix3Xd x = s.segment<3>(3), v = s.segment<3>(9), a(3, 1);
    const Eigen::Vector3d a_bail = solver.solveFree(*b.chain.model, b.chain.geometry, b.chain.data, 0.0, bail, x, v, a);
    Eigen::Matrix<double, 12, 1> d;
    d << s.segment<6>(6), a_bail, a.col(0);
    return d;
  };
  const double h = 0.01;
  for (int i = 0; i < 2000; ++i)
  {
    const auto k1 = f(y), k2 = f(y + 0.5 * h * k1), k3 = f(y + 0.5 * h * k2), k4 = f(y + h * k3);
    y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  const double c2 = 0.5 * b.water.water_density * b.end.normal_drag_coefficient * b.end.diameter;
  const double v_terminal = std::sqrt(b.netWeight() / (c2 * b.end.length));
  std::printf("terminal velocity: %.6f m/s (closed form %.6f m/s)\n", -y(8), v_terminal);
  EXPECT_NEAR(y(8), -v_terminal, 1e-6 * v_terminal);
  EXPECT_NEAR(y(11), -v_terminal, 1e-6 * v_terminal);
  EXPECT_NEAR(y(2) - y(5), 0.0, 1e-9);               // still level
  EXPECT_LT(y(2), -50.0 - 20.0 * v_terminal + 2.0);  // and it did sink, the last ~1 s short of the whole 20 s
}

TEST(FreeChain, TheFreeSolveIsThePrescribedSolveWithZeroTensionAtTheFreeJoint)
{
  CableParams cable;
  cable.length = 30.0;
  cable.segments = 3;
  Environment water;
  water.current_W = Eigen::Vector3d(0.3, -0.2, 0.0);
  const FreeChain c = freeChain(cable, EndElementParams(), water, 3);
  ShipEndState first;
  first.p_W = Eigen::Vector3d(0.0, 0.0, -5.0);
  first.v_W = Eigen::Vector3d(1.5, 0.2, -0.3);
  const Eigen::Matrix3Xd x = bentJoints(c.geometry, first.p_W);
  Eigen::Matrix3Xd v(3, x.cols()), a_free(3, x.cols()), a(3, x.cols()), T;
  v.colwise() = first.v_W;
  v.col(1) += Eigen::Vector3d(0.0, 0.5, 0.0);  // not rigid-compatible: the constraints' c terms act too
  ChainSolver solver;
  first.a_W = solver.solveFree(*c.model, c.geometry, c.data, 0.0, first, x, v, a_free);
  solver.solve(*c.model, c.geometry, c.data, 0.0, first, x, v, a, &T);
  EXPECT_LT(T.col(0).norm(), 1e-9 * T.cwiseAbs().maxCoeff());
  EXPECT_LT((a - a_free).cwiseAbs().maxCoeff(), 1e-10);
}

}  // namespace
}  // namespace tow_sim
