#include "tow_sim/core/analysis/modes.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>

#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
// Each element's axis s and the two directions its aft joint moves in when it turns: b[0] in the vertical plane
// through s (turning about the horizontal n normal to s), b[1] out of it (turning about m = s x n).
struct ElementFrames
{
  std::vector<Eigen::Vector3d> s, n, m;
  std::vector<double> length;
};

ElementFrames framesOf(const ChainGeometry& geometry, const ShipEndState& ship, const Eigen::Matrix3Xd& x)
{
  ElementFrames f;
  for (Eigen::Index e = 0; e < x.cols(); ++e)
  {
    const Eigen::Vector3d fore = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
    const double l = geometry.elementLength(static_cast<int>(e));
    const Eigen::Vector3d s = (x.col(e) - fore) / l;
    Eigen::Vector3d n = Eigen::Vector3d::UnitZ().cross(s);
    n = n.norm() > 1e-9 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitY();  // a vertical element
    f.s.push_back(s);
    f.n.push_back(n);
    f.m.push_back(s.cross(n));
    f.length.push_back(l);
  }
  return f;
}

// The joints with element e's axis turned by the angle q about axis (n or m): the joints aft move with it.
Eigen::Matrix3Xd turned(const Eigen::Matrix3Xd& x, const ElementFrames& f, const ShipEndState& ship, Eigen::Index e,
                        const Eigen::Vector3d& axis, double q)
{
  Eigen::Matrix3Xd out = x;
  const Eigen::Vector3d fore = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
  const Eigen::Vector3d shift =
      fore + f.length[static_cast<size_t>(e)] * (Eigen::AngleAxisd(q, axis) * f.s[static_cast<size_t>(e)]) - x.col(e);
  out.rightCols(x.cols() - e).colwise() += shift;
  return out;
}

// The joints' velocities with element e's axis turning at the rate w about axis: the joints aft move with it.
Eigen::Matrix3Xd turning(const Eigen::Matrix3Xd& v, const ElementFrames& f, Eigen::Index e, const Eigen::Vector3d& axis,
                         double w)
{
  Eigen::Matrix3Xd out = v;
  out.rightCols(v.cols() - e).colwise() +=
      f.length[static_cast<size_t>(e)] * w * axis.cross(f.s[static_cast<size_t>(e)]);
  return out;
}

// The angles' accelerations (two per element: about n, about m) from the joints' accelerations.
Eigen::VectorXd angularAccelerations(const ElementFrames& f, const ShipEndState& ship, const Eigen::Matrix3Xd& a)
{
  Eigen::VectorXd q(2 * a.cols());
  for (Eigen::Index e = 0; e < a.cols(); ++e)
  {
    const size_t i = static_cast<size_t>(e);
    const Eigen::Vector3d da = a.col(e) - (e == 0 ? ship.a_W : Eigen::Vector3d(a.col(e - 1)));
    q(2 * e) = da.dot(f.n[i].cross(f.s[i])) / f.length[i];
    q(2 * e + 1) = da.dot(f.m[i].cross(f.s[i])) / f.length[i];
  }
  return q;
}

// The joints' displacements (complex) of a mode from its angles.
Eigen::Matrix3Xcd jointDisplacements(const ElementFrames& f, const Eigen::VectorXcd& angles)
{
  const Eigen::Index n = angles.size() / 2;
  Eigen::Matrix3Xcd d(3, n);
  Eigen::Vector3cd sum = Eigen::Vector3cd::Zero();
  for (Eigen::Index e = 0; e < n; ++e)
  {
    const size_t i = static_cast<size_t>(e);
    sum += f.length[i] * (angles(2 * e) * f.n[i].cross(f.s[i]).cast<std::complex<double>>() +
                          angles(2 * e + 1) * f.m[i].cross(f.s[i]).cast<std::complex<double>>());
    d.col(e) = sum;
  }
  return d;
}

// The displacements at the phase of the largest one, which is 1.
Eigen::Matrix3Xd realShape(const Eigen::Matrix3Xcd& d)
{
  Eigen::Index row = 0, col = 0;
  d.cwiseAbs().maxCoeff(&row, &col);
  return (d / d(row, col)).real();
}

