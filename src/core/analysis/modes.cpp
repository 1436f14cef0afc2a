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
// One coordinate of the small motions: element e's aft joint, and every joint aft of it, moves by scale * q along
// `direction`. Turning about n (in-plane) or m (out-of-plane) by the angle q [rad]: direction axis x s, scale the
// element's length. Stretching an elastic segment by q [m]: direction s, scale 1.
struct Coordinate
{
  enum class Kind
  {
    kInPlane,
    kOutOfPlane,
    kStretch
  };
  Eigen::Index element = 0;
  Kind kind = Kind::kInPlane;
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();  // of the turn (zero for a stretch)
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  double scale = 1.0;
  double stretch = 0.0;  // [m] a stretch coordinate's segment: its length less its rest length
};

// Each element's axis s, the horizontal n normal to it and m = s x n, its length, and the coordinates: two turns
// per element, in element order, and a stretch after them for an elastic cable segment.
struct ElementFrames
{
  std::vector<Eigen::Vector3d> s, n, m;
  std::vector<double> length;
  std::vector<Coordinate> coordinates;
};

ElementFrames framesOf(const ChainModel& model, const ChainGeometry& geometry, const ShipEndState& ship,
                       const Eigen::Matrix3Xd& x)
{
  ElementFrames f;
  for (Eigen::Index e = 0; e < x.cols(); ++e)
  {
    const Eigen::Vector3d fore = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
    // A stretching segment turns at its actual length; a rigid one is its length.
    const bool stretches = model.elastic() && e < geometry.segments;
    const double l = stretches ? (x.col(e) - fore).norm() : geometry.elementLength(static_cast<int>(e));
    const Eigen::Vector3d s = (x.col(e) - fore) / l;
    Eigen::Vector3d n = Eigen::Vector3d::UnitZ().cross(s);
    n = n.norm() > 1e-9 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitY();  // a vertical element
    f.s.push_back(s);
    f.n.push_back(n);
    f.m.push_back(s.cross(n));
    f.length.push_back(l);
    f.coordinates.push_back({ e, Coordinate::Kind::kInPlane, n, n.cross(s), l });
    f.coordinates.push_back({ e, Coordinate::Kind::kOutOfPlane, s.cross(n), s.cross(n).cross(s), l });
    if (stretches)
      f.coordinates.push_back({ e, Coordinate::Kind::kStretch, Eigen::Vector3d::Zero(), s, 1.0,
                                l - geometry.elementLength(static_cast<int>(e)) });
  }
  return f;
}

// The joints with coordinate c moved to q: turned exactly (its length kept) or stretched; the joints aft move with it.
Eigen::Matrix3Xd moved(const Eigen::Matrix3Xd& x, const ElementFrames& f, const ShipEndState& ship, const Coordinate& c,
                       double q)
{
  Eigen::Matrix3Xd out = x;
  const Eigen::Index e = c.element;
  const size_t i = static_cast<size_t>(e);
  const Eigen::Vector3d fore = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
  const Eigen::Vector3d shift =
      c.kind == Coordinate::Kind::kStretch
          ? Eigen::Vector3d(q * f.s[i])
          : Eigen::Vector3d(fore + f.length[i] * (Eigen::AngleAxisd(q, c.axis) * f.s[i]) - x.col(e));
  out.rightCols(x.cols() - e).colwise() += shift;
  return out;
}

// The joints' velocities with coordinate c changing at the rate w: the joints aft move with it.
Eigen::Matrix3Xd moving(const Eigen::Matrix3Xd& v, const Coordinate& c, double w)
{
  Eigen::Matrix3Xd out = v;
  out.rightCols(v.cols() - c.element).colwise() += c.scale * w * c.direction;
  return out;
}

// The coordinates' accelerations from the joints' accelerations.
Eigen::VectorXd coordinateAccelerations(const ElementFrames& f, const ShipEndState& ship, const Eigen::Matrix3Xd& a)
{
  Eigen::VectorXd q(f.coordinates.size());
  for (size_t k = 0; k < f.coordinates.size(); ++k)
  {
    const Coordinate& c = f.coordinates[k];
    const Eigen::Vector3d da = a.col(c.element) - (c.element == 0 ? ship.a_W : Eigen::Vector3d(a.col(c.element - 1)));
    q(static_cast<Eigen::Index>(k)) = da.dot(c.direction) / c.scale;
  }
  return q;
}

