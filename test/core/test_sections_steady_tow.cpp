// The steady tow of a cable of two sections with a clump weight at the joint between them (docs/physics.md
// §4, §11), configured as a SimulationConfig and run by TowRun, against the continuous cable integrated here,
// section by section, in the vertical plane of the tow:
//   dT/ds = f(a),   dx/ds = a = -T/|T|   (s from the tow point aft, T the pull toward the ship)
// with f per unit length the normal drag -C2 |u_n| u_n (P11), Pode's tangential drag -C1 |u|^2 sigma(u_t) a
// (P12) and the weight in water -(mu - rho pi D^2/4) g z (P9), u = U x the cable's velocity through still
// water; the constants come from the section parameters here, not from the model. Across the clump's joint
// the pull jumps by its weight in water (m - rho V) g and its drag 1/2 rho C_D A U^2 (P47). The integration
// starts from the pull tow_sim reports at the bail: the vehicle is not what is checked, the cable and the
// clump are. Compared, within 0.1 %: the clump's joint and the bail relative to the tow point (depth and
// layback) and the tension there,
//   - for the steady-tow equilibrium TowRun::start lays the cable out in;
//   - for the dynamics after 2400 s of towing (the solver's body load, docs/solver.md (S23)).
// The chain's discretisation error is second order: the largest difference, at the bail's depth, measured
// 1.1e-4, 2.9e-5 and 7.7e-6 with 100 + 50, 200 + 100 (used here) and 400 + 200 segments. References that
// leave out the clump, its drag, or the lower section's own constants miss by more than 1 %.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/ship_path.h"

