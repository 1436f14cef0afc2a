#include "tow_sim/core/chain/chain_solver.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "tow_sim/core/chain/element_equations.h"
#include "tow_sim/core/geometry.h"

namespace tow_sim
{
namespace
{
// (S20)-(S20'): an elastic segment's stretch. Its joints move apart along s, which the rigid projection has no
// inertia for: the stretch mode's m/12 s s^T in the consistent-mass pattern [1 -1; -1 1] (with the rigid
// part, m [1/3 1/6; 1/6 1/3] for the structural mass); its tension T = max(0, EA eps + C deps/dt) (C the axial
// damping) pulls the forward joint aft (+T s) and the aft joint forward (-T s). m.h_f, m.h_a are w_f, w_a.
void addStretch(const CableParams& cable, double rest_length, double mass, const ElementKinematics& k, ElementTerms& m)
{
  const Eigen::Matrix3d stretch = (mass / 12.0) * k.s * k.s.transpose();  // (S20'): (m/12) s s^T
  m.M_ff += stretch;
  m.M_aa += stretch;
  m.M_fa -= stretch;
  m.M_af -= stretch;
  m.tension = cable.axialTension(k.length, k.s.dot(k.v_a - k.v_f), rest_length);  // (S20)
  // (S20'): w_f += T s, w_a -= T s; no length constraint, so no Psi (and mu = -T, (S21)).
  m.h_f += m.tension * k.s;
  m.h_a -= m.tension * k.s;
  m.c = 0.0;
}

// (S1): [a_G; domega/dt] = J_f a_f + J_a a_a, J = [J_f J_a] (jointMap); (S5): M_XY = J_X^T M J_Y and
// w_X = J_X^T w, M_f* and w_f (m.h_f) of (S3), M_a* and w_a (m.h_a) of (S4). J_f = [(1 - vartheta) I; -S],
// J_a = [vartheta I; S], S = [s]x / d. When M has no coupling between translation and rotation (a cable
// segment; a body whose CG is its centre of added mass), M = diag(M_t, M_r), the products reduce to (S5b)
// M_ff = (1 - vartheta)^2 M_t - Q, M_fa = M_af = vartheta (1 - vartheta) M_t + Q, M_aa = vartheta^2 M_t - Q
// with Q = S M_r S, and w_f = (1 - vartheta) F + S tau, w_a = vartheta F - S tau (w = [F; tau]): the same
// numbers to rounding, a fifth of the arithmetic (the cable's segments are all such).
void projectOntoJoints(const BodyDynamics& body, const ElementKinematics& k, ElementTerms& m)
{
  const double theta = body.cg_fraction;
  if (body.mass.topRightCorner<3, 3>().isZero(0.0) && body.mass.bottomLeftCorner<3, 3>().isZero(0.0))
  {
    const Eigen::Matrix3d S = skew(k.s) / k.length;
    const Eigen::Matrix3d Q = S * body.mass.bottomRightCorner<3, 3>() * S;
    const Eigen::Matrix3d M_t = body.mass.topLeftCorner<3, 3>();
    m.M_ff = (1.0 - theta) * (1.0 - theta) * M_t - Q;
    m.M_fa = theta * (1.0 - theta) * M_t + Q;
    m.M_af = m.M_fa;
    m.M_aa = theta * theta * M_t - Q;
    const Eigen::Vector3d S_tau = S * body.wrench.tail<3>();
    m.h_f = (1.0 - theta) * body.wrench.head<3>() + S_tau;
    m.h_a = theta * body.wrench.head<3>() - S_tau;
    return;
  }
  const Matrix6d J = jointMap(k.s, k.length, theta);
  const Matrix6d MJ = body.mass * J;
  m.M_ff = J.leftCols<3>().transpose() * MJ.leftCols<3>();
  m.M_fa = J.leftCols<3>().transpose() * MJ.rightCols<3>();
  m.M_af = J.rightCols<3>().transpose() * MJ.leftCols<3>();
  m.M_aa = J.rightCols<3>().transpose() * MJ.rightCols<3>();
  m.h_f = J.leftCols<3>().transpose() * body.wrench;
  m.h_a = J.rightCols<3>().transpose() * body.wrench;
}

// Bending (physics.md §11, (P48); docs/solver.md §11): the moments on cable segment e (axis s) from the joints
// at its two ends, each kappa_b theta toward straight, between it and its neighbours (none at the tow point or
// the bail): a load in the wrench w like any other.
Eigen::Vector3d bendingMoments(const ChainModel& model, const ChainGeometry& geometry, const Eigen::Vector3d& first,
                               const Eigen::Ref<const Eigen::Matrix3Xd>& x, int e, const Eigen::Vector3d& s)
{
  auto axis = [&](int i) -> Eigen::Vector3d
  { return (x.col(i) - (i == 0 ? first : Eigen::Vector3d(x.col(i - 1)))).normalized(); };
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  if (e >= 1)
    moment -= bendingMoment(axis(e - 1), s, model.jointBendingStiffness(e, geometry));
  if (e + 1 < geometry.segments)
    moment += bendingMoment(s, axis(e + 1), model.jointBendingStiffness(e + 1, geometry));
  return moment;
}
}  // namespace

// (S1)-(S6) per element, the matrix and vector passes of the backward sweep (S7)-(S13), the forward sweep (S14).
void ChainSolver::solve(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                        const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                        const Eigen::Ref<const Eigen::Matrix3Xd>& v, Eigen::Ref<Eigen::Matrix3Xd> a,
                        Eigen::Matrix3Xd* tensions, std::vector<double>* multipliers)
{
  terms_.resize(static_cast<size_t>(geometry.elementCount()));  // the winch re-meshes between calls
  elementTerms(model, geometry, data, t, ship, x, v);
  sweep_.factor(terms_);
  sweep_.solve(terms_, ship.a_W, a, tensions, multipliers);
}

// As solve() with a free first joint: its acceleration from (S22), docs/solver.md §9.
Eigen::Vector3d ChainSolver::solveFree(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                       double t, const ShipEndState& first, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                                       const Eigen::Ref<const Eigen::Matrix3Xd>& v, Eigen::Ref<Eigen::Matrix3Xd> a,
                                       Eigen::Matrix3Xd* tensions, std::vector<double>* multipliers,
                                       const Eigen::Vector3d& first_force)
{
  // No winch pays out a free chain: its first element keeps its length (whatever the geometry it came from).
  ChainGeometry free_geometry = geometry;
  free_geometry.first_rate = free_geometry.first_acceleration = 0.0;
  terms_.resize(static_cast<size_t>(free_geometry.elementCount()));
  elementTerms(model, free_geometry, data, t, first, x, v);
  sweep_.factor(terms_);
  return sweep_.solveFree(terms_, a, tensions, multipliers, first_force);
}

// (S1)-(S6): each element's equations (elementEquations) from the end body forward.
void ChainSolver::elementTerms(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                               const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                               const Eigen::Ref<const Eigen::Matrix3Xd>& v)
{
  BodyDynamics body;
  for (int e = static_cast<int>(terms_.size()) - 1; e >= 0; --e)
  {
    const Eigen::Vector3d x_f = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
    const Eigen::Vector3d v_f = e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1));
    ElementKinematics k = ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
    if (e == geometry.segments && geometry.rollingEnd())
    {
      k.roll = end_roll_.x();
      k.roll_rate = end_roll_.y();
    }
    const Eigen::Vector3d* bending = nullptr;
    Eigen::Vector3d moments;
    if (model.bends() && e < geometry.segments)
    {
      moments = bendingMoments(model, geometry, ship.p_W, x, e, k.s);  // §11: couples in w
      bending = &moments;
    }
    elementEquations(model, geometry, data, t, e, k, bending, body, terms_[static_cast<size_t>(e)]);
  }
}

