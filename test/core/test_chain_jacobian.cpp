// The implicit stepper's load derivatives (chain_jacobian.h) against central differences of the loads
// they differentiate: the drag and rotation-drag moment (also where the normal flow vanishes and inside the
// tangential drag's smoothing band), a cable segment's projected loads in its joint velocities (with the
// winch paying out and on the seabed), the seabed contact force, the geometric stiffness, and the end
// body's own central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "core/random_chain.h"
#include "tow_sim/core/chain/chain_jacobian.h"
#include "tow_sim/core/geometry.h"

namespace tow_sim
{
namespace
{
using test::EndKind;
using test::makeRandomCase;
using test::RandomCase;
using test::randomVector;

// Central differences of f (R^3 -> R^3) at x with step h.
Eigen::Matrix3d centralDifferences(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& f,
                                   const Eigen::Vector3d& x, double h)
{
  Eigen::Matrix3d J;
  for (int j = 0; j < 3; ++j)
  {
    Eigen::Vector3d plus = x, minus = x;
    plus[j] += h;
    minus[j] -= h;
    J.col(j) = (f(plus) - f(minus)) / (2.0 * h);
  }
  return J;
}

double relativeDifference(const Eigen::MatrixXd& value, const Eigen::MatrixXd& reference)
{
  return (value - reference).norm() / std::max(reference.norm(), 1e-300);
}

// The drag and moment at u = the centre's velocity through the water, dv = v_a - v_f, axis s, length d.
struct DragCase
{
  Eigen::Vector3d s, u, dv;
  double d, c1, c2, smoothing;
  TangentialDragModel model;

