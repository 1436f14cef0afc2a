#include "tow_sim/core/integration/implicit_stepper.h"

#include <algorithm>
#include <cmath>

namespace tow_sim
{
void ImplicitStepper::linearise(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                                const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                                const Eigen::Ref<const Eigen::Matrix3Xd>& v,
                                const Eigen::Ref<const Eigen::Matrix3Xd>& a, const std::vector<ElementTerms>& terms,
                                const std::vector<double>& multipliers, double winch_d_length, double winch_d_rate)
{
  const size_t n = terms.size();
  inertia_ = terms;
  jacobians_.resize(n);
  stage_.resize(n);
  for (size_t i = 0; i < n; ++i)
  {
    const int e = static_cast<int>(i);
    const Eigen::Vector3d x_f = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
    const Eigen::Vector3d v_f = e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1));
    const ElementKinematics k = ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
    Vector6d a_joints;
    a_joints << (e == 0 ? ship.a_W : Eigen::Vector3d(a.col(e - 1))), a.col(e);
    elementJacobian(model, e, t, k, geometry, data, multipliers[i], jacobians_[i], &a_joints);
    if (model.bends())
      addBendingStiffness(model, geometry, ship.p_W, x, e, jacobians_[i]);
    stage_[i].s = terms[i].s;
    stage_[i].constrained = terms[i].constrained;
  }
  winch_d_length_ = winch_d_length;
  winch_d_rate_ = winch_d_rate;
  h_ = 0.0;  // factor() must follow
}

// (S19): the stage matrix N = M - gamma h D - (gamma h)^2 K per element, with D = dh/dv and K = dh/dx of
// (S16); the sweep's matrix pass then factors (S18) as it does (S3)-(S6).
void ImplicitStepper::factor(double h)
{
  const double gh = gamma_ * h, gh2 = gh * gh;
  for (size_t i = 0; i < stage_.size(); ++i)
  {
    const ElementTerms& M = inertia_[i];
    const Matrix6d& D = jacobians_[i].dh_dv;
    const Matrix6d& K = jacobians_[i].dh_dx;
    ElementTerms& N = stage_[i];
    N.M_ff = M.M_ff - gh * D.topLeftCorner<3, 3>() - gh2 * K.topLeftCorner<3, 3>();
    N.M_fa = M.M_fa - gh * D.topRightCorner<3, 3>() - gh2 * K.topRightCorner<3, 3>();
    N.M_af = M.M_af - gh * D.bottomLeftCorner<3, 3>() - gh2 * K.bottomLeftCorner<3, 3>();
    N.M_aa = M.M_aa - gh * D.bottomRightCorner<3, 3>() - gh2 * K.bottomRightCorner<3, 3>();
  }
  sweep_.factor(stage_);
  h_ = h;
}

void ImplicitStepper::solve(const std::vector<double>& r, const TowPointRates& tow, std::vector<double>& K)
{
  const StateLayout L{ joints() };
  const double gh = gamma_ * h_;
  const auto r_x = L.positions(r);
  const auto r_v = L.velocities(r);
  for (size_t i = 0; i < stage_.size(); ++i)
  {
    // (S19): g = M r_v + gamma h K r_x over the element's two joints, c' = s.(r_v,a - r_v,f): the loads and
    // the constraint of (S18), the linearised element (S17) scaled by gamma h. For the tow point, whose K is
    // known, the same form holds with r_v = K_v (its acceleration increment is not an unknown: K_v - r_v = 0)
    // and r_x = K_x - gamma h K_v.
    const Eigen::Index e = static_cast<Eigen::Index>(i);
    const Eigen::Vector3d rv_f = e == 0 ? tow.v : Eigen::Vector3d(r_v.col(e - 1));
    const Eigen::Vector3d rx_f = e == 0 ? Eigen::Vector3d(tow.x - gh * tow.v) : Eigen::Vector3d(r_x.col(e - 1));
    const Eigen::Vector3d rv_a = r_v.col(e), rx_a = r_x.col(e);
    const ElementTerms& M = inertia_[i];
    const Matrix6d& Kx = jacobians_[i].dh_dx;
    ElementTerms& stage = stage_[i];
    stage.h_f =
        M.M_ff * rv_f + M.M_fa * rv_a + gh * (Kx.topLeftCorner<3, 3>() * rx_f + Kx.topRightCorner<3, 3>() * rx_a);
    stage.h_a =
        M.M_af * rv_f + M.M_aa * rv_a + gh * (Kx.bottomLeftCorner<3, 3>() * rx_f + Kx.bottomRightCorner<3, 3>() * rx_a);
    stage.c = stage.s.dot(rv_a - rv_f);
  }
  K.resize(r.size());
  K_v_.resize(3, L.joints);
  sweep_.solve(stage_, tow.v, K_v_);
  L.velocities(K) = K_v_;
  L.positions(K) = r_x + gh * K_v_;  // K_x = r_x + gamma h K_v (docs/solver.md §7)
  // The winch: [1, -gh; -gh a_L, 1 - gh a_R] (K_L, K_R) = (r_L, r_R).
  const double r_L = L.cableOut(r), r_R = L.payoutRate(r);
  const double det = (1.0 - gh * winch_d_rate_) - gh * gh * winch_d_length_;
  L.payoutRate(K) = (r_R + gh * winch_d_length_ * r_L) / det;
  L.cableOut(K) = r_L + gh * L.payoutRate(K);
}