// (S1)-(S6) for element e: its loads (ChainModel::elementDynamics) and its Newton-Euler equations (S2) projected
// onto its forward and aft joint accelerations, the terms of (S3) (forward joint) and (S4) (aft joint). Names
// here: body.cg_fraction is vartheta of (S1), m.h_f and m.h_a are w_f and w_a, m.c is Psi.
void elementEquations(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t, int e,
                      const ElementKinematics& k, const Eigen::Vector3d* bending, BodyDynamics& body, ElementTerms& m)
{
  const bool elastic = model.elastic() && e < geometry.segments;
  model.elementDynamics(e, t, k, geometry, data, body, !elastic);
  // (S6), winch: while the winch changes the first segment's length d_1, its axis s = (x_a - x_f)/d_1 turns
  // with domega/dt = s x (a_a - a_f)/d_1 - 2 (L'/d_1) omega (L' = first_rate): the known part goes to w.
  if (e == 0 && geometry.first_rate != 0.0)
    body.wrench -= body.mass.rightCols<3>() * (-2.0 * geometry.first_rate / k.length * k.omega);
  if (bending)
    body.wrench.tail<3>() += *bending;

  projectOntoJoints(body, k, m);
  m.s = k.s;
  m.constrained = !elastic;
  if (const JointBody* point = model.bodyAft(e, geometry))  // (S23): a point body on the aft joint, M_aa, w_a
  {
    m.M_aa.diagonal().array() += point->inertia();
    m.h_a += point->force(data.environment, t, k.x_a, k.v_a);
  }
  if (elastic)
  {
    addStretch(model.segmentCable(e, geometry), geometry.elementLength(e), model.segmentModel(e, geometry).mass, k, m);
    m.h_a += model.segmentContactForce(e, k, geometry);  // at its aft joint itself
    return;
  }
  // (S6): s.(a_a - a_f) = Psi, Psi = -|v_a - v_f|^2 / d; at the winch |x_a - x_f| = d_1(t) gives
  // Psi = (L'^2 + d_1 L'' - |v_a - v_f|^2) / d_1 (L' = first_rate, L'' = first_acceleration).
  m.c = -(k.v_a - k.v_f).squaredNorm() / k.length;
  if (e == 0)
    m.c += geometry.first_rate * geometry.first_rate / k.length + geometry.first_acceleration;
}

