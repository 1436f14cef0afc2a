#include "tow_sim/core/chain_solver.h"
#include "tow_sim/core/geometry.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

namespace tow_sim
{
namespace
{
using Matrix63d = Eigen::Matrix<double, 6, 3>;

}  // namespace

ChainSolver::ChainSolver(const ChainModel& model) : model_(model)
{
  const int n = model_.elementCount();
  X_.resize(n);
  K_.resize(n);
  y_.resize(n);
  k_.resize(n);
}

void ChainSolver::solve(double t, const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                        const Eigen::Ref<const Eigen::Matrix3Xd>& v, Eigen::Ref<Eigen::Matrix3Xd> a,
                        Eigen::Matrix3Xd* tensions)
{
  const int n = model_.elementCount();
  if (static_cast<int>(X_.size()) != n)  // the winch re-meshed
  {
    X_.resize(n);
    K_.resize(n);
    y_.resize(n);
    k_.resize(n);
  }
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  BodyDynamics body;
  Eigen::Matrix3d K_aft = Eigen::Matrix3d::Zero();  // nothing pulls on the end body's tail point
  Eigen::Vector3d k_aft = Eigen::Vector3d::Zero();

  // Backward sweep: from the end body (e = n-1) to the first cable segment (e = 0).
  for (int e = n - 1; e >= 0; --e)
  {
    const Eigen::Vector3d x_f = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
    const Eigen::Vector3d v_f = e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1));
    const ElementKinematics k = ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
    model_.elementDynamics(e, t, k, body);
    // While the winch changes the first segment's length L, its axis s = (x_a - x_f)/L turns with
    // dw/dt = s x (a_a - a_f)/L - 2 (L'/L) w: the known part goes to the right-hand side.
    if (e == 0 && model_.firstRate() != 0.0)
      body.wrench -= body.mass.rightCols<3>() * (-2.0 * model_.firstRate() / k.length * k.omega);

    // Map the Newton-Euler equations onto the joint accelerations: [a_G; dw/dt] = J_f a_f + J_a a_a.
    const double gamma = body.cg_fraction;
    const Eigen::Matrix3d S = skew(k.s) / k.length;
    Matrix63d J_f, J_a;
    J_f << (1.0 - gamma) * I3, -S;
    J_a << gamma * I3, S;
    const Matrix63d MJ_f = body.mass * J_f;
    const Matrix63d MJ_a = body.mass * J_a;
    const Eigen::Matrix3d M_ff = J_f.transpose() * MJ_f;
    const Eigen::Matrix3d M_fa = J_f.transpose() * MJ_a;
    const Eigen::Matrix3d M_af = J_a.transpose() * MJ_f;
    const Eigen::Matrix3d M_aa = J_a.transpose() * MJ_a;
    const Eigen::Vector3d h_f = J_f.transpose() * body.wrench;
    const Eigen::Vector3d h_a = J_a.transpose() * body.wrench;

    // Aft joint: M_af a_f + M_aa a_a = h_a - T_aft + mu s with T_aft = K_aft a_a + k_aft, and the length
    // constraint s.a_a = s.a_f + c0. mu is the axial reaction that keeps the element's length.
    // M_aa + K_aft may be singular along s (an end body with its CG at the bail has no inertia at its
    // tail joint along its axis), so solve with A = M_aa + K_aft + kappa s s^T, which is regular, and
    // mu' = mu + kappa s.a_a in place of mu: exact, since s.a_a is fixed by the constraint.
    // The first segment may change length at the winch: |x_a - x_f| = L(t) gives
    // s.(a_a - a_f) = (L'^2 + L L'' - |v_a - v_f|^2) / L.
    double c0 = -(k.v_a - k.v_f).squaredNorm() / k.length;
    if (e == 0)
      c0 += model_.firstRate() * model_.firstRate() / k.length + model_.firstAcceleration();
    Eigen::Matrix3d A = M_aa + K_aft;
    const double kappa = A.trace() / 3.0;
    A += kappa * k.s * k.s.transpose();
    const Eigen::Matrix3d B = A.inverse();
    const Eigen::Vector3d r0 = h_a - k_aft;
    const Eigen::Vector3d u = B * k.s;
    const Eigen::Vector3d u_t = B.transpose() * k.s;
    const double sigma = k.s.dot(u);
    // mu' = xi'.a_f + eta' from the constraint; mu = mu' - kappa (s.a_f + c0).
    const Eigen::Vector3d xi_prime = (k.s + M_af.transpose() * u_t) / sigma;
    const double eta_prime = (c0 - u_t.dot(r0)) / sigma;
    const Eigen::Vector3d xi = xi_prime - kappa * k.s;
    const double eta = eta_prime - kappa * c0;
    X_[e] = -B * M_af + u * xi_prime.transpose();
    y_[e] = B * r0 + eta_prime * u;
    // Forward joint: T_fwd = M_ff a_f + M_fa a_a - h_f + mu s.
    K_[e] = M_ff + M_fa * X_[e] + k.s * xi.transpose();
    k_[e] = M_fa * y_[e] - h_f + eta * k.s;
    K_aft = K_[e];
    k_aft = k_[e];
  }

  // Forward sweep from the ship's known acceleration.
  Eigen::Vector3d a_f = ship.a_W;
  for (int e = 0; e < n; ++e)
  {
    if (tensions)
      tensions->col(e) = K_[e] * a_f + k_[e];
    a.col(e) = X_[e] * a_f + y_[e];
    a_f = a.col(e);
  }
}

}  // namespace tow_sim
