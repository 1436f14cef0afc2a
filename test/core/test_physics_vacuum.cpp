// Checks in vacuum against closed forms (physics.md §8): energy conservation of a released chain and
// the small-swing frequencies of a hanging chain, omega_n = (j_{0,n}/2) sqrt(g/L).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/chain_fixtures.h"
#include "tow_sim/core/chain/chain_solver.h"

namespace tow_sim
{
namespace
{
Environment vacuum()
{
  Environment env;
  env.water_density = 0.0;
  return env;
}

// A chain released in vacuum from a straight line 30 degrees below the horizontal, with a sideways push
// at the end so that the motion is fully three-dimensional: its energy, sampled each second,
// relative to the start (largest |E - E0| / |E0|, and the largest gain).
struct EnergyDrift
{
  double worst = 0.0;
  double largest_gain = 0.0;
  double moved = 0.0;  // |x(end) - x(0)| over all joints [m]
  int steps = 0, rejected = 0;
};

EnergyDrift releasedChainDrift(const NumericsParams& num, int seconds = 100)
{
  CableParams cable;
  cable.segments = 8;
  cable.length = 8.0;
  cable.mass_per_length = 1.5;
  EndElementParams end = test::endLikeSegment(cable);
  end.mass = 4.0;  // a heavier end body, CG off the middle, given inertia
  end.cg_from_bail = 0.7;
  end.transverse_inertia = 0.6;
  const Environment env = vacuum();
  auto model = test::makeModel(cable, end, env, num);
  const ShipMotion fixed = constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  Simulator sim(model, fixed);
  ChainState start =
      straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.0, -0.577), Eigen::Vector3d::Zero());
  const int n = model->jointCount();
  for (int j = 0; j < n; ++j)
    start.v.col(j) = Eigen::Vector3d(0.0, 0.3 * j / n, 0.0);
  sim.reset(0.0, start);
  const double e0 = test::chainEnergy(*model, cable, end, env.gravity, fixed(0.0), sim.state());
  EnergyDrift drift;
  for (int i = 1; i <= seconds; ++i)
  {
    const StepReport r = sim.advanceTo(i * 1.0);
    drift.steps += r.steps;
    drift.rejected += r.rejected;
    const double e = test::chainEnergy(*model, cable, end, env.gravity, fixed(sim.time()), sim.state());
    drift.worst = std::max(drift.worst, std::abs(e - e0) / std::abs(e0));
    drift.largest_gain = std::max(drift.largest_gain, (e - e0) / std::abs(e0));
  }
  drift.moved = (sim.state().x - start.x).norm();
  return drift;
}

TEST(Vacuum, ReleasedChainKeepsItsEnergy)
{
  // dopri5 at tight tolerances conserves the energy of the model: this checks the physics.
  NumericsParams num;
  num.stepper = StepperType::kDopri5;
  num.abs_tol = 1e-12;
  num.rel_tol = 1e-12;
  num.max_step = 0.05;
  const EnergyDrift drift = releasedChainDrift(num);
  std::printf("dopri5: largest relative energy drift over 100 s: %.3g\n", drift.worst);
  EXPECT_LT(drift.worst, 1e-6);
  EXPECT_GT(drift.moved, 1.0);  // the chain did swing: it is far from where it started
}

TEST(Vacuum, ImplicitStepperConvergesToTheConservedEnergy)
{
  // The implicit stepper (L-stable ROS2) does not conserve energy exactly: its drift is a truncation
  // error that must stay small at the default tolerances and shrink as they are tightened. (Undamped,
  // the chain's zig-zag modes at ~35 rad/s stay excited and hold its steps near 0.2 ms; in water the
  // drag damps them.)
  NumericsParams num;
  num.stepper = StepperType::kImplicit;
  const EnergyDrift hundred = releasedChainDrift(num);
  std::printf("implicit, default tolerances: largest relative energy drift over 100 s %.3g (%d steps, %d rejected)\n",
              hundred.worst, hundred.steps, hundred.rejected);
  EXPECT_LT(hundred.worst, 2e-3);
  EXPECT_GT(hundred.moved, 1.0);
  const EnergyDrift loose = releasedChainDrift(num, 20);
  num.implicit_position_tol = num.implicit_velocity_tol = num.implicit_rel_tol = 2e-6;
  const EnergyDrift tight = releasedChainDrift(num, 20);
  std::printf("over 20 s: %.3g at the default tolerances, %.3g at 2e-6\n", loose.worst, tight.worst);
  EXPECT_LT(tight.worst, loose.worst / 4.0);
}

