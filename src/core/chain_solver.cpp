#include "tow_sim/core/chain_solver.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "tow_sim/core/geometry.h"

namespace tow_sim
{
namespace
{
using Matrix63d = Eigen::Matrix<double, 6, 3>;
}  // namespace

void ChainSolver::solve(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                        const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                        const Eigen::Ref<const Eigen::Matrix3Xd>& v, Eigen::Ref<Eigen::Matrix3Xd> a,
                        Eigen::Matrix3Xd* tensions)
{
  const size_t n = static_cast<size_t>(geometry.elementCount());
  if (terms_.size() != n)  // first call, or the winch re-meshed
  {
    terms_.resize(n);
    Phi_.resize(n);
    K_.resize(n);
    phi_.resize(n);
    tau_.resize(n);
  }
  elementTerms(model, geometry, data, t, ship, x, v);
  backwardSweep();
  forwardSweep(ship.a_W, a, tensions);
}

// (S1)-(S6): each element's loads (ChainModel::elementDynamics) and its Newton-Euler equations projected
// onto its forward and aft joint accelerations.
void ChainSolver::elementTerms(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                               const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                               const Eigen::Ref<const Eigen::Matrix3Xd>& v)
{
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  BodyDynamics body;
  for (int e = static_cast<int>(terms_.size()) - 1; e >= 0; --e)
  {
    const Eigen::Vector3d x_f = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
    const Eigen::Vector3d v_f = e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1));
    const ElementKinematics k = ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
    model.elementDynamics(e, t, k, geometry, data, body);
    // While the winch changes the first segment's length L, its axis s = (x_a - x_f)/L turns with
    // dw/dt = s x (a_a - a_f)/L - 2 (L'/L) w: the known part goes to the loads.
    if (e == 0 && geometry.first_rate != 0.0)
      body.wrench -= body.mass.rightCols<3>() * (-2.0 * geometry.first_rate / k.length * k.omega);

    // (S1): [a_G; dw/dt] = J_f a_f + J_a a_a.
    const double gamma = body.cg_fraction;
    const Eigen::Matrix3d S = skew(k.s) / k.length;
    Matrix63d J_f, J_a;
    J_f << (1.0 - gamma) * I3, -S;
    J_a << gamma * I3, S;
    // (S5): the projected inertia and loads.
    const Matrix63d MJ_f = body.mass * J_f;
    const Matrix63d MJ_a = body.mass * J_a;
    ElementTerms& m = terms_[static_cast<size_t>(e)];
    m.M_ff = J_f.transpose() * MJ_f;
    m.M_fa = J_f.transpose() * MJ_a;
    m.M_af = J_a.transpose() * MJ_f;
    m.M_aa = J_a.transpose() * MJ_a;
    m.h_f = J_f.transpose() * body.wrench;
    m.h_a = J_a.transpose() * body.wrench;
    m.s = k.s;
    // (S6): s.(a_a - a_f) = c; at the winch |x_a - x_f| = L(t) gives c = (L'^2 + L L'' - |v_a - v_f|^2) / L.
    m.c = -(k.v_a - k.v_f).squaredNorm() / k.length;
    if (e == 0)
      m.c += geometry.first_rate * geometry.first_rate / k.length + geometry.first_acceleration;
  }
}

// (S7)-(S13), from the end body (nothing pulls on its tail point: K = 0, tau = 0) to the ship.
void ChainSolver::backwardSweep()
{
  Eigen::Matrix3d K_aft = Eigen::Matrix3d::Zero();
  Eigen::Vector3d tau_aft = Eigen::Vector3d::Zero();
  for (int e = static_cast<int>(terms_.size()) - 1; e >= 0; --e)
  {
    const size_t i = static_cast<size_t>(e);
    const ElementTerms& m = terms_[i];
    const Eigen::Vector3d& s = m.s;
    // (S8)-(S9): the aft joint's inertia A = M_aa + K_aft, regularised along s by kappa s s^T (s.a_a is fixed
    // by the constraint, so only the multiplier changes: mu' = mu + kappa s.a_a).
    Eigen::Matrix3d A = m.M_aa + K_aft;
    const double kappa = A.trace() / 3.0;
    A += kappa * s * s.transpose();
    const Eigen::Matrix3d A_inv = A.inverse();
    const Eigen::Vector3d r0 = m.h_a - tau_aft;
    const Eigen::Vector3d b = A_inv * s;
    const Eigen::Vector3d b_t = A_inv.transpose() * s;
    const double sigma = s.dot(b);
    // (S10)-(S11): the multiplier from the length constraint, affine in a_f.
    const Eigen::Vector3d xi_reg = (s + m.M_af.transpose() * b_t) / sigma;
    const double eta_reg = (m.c - b_t.dot(r0)) / sigma;
    const Eigen::Vector3d xi = xi_reg - kappa * s;
    const double eta = eta_reg - kappa * m.c;
    // (S12): the acceleration transfer to the aft joint.
    Phi_[i] = -A_inv * m.M_af + b * xi_reg.transpose();
    phi_[i] = A_inv * r0 + eta_reg * b;
    // (S13): the tension at the forward joint, affine in its acceleration.
    K_[i] = m.M_ff + m.M_fa * Phi_[i] + s * xi.transpose();
    tau_[i] = m.M_fa * phi_[i] - m.h_f + eta * s;
    K_aft = K_[i];
    tau_aft = tau_[i];
  }
}

// (S14), from the ship's known acceleration.
void ChainSolver::forwardSweep(const Eigen::Vector3d& a_ship, Eigen::Ref<Eigen::Matrix3Xd> a,
                               Eigen::Matrix3Xd* tensions) const
{
  Eigen::Vector3d a_f = a_ship;
  for (size_t i = 0; i < terms_.size(); ++i)
  {
    const Eigen::Index e = static_cast<Eigen::Index>(i);
    if (tensions)
      tensions->col(e) = K_[i] * a_f + tau_[i];
    a.col(e) = Phi_[i] * a_f + phi_[i];
    a_f = a.col(e);
  }
}

}  // namespace tow_sim