// (S8)-(S13), matrices only, from the end body (nothing pulls on its tail point: Lambda = 0) to the ship.
// K_aft and f.K here are Lambda of (S7) and (S13) (the apparent inertia), not the load stiffness K.
void ChainSweep::factor(const std::vector<ElementTerms>& terms)
{
  factors_.resize(terms.size());
  Eigen::Matrix3d K_aft = Eigen::Matrix3d::Zero();
  for (int e = static_cast<int>(terms.size()) - 1; e >= 0; --e)
  {
    const ElementTerms& m = terms[static_cast<size_t>(e)];
    Factor& f = factors_[static_cast<size_t>(e)];
    const Eigen::Vector3d& s = m.s;
    if (!m.constrained)
    {
      // (S21): no multiplier; A = M_aa + Lambda_aft is regular (the stretch inertia along s);
      // Phi = -A^-1 M_af, Lambda = M_ff + M_fa Phi (b, b_t, xi zero; sigma = 1 so that loads() divides safely).
      f.kappa = 0.0;
      f.A_inv = (m.M_aa + K_aft).inverse();
      f.b.setZero();
      f.b_t.setZero();
      f.sigma = 1.0;
      f.xi.setZero();
      f.Phi = -f.A_inv * m.M_af;
      f.K = m.M_ff + m.M_fa * f.Phi;
      K_aft = f.K;
      continue;
    }
    // (S8)-(S9): the aft joint's inertia A = M_aa + Lambda_aft, regularised along s by kappa s s^T (s.a_a is
    // fixed by the constraint, so only the multiplier changes: mu' = mu + kappa s.a_a); A here becomes A'.
    Eigen::Matrix3d A = m.M_aa + K_aft;
    f.kappa = A.trace() / 3.0;
    A += f.kappa * s * s.transpose();
    f.A_inv = A.inverse();
    f.b = f.A_inv * s;                // (S9): b = A'^-1 s
    f.b_t = f.A_inv.transpose() * s;  // (S10): b_t = A'^-T s
    f.sigma = s.dot(f.b);             // (S10): sigma = s^T A'^-1 s
    // (S10)-(S11): the multiplier from the length constraint, affine in a_f: its a_f part,
    // xi' = (s + M_af^T b_t)/sigma (xi_reg) and xi = xi' - kappa s.
    const Eigen::Vector3d xi_reg = (s + m.M_af.transpose() * f.b_t) / f.sigma;
    f.xi = xi_reg - f.kappa * s;
    // (S12)-(S13): the acceleration transfer to the aft joint, Phi = -A'^-1 M_af + b xi'^T, and the tension at
    // the forward joint, Lambda = M_ff + M_fa Phi + s xi^T.
    f.Phi = -f.A_inv * m.M_af + f.b * xi_reg.transpose();
    f.K = m.M_ff + m.M_fa * f.Phi + s * f.xi.transpose();
    K_aft = f.K;
  }
}