std::string dominantPart(const ElementFrames& f, const Eigen::VectorXcd& angles, const Eigen::Matrix3Xcd& d,
                         bool end_body)
{
  const Eigen::Index n = angles.size() / 2, cable = end_body ? n - 1 : n;
  if (end_body)
  {
    const double l_end = f.length[static_cast<size_t>(n - 1)];
    const double turn = l_end * std::hypot(std::abs(angles(2 * n - 2)), std::abs(angles(2 * n - 1)));
    const double cable_peak = cable > 0 ? d.leftCols(cable).colwise().norm().maxCoeff() : 0.0;
    if (turn > cable_peak)  // the end body turns through more than the cable's joints move
      return std::abs(angles(2 * n - 2)) >= std::abs(angles(2 * n - 1)) ? "vehicle pitch" : "vehicle yaw";
  }
  double in = 0.0, out = 0.0;
  for (Eigen::Index e = 0; e < cable; ++e)
  {
    const double l = f.length[static_cast<size_t>(e)];
    in += std::norm(l * angles(2 * e));
    out += std::norm(l * angles(2 * e + 1));
  }
  return in >= out ? "in-plane" : "out-of-plane";
}

// The linearised equations about the state: rows q'' (two per element) and then the tension magnitudes at the
// tow point and at the last element's forward joint; columns the angles (K), their rates (D) and, along
// `input` (a tow-point translation per unit input), the input's displacement, velocity and acceleration.
struct Linearisation
{
  Eigen::MatrixXd K, D;           // (2n + 2) x 2n
  Eigen::VectorXd G_x, G_v, G_a;  // 2n + 2
};

Eigen::VectorXd outputsOf(ChainSolver& solver, const ChainModel& model, const ChainGeometry& geometry,
                          const ChainData& data, double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                          const Eigen::Matrix3Xd& v, const ElementFrames& f)
{
  const Eigen::Index n = x.cols();
  Eigen::Matrix3Xd a(3, n), tensions(3, n);
  solver.solve(model, geometry, data, t, ship, x, v, a, &tensions);
  Eigen::VectorXd out(2 * n + 2);
  out.head(2 * n) = angularAccelerations(f, ship, a);
  out(2 * n) = tensions.col(0).norm();
  out(2 * n + 1) = tensions.col(n - 1).norm();
  return out;
}

Linearisation linearise(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                        const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double h,
                        const ElementFrames& f, const Eigen::Vector3d& input)
{
  const Eigen::Index n = x.cols();
  Linearisation L;
  L.K.resize(2 * n + 2, 2 * n);
  L.D.resize(2 * n + 2, 2 * n);
  ChainSolver solver;
  auto out = [&](const Eigen::Matrix3Xd& xs, const Eigen::Matrix3Xd& vs, const ShipEndState& end)
  { return outputsOf(solver, model, geometry, data, t, end, xs, vs, f); };
  for (Eigen::Index e = 0; e < n; ++e)
    for (int k = 0; k < 2; ++k)
    {
      const Eigen::Vector3d& axis = k == 0 ? f.n[static_cast<size_t>(e)] : f.m[static_cast<size_t>(e)];
      L.K.col(2 * e + k) =
          (out(turned(x, f, ship, e, axis, h), v, ship) - out(turned(x, f, ship, e, axis, -h), v, ship)) / (2.0 * h);
      L.D.col(2 * e + k) =
          (out(x, turning(v, f, e, axis, h), ship) - out(x, turning(v, f, e, axis, -h), ship)) / (2.0 * h);
    }
  ShipEndState plus = ship, minus = ship;  // the tow point and every joint displaced, then moving, along input
  plus.p_W += h * input;
  minus.p_W -= h * input;
  L.G_x = (out(x.colwise() + h * input, v, plus) - out(x.colwise() - h * input, v, minus)) / (2.0 * h);
  plus = minus = ship;
  plus.v_W += h * input;
  minus.v_W -= h * input;
  L.G_v = (out(x, v.colwise() + h * input, plus) - out(x, v.colwise() - h * input, minus)) / (2.0 * h);
  plus = minus = ship;
  plus.a_W += h * input;
  minus.a_W -= h * input;
  L.G_a = (out(x, v, plus) - out(x, v, minus)) / (2.0 * h);
  return L;
}

void requireRigid(const ChainModel& model)
{
  if (model.elastic())
    throw std::invalid_argument(
        "small motions: the rigid cable only (cable.axial_stiffness: 0); an elastic "
        "segment's stretch is not one of the coordinates");
}
}  // namespace

