// The implicit stepper's stage solve (I - gamma h J) K = r in O(nu) must equal a dense solve of the same
// equations written the other way round: J assembled explicitly as a 6(nu+1)+2 square matrix, its
// acceleration rows from a dense KKT solve per column (the joint-space inertia built here from each
// element's 6 x 6 body inertia, the length constraints, the load derivatives D and K of elementJacobian,
// which test_chain_jacobian checks against central differences), then I - gamma h J factored with a full
// pivot LU. Random states, nu = 1 .. 20, the vehicle in Approaches A, B and B + Munk, the winch paying
// out, a seabed under part of the chain, a free first joint (a parted cable), an elastic cable.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <limits>
#include <random>

#include "core/random_chain.h"
#include "tow_sim/core/chain/chain_jacobian.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/integration/implicit_stepper.h"
#include "tow_sim/core/integration/simulator.h"

namespace tow_sim
{
namespace
{
using test::EndKind;
using test::makeRandomCase;
using test::RandomCase;

Eigen::Matrix3d crossMatrix(const Eigen::Vector3d& r)
{
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

struct Linearisation
{
  double d_length = 0.0, d_rate = 0.0;  // the winch's rate law's derivatives (given, not computed)
};

// The dense J of the linearised chain: d/dt (x, v, L, R) = (v, a, R, a_w(L, R)) with
// M a = K (x, x_tow) + D (v, v_tow) + G^T lambda, G a = 0 (M, G frozen at the state); its last six columns
// are the chain's response to the tow point's position and velocity (x_tow, v_tow). With `free` the first
// joint is an unknown too (a parted cable's free end, docs/solver.md (S27)): its rows and columns are laid
// out as StateLayout{nu + 1, true} says (after the cable out and the rate), the force on it from outside is
// the seabed's, and there are no tow-point columns.
using MatrixXld = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
using VectorXld = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

// J of a free chain from the ordering (x_1, x_2 .., v_1, v_2 .., L, R) to StateLayout's
// (x_2 .., v_2 .., L, R, x_1, v_1), n joints after the free one.
MatrixXld freeLayoutOrder(const MatrixXld& J, int n)
{
  const int size = static_cast<int>(J.rows()), dof = 3 * n + 3;
  std::vector<int> to(static_cast<size_t>(size));
  for (int i = 0; i < 3; ++i)
  {
    to[static_cast<size_t>(i)] = 6 * n + 2 + i;
    to[static_cast<size_t>(dof + i)] = 6 * n + 5 + i;
  }
  for (int i = 0; i < 3 * n; ++i)
  {
    to[static_cast<size_t>(3 + i)] = i;
    to[static_cast<size_t>(dof + 3 + i)] = 3 * n + i;
  }
  to[static_cast<size_t>(2 * dof)] = 6 * n;
  to[static_cast<size_t>(2 * dof + 1)] = 6 * n + 1;
  MatrixXld laid_out = MatrixXld::Zero(size, J.cols());
  for (int a = 0; a < size; ++a)
    for (int b = 0; b < size; ++b)
      laid_out(to[static_cast<size_t>(a)], to[static_cast<size_t>(b)]) = J(a, b);
  return laid_out;
}

// The seabed's force on a free first joint at `first` (half its segment's length in contact, as Chain's), and
// its derivatives.
Eigen::Vector3d freeJointContact(const RandomCase& c, const ShipEndState& first, Eigen::Matrix3d& df_dp,
                                 Eigen::Matrix3d& df_dv)
{
  df_dp.setZero();
  df_dv.setZero();
  const Seabed* bottom = c.model->seabed();
  if (!bottom || c.geometry.segments == 0)
    return Eigen::Vector3d::Zero();
  const double k = bottom->params().stiffness * 0.5 * c.geometry.elementLength(0);
  const double damping = bottom->params().damping * 0.5 * c.geometry.elementLength(0);
  bottom->contactJacobian(first.p_W, first.v_W, k, damping, df_dp, df_dv);
  return bottom->contactForce(first.p_W, first.v_W, k, damping);
}

// The constraint row of each element (-1: none), one per rigid element: an elastic cable's segments carry none
// (their tension is a load); `count` the number of rows.
std::vector<int> constraintRows(const RandomCase& c, int& count)
{
  const int n = c.geometry.elementCount();
  std::vector<int> row(static_cast<size_t>(n), -1);
  count = 0;
  for (int e = 0; e < n; ++e)
    if (!c.model->elastic() || e >= c.geometry.segments)
      row[static_cast<size_t>(e)] = count++;
  return row;
}

// A stretching segment of mass m along s: its kinetic energy (m/24)|s.(v_a - v_f)|^2 beyond the rigid body's
// (docs/solver.md §8), as joint-space inertia over (a_f, a_a).
Matrix6d stretchInertia(double m, const Eigen::Vector3d& s)
{
  const Eigen::Matrix3d ss = s * s.transpose() * (m / 12.0);
  Matrix6d M;
  M << ss, -ss, -ss, ss;
  return M;
}

// The accelerations' rows a = A rhs_cols of the KKT system [M -G^T; G 0] (a, lambda) = (rhs, 0), in long double:
// J has entries up to M^-1 K, and the reference must stay well inside 1e-8 at large h.
MatrixXld kktSolve(const Eigen::MatrixXd& M, const Eigen::MatrixXd& G, const Eigen::MatrixXd& rhs)
{
  const Eigen::Index dof = M.rows(), m = G.rows();
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(dof + m, dof + m);
  kkt << M, -G.transpose(), G, Eigen::MatrixXd::Zero(m, m);
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(dof + m, rhs.cols());
  full.topRows(dof) = rhs;
  return kkt.cast<long double>().fullPivLu().solve(full.cast<long double>());
}

MatrixXld denseJacobian(const RandomCase& c, double t, const Linearisation& lin, const std::vector<double>& multipliers,
                        const Eigen::Matrix3Xd& accelerations, bool free = false)
{
  const ChainModel& model = *c.model;
  const int n = c.geometry.elementCount();  // = joints
  const int first = free ? 3 : 0;           // the free joint's unknowns come first in this ordering
  const int dof = 3 * n + first;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(dof, dof), D = M, K = M;
  int constraints = 0;
  const std::vector<int> row = constraintRows(c, constraints);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(constraints, dof);
  Eigen::Matrix3d K_tow = Eigen::Matrix3d::Zero(), D_tow = K_tow;  // joint x_2's load on the tow point's motion
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  for (int e = 0; e < n; ++e)
  {
    const Eigen::Vector3d x_f = e == 0 ? c.ship.p_W : Eigen::Vector3d(c.x.col(e - 1));
    const Eigen::Vector3d v_f = e == 0 ? c.ship.v_W : Eigen::Vector3d(c.v.col(e - 1));
    const ElementKinematics k = ElementKinematics::fromJoints(x_f, c.x.col(e), v_f, c.v.col(e));
    BodyDynamics body;
    model.elementDynamics(e, t, k, c.geometry, c.data, body);
    // (a_G, dw/dt) = P (a_f, a_a): a_G = (1-g) a_f + g a_a, dw/dt = s x (a_a - a_f) / l.
    const double g = body.cg_fraction;
    Matrix6d P;
    P << (1.0 - g) * I3, g * I3, -crossMatrix(k.s) / k.length, crossMatrix(k.s) / k.length;
    Matrix6d M_e = P.transpose() * body.mass * P;
    if (row[static_cast<size_t>(e)] < 0)
      M_e += stretchInertia(model.segmentModel(e, c.geometry).mass, k.s);
    ElementJacobian jac;
    Vector6d a_joints;
    a_joints << (e == 0 ? c.ship.a_W : Eigen::Vector3d(accelerations.col(e - 1))), accelerations.col(e);
    elementJacobian(model, e, t, k, c.geometry, c.data, multipliers[e], jac, &a_joints);
    // Columns/rows of the element's two joints; the forward one of element 0 is the tow point (no unknown)
    // or the free joint.
    const int cols[2] = { e == 0 ? (free ? 0 : -1) : first + 3 * (e - 1), first + 3 * e };
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        if (cols[a] >= 0 && cols[b] >= 0)
        {
          M.block<3, 3>(cols[a], cols[b]) += M_e.block<3, 3>(3 * a, 3 * b);
          D.block<3, 3>(cols[a], cols[b]) += jac.dh_dv.block<3, 3>(3 * a, 3 * b);
          K.block<3, 3>(cols[a], cols[b]) += jac.dh_dx.block<3, 3>(3 * a, 3 * b);
        }
    if (e == 0)
    {
      K_tow = jac.dh_dx.block<3, 3>(3, 0);
      D_tow = jac.dh_dv.block<3, 3>(3, 0);
    }
    const int r = row[static_cast<size_t>(e)];
    if (r < 0)
      continue;
    G.block<1, 3>(r, cols[1]) = k.s.transpose();
    if (cols[0] >= 0)
      G.block<1, 3>(r, cols[0]) = -k.s.transpose();
  }
  if (free)  // the seabed on the free joint
  {
    Eigen::Matrix3d df_dp, df_dv;
    freeJointContact(c, c.ship, df_dp, df_dv);
    K.topLeftCorner<3, 3>() += df_dp;
    D.topLeftCorner<3, 3>() += df_dv;
  }
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(dof, 2 * dof + 6);
  rhs << K, D, Eigen::MatrixXd::Zero(dof, 6);
  rhs.block<3, 3>(first, 2 * dof) = K_tow;
  rhs.block<3, 3>(first, 2 * dof + 3) = D_tow;
  const MatrixXld sol = kktSolve(M, G, rhs);
  const int size = 2 * dof + 2;
  MatrixXld J = MatrixXld::Zero(size, size + 6);
  J.block(0, dof, dof, dof).setIdentity();
  J.block(dof, 0, dof, 2 * dof) = sol.topRows(dof).leftCols(2 * dof);
  J.block(dof, size, dof, 6) = sol.topRows(dof).rightCols(6);
  J(2 * dof, 2 * dof + 1) = 1.0;
  J(2 * dof + 1, 2 * dof) = lin.d_length;
  J(2 * dof + 1, 2 * dof + 1) = lin.d_rate;
  return free ? freeLayoutOrder(J, n) : J;
}

// One random case: the O(nu) stage solve against the dense one for several step sizes and right-hand sides.
// With `free`, the case's tow point is the free first joint of a parted chain (no winch on it).
void expectStageMatchesDense(const RandomCase& c, double t, std::mt19937& rng, const std::string& what,
                             bool free = false)
{
  const int n = c.geometry.elementCount();
  ChainSolver solver;
  Eigen::Matrix3Xd a(3, n);
  std::vector<double> multipliers;
  ShipEndState first = c.ship;
  Eigen::Matrix3d dF_dx = Eigen::Matrix3d::Zero(), dF_dv = Eigen::Matrix3d::Zero();
  if (free)
    first.a_W = solver.solveFree(*c.model, c.geometry, c.data, t, c.ship, c.x, c.v, a, nullptr, &multipliers,
                                 freeJointContact(c, c.ship, dF_dx, dF_dv));
  else
    solver.solve(*c.model, c.geometry, c.data, t, c.ship, c.x, c.v, a, nullptr, &multipliers);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Linearisation lin{ -0.5 + u(rng), -2.0 + u(rng) };
  const StateLayout layout{ n, free };
  ImplicitStepper stepper;
  if (free)
  {
    stepper.beginLinearisation(1, lin.d_length, lin.d_rate);
    stepper.lineariseChain(0, layout, *c.model, c.geometry, c.data, t, first, c.x, c.v, a, solver.terms(), multipliers,
                           dF_dx, dF_dv);
  }
  else
    stepper.linearise(*c.model, c.geometry, c.data, t, c.ship, c.x, c.v, a, solver.terms(), multipliers, lin.d_length,
                      lin.d_rate);
  RandomCase linearised = c;
  linearised.ship = first;
  const MatrixXld J = denseJacobian(linearised, t, lin, multipliers, a, free);
  for (double h : { 1e-3, 0.05, 0.5, 2.0 })
  {
    stepper.factor(h);
    // W over the chain's own state (the tow point's rows are not solved for).
    const int size = static_cast<int>(layout.size());
    const MatrixXld W = MatrixXld::Identity(size, size) -
                        static_cast<long double>(ImplicitStepper::kGamma * h) * J.topLeftCorner(size, size);
    const auto lu = W.fullPivLu();
    for (int trial = 0; trial < 2; ++trial)
    {
      std::vector<double> r(layout.size()), K;
      for (double& value : r)
        value = u(rng);
      // The tow point's increments are known: they move to the right-hand side (none on a free chain).
      const TowPointRates tow{ test::randomVector(rng, 1.0), test::randomVector(rng, 1.0) };
      stepper.solve(r, tow, K);
      VectorXld K_tow(6);
      K_tow << tow.x.cast<long double>(), tow.v.cast<long double>();
      const VectorXld rhs =
          Eigen::Map<const Eigen::VectorXd>(r.data(), r.size()).cast<long double>() +
          static_cast<long double>(ImplicitStepper::kGamma * h) * J.rightCols(6).topRows(r.size()) * K_tow;
      const Eigen::VectorXd reference = lu.solve(rhs).cast<double>();
      const Eigen::Map<const Eigen::VectorXd> value(K.data(), K.size());
      const double error = (value - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
      // A stiff elastic cable at long steps makes W ill-conditioned (1/rcond up to 1e13 at EA 1e8, h = 2 s): the
      // O(nu) solve in double then carries that much more rounding.
      const double tolerance = 1e-8 + 10.0 * std::numeric_limits<double>::epsilon() / static_cast<double>(lu.rcond());
      EXPECT_LT(error, tolerance) << what << ", nu = " << n - 1 << ", h = " << h << ", rcond " << lu.rcond();
    }
  }
}

TEST(ImplicitStage, RandomChainsWithARigidEndMatchTheDenseSolve)
{
  std::mt19937 rng(2024);
  for (int segments = 1; segments <= 20; ++segments)
    for (int trial = 0; trial < 3; ++trial)
      expectStageMatchesDense(makeRandomCase(segments, rng), 0.0, rng, "rigid end");
}

TEST(ImplicitStage, TheVehicleInApproachesAAndBAndWithMunkTerms)
{
  std::mt19937 rng(99);
  for (EndKind kind : { EndKind::kVehicleA, EndKind::kVehicleB, EndKind::kVehicleBMunk })
    for (int segments = 1; segments <= 20; ++segments)
      expectStageMatchesDense(makeRandomCase(segments, rng, kind), 0.4, rng,
                              "vehicle kind " + std::to_string(static_cast<int>(kind)));
}

TEST(ImplicitStage, WithTheWinchPayingOutAndASeabed)
{
  std::mt19937 rng(31337);
  for (EndKind kind : { EndKind::kRigid, EndKind::kVehicleB })
    for (int segments = 1; segments <= 20; ++segments)
    {
      expectStageMatchesDense(makeRandomCase(segments, rng, kind, true), 0.2, rng, "winch");
      expectStageMatchesDense(makeRandomCase(segments, rng, kind, false, true), 0.2, rng, "seabed");
    }
}

TEST(ImplicitStage, AnElasticCableMatchesTheDenseSolve)
{
  // Its segments carry no constraint: the sweep's (S21) for them, their axial stiffness and damping in J
  // (docs/solver.md §8), the consistent stretch inertia coded here from the rod's kinetic energy; the end
  // body constrained as always. Attached and parted (the free first joint).
  std::mt19937 rng(29);
  for (EndKind kind : { EndKind::kRigid, EndKind::kVehicleA })
    for (int segments = 1; segments <= 20; ++segments)
    {
      expectStageMatchesDense(makeRandomCase(segments, rng, kind, false, false, true), 0.1, rng, "elastic");
      expectStageMatchesDense(makeRandomCase(segments, rng, kind, false, false, true), 0.1, rng, "elastic, free", true);
    }
}

TEST(ImplicitStage, AFreeFirstJointMatchesTheDenseSolve)
{
  // A parted cable's vehicle side: the first joint's position and velocity are unknowns of the stage, with
  // nothing pulling on it but the seabed (about half of the cases lie on it there).
  std::mt19937 rng(4711);
  int in_contact = 0;
  for (EndKind kind : { EndKind::kRigid, EndKind::kVehicleA, EndKind::kVehicleB })
    for (int segments = 1; segments <= 20; ++segments)
    {
      expectStageMatchesDense(makeRandomCase(segments, rng, kind), 0.3, rng, "free", true);
      const RandomCase on_bottom = makeRandomCase(segments, rng, kind, false, true);
      Eigen::Matrix3d df_dp, df_dv;
      freeJointContact(on_bottom, on_bottom.ship, df_dp, df_dv);
      in_contact += df_dp.norm() > 0.0;
      expectStageMatchesDense(on_bottom, 0.3, rng, "free on a seabed", true);
    }
  EXPECT_GT(in_contact, 5);  // the free joint's contact was exercised
}

}  // namespace
}  // namespace tow_sim