// (S9)-(S13) for the loads w_X and Psi (tau_aft = 0 at the tail), then (S14) from the first joint's acceleration.
void ChainSweep::solve(const std::vector<ElementTerms>& terms, const Eigen::Vector3d& a_first,
                       Eigen::Ref<Eigen::Matrix3Xd> a, Eigen::Matrix3Xd* tensions, std::vector<double>* multipliers)
{
  loads(terms);
  forward(terms, a_first, a, tensions, multipliers);
}

// (S22): nothing pulls on the first joint, T_1 = Lambda_1 a_1 + tau_1 = 0 (or F, first_force, from outside:
// a_1 = Lambda_1^-1 (F - tau_1)). Lambda_1 (factors_.front().K), the apparent inertia of the whole chain at that
// joint, is regular when its elements have mass. Over the implicit stage's N_XY, w~_X this is (S27).
Eigen::Vector3d ChainSweep::solveFree(const std::vector<ElementTerms>& terms, Eigen::Ref<Eigen::Matrix3Xd> a,
                                      Eigen::Matrix3Xd* tensions, std::vector<double>* multipliers,
                                      const Eigen::Vector3d& first_force)
{
  loads(terms);
  const Eigen::Vector3d a_first = factors_.front().K.partialPivLu().solve(first_force - tau_.front());
  forward(terms, a_first, a, tensions, multipliers);
  return a_first;
}

// The vector pass (S10)-(S13) ((S21) for an unconstrained element), from the tail (tau = 0 there) forward;
// m.h_f, m.h_a are w_f, w_a and m.c is Psi (or the stage's w~_X, Psi~).
void ChainSweep::loads(const std::vector<ElementTerms>& terms)
{
  const size_t n = terms.size();
  phi_.resize(n);
  tau_.resize(n);
  eta_.resize(n);
  Eigen::Vector3d tau_aft = Eigen::Vector3d::Zero();
  for (int e = static_cast<int>(n) - 1; e >= 0; --e)
  {
    const size_t i = static_cast<size_t>(e);
    const ElementTerms& m = terms[i];
    const Factor& f = factors_[i];
    const Eigen::Vector3d r0 = m.h_a - tau_aft;                                    // (S8): r_0 = w_a - tau_aft
    const double eta_reg = m.constrained ? (m.c - f.b_t.dot(r0)) / f.sigma : 0.0;  // (S10) eta'; (S21): none
    eta_[i] = eta_reg - f.kappa * m.c;                                             // (S11) eta = eta' - kappa Psi
    phi_[i] = f.A_inv * r0 + eta_reg * f.b;                                        // (S12) phi = A'^-1 r_0 + eta' b
    tau_[i] = m.M_fa * phi_[i] - m.h_f + eta_[i] * m.s;                            // (S13) tau = M_fa phi - w_f + eta s
    tau_aft = tau_[i];
  }
}

// (S14): T_lambda = Lambda a_f + tau, a_aft = Phi a_f + phi, from the first joint aft; mu from (S11) (elastic:
// mu = -T, (S21)).
void ChainSweep::forward(const std::vector<ElementTerms>& terms, const Eigen::Vector3d& a_first,
                         Eigen::Ref<Eigen::Matrix3Xd> a, Eigen::Matrix3Xd* tensions, std::vector<double>* multipliers)
{
  const size_t n = terms.size();
  if (tensions)
    tensions->resize(3, static_cast<Eigen::Index>(n));  // no-op when sized already
  if (multipliers)
    multipliers->resize(n);
  Eigen::Vector3d a_f = a_first;
  for (size_t i = 0; i < n; ++i)
  {
    const Eigen::Index e = static_cast<Eigen::Index>(i);
    const Factor& f = factors_[i];
    if (tensions)
      tensions->col(e) = f.K * a_f + tau_[i];  // (S14): T = Lambda a_f + tau
    if (multipliers)
      (*multipliers)[i] = terms[i].constrained ? f.xi.dot(a_f) + eta_[i] : -terms[i].tension;  // (S11)
    a.col(e) = f.Phi * a_f + phi_[i];  // (S14): a_aft = Phi a_f + phi
    a_f = a.col(e);
  }
}

}  // namespace tow_sim