namespace tow_sim
{
namespace
{
constexpr double kSpeed = 1.5;       // [m/s] the ship's, along +x
constexpr double kTolerance = 1e-3;  // relative
constexpr int kUpperSegments = 200;  // the clump's joint is x_{201}
constexpr int kSegments = 300;       // the bail is x_{301}

// An armoured upper section, a near-neutral tether below it, a 500 kg clump between them, the default vehicle.
SimulationConfig clumpedTow()
{
  SimulationConfig c;
  CableParams upper, lower;
  upper.length = 400.0;
  upper.segments = kUpperSegments;
  upper.diameter = 0.017;
  upper.mass_per_length = 0.9;
  upper.normal_drag_coefficient = 1.2;
  upper.tangential_drag_coefficient = 0.01;
  lower.length = 150.0;
  lower.segments = kSegments - kUpperSegments;
  lower.diameter = 0.025;
  lower.mass_per_length = 0.55;  // in water 0.047 kg/m: near neutral
  lower.normal_drag_coefficient = 1.5;
  lower.tangential_drag_coefficient = 0.02;
  c.sections = { upper, lower };
  c.cable.length = upper.length + lower.length;
  c.cable.segments = kSegments;
  CableBodyParams clump;
  clump.at = upper.length;
  clump.body.mass = 500.0;
  clump.body.displaced_volume = 0.064;
  clump.body.drag_area = 0.3;
  c.bodies = { clump };
  return c;
}

// The tow at kSpeed laid out as towing_chart.cpp's chartPoint() does (the steady-tow equilibrium), then
// advanced to t_end [s] (0: not at all).
TowSnapshot steadyTow(const SimulationConfig& c, double t_end = 0.0)
{
  TowRun run(c, straightShip(kSpeed, -20.0, 10.0 * (static_cast<int>(t_end / 10.0) + 2), 10.0), InitialShape());
  const std::string warning = run.start(0.0);
  EXPECT_EQ(warning, "");
  if (t_end > 0.0)
    run.advanceTo(t_end);
  return run.snapshot();
}

// A uniform section of the continuous cable: its length [m], weight in water [N/m], C1 and C2 [N s^2/m^3].
struct Section
{
  double length, weight, c1, c2;
};

Section section(const CableParams& p, const Environment& env)
{
  const double rho = env.water_density;
  return { p.length, (p.mass_per_length - rho * 0.25 * kPi * p.diameter * p.diameter) * env.gravity,
           0.5 * rho * p.tangential_drag_coefficient * kPi * p.diameter,
           0.5 * rho * p.normal_drag_coefficient * p.diameter };
}

// dy/ds for y = (T_x, T_z, x, z) in the vertical plane (x forward, z up): (P11), (P12), (P9) per unit length.
Eigen::Vector4d slope(const Section& c, const Eigen::Vector4d& y, double v_eps)
{
  const Eigen::Vector2d a = -y.head<2>().normalized();  // the cable's direction, aft
  const Eigen::Vector2d u(kSpeed, 0.0);
  const double u_t = u.dot(a);
  const Eigen::Vector2d u_n = u - u_t * a;
  const double sigma = u_t / std::sqrt(u_t * u_t + v_eps * v_eps);
  Eigen::Vector4d dy;
  dy.head<2>() = -c.c2 * u_n.norm() * u_n - c.c1 * u.squaredNorm() * sigma * a - Eigen::Vector2d(0.0, c.weight);
  dy.tail<2>() = a;
  return dy;
}

// Classical RK4 up a section, from its aft end to its forward end (s decreasing), steps of 2.5 cm.
void climb(const Section& c, double v_eps, Eigen::Vector4d& y)
{
  const int n = static_cast<int>(std::ceil(c.length / 0.025));
  const double h = -c.length / n;
  for (int i = 0; i < n; ++i)
  {
    const Eigen::Vector4d k1 = slope(c, y, v_eps), k2 = slope(c, y + 0.5 * h * k1, v_eps),
                          k3 = slope(c, y + 0.5 * h * k2, v_eps), k4 = slope(c, y + h * k3, v_eps);
    y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
}

// What is compared, in the plane of the tow: positions [m] relative to the tow point, the pull there [N].
struct Profile
{
  Eigen::Vector2d clump, bail, top_tension;
};

// The continuous cable from the bail's pull T_bail (x, z) [N] up to the tow point, the clump's jump between the
// sections: T above = T below + (drag, weight in water).
Profile reference(const Section& upper, const Section& lower, double clump_weight, double clump_drag,
                  const Eigen::Vector2d& T_bail, double v_eps)
{
  Eigen::Vector4d y(T_bail.x(), T_bail.y(), 0.0, 0.0);
  climb(lower, v_eps, y);
  const Eigen::Vector2d clump = y.tail<2>();
  y(0) += clump_drag;
  y(1) += clump_weight;
  climb(upper, v_eps, y);
  return { clump - y.tail<2>(), -y.tail<2>(), y.head<2>() };
}

// tow_sim's, from the snapshot's joints (world, tow point first) and tensions.
Profile simulated(const TowSnapshot& s)
{
  auto plane = [](const Eigen::Vector3d& v) { return Eigen::Vector2d(v.x(), v.z()); };
  return { plane(s.joints.col(kUpperSegments) - s.joints.col(0)), plane(s.joints.col(kSegments) - s.joints.col(0)),
           plane(s.tensions.col(0)) };
}

// Relative differences of the clump's depth and layback, the bail's depth and layback, the tension at the
// tow point.
std::vector<double> differences(const Profile& sim, const Profile& ref)
{
  auto rel = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
  return { rel(sim.clump.y(), ref.clump.y()), rel(sim.clump.x(), ref.clump.x()), rel(sim.bail.y(), ref.bail.y()),
           rel(sim.bail.x(), ref.bail.x()), rel(sim.top_tension.norm(), ref.top_tension.norm()) };
}

// The reference for the configuration: its sections, its clump, tow_sim's pull at the bail.
Profile referenceFor(const SimulationConfig& c, const TowSnapshot& s)
{
  const Environment& env = c.environment;
  const JointBody& b = c.bodies.front().body;
  const Eigen::Vector3d T_bail = s.tensions.col(kSegments);
  return reference(section(c.sections[0], env), section(c.sections[1], env),
                   (b.mass - env.water_density * b.displaced_volume) * env.gravity,
                   0.5 * env.water_density * b.drag_area * kSpeed * kSpeed, Eigen::Vector2d(T_bail.x(), T_bail.z()),
                   c.numerics.tangential_smoothing_speed);
}

// Each of the compared quantities of tow_sim's tow within kTolerance of the continuous cable's, printed.
void expectMatchesReference(const SimulationConfig& c, const TowSnapshot& s, const char* label)
{
  ASSERT_EQ(s.segments, kSegments);
  // Straight ahead in still water: the tow stays in the vertical plane of the track.
  EXPECT_LT(s.joints.row(1).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(s.tensions.row(1).cwiseAbs().maxCoeff(), 1e-9 * s.tension_ship);
  const Profile ref = referenceFor(c, s);
  const std::vector<double> d = differences(simulated(s), ref);
  std::printf(
      "%s vs the continuous cable (relative): clump depth %.2e (%.3f m), clump layback %.2e (%.3f m),\n"
      "  bail depth %.2e (%.3f m), bail layback %.2e (%.3f m), tension at the tow point %.2e (%.2f N)\n",
      label, d[0], -ref.clump.y(), d[1], -ref.clump.x(), d[2], -ref.bail.y(), d[3], -ref.bail.x(), d[4],
      ref.top_tension.norm());
  const char* what[] = { "clump depth", "clump layback", "bail depth", "bail layback", "tension at the tow point" };
  for (size_t i = 0; i < d.size(); ++i)
    EXPECT_LT(d[i], kTolerance) << label << ": " << what[i];
}

// The steady-tow equilibrium TowRun starts from (the shooting must add the clump's load at its joint).
TEST(SectionsSteadyTow, EquilibriumMatchesTheContinuousCableIntegratedHere)
{
  const SimulationConfig c = clumpedTow();
  expectMatchesReference(c, steadyTow(c), "steady-tow equilibrium");
}

// The dynamics (the solver's body load on its joint, docs/solver.md (S23)) after 2400 s of towing: settled
// within the chain's discretisation (measured 2.9e-5) even from a start that left the clump out (6e-4 off
// still at 1200 s).
TEST(SectionsSteadyTow, DynamicsSettleOnTheContinuousCableIntegratedHere)
{
  const SimulationConfig c = clumpedTow();
  expectMatchesReference(c, steadyTow(c, 2400.0), "dynamics after 2400 s");
}

// The comparisons above can fail: references that leave out the clump, its drag alone, or the lower
// section's own constants (the upper's everywhere) each miss the full reference by more than ten times the
// tolerance, so a tow_sim that made one of these mistakes could not pass (measured 0.67, 0.039, 0.16).
TEST(SectionsSteadyTow, ReferencesWithPlantedMistakesMissByMoreThanOnePercent)
{
  const SimulationConfig c = clumpedTow();
  const TowSnapshot s = steadyTow(c);
  const Environment& env = c.environment;
  const JointBody& b = c.bodies.front().body;
  const Section upper = section(c.sections[0], env), lower = section(c.sections[1], env);
  const double weight = (b.mass - env.water_density * b.displaced_volume) * env.gravity;
  const double drag = 0.5 * env.water_density * b.drag_area * kSpeed * kSpeed;
  const Eigen::Vector2d T_bail(s.tensions(0, kSegments), s.tensions(2, kSegments));
  const double v_eps = c.numerics.tangential_smoothing_speed;
  Section lower_as_upper = upper;
  lower_as_upper.length = lower.length;
  const Profile full = reference(upper, lower, weight, drag, T_bail, v_eps);
  const struct
  {
    const char* name;
    Profile ref;
  } planted[] = { { "no clump", reference(upper, lower, 0.0, 0.0, T_bail, v_eps) },
                  { "no clump drag", reference(upper, lower, weight, 0.0, T_bail, v_eps) },
                  { "lower section as the upper", reference(upper, lower_as_upper, weight, drag, T_bail, v_eps) } };
  for (const auto& p : planted)
  {
    const std::vector<double> d = differences(p.ref, full);
    const double worst = *std::max_element(d.begin(), d.end());
    std::printf("planted mistake '%s': largest relative difference from the full reference %.3g\n", p.name, worst);
    EXPECT_GT(worst, 10.0 * kTolerance) << p.name;
  }
}

}  // namespace
}  // namespace tow_sim