  ElementKinematics kinematics(const Eigen::Vector3d& u_at, const Eigen::Vector3d& dv_at) const
  {
    // Joints about the origin with the centre's velocity u_at (no current) and the relative velocity dv_at.
    return ElementKinematics::fromJoints(-0.5 * d * s, 0.5 * d * s, u_at - 0.5 * dv_at, u_at + 0.5 * dv_at);
  }
  VelocityForces forces(const Eigen::Vector3d& u_at, const Eigen::Vector3d& dv_at) const
  {
    return velocityForces(kinematics(u_at, dv_at), Eigen::Vector3d::Zero(), c1, c2, model, smoothing);
  }
};

void expectDragJacobianMatches(const DragCase& c, double step, double tolerance, const std::string& what)
{
  const VelocityForceJacobian J =
      velocityForceJacobian(c.kinematics(c.u, c.dv), Eigen::Vector3d::Zero(), c.c1, c.c2, c.model, c.smoothing);
  const Eigen::Matrix3d force_u =
      centralDifferences([&](const Eigen::Vector3d& u) { return c.forces(u, c.dv).force; }, c.u, step);
  const Eigen::Matrix3d moment_u =
      centralDifferences([&](const Eigen::Vector3d& u) { return c.forces(u, c.dv).moment; }, c.u, step);
  // The moment is linear in dv: a large step has no truncation error and less rounding.
  const Eigen::Matrix3d moment_dv =
      centralDifferences([&](const Eigen::Vector3d& dv) { return c.forces(c.u, dv).moment; }, c.dv, 1e-3);
  EXPECT_LT(relativeDifference(J.force_u, force_u), tolerance) << what << "\n" << J.force_u << "\n" << force_u;
  EXPECT_LT(relativeDifference(J.moment_u, moment_u), tolerance) << what << "\n" << J.moment_u << "\n" << moment_u;
  EXPECT_LT(relativeDifference(J.moment_dv, moment_dv), tolerance) << what;
}

TEST(ChainJacobian, DragAndRotationDragMomentMatchCentralDifferences)
{
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial)
  {
    DragCase c;
    c.s = randomVector(rng, 1.0).normalized();
    c.u = randomVector(rng, 3.0);
    c.dv = randomVector(rng, 1.0);
    c.d = 0.2 + 10.0 * unit(rng);
    c.c1 = 5.0 * unit(rng);
    c.c2 = 50.0 * unit(rng);
    c.smoothing = 0.001 + 0.1 * unit(rng);
    c.model = trial % 2 ? TangentialDragModel::kPode : TangentialDragModel::kQuadratic;
    switch (trial % 4)
    {
      case 0:  // general
        break;
      case 1:  // the tangential flow inside the smoothing band: |u.s| = 0.3 e
        c.u += (0.3 * c.smoothing - c.u.dot(c.s)) * c.s;
        break;
      case 2:  // the normal flow nearly gone: |u_n| = 1e-4 m/s
      {
        const Eigen::Vector3d u_n = c.u - c.u.dot(c.s) * c.s;
        c.u += (1e-4 / u_n.norm() - 1.0) * u_n;
        break;
      }
      case 3:  // quadratic tangential drag near u.s = 0 (|u.s| = 1e-3)
        c.u += (1e-3 - c.u.dot(c.s)) * c.s;
        break;
    }
    // Steps well inside the features: the band, |u_n|, |u.s|.
    const double step = trial % 4 == 0 ? 1e-6 : 1e-8;
    expectDragJacobianMatches(c, step, 1e-6, "trial " + std::to_string(trial));
  }
}

TEST(ChainJacobian, DragDerivativeVanishesWithTheNormalFlow)
{
  // u along the axis: the normal drag and the moment have zero derivative in u_n's plane at u_n = 0
  // (both are quadratic there), which is what velocityForceJacobian returns.
  DragCase c{
    Eigen::Vector3d::UnitX(),  Eigen::Vector3d(1.5, 0.0, 0.0), Eigen::Vector3d(0.0, 0.3, 0.0), 1.0, 2.0, 30.0, 0.01,
    TangentialDragModel::kPode
  };
  const VelocityForceJacobian J =
      velocityForceJacobian(c.kinematics(c.u, c.dv), Eigen::Vector3d::Zero(), c.c1, c.c2, c.model, c.smoothing);
  EXPECT_EQ((J.force_u.bottomRightCorner<2, 2>().norm()), 0.0);
  EXPECT_EQ(J.moment_u.norm(), 0.0);
  EXPECT_EQ(J.moment_dv.norm(), 0.0);
}

// The loads of element e as the solver projects them (ChainSolver::elementTerms): h = [J_f J_a]^T w, with
// the winch's turning term on the first segment.
Vector6d projectedLoads(const RandomCase& c, int e, double t, const ElementKinematics& k)
{
  BodyDynamics body;
  c.model->elementDynamics(e, t, k, c.geometry, c.data, body);
  if (e == 0 && c.geometry.first_rate != 0.0)
    body.wrench -= body.mass.rightCols<3>() * (-2.0 * c.geometry.first_rate / k.length * k.omega);
  return jointMap(k.s, k.length, body.cg_fraction).transpose() * body.wrench;
}

ElementKinematics kinematicsOf(const RandomCase& c, int e)
{
  const Eigen::Vector3d x_f = e == 0 ? c.ship.p_W : Eigen::Vector3d(c.x.col(e - 1));
  const Eigen::Vector3d v_f = e == 0 ? c.ship.v_W : Eigen::Vector3d(c.v.col(e - 1));
  return ElementKinematics::fromJoints(x_f, c.x.col(e), v_f, c.v.col(e));
}

// d h / d(v_f, v_a) by central differences.
Matrix6d velocityDifferences(const RandomCase& c, int e, double t, double step)
{
  const ElementKinematics k = kinematicsOf(c, e);
  Matrix6d D;
  for (int j = 0; j < 6; ++j)
  {
    Eigen::Vector3d v_f = k.v_f, v_a = k.v_a;
    Eigen::Vector3d& v = j < 3 ? v_f : v_a;
    v[j % 3] += step;
    const Vector6d plus = projectedLoads(c, e, t, ElementKinematics::fromJoints(k.x_f, k.x_a, v_f, v_a));
    v[j % 3] -= 2.0 * step;
    const Vector6d minus = projectedLoads(c, e, t, ElementKinematics::fromJoints(k.x_f, k.x_a, v_f, v_a));
    D.col(j) = (plus - minus) / (2.0 * step);
  }
  return D;
}

TEST(ChainJacobian, CableSegmentVelocityBlockMatchesCentralDifferencesOfItsLoads)
{
  // Every velocity dependence of a segment's loads is in the block: drag, moment, the winch's term and
  // the seabed's damping and friction. Random chains, the winch paying out, half the joints in the bottom.
  std::mt19937 rng(8);
  int on_bottom = 0;
  for (int trial = 0; trial < 60; ++trial)
  {
    const RandomCase c = makeRandomCase(3 + trial % 5, rng, EndKind::kRigid, trial % 2 == 0, trial % 3 == 0);
    for (int e = 0; e < c.model->segments(); ++e)
    {
      const ElementKinematics k = kinematicsOf(c, e);
      if (c.model->seabed() && c.model->seabed()->altitude(k.x_a) < 0.0)
        ++on_bottom;
      ElementJacobian J;
      elementJacobian(*c.model, e, 0.0, k, c.geometry, c.data, 0.0, J);
      const Matrix6d D = velocityDifferences(c, e, 0.0, 1e-6);
      EXPECT_LT(relativeDifference(J.dh_dv, D), 1e-6) << "trial " << trial << ", element " << e;
    }
  }
  EXPECT_GT(on_bottom, 20);  // the seabed's terms were exercised
}

TEST(ChainJacobian, SeabedContactForceDerivativesMatchCentralDifferences)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (bool grid : { false, true })
  {
    SeabedParams p;
    p.friction = 0.7;
    p.friction_speed = 0.05;
    if (grid)
    {
      p.type = SeabedParams::Type::kGrid;
      p.grid.origin = Eigen::Vector2d(0.0, 0.0);
      p.grid.spacing = Eigen::Vector2d(10.0, 10.0);
      p.grid.depth.resize(3, 3);
      p.grid.depth << 50, 52, 55, 51, 54, 58, 53, 57, 62;
    }
    else
    {
      p.type = SeabedParams::Type::kFlat;
      p.depth = 50.0;
    }
    const Seabed bottom(p);
    for (int trial = 0; trial < 100; ++trial)
    {
      // Inside a grid cell (the bilinear depth is smooth there), 0 .. 0.2 m into the bottom, sliding.
      const double x = 1.0 + 8.0 * unit(rng), y = 1.0 + 8.0 * unit(rng);
      const Eigen::Vector3d p_W(x, y, bottom.bottomZ(x, y) - 0.2 * unit(rng) - 1e-3);
      const Eigen::Vector3d v_W = randomVector(rng, 0.3);
      const double k = 1e4, damping = 50.0 * unit(rng);
      if ((k * -bottom.altitude(p_W) * bottom.normal(x, y).z() - damping * v_W.dot(bottom.normal(x, y))) <= 0.01)
        continue;  // not pushing: nothing to differentiate
      Eigen::Matrix3d df_dp, df_dv;
      bottom.contactJacobian(p_W, v_W, k, damping, df_dp, df_dv);
      const Eigen::Matrix3d fd_v = centralDifferences(
          [&](const Eigen::Vector3d& v) { return bottom.contactForce(p_W, v, k, damping); }, v_W, 1e-7);
      EXPECT_LT(relativeDifference(df_dv, fd_v), 1e-6) << (grid ? "grid" : "flat") << " trial " << trial;
      const Eigen::Matrix3d fd_p = centralDifferences(
          [&](const Eigen::Vector3d& q) { return bottom.contactForce(q, v_W, k, damping); }, p_W, 1e-7);
      // On a grid the normal turns with the position: left out, so there only the flat bottom is exact.
      const double tolerance = grid ? 0.05 : 1e-6;
      EXPECT_LT(relativeDifference(df_dp, fd_p), tolerance) << (grid ? "grid" : "flat") << " trial " << trial;
    }
    // Above the bottom: no force, no derivative.
    Eigen::Matrix3d df_dp, df_dv;
    bottom.contactJacobian(Eigen::Vector3d(5.0, 5.0, -10.0), Eigen::Vector3d(1.0, 0.0, -1.0), 1e4, 10.0, df_dp, df_dv);
    EXPECT_EQ(df_dp.norm() + df_dv.norm(), 0.0);
  }
}

