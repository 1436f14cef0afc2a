// The chain's small motions in the joints' own displacements, each element linearised alone (docs/physics.md §12,
// (P53b)): the response to ship motion in O(nu) per period (modes.h, motionResponses) and the lowest natural modes
// by shift-invert Arnoldi, O(nu) per iteration (lowestModes, (P52b)).
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

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

// Element i's projected inertia M_XY as one 6 x 6 matrix over (forward, aft).
Matrix6d massOf(const JointLinearisation& L, size_t i)
{
  const ElementTerms& M = L.terms[i];
  Matrix6d mass;
  mass << M.M_ff, M.M_fa, M.M_af, M.M_aa;
  return mass;
}

// A_XY = lambda^2 M_XY - lambda D_XY - K_XY of element i: (P53b)'s operator on the joints' amplitudes X e^(lambda t)
// (lambda = i w for a harmonic motion).
Eigen::Matrix<C, 6, 6> harmonicBlock(const JointLinearisation& L, size_t i, C lambda)
{
  return (lambda * lambda) * massOf(L, i).cast<C>() - lambda * L.D[i].cast<C>() - L.K[i].cast<C>();
}

// The unknowns of (P53b) at one lambda: the joints' amplitudes X_2 .. X_{nu+2} (3 each) and each element's
// multiplier's, in that order; the rows: each joint's equation (its two elements' (S3)/(S4) summed) and each
// element's constraint s.(X_a - X_f) = 0. The tow point's amplitude is the input: its columns go to the right.
Eigen::SparseMatrix<C> harmonicMatrix(const JointLinearisation& L, C lambda, std::vector<Eigen::Matrix<C, 6, 6>>& A)
{
  const Eigen::Index n = static_cast<Eigen::Index>(L.terms.size()), size = 4 * n;
  std::vector<Eigen::Triplet<C>> entries;
  entries.reserve(static_cast<size_t>(48 * n));
  A.resize(L.terms.size());
  for (Eigen::Index e = 0; e < n; ++e)
  {
    const size_t i = static_cast<size_t>(e);
    A[i] = harmonicBlock(L, i, lambda);
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
// The joints' rows and columns of M_XY, D and K summed over the elements (the tow point's dropped: it holds
// still in a mode), for the products of the shift-invert operator.
struct JointMatrices
{
  Eigen::SparseMatrix<C> M, D;
};

JointMatrices jointMatrices(const JointLinearisation& L)
{
  const Eigen::Index n = static_cast<Eigen::Index>(L.terms.size());
  std::vector<Eigen::Triplet<C>> m, d;
  for (Eigen::Index e = 0; e < n; ++e)
  {
    const size_t i = static_cast<size_t>(e);
    const Matrix6d mass = massOf(L, i);
    for (int row = 0; row < 6; ++row)
      for (int col = 0; col < 6; ++col)
      {
        const Eigen::Index r = row < 3 ? e - 1 : e, c = col < 3 ? e - 1 : e;
        if (r < 0 || c < 0)
          continue;
        m.emplace_back(3 * r + row % 3, 3 * c + col % 3, mass(row, col));
        d.emplace_back(3 * r + row % 3, 3 * c + col % 3, L.D[i](row, col));
      }
  }
  JointMatrices out{ Eigen::SparseMatrix<C>(3 * n, 3 * n), Eigen::SparseMatrix<C>(3 * n, 3 * n) };
  out.M.setFromTriplets(m.begin(), m.end());
  out.D.setFromTriplets(d.begin(), d.end());
  return out;
}

// (P52b)'s operator y -> z = (A - sigma B)^-1 B y on y = (X, V): A(sigma) z_X + S z_mu = (D - sigma M) y_X - M y_V
// with s.dz = 0 per element, z_V = y_X + sigma z_X.
Eigen::VectorXcd shiftInvert(const Eigen::SparseLU<Eigen::SparseMatrix<C>>& lu, const JointMatrices& J, C sigma,
                             const Eigen::VectorXcd& y)
{
  const Eigen::Index dof = J.M.rows(), n = dof / 3;
  const Eigen::VectorXcd y_x = y.head(dof), y_v = y.tail(dof);
  Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(dof + n);
  rhs.head(dof) = J.D * y_x - sigma * (J.M * y_x) - J.M * y_v;
  const Eigen::VectorXcd z = lu.solve(rhs);
  Eigen::VectorXcd out(2 * dof);
  out.head(dof) = z.head(dof);
  out.tail(dof) = y_x + sigma * z.head(dof);
  return out;
}

// A mode from its eigenvalue and its joints' amplitudes X (3 x n): the end body's turning against the cable's
// joints, and the cable's in-plane and out-of-plane parts (as dominantPart in modes.cpp, from (P51)'s angles).
Mode modeOf(const JointLinearisation& L, C lambda, const Eigen::Matrix3Xcd& X, bool end_body)
{
  Mode mode;
  mode.frequency = std::abs(lambda);
  mode.damping_ratio = mode.frequency > 0.0 ? -lambda.real() / mode.frequency : 0.0;
  mode.period = lambda.imag() > 0.0 ? 2.0 * kPi / lambda.imag() : std::numeric_limits<double>::infinity();
  Eigen::Index row = 0, col = 0;
  X.cwiseAbs().maxCoeff(&row, &col);
  mode.shape = (X / X(row, col)).real();
  const Eigen::Index n = X.cols(), cable = end_body ? n - 1 : n;
  double in = 0.0, out = 0.0, turn = 0.0;
  for (Eigen::Index e = 0; e < n; ++e)
  {
    const Eigen::Vector3d& s = L.terms[static_cast<size_t>(e)].s;
    Eigen::Vector3d nv = Eigen::Vector3d::UnitZ().cross(s);
    nv = nv.norm() > 1e-9 ? Eigen::Vector3d(nv.normalized()) : Eigen::Vector3d::UnitY();
    const Eigen::Vector3cd d = X.col(e) - (e == 0 ? Eigen::Vector3cd::Zero() : Eigen::Vector3cd(X.col(e - 1)));
    // l alpha and l beta: the joint's displacement relative to the one before, along n x s and m x s.
    const double a = std::norm(nv.cross(s).cast<C>().dot(d)), b = std::norm(s.cross(nv).cross(s).cast<C>().dot(d));
    if (e < cable)
    {
      in += a;
      out += b;
    }
    else
      turn = std::sqrt(a + b);
    if (e == n - 1 && end_body && turn > (cable > 0 ? X.leftCols(cable).colwise().norm().maxCoeff() : 0.0))
    {
      mode.dominant = a >= b ? "vehicle pitch" : "vehicle yaw";
      return mode;
    }
  }
  mode.dominant = in >= out ? "in-plane" : "out-of-plane";
  return mode;
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
    const Eigen::SparseMatrix<C> matrix = harmonicMatrix(L, C(0.0, w), A);
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

namespace
{
// (P52b): the Krylov space of the shift-invert operator about sigma = 0 from `start`, by Arnoldi with the
// Gram-Schmidt pass done twice; H (k + 1) x k, V its k + 1 orthonormal columns (k < m where the space closes).
struct Krylov
{
  Eigen::MatrixXcd V, H;
  Eigen::Index k = 0;
};

Krylov arnoldi(const Eigen::SparseLU<Eigen::SparseMatrix<C>>& lu, const JointMatrices& J, const Eigen::VectorXcd& start,
               Eigen::Index m)
{
  Krylov K{ Eigen::MatrixXcd::Zero(start.size(), m + 1), Eigen::MatrixXcd::Zero(m + 1, m), m };
  K.V.col(0) = start.normalized();
  for (Eigen::Index j = 0; j < m; ++j)
  {
    Eigen::VectorXcd w = shiftInvert(lu, J, 0.0, K.V.col(j));
    for (int pass = 0; pass < 2; ++pass)
    {
      const Eigen::VectorXcd h = K.V.leftCols(j + 1).adjoint() * w;
      w -= K.V.leftCols(j + 1) * h;
      K.H.col(j).head(j + 1) += h;
    }
    K.H(j + 1, j) = w.norm();
    if (std::abs(K.H(j + 1, j)) <= 1e-14 * K.H.col(j).norm())
    {
      K.k = j + 1;  // an invariant space: its Ritz pairs are exact
      break;
    }
    K.V.col(j + 1) = w / K.H(j + 1, j);
  }
  return K;
}
// The modes of the `take` largest Ritz values (in `order`) of the Krylov space K: lambda = sigma + 1/theta
// (sigma = 0), one of each conjugate pair, the `count` lowest in ascending natural frequency.
std::vector<Mode> ritzModes(const JointLinearisation& L, const Krylov& K,
                            const Eigen::ComplexEigenSolver<Eigen::MatrixXcd>& ritz,
                            const std::vector<Eigen::Index>& order, Eigen::Index take, std::size_t count, bool end_body)
{
  const Eigen::Index dof = K.V.rows() / 2;
  std::vector<Mode> modes;
  for (Eigen::Index i = 0; i < take; ++i)
  {
    const Eigen::Index r = order[static_cast<size_t>(i)];
    C lambda = 1.0 / ritz.eigenvalues()(r);  // theta = 1/(lambda - sigma)
    if (std::abs(lambda.imag()) <= 1e-9 * std::abs(lambda))
      lambda = lambda.real();  // a motion that decays without oscillating, kept once
    else if (lambda.imag() < 0.0)
      continue;  // one of each conjugate pair
    const Eigen::VectorXcd y = K.V.leftCols(K.k) * ritz.eigenvectors().col(r);
    modes.push_back(modeOf(L, lambda, Eigen::Map<const Eigen::Matrix3Xcd>(y.data(), 3, dof / 3), end_body));
  }
  std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) { return a.frequency < b.frequency; });
  modes.resize(std::min(count, modes.size()));
  return modes;
}
}  // namespace

std::vector<Mode> lowestModes(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                              const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                              std::size_t count, double step)
{
  auto dense = [&]
  {
    std::vector<Mode> modes = naturalModes(model, geometry, data, t, ship, x, v, step);
    modes.resize(std::min(count, modes.size()));
    return modes;
  };
  // The dense linearisation, as motionResponses; and where the Krylov space would hold a good part of the whole.
  if (model.elastic() || model.bends() || 8 * count + 40 >= 6 * static_cast<std::size_t>(x.cols()))
    return dense();
  const JointLinearisation L = lineariseJoints(model, geometry, data, t, ship, x, v, step);
  const JointMatrices J = jointMatrices(L);
  const Eigen::Index dof = J.M.rows(), size = 2 * dof;
  std::vector<Eigen::Matrix<C, 6, 6>> A;
  Eigen::SparseLU<Eigen::SparseMatrix<C>> lu(harmonicMatrix(L, 0.0, A));
  if (lu.info() != Eigen::Success)  // a mode of zero frequency: nothing to invert about 0; the dense solve has it
    return dense();
  // A start in the operator's range, where the constraints hold (the pencil's infinite eigenvalues purged).
  std::mt19937 random(1);
  std::normal_distribution<double> normal;
  Eigen::VectorXcd start(size);
  for (Eigen::Index i = 0; i < size; ++i)
    start(i) = normal(random);
  start = shiftInvert(lu, J, 0.0, shiftInvert(lu, J, 0.0, start));
  // 2 count eigenvalues (a conjugate pair per oscillating mode), each Ritz pair's residual within 1e-10 of it.
  const Eigen::Index wanted = std::min<Eigen::Index>(size, 2 * static_cast<Eigen::Index>(count));
  for (Eigen::Index m = std::min<Eigen::Index>(size, 4 * wanted + 40);; m = std::min<Eigen::Index>(size, 2 * m))
  {
    const Krylov K = arnoldi(lu, J, start, m);
    const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> ritz(K.H.topLeftCorner(K.k, K.k));
    std::vector<Eigen::Index> order(static_cast<size_t>(K.k));
    for (Eigen::Index i = 0; i < K.k; ++i)
      order[static_cast<size_t>(i)] = i;
    std::sort(order.begin(), order.end(),
              [&](Eigen::Index a, Eigen::Index b)
              { return std::abs(ritz.eigenvalues()(a)) > std::abs(ritz.eigenvalues()(b)); });
    const Eigen::Index take = std::min(wanted, K.k);
    bool converged = true;
    for (Eigen::Index i = 0; i < take && K.k < size; ++i)
    {
      const Eigen::Index r = order[static_cast<size_t>(i)];
      const double residual = std::abs(K.H(K.k, K.k - 1) * ritz.eigenvectors()(K.k - 1, r));
      converged = converged && residual <= 1e-10 * std::abs(ritz.eigenvalues()(r));
    }
    if (!converged && m < size)
      continue;
    return ritzModes(L, K, ritz, order, take, count, geometry.end_body);
  }
}

}  // namespace tow_sim