// The joints' displacements (complex) of a mode from its coordinates.
Eigen::Matrix3Xcd jointDisplacements(const ElementFrames& f, const Eigen::VectorXcd& q)
{
  const Eigen::Index n = static_cast<Eigen::Index>(f.s.size());
  Eigen::Matrix3Xcd d = Eigen::Matrix3Xcd::Zero(3, n);
  for (size_t k = 0; k < f.coordinates.size(); ++k)
  {
    const Coordinate& c = f.coordinates[k];
    d.rightCols(n - c.element).colwise() +=
        (c.scale * q(static_cast<Eigen::Index>(k))) * c.direction.cast<std::complex<double>>();
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

std::string dominantPart(const ElementFrames& f, const Eigen::VectorXcd& q, const Eigen::Matrix3Xcd& d, bool end_body)
{
  const Eigen::Index n = static_cast<Eigen::Index>(f.s.size()), cable = end_body ? n - 1 : n;
  const Eigen::Index dof = q.size();
  if (end_body)  // its two turns are the last coordinates
  {
    const double l_end = f.length.back();
    const double turn = l_end * std::hypot(std::abs(q(dof - 2)), std::abs(q(dof - 1)));
    const double cable_peak = cable > 0 ? d.leftCols(cable).colwise().norm().maxCoeff() : 0.0;
    if (turn > cable_peak)  // the end body turns through more than the cable's joints move
      return std::abs(q(dof - 2)) >= std::abs(q(dof - 1)) ? "vehicle pitch" : "vehicle yaw";
  }
  double in = 0.0, out = 0.0, axial = 0.0;
  for (size_t k = 0; k < f.coordinates.size(); ++k)
  {
    const Coordinate& c = f.coordinates[k];
    if (c.element >= cable)
      continue;
    const double part = std::norm(c.scale * q(static_cast<Eigen::Index>(k)));
    (c.kind == Coordinate::Kind::kInPlane ? in : c.kind == Coordinate::Kind::kOutOfPlane ? out : axial) += part;
  }
  if (axial > in && axial > out)
    return "axial";
  return in >= out ? "in-plane" : "out-of-plane";
}

// The linearised equations about the state: rows q'' (one per coordinate) and then the tension magnitudes at the
// tow point and at the last element's forward joint; columns the coordinates (K), their rates (D) and, along
// each input (a tow-point translation per unit input), the input's displacement, velocity and acceleration.
struct Forcing
{
  Eigen::VectorXd G_x, G_v, G_a;  // N + 2
};
struct Linearisation
{
  Eigen::MatrixXd K, D;     // (N + 2) x N, N coordinates
  std::vector<Forcing> by;  // one per input
};

Eigen::VectorXd outputsOf(ChainSolver& solver, const ChainModel& model, const ChainGeometry& geometry,
                          const ChainData& data, double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                          const Eigen::Matrix3Xd& v, const ElementFrames& f)
{
  const Eigen::Index n = x.cols();
  Eigen::Matrix3Xd a(3, n), tensions(3, n);
  solver.solve(model, geometry, data, t, ship, x, v, a, &tensions);
  const Eigen::Index dof = static_cast<Eigen::Index>(f.coordinates.size());
  Eigen::VectorXd out(dof + 2);
  out.head(dof) = coordinateAccelerations(f, ship, a);
  out(dof) = tensions.col(0).norm();
  out(dof + 1) = tensions.col(n - 1).norm();
  return out;
}

Linearisation linearise(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                        const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double h,
                        const ElementFrames& f, const std::vector<Eigen::Vector3d>& inputs)
{
  const Eigen::Index dof = static_cast<Eigen::Index>(f.coordinates.size());
  Linearisation L;
  L.K.resize(dof + 2, dof);
  L.D.resize(dof + 2, dof);
  ChainSolver solver;
  auto out = [&](const Eigen::Matrix3Xd& xs, const Eigen::Matrix3Xd& vs, const ShipEndState& end)
  { return outputsOf(solver, model, geometry, data, t, end, xs, vs, f); };
  const double floor = 1e-12 * (1.0 + x.cwiseAbs().maxCoeff());  // [m] a step rounding leaves exact to 1e-4
  Eigen::VectorXd at_rest;
  for (Eigen::Index k = 0; k < dof; ++k)
  {
    const Coordinate& c = f.coordinates[static_cast<size_t>(k)];
    // A stretch is differenced in metres by the same number as a turn in radians, but by no more than a tenth of
    // the segment's stretch, so that the tension-only spring does not go slack within the step (a stiff cable's
    // stretch can be 1e-7 m). Where that would be below rounding, one-sided on the taut side by 100 times that; a
    // segment at or below its rest length, one-sided on the slack side (it carries no tension: its spring is not
    // linear there, and slack is what it is).
    const bool stretch = c.kind == Coordinate::Kind::kStretch;
    const double hc = stretch && c.stretch > 0.0 ? std::min(h, 0.1 * c.stretch) : h;
    if (stretch && (c.stretch <= 0.0 || hc < floor))
    {
      if (at_rest.size() == 0)
        at_rest = out(x, v, ship);
      const double step = c.stretch > 0.0 ? 100.0 * floor : -h;
      L.K.col(k) = (out(moved(x, f, ship, c, step), v, ship) - at_rest) / step;
      L.D.col(k) = (out(x, moving(v, c, step), ship) - at_rest) / step;
      continue;
    }
    L.K.col(k) = (out(moved(x, f, ship, c, hc), v, ship) - out(moved(x, f, ship, c, -hc), v, ship)) / (2.0 * hc);
    L.D.col(k) = (out(x, moving(v, c, hc), ship) - out(x, moving(v, c, -hc), ship)) / (2.0 * hc);
  }
  for (const Eigen::Vector3d& input : inputs)
  {
    Forcing G;
    ShipEndState plus = ship, minus = ship;  // the tow point and every joint displaced, then moving, along input
    plus.p_W += h * input;
    minus.p_W -= h * input;
    G.G_x = (out(x.colwise() + h * input, v, plus) - out(x.colwise() - h * input, v, minus)) / (2.0 * h);
    plus = minus = ship;
    plus.v_W += h * input;
    minus.v_W -= h * input;
    G.G_v = (out(x, v.colwise() + h * input, plus) - out(x, v.colwise() - h * input, minus)) / (2.0 * h);
    plus = minus = ship;
    plus.a_W += h * input;
    minus.a_W -= h * input;
    G.G_a = (out(x, v, plus) - out(x, v, minus)) / (2.0 * h);
    L.by.push_back(G);
  }
  return L;
}

}  // namespace

std::vector<Mode> naturalModes(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                               const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                               double step)
{
  const ElementFrames f = framesOf(model, geometry, ship, x);
  const Linearisation L = linearise(model, geometry, data, t, ship, x, v, step, f, {});
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
    const Eigen::VectorXcd q = eig.eigenvectors().col(i).head(dof);
    const Eigen::Matrix3Xcd d = jointDisplacements(f, q);
    mode.shape = realShape(d);
    mode.dominant = dominantPart(f, q, d, geometry.end_body);
    modes.push_back(mode);
  }
  std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) { return a.frequency < b.frequency; });
  return modes;
}

