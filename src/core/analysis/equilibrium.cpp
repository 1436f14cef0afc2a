#include "tow_sim/core/analysis/equilibrium.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace tow_sim
{
namespace
{
constexpr int kMaxIterations = 60;
constexpr int kMaxPasses = 100;  // shooting passes in a current profile

// The element's loads with its aft joint at x_aft, axis s, both joints moving at u. (Only the depth of
// x_aft matters, through a current profile.)
struct Balance
{
  const ChainModel& model;
  const ChainGeometry& geometry;
  const ChainData& data;
  int element;
  double t;
  Eigen::Vector3d u;
  Eigen::Vector3d T_aft;  // tension at the aft joint (0 below the vehicle)
  Eigen::Vector3d x_aft;
  double length;  // [m] the element's (an elastic segment's stretched length)

  // Moment about the CG of everything on the element, given that the force balance fixes
  // T_fwd = T_aft - F: M - l s x (T_aft - gamma F). Also returns T_fwd.
  Eigen::Vector3d residual(const Eigen::Vector3d& s, Eigen::Vector3d* T_fwd = nullptr) const
  {
    const double l = length;
    const ElementKinematics k = ElementKinematics::fromJoints(x_aft - l * s, x_aft, u, u);
    BodyDynamics body;
    model.elementDynamics(element, t, k, geometry, data, body, false);  // the steady tow clear of the seabed
    const Eigen::Vector3d F = body.wrench.head<3>(), M = body.wrench.tail<3>();
    if (T_fwd)
      *T_fwd = T_aft - F;
    return M - l * k.s.cross(T_aft - body.cg_fraction * F);
  }
};

Eigen::Matrix<double, 3, 2> tangentBasis(const Eigen::Vector3d& s)
{
  Eigen::Matrix<double, 3, 2> B;
  const Eigen::Vector3d e1 = s.unitOrthogonal();
  B << e1, s.cross(e1);
  return B;
}

// Moment residual on the two axes normal to s, and its Jacobian over small rotations of s about them.
void linearise(const Balance& b, const Eigen::Vector3d& s, Eigen::Vector2d& r, Eigen::Matrix2d& J)
{
  const Eigen::Matrix<double, 3, 2> B = tangentBasis(s);
  r = B.transpose() * b.residual(s);
  const double h = 1e-7;
  for (int j = 0; j < 2; ++j)
  {
    const Eigen::Vector3d axis = B.col(j);
    const Eigen::Vector3d sp = Eigen::AngleAxisd(h, axis) * s, sm = Eigen::AngleAxisd(-h, axis) * s;
    // Project the moments of the rotated states on the same axes (they stay normal to s to first order).
    J.col(j) = B.transpose() * (b.residual(sp) - b.residual(sm)) / (2.0 * h);
  }
}

// Newton on the unit sphere from s0; returns false if it does not converge.
bool solveDirection(const Balance& b, Eigen::Vector3d& s, int& iterations, double& residual, double scale)
{
  for (int it = 0; it < kMaxIterations; ++it, ++iterations)
  {
    Eigen::Vector2d r;
    Eigen::Matrix2d J;
    linearise(b, s, r, J);
    residual = r.norm();
    if (residual <= 1e-10 * scale)
      return true;
    const Eigen::FullPivLU<Eigen::Matrix2d> lu(J);
    if (!lu.isInvertible())
      return false;
    Eigen::Vector2d step = -lu.solve(r);
    const double max_step = 0.5;  // [rad]
    if (step.norm() > max_step)
      step *= max_step / step.norm();
    const Eigen::Matrix<double, 3, 2> B = tangentBasis(s);
    // Halve the step while the residual grows.
    double alpha = 1.0;
    for (int halving = 0; halving < 20; ++halving, alpha *= 0.5)
    {
      const Eigen::Vector3d rotation = B * (alpha * step);
      const Eigen::Vector3d trial = (Eigen::AngleAxisd(rotation.norm(), rotation.normalized()) * s).normalized();
      const Eigen::Vector2d r_trial = tangentBasis(trial).transpose() * b.residual(trial);
      if (r_trial.norm() < residual || halving == 19)
      {
        s = trial;
        break;
      }
    }
  }
  return false;
}

// A balanced direction is stable when turning the element raises a moment that turns it back.
bool isStable(const Balance& b, const Eigen::Vector3d& s)
{
  Eigen::Vector2d r;
  Eigen::Matrix2d J;
  linearise(b, s, r, J);
  // Rotating s by phi about axis n changes the moment about n by J phi; restoring means the symmetric
  // part is negative (semi-)definite. The moment of a rotation about e1 acts about e1: compare on the
  // rotation axes, which for s' = R(phi n) s is the same basis.
  const Eigen::Matrix2d S = 0.5 * (J + J.transpose());
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(S).eigenvalues().maxCoeff() <= 1e-9 * (1.0 + S.norm());
}

EquilibriumResult shoot(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                        const Eigen::Vector3d& tow_point_W, const Eigen::Vector3d& ship_velocity_W,
                        const Eigen::Matrix3Xd& joints, int iterations, const std::vector<double>& lengths);
std::vector<double> elementLengths(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                   double t, const Eigen::Vector3d& tow_point_W, const Eigen::Vector3d& ship_velocity_W,
                                   const EquilibriumResult* stretched);
}  // namespace

EquilibriumResult steadyTowEquilibrium(const ChainModel& model, double t, const Eigen::Vector3d& tow_point_W,
                                       const Eigen::Vector3d& ship_velocity_W)
{
  return steadyTowEquilibrium(model, model.initialGeometry(), model.initialData(t), t, tow_point_W, ship_velocity_W);
}

EquilibriumResult steadyTowEquilibrium(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                       double t, const Eigen::Vector3d& tow_point_W,
                                       const Eigen::Vector3d& ship_velocity_W)
{
  if (!tow_point_W.allFinite() || !ship_velocity_W.allFinite())
    throw std::runtime_error("equilibrium: tow point and ship velocity must be finite");
  const int n = geometry.elementCount();
  // With a current profile each element's balance depends on its depth, which is known only once the
  // shape hangs from the tow point, and an elastic segment's on its stretch, known once its tension is:
  // repeat the shooting with the depths and stretches of the previous pass until they settle. A rigid
  // cable in a uniform current needs one pass.
  const bool depth_dependent = !data.environment.current_profile.empty();
  const bool repeat = depth_dependent || model.elastic();
  Eigen::Matrix3Xd joints = tow_point_W.replicate(1, n);
  EquilibriumResult result;
  for (int pass = 0; pass < (repeat ? kMaxPasses : 1); ++pass)
  {
    const std::vector<double> lengths =
        elementLengths(model, geometry, data, t, tow_point_W, ship_velocity_W, pass > 0 ? &result : nullptr);
    result = shoot(model, geometry, data, t, tow_point_W, ship_velocity_W, joints, result.iterations, lengths);
    const double moved = (result.state.x - joints).cwiseAbs().maxCoeff();
    joints = result.state.x;
    if (moved < 1e-7 * (1.0 + geometry.totalLength()))
      return result;
  }
  if (repeat)
    throw std::runtime_error("equilibrium: the shape did not settle in the current profile or the stretch after " +
                             std::to_string(kMaxPasses) + " passes");
  return result;
}

namespace
{
// The first of the candidate directions from which Newton converges to a stable balance, into s.
template <size_t N>
bool firstStable(const Balance& b, const Eigen::Vector3d (&candidates)[N], double scale, int& iterations,
                 double& residual, Eigen::Vector3d& s)
{
  for (const Eigen::Vector3d& start : candidates)
  {
    s = start;
    if (solveDirection(b, s, iterations, residual, scale) && isStable(b, s))
      return true;
  }
  return false;
}

// The pull on element e at its aft joint x_W [m], moving at v_W [m/s], under the cable below's T_below [N]:
// T_below less the load of a point body at that joint (its steady balance, docs/solver.md §11). The tension
// reported at that joint stays the cable's below.
Eigen::Vector3d pullAbove(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                          int e, const Eigen::Vector3d& x_W, const Eigen::Vector3d& v_W, const Eigen::Vector3d& T_below)
{
  const JointBody* body = model.bodyAft(e, geometry);
  return body ? Eigen::Vector3d(T_below - body->force(data.environment, t, x_W, v_W)) : T_below;
}

// The element lengths: the geometry's; for an elastic cable with a solution `stretched` at hand, each
// segment stretched by its tension there, N = -s.(T_fwd + T_aft)/2 (its static balance, docs/solver.md §8), T_aft
// the pull of what hangs below it (the cable's less a point body's load at that joint).
std::vector<double> elementLengths(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                   double t, const Eigen::Vector3d& tow_point_W, const Eigen::Vector3d& ship_velocity_W,
                                   const EquilibriumResult* stretched)
{
  const int n = geometry.elementCount();
  std::vector<double> lengths(static_cast<size_t>(n));
  for (int e = 0; e < n; ++e)
  {
    double& length = lengths[static_cast<size_t>(e)] = geometry.elementLength(e);
    if (!stretched || !model.elastic() || e >= geometry.segments)
      continue;
    const Eigen::Matrix3Xd& x = stretched->state.x;
    const Eigen::Vector3d s = (x.col(e) - (e == 0 ? tow_point_W : Eigen::Vector3d(x.col(e - 1)))).normalized();
    const Eigen::Vector3d aft =
        pullAbove(model, geometry, data, t, e, x.col(e), ship_velocity_W, stretched->tensions.col(e + 1));
    length *= 1.0 + std::max(-0.5 * s.dot(stretched->tensions.col(e) + aft), 0.0) /
                        *model.segmentCable(e, geometry).axial_stiffness;
  }
  return lengths;
}

EquilibriumResult shoot(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                        const Eigen::Vector3d& tow_point_W, const Eigen::Vector3d& ship_velocity_W,
                        const Eigen::Matrix3Xd& joints, int iterations, const std::vector<double>& lengths)
{
  const int n = geometry.elementCount();
  EquilibriumResult result;
  result.iterations = iterations;
  result.tensions.resize(3, n);
  Eigen::Matrix3Xd axes(3, n);
  // The first guess for the vehicle: trailing the flow past it, slightly down.
  const Eigen::Vector3d flow = ship_velocity_W - data.environment.currentAt(joints.col(n - 1).z());
  Eigen::Vector3d guess =
      flow.norm() > 1e-6 ? Eigen::Vector3d(-flow.normalized()) : Eigen::Vector3d(-Eigen::Vector3d::UnitZ());
  guess = (guess - 0.2 * Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Vector3d T_aft = Eigen::Vector3d::Zero();
  for (int e = n - 1; e >= 0; --e)
  {
    const Eigen::Vector3d T_above = pullAbove(model, geometry, data, t, e, joints.col(e), ship_velocity_W, T_aft);
    const Balance b{
      model, geometry, data, e, t, ship_velocity_W, T_above, joints.col(e), lengths[static_cast<size_t>(e)]
    };
    Eigen::Vector3d F_guess;
    b.residual(guess, &F_guess);
    const double scale = 1.0 + geometry.elementLength(e) * (T_aft.norm() + F_guess.norm());
    // Candidates: the guess, the guess tipped, and the reversed guess; the first stable balance wins.
    const Eigen::Vector3d candidates[] = { guess, (guess - 0.5 * Eigen::Vector3d::UnitZ()).normalized(),
                                           (Eigen::AngleAxisd(0.3, guess.unitOrthogonal()) * guess).normalized(),
                                           -guess };
    double residual = 0.0;
    Eigen::Vector3d s;
    if (!firstStable(b, candidates, scale, result.iterations, residual, s))
    {
      std::ostringstream os;
      os << "equilibrium: no stable direction balances element " << e + 1 << " of " << n
         << (e == n - 1 ? " (the vehicle)" : "") << " at ship velocity (" << ship_velocity_W.transpose()
         << ") m/s and current (" << data.environment.currentAt(joints.col(e).z()).transpose()
         << ") m/s; moment residual " << residual << " N m";
      throw std::runtime_error(os.str());
    }
    result.largest_residual = std::max(result.largest_residual, residual);
    axes.col(e) = s;
    Eigen::Vector3d T_fwd;
    b.residual(s, &T_fwd);
    result.tensions.col(e) = T_fwd;
    T_aft = T_fwd;
    guess = s;
  }
  result.state.x.resize(3, n);
  result.state.v.resize(3, n);
  Eigen::Vector3d p = tow_point_W;
  for (int e = 0; e < n; ++e)
  {
    p += lengths[static_cast<size_t>(e)] * axes.col(e);
    result.state.x.col(e) = p;
    result.state.v.col(e) = ship_velocity_W;
  }
  return result;
}
}  // namespace

}  // namespace tow_sim