// Linearised in-plane swing of a chain of nu+1 equal rods hanging from a fixed point: the stiffness
// matrix d(theta'')/d(theta) by central differences of the solver's accelerations, then its eigenvalues.
TEST(Vacuum, HangingChainFrequenciesMatchBessel)
{
  CableParams cable;
  cable.segments = 50;
  cable.length = 50.0;
  cable.mass_per_length = 1.0;
  const EndElementParams end = test::endLikeSegment(cable);  // rod 51 of 51
  const Environment env = vacuum();
  auto model = test::makeModel(cable, end, env);
  ChainSolver solver;
  const ChainData data = model->initialData();
  const int n = model->elementCount();
  const double d = cable.segmentLength();
  const double total_length = n * d;
  const ShipEndState ship;

  auto angularAccelerations = [&](const Eigen::VectorXd& theta)
  {
    Eigen::Matrix3Xd x(3, n), v = Eigen::Matrix3Xd::Zero(3, n), a(3, n);
    Eigen::Vector3d p = ship.p_W;
    for (int e = 0; e < n; ++e)
    {
      p += d * Eigen::Vector3d(std::sin(theta(e)), 0.0, -std::cos(theta(e)));
      x.col(e) = p;
    }
    solver.solve(*model, model->initialGeometry(), data, 0.0, ship, x, v, a);
    Eigen::VectorXd theta_dd(n);
    Eigen::Vector3d a_f = ship.a_W;
    for (int e = 0; e < n; ++e)
    {
      const Eigen::Vector3d da = a.col(e) - a_f;  // at rest: theta'' = (cos th da_x + sin th da_z) / d
      theta_dd(e) = (std::cos(theta(e)) * da.x() + std::sin(theta(e)) * da.z()) / d;
      a_f = a.col(e);
    }
    return theta_dd;
  };

  const double h = 1e-6;
  Eigen::MatrixXd stiffness(n, n);
  for (int j = 0; j < n; ++j)
  {
    Eigen::VectorXd plus = Eigen::VectorXd::Zero(n), minus = Eigen::VectorXd::Zero(n);
    plus(j) = h;
    minus(j) = -h;
    stiffness.col(j) = -(angularAccelerations(plus) - angularAccelerations(minus)) / (2.0 * h);
  }
  Eigen::EigenSolver<Eigen::MatrixXd> eig(stiffness);
  std::vector<double> omega;
  for (int i = 0; i < n; ++i)
  {
    EXPECT_NEAR(eig.eigenvalues()(i).imag(), 0.0, 1e-6);
    EXPECT_GT(eig.eigenvalues()(i).real(), 0.0);
    omega.push_back(std::sqrt(eig.eigenvalues()(i).real()));
  }
  std::sort(omega.begin(), omega.end());
  const double bessel_zeros[] = { 2.404825557695773, 5.520078110286311, 8.653727912911013 };
  for (int mode = 0; mode < 3; ++mode)
  {
    const double expected = 0.5 * bessel_zeros[mode] * std::sqrt(env.gravity / total_length);
    std::printf("mode %d: omega = %.6f rad/s, Bessel %.6f rad/s, ratio %.5f\n", mode + 1, omega[mode], expected,
                omega[mode] / expected);
    EXPECT_NEAR(omega[mode] / expected, 1.0, 0.01) << "mode " << mode + 1;
  }
}

}  // namespace
}  // namespace tow_sim