std::vector<std::vector<MotionResponse>> motionResponsesDense(const ChainModel& model, const ChainGeometry& geometry,
                                                              const ChainData& data, double t, const ShipEndState& ship,
                                                              const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                                              const std::vector<Eigen::Vector3d>& inputs,
                                                              const std::vector<double>& periods, double cg_fraction,
                                                              double step)
{
  const ElementFrames f = framesOf(model, geometry, ship, x);
  const Linearisation L = linearise(model, geometry, data, t, ship, x, v, step, f, inputs);
  const Eigen::Index n = x.cols(), dof = static_cast<Eigen::Index>(f.coordinates.size());
  using C = std::complex<double>;
  const C i(0.0, 1.0);
  // The end body's lateral axis (port) for its pitch: horizontal, normal to its forward direction -s.
  const Eigen::Vector3d s_end = f.s.back(), y_body = Eigen::Vector3d::UnitZ().cross(-s_end).normalized();
  std::vector<std::vector<MotionResponse>> out(inputs.size());
  for (double period : periods)
  {
    const double w = 2.0 * kPi / period;
    // (-w^2 I - i w D - K) Q = (G_x + i w G_v - w^2 G_a), per unit input displacement: one factorisation per period
    const Eigen::PartialPivLU<Eigen::MatrixXcd> A(-w * w * Eigen::MatrixXcd::Identity(dof, dof) -
                                                  i * w * L.D.topRows(dof).cast<C>() - L.K.topRows(dof).cast<C>());
    for (size_t k = 0; k < inputs.size(); ++k)
    {
      const Forcing& F = L.by[k];
      const Eigen::Vector3cd input = inputs[k].cast<C>();
      const Eigen::VectorXcd G = (F.G_x + i * w * F.G_v - w * w * F.G_a).cast<C>();
      const Eigen::VectorXcd Q = A.solve(G.head(dof));
      const Eigen::Matrix3Xcd d = jointDisplacements(f, Q).colwise() + input;
      const Eigen::Vector3cd bail = n > 1 ? Eigen::Vector3cd(d.col(n - 2)) : input;
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
      out[k].push_back(r);
    }
  }
  return out;
}

std::vector<MotionResponse> motionResponse(const ChainModel& model, const ChainGeometry& geometry,
                                           const ChainData& data, double t, const ShipEndState& ship,
                                           const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                           const Eigen::Vector3d& input, const std::vector<double>& periods,
                                           double cg_fraction, double step)
{
  return motionResponses(model, geometry, data, t, ship, x, v, { input }, periods, cg_fraction, step).front();
}

}  // namespace tow_sim