std::vector<Mode> naturalModes(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                               const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                               double step)
{
  requireRigid(model);
  const ElementFrames f = framesOf(geometry, ship, x);
  const Linearisation L = linearise(model, geometry, data, t, ship, x, v, step, f, Eigen::Vector3d::UnitZ());
  const Eigen::Index dof = L.K.cols();
  const Eigen::MatrixXd K = L.K.topRows(dof), D = L.D.topRows(dof);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * dof, 2 * dof);
  A.topRightCorner(dof, dof).setIdentity();
  A.bottomLeftCorner(dof, dof) = K;
  A.bottomRightCorner(dof, dof) = D;
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(A);
  if (eig.info() != Eigen::Success)
    throw std::runtime_error("natural modes: the eigenvalue solver did not converge");
  std::vector<Mode> modes;
  for (Eigen::Index i = 0; i < 2 * dof; ++i)
  {
    const std::complex<double> lambda = eig.eigenvalues()(i);
    if (lambda.imag() < 0.0)
      continue;  // one of each conjugate pair (real eigenvalues are kept)
    Mode mode;
    mode.frequency = std::abs(lambda);
    mode.damping_ratio = mode.frequency > 0.0 ? -lambda.real() / mode.frequency : 0.0;
    mode.period = lambda.imag() > 0.0 ? 2.0 * kPi / lambda.imag() : std::numeric_limits<double>::infinity();
    const Eigen::VectorXcd angles = eig.eigenvectors().col(i).head(dof);
    const Eigen::Matrix3Xcd d = jointDisplacements(f, angles);
    mode.shape = realShape(d);
    mode.dominant = dominantPart(f, angles, d, geometry.end_body);
    modes.push_back(mode);
  }
  std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) { return a.frequency < b.frequency; });
  return modes;
}

std::vector<MotionResponse> motionResponse(const ChainModel& model, const ChainGeometry& geometry,
                                           const ChainData& data, double t, const ShipEndState& ship,
                                           const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                           const Eigen::Vector3d& input, const std::vector<double>& periods,
                                           double cg_fraction, double step)
{
  requireRigid(model);
  const ElementFrames f = framesOf(geometry, ship, x);
  const Linearisation L = linearise(model, geometry, data, t, ship, x, v, step, f, input);
  const Eigen::Index n = x.cols(), dof = 2 * n;
  using C = std::complex<double>;
  const C i(0.0, 1.0);
  // The end body's lateral axis (port) for its pitch: horizontal, normal to its forward direction -s.
  const Eigen::Vector3d s_end = f.s.back(), y_body = Eigen::Vector3d::UnitZ().cross(-s_end).normalized();
  std::vector<MotionResponse> out;
  for (double period : periods)
  {
    const double w = 2.0 * kPi / period;
    // (-w^2 I - i w D - K) Q = (G_x + i w G_v - w^2 G_a), per unit input displacement
    const Eigen::MatrixXcd A =
        -w * w * Eigen::MatrixXcd::Identity(dof, dof) - i * w * L.D.topRows(dof).cast<C>() - L.K.topRows(dof).cast<C>();
    const Eigen::VectorXcd G = (L.G_x + i * w * L.G_v - w * w * L.G_a).cast<C>();
    const Eigen::VectorXcd Q = A.partialPivLu().solve(G.head(dof));
    const Eigen::Matrix3Xcd d = jointDisplacements(f, Q).colwise() + input.cast<C>();
    const Eigen::Vector3cd bail = n > 1 ? Eigen::Vector3cd(d.col(n - 2)) : Eigen::Vector3cd(input.cast<C>());
    const Eigen::Vector3cd cg = bail + cg_fraction * (Eigen::Vector3cd(d.col(n - 1)) - bail);
    MotionResponse r;
    r.period = period;
    r.surge = cg.x();
    r.sway = cg.y();
    r.heave = cg.z();
    r.pitch = Q(dof - 2) * f.n.back().dot(y_body) + Q(dof - 1) * f.m.back().dot(y_body);
    const Eigen::VectorXcd tension =
        L.K.bottomRows(2).cast<C>() * Q + i * w * (L.D.bottomRows(2).cast<C>() * Q) + G.tail(2);
    r.tension_ship = tension(0);
    r.tension_vehicle = tension(1);
    out.push_back(r);
  }
  return out;
}

}  // namespace tow_sim
