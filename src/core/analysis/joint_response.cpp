// The response to ship motion in O(nu) per period (modes.h, motionResponses): the chain's small motions in the
// joints' own displacements, each element linearised alone (docs/physics.md §12, (P53b)).
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

#include "tow_sim/core/analysis/modes.h"
#include "tow_sim/core/chain/element_equations.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/geometry.h"

namespace tow_sim
{
namespace
{
using C = std::complex<double>;

// (P53b) about the state: per element its projected inertia M_XY (S5), D = d(w_f, w_a)/d(v_f, v_a) and
// K = d(w_f - mu s, w_a + mu s)/d(x_f, x_a), the loads by central differences in the element's own two joints
// (nothing else moves them: O(nu) in all) and the multiplier's force turning with the axis; and the state's
// tensions (their directions turn the tensions' increments into their magnitudes').
struct JointLinearisation
{
  std::vector<ElementTerms> terms;
  std::vector<Matrix6d> D, K;
  Eigen::Matrix3Xd tensions;
};

JointLinearisation lineariseJoints(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                   double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                                   const Eigen::Matrix3Xd& v, double step)
{
  const Eigen::Index n = x.cols();
  JointLinearisation L;
  ChainSolver solver;
  Eigen::Matrix3Xd a(3, n);
  std::vector<double> mu;
  solver.solve(model, geometry, data, t, ship, x, v, a, &L.tensions, &mu);
  L.terms = solver.terms();
  L.D.resize(static_cast<size_t>(n));
  L.K.resize(static_cast<size_t>(n));
  BodyDynamics body;
  ElementTerms m;
  for (Eigen::Index e = 0; e < n; ++e)
  {
    const size_t i = static_cast<size_t>(e);
    Eigen::Vector3d joint[4] = { e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1)), x.col(e),
                                 e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1)), v.col(e) };
    const double length = (joint[1] - joint[0]).norm();
    auto loads = [&]() -> Vector6d
    {
      elementEquations(model, geometry, data, t, static_cast<int>(e),
                       ElementKinematics::fromJoints(joint[0], joint[1], joint[2], joint[3]), nullptr, body, m);
      Vector6d w;
      w << m.h_f, m.h_a;
      return w;
    };
    for (int j = 0; j < 12; ++j)
    {
      Eigen::Vector3d& component_of = joint[j / 3];
      const double saved = component_of[j % 3];
      const bool position = j < 6;
      const double h = step * (position ? std::max(1.0, length) : std::max(1.0, std::abs(saved)));
      component_of[j % 3] = saved + h;
      const Vector6d plus = loads();
      component_of[j % 3] = saved - h;
      const Vector6d minus = loads();
      component_of[j % 3] = saved;
      (position ? L.K[i] : L.D[i]).col(j % 6) = (plus - minus) / (2.0 * h);
    }
    // -mu s on the forward joint and +mu s on the aft one turn with s: d s / d x_a = (I - s s^T)/d.
    const Eigen::Vector3d& s = L.terms[i].s;
    const Eigen::Matrix3d G = -mu[i] / length * (Eigen::Matrix3d::Identity() - s * s.transpose());
    L.K[i].topLeftCorner<3, 3>() -= G;
    L.K[i].topRightCorner<3, 3>() += G;
    L.K[i].bottomLeftCorner<3, 3>() += G;
    L.K[i].bottomRightCorner<3, 3>() -= G;
  }
  return L;
}

// A_XY = -w^2 M_XY - i w D_XY - K_XY of element i: (P53b)'s operator on the joints' complex amplitudes.
Eigen::Matrix<C, 6, 6> harmonicBlock(const JointLinearisation& L, size_t i, double w)
{
  const ElementTerms& M = L.terms[i];
  Matrix6d mass;
  mass << M.M_ff, M.M_fa, M.M_af, M.M_aa;
  return (-w * w) * mass.cast<C>() - C(0.0, w) * L.D[i].cast<C>() - L.K[i].cast<C>();
}

// The unknowns of (P53b) at one period: the joints' amplitudes X_2 .. X_{nu+2} (3 each) and each element's
// multiplier's, in that order; the rows: each joint's equation (its two elements' (S3)/(S4) summed) and each
// element's constraint s.(X_a - X_f) = 0. The tow point's amplitude is the input: its columns go to the right.
Eigen::SparseMatrix<C> harmonicMatrix(const JointLinearisation& L, double w, std::vector<Eigen::Matrix<C, 6, 6>>& A)
{
  const Eigen::Index n = static_cast<Eigen::Index>(L.terms.size()), size = 4 * n;
  std::vector<Eigen::Triplet<C>> entries;
  entries.reserve(static_cast<size_t>(48 * n));
  A.resize(L.terms.size());
  for (Eigen::Index e = 0; e < n; ++e)
  {
    const size_t i = static_cast<size_t>(e);
    A[i] = harmonicBlock(L, i, w);
    const Eigen::Vector3d& s = L.terms[i].s;
    const Eigen::Index multiplier = 3 * n + e;
    for (int row = 0; row < 6; ++row)
    {
      const Eigen::Index joint = row < 3 ? e - 1 : e;
      if (joint < 0)
        continue;  // the tow point's own equation: its tension, which follows from the rest
      for (int col = 0; col < 6; ++col)
      {
        const Eigen::Index of = col < 3 ? e - 1 : e;
        if (of >= 0)
          entries.emplace_back(3 * joint + row % 3, 3 * of + col % 3, A[i](row, col));
      }
      entries.emplace_back(3 * joint + row % 3, multiplier, row < 3 ? s[row % 3] : -s[row % 3]);  // +-mu s
    }
    for (int k = 0; k < 3; ++k)
    {
      entries.emplace_back(multiplier, 3 * e + k, s[k]);
      if (e > 0)
        entries.emplace_back(multiplier, 3 * (e - 1) + k, -s[k]);
    }
  }
  Eigen::SparseMatrix<C> matrix(size, size);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}