// (S15): W K_i = f(t + c_i h, y + h sum_{j<i} a_ij K_j) + sum_{j<i} c_ij K_j (+ the tow point's K_t,i (v, a)),
// each solved in O(nu) by solve(); y_next = y + h sum m_i K_i, error = h sum e_i K_i.
void ImplicitStepper::stages(const RosenbrockTableau& rw, double t, double h, const std::vector<double>& y,
                             const std::vector<double>& f0, const ShipEndState& ship, const Derivative& f,
                             std::vector<double>& y_next, std::vector<double>& error)
{
  const size_t n = y.size();
  stage_k_.resize(rw.stages);
  stage_y_.resize(n);
  stage_f_.resize(n);
  double K_t[RosenbrockTableau::kMaxStages];
  for (int i = 0; i < rw.stages; ++i)
  {
    double t_stage = t;
    K_t[i] = 1.0;
    if (i == 0)
      stage_f_ = f0;
    else
    {
      stage_y_ = y;
      for (int j = 0; j < i; ++j)
      {
        t_stage += h * rw.a[i][j] * K_t[j];
        K_t[i] += rw.c[i][j] * K_t[j];
        if (rw.a[i][j] != 0.0)
          for (size_t q = 0; q < n; ++q)
            stage_y_[q] += h * rw.a[i][j] * stage_k_[j][q];
      }
      f(t_stage, stage_y_, stage_f_);
      for (int j = 0; j < i; ++j)
        for (size_t q = 0; q < n; ++q)
          stage_f_[q] += rw.c[i][j] * stage_k_[j][q];
    }
    solve(stage_f_, TowPointRates{ K_t[i] * ship.v_W, K_t[i] * ship.a_W }, stage_k_[i]);
  }
  y_next = y;
  error.assign(n, 0.0);
  for (int i = 0; i < rw.stages; ++i)
    for (size_t q = 0; q < n; ++q)
    {
      y_next[q] += h * rw.m[i] * stage_k_[i][q];
      error[q] += h * rw.e[i] * stage_k_[i][q];
    }
}

// (S24): positions relative to the tow point, velocities as they are.
double implicitErrorNorm(const NumericsParams& num, const StateLayout& L, bool winch, const std::vector<double>& error,
                         const std::vector<double>& y, const std::vector<double>& y_next, const Eigen::Vector3d& p0,
                         const Eigen::Vector3d& p1)
{
  const auto e_x = L.positions(error), e_v = L.velocities(error);
  const auto x0 = L.positions(y), x1 = L.positions(y_next);
  const auto v0 = L.velocities(y), v1 = L.velocities(y_next);
  double sum = 0.0;
  for (int j = 0; j < L.joints; ++j)
    for (int i = 0; i < 3; ++i)
    {
      const double scale_x = num.implicit_position_tol +
                             num.implicit_rel_tol * std::max(std::abs(x0(i, j) - p0[i]), std::abs(x1(i, j) - p1[i]));
      const double scale_v =
          num.implicit_velocity_tol + num.implicit_rel_tol * std::max(std::abs(v0(i, j)), std::abs(v1(i, j)));
      sum += std::pow(e_x(i, j) / scale_x, 2) + std::pow(e_v(i, j) / scale_v, 2);
    }
  double count = 6.0 * L.joints;
  if (winch)
  {
    const double scale_l = num.implicit_position_tol +
                           num.implicit_rel_tol * std::max(std::abs(L.cableOut(y)), std::abs(L.cableOut(y_next)));
    const double scale_r = num.implicit_velocity_tol +
                           num.implicit_rel_tol * std::max(std::abs(L.payoutRate(y)), std::abs(L.payoutRate(y_next)));
    sum += std::pow(L.cableOut(error) / scale_l, 2) + std::pow(L.payoutRate(error) / scale_r, 2);
    count += 2.0;
  }
  return std::sqrt(sum / count);
}

}  // namespace tow_sim