TEST(ChainJacobian, GeometricStiffnessIsTheDerivativeOfTheAxialForceTurningWithTheAxis)
{
  std::mt19937 rng(17);
  for (int trial = 0; trial < 50; ++trial)
  {
    const Eigen::Vector3d x_f = randomVector(rng, 10.0), x_a = x_f + randomVector(rng, 3.0);
    const double mu = -1000.0 * (trial + 1);  // a tension
    // The axial force as loads on the two joints: (-mu s, +mu s), s = (x_a - x_f)/|x_a - x_f|.
    auto axial = [&](const Eigen::Vector3d& f, const Eigen::Vector3d& a)
    {
      const Eigen::Vector3d s = (a - f).normalized();
      Vector6d h;
      h << -mu * s, mu * s;
      return h;
    };
    Matrix6d fd;
    for (int j = 0; j < 6; ++j)
    {
      Eigen::Vector3d f = x_f, a = x_a;
      Eigen::Vector3d& moved = j < 3 ? f : a;
      moved[j % 3] += 1e-6;
      const Vector6d plus = axial(f, a);
      moved[j % 3] -= 2e-6;
      fd.col(j) = (plus - axial(f, a)) / 2e-6;
    }
    ElementJacobian J;
    J.dh_dx.setZero();
    J.dh_dv.setZero();
    addGeometricStiffness(ElementKinematics::fromJoints(x_f, x_a, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), mu,
                          J);
    EXPECT_LT(relativeDifference(J.dh_dx, fd), 1e-7) << "trial " << trial;
  }
  // A compression adds nothing.
  ElementJacobian J;
  J.dh_dx.setZero();
  addGeometricStiffness(ElementKinematics::fromJoints(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                                      Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                        500.0, J);
  EXPECT_EQ(J.dh_dx.norm(), 0.0);
}

// An elastic segment's axial force as loads on its joints, (+T s, -T s) with T = max(0, EA (d/d0 - 1) +
// c s.(v_a - v_f)/d0) written out here: its derivatives in the joint positions (at rest: the stiffness and
// the force turning with the axis) and in the velocities (the damping) against central differences, taut;
// slack, nothing.
TEST(ChainJacobian, ElasticAxialForceDerivativesMatchCentralDifferences)
{
  CableParams cable;
  cable.axial_stiffness = 2.0e5;
  cable.axial_damping = 3.0e3;
  const double d0 = 2.0;
  std::mt19937 rng(29);
  auto loads = [&](const Eigen::Vector3d& x_f, const Eigen::Vector3d& x_a, const Eigen::Vector3d& v_f,
                   const Eigen::Vector3d& v_a)
  {
    const Eigen::Vector3d s = (x_a - x_f).normalized();
    const double d = (x_a - x_f).norm();
    const double T =
        std::max(0.0, *cable.axial_stiffness * (d / d0 - 1.0) + cable.axial_damping * s.dot(v_a - v_f) / d0);
    Vector6d h;
    h << T * s, -T * s;
    return h;
  };
  for (int trial = 0; trial < 40; ++trial)
  {
    const Eigen::Vector3d x_f = randomVector(rng, 10.0);
    const Eigen::Vector3d axis = randomVector(rng, 1.0).normalized();
    const Eigen::Vector3d x_a = x_f + d0 * (1.01 + 0.002 * trial) * axis;  // stretched 1 .. 9 %
    const bool moving = trial % 2 == 1;
    // Moving: the relative velocity along the axis only (its normal part turns s, left out of J).
    const Eigen::Vector3d v_f = randomVector(rng, 1.0), v_a = v_f + (moving ? 0.05 : 0.0) * axis;
    Matrix6d fd_x, fd_v;
    for (int j = 0; j < 12; ++j)
    {
      Eigen::Vector3d joint[4] = { x_f, x_a, v_f, v_a };
      joint[j / 3][j % 3] += 1e-6;
      const Vector6d plus = loads(joint[0], joint[1], joint[2], joint[3]);
      joint[j / 3][j % 3] -= 2e-6;
      (j < 6 ? fd_x : fd_v).col(j % 6) = (plus - loads(joint[0], joint[1], joint[2], joint[3])) / 2e-6;
    }
    const ElementKinematics k = ElementKinematics::fromJoints(x_f, x_a, v_f, v_a);
    const double T = -loads(x_f, x_a, v_f, v_a).tail<3>().dot(k.s);
    ElementJacobian J;
    J.dh_dx.setZero();
    J.dh_dv.setZero();
    addGeometricStiffness(k, -T, J);
    addAxialStiffness(cable, d0, k, J);
    if (!moving)  // with a stretch rate the damping's turning with s is left out of J
    {
      EXPECT_LT(relativeDifference(J.dh_dx, fd_x), 1e-6) << "trial " << trial;
    }
    EXPECT_LT(relativeDifference(J.dh_dv, fd_v), 1e-6) << "trial " << trial;
  }
  // Slack: no force, no derivative.
  ElementJacobian J;
  J.dh_dx.setZero();
  J.dh_dv.setZero();
  addAxialStiffness(cable, d0,
                    ElementKinematics::fromJoints(Eigen::Vector3d::Zero(), 1.9 * Eigen::Vector3d::UnitX(),
                                                  Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                    J);
  EXPECT_EQ(J.dh_dx.norm() + J.dh_dv.norm(), 0.0);
}

TEST(ChainJacobian, EndBodyDifferencesMatchCentralDifferencesOfItsLoads)
{
  // The vehicle in Approach A, B and B with the Munk terms, fins moving, thrust, on the seabed or not.
  std::mt19937 rng(99);
  for (EndKind kind : { EndKind::kRigid, EndKind::kVehicleA, EndKind::kVehicleB, EndKind::kVehicleBMunk })
  {
    for (int trial = 0; trial < 10; ++trial)
    {
      const RandomCase c = makeRandomCase(2, rng, kind, false, trial % 2 == 1);
      const int e = c.model->segments();
      const ElementKinematics k = kinematicsOf(c, e);
      const double t = 0.4;
      ElementJacobian J;
      elementJacobian(*c.model, e, t, k, c.geometry, c.data, 0.0, J);
      const Matrix6d D = velocityDifferences(c, e, t, 1e-5);
      EXPECT_LT(relativeDifference(J.dh_dv, D), 1e-5) << "kind " << static_cast<int>(kind) << ", trial " << trial;
      Matrix6d K;
      for (int j = 0; j < 6; ++j)
      {
        Eigen::Vector3d x_f = k.x_f, x_a = k.x_a;
        Eigen::Vector3d& x = j < 3 ? x_f : x_a;
        x[j % 3] += 1e-5;
        const Vector6d plus = projectedLoads(c, e, t, ElementKinematics::fromJoints(x_f, x_a, k.v_f, k.v_a));
        x[j % 3] -= 2e-5;
        const Vector6d minus = projectedLoads(c, e, t, ElementKinematics::fromJoints(x_f, x_a, k.v_f, k.v_a));
        K.col(j) = (plus - minus) / 2e-5;
      }
      EXPECT_LT(relativeDifference(J.dh_dx, K), 1e-5) << "kind " << static_cast<int>(kind) << ", trial " << trial;
    }
  }
}

TEST(ChainJacobian, EndBodyInertiaTurningWithItsAxisMatchesCentralDifferences)
{
  // With the joints' accelerations given, K also holds -d(J^T M_b J)/dx (a_f, a_a).
  std::mt19937 rng(5150);
  for (EndKind kind : { EndKind::kVehicleA, EndKind::kVehicleB, EndKind::kVehicleBMunk })
  {
    for (int trial = 0; trial < 10; ++trial)
    {
      const RandomCase c = makeRandomCase(2, rng, kind);
      const int e = c.model->segments();
      const ElementKinematics k = kinematicsOf(c, e);
      const double t = 0.4;
      Vector6d a;
      a << test::randomVector(rng, 20.0), test::randomVector(rng, 20.0);
      ElementJacobian J;
      elementJacobian(*c.model, e, t, k, c.geometry, c.data, 0.0, J, &a);
      auto balance = [&](const ElementKinematics& kk) -> Vector6d
      {
        BodyDynamics body;
        c.model->elementDynamics(e, t, kk, c.geometry, c.data, body);
        const Matrix6d map = jointMap(kk.s, kk.length, body.cg_fraction);
        return map.transpose() * (body.wrench - body.mass * (map * a));
      };
      Matrix6d K;
      for (int j = 0; j < 6; ++j)
      {
        Eigen::Vector3d x_f = k.x_f, x_a = k.x_a;
        Eigen::Vector3d& x = j < 3 ? x_f : x_a;
        x[j % 3] += 1e-5;
        const Vector6d plus = balance(ElementKinematics::fromJoints(x_f, x_a, k.v_f, k.v_a));
        x[j % 3] -= 2e-5;
        const Vector6d minus = balance(ElementKinematics::fromJoints(x_f, x_a, k.v_f, k.v_a));
        K.col(j) = (plus - minus) / 2e-5;
      }
      EXPECT_LT(relativeDifference(J.dh_dx, K), 1e-5) << "kind " << static_cast<int>(kind) << ", trial " << trial;
      // And the term is there: without the accelerations K differs.
      ElementJacobian without;
      elementJacobian(*c.model, e, t, k, c.geometry, c.data, 0.0, without);
      EXPECT_GT(relativeDifference(without.dh_dx, K), 5e-5) << "kind " << static_cast<int>(kind);
    }
  }
}

}  // namespace
}  // namespace tow_sim