// What motionResponses reports of a solution: the vehicle's CG a fraction cg_fraction from the bail to the tail
// (the end element of length l_end), the tensions' magnitudes along their equilibrium directions.
struct Outputs
{
  double cg_fraction, l_end;
  Eigen::Vector3d t_ship, t_vehicle;
};

// The outputs of (P53b)'s solution X for the tow point's amplitude `input`.
MotionResponse responseOf(const JointLinearisation& L, const std::vector<Eigen::Matrix<C, 6, 6>>& A, const Outputs& o,
                          const Eigen::Vector3cd& input, const Eigen::VectorXcd& X)
{
  const Eigen::Index n = static_cast<Eigen::Index>(L.terms.size());
  auto joint = [&](Eigen::Index j) -> Eigen::Vector3cd
  { return j < 0 ? input : Eigen::Vector3cd(X.segment<3>(3 * j)); };
  // T at element e's forward joint: its (S3), A_ff X_f + A_fa X_a + mu s.
  auto tension = [&](Eigen::Index e)
  {
    const size_t i = static_cast<size_t>(e);
    return Eigen::Vector3cd(A[i].topLeftCorner<3, 3>() * joint(e - 1) + A[i].topRightCorner<3, 3>() * joint(e) +
                            X(3 * n + e) * L.terms[i].s.cast<C>());
  };
  const Eigen::Vector3cd bail = joint(n - 2), tail = joint(n - 1);
  const Eigen::Vector3cd cg = bail + o.cg_fraction * (tail - bail);
  // The end body's axis turns by s x ds about its lateral axis (horizontal, normal to its forward direction -s).
  const Eigen::Vector3d s_end = L.terms.back().s, y_body = Eigen::Vector3d::UnitZ().cross(-s_end).normalized();
  const Eigen::Vector3cd ds = (tail - bail) / o.l_end;
  MotionResponse r;
  r.surge = cg.x();
  r.sway = cg.y();
  r.heave = cg.z();
  r.pitch = y_body.cast<C>().dot(skew(s_end).cast<C>() * ds);  // (Eigen's cross conjugates complex vectors)
  r.tension_ship = o.t_ship.cast<C>().dot(tension(0));
  r.tension_vehicle = o.t_vehicle.cast<C>().dot(tension(n - 1));
  return r;
}
}  // namespace

std::vector<std::vector<MotionResponse>> motionResponses(const ChainModel& model, const ChainGeometry& geometry,
                                                         const ChainData& data, double t, const ShipEndState& ship,
                                                         const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                                         const std::vector<Eigen::Vector3d>& inputs,
                                                         const std::vector<double>& periods, double cg_fraction,
                                                         double step)
{
  if (model.elastic() || model.bends())  // a stretch or a bend reaches past the element: the dense linearisation
    return motionResponsesDense(model, geometry, data, t, ship, x, v, inputs, periods, cg_fraction, step);
  const JointLinearisation L = lineariseJoints(model, geometry, data, t, ship, x, v, step);
  const Eigen::Index n = x.cols();
  const Outputs outputs{ cg_fraction, (x.col(n - 1) - (n > 1 ? Eigen::Vector3d(x.col(n - 2)) : ship.p_W)).norm(),
                         L.tensions.col(0).normalized(), L.tensions.col(n - 1).normalized() };
  std::vector<std::vector<MotionResponse>> out(inputs.size());
  std::vector<Eigen::Matrix<C, 6, 6>> A;
  Eigen::SparseLU<Eigen::SparseMatrix<C>> lu;
  for (size_t p = 0; p < periods.size(); ++p)
  {
    const double w = 2.0 * kPi / periods[p];
    const Eigen::SparseMatrix<C> matrix = harmonicMatrix(L, w, A);
    if (p == 0)
      lu.analyzePattern(matrix);  // the same pattern at every period
    lu.factorize(matrix);
    if (lu.info() != Eigen::Success)
      throw std::runtime_error("motion response: the linearised chain is singular at the period " +
                               std::to_string(periods[p]) + " s");
    for (size_t k = 0; k < inputs.size(); ++k)
    {
      // The tow point moves by `input` per unit: the first element's columns of it on the right.
      const Eigen::Vector3cd input = inputs[k].cast<C>();
      Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(4 * n);
      rhs.segment<3>(0) = -A[0].bottomLeftCorner<3, 3>() * input;
      rhs(3 * n) = L.terms[0].s.cast<C>().dot(input);
      out[k].push_back(responseOf(L, A, outputs, input, lu.solve(rhs)));
      out[k].back().period = periods[p];
    }
  }
  return out;
}

}  // namespace tow_sim
