// Bending stiffness (cable.bending_stiffness, physics.md §11) against answers computed here, not by the code:
//   - a taut span between the fixed tow point and a heavy end body in vacuum (the tension the end body's
//     weight): the first lateral frequency against the beam-string closed form
//     w1^2 = (pi/L)^2 (T + EI (pi/L)^2) / m, with and without EI;
//   - a chain without tension (no gravity) pinned at the tow point, its far end free: the first flexural
//     frequency against the pinned-free beam's, (beta L)^2 sqrt(EI / (m L^4)) with tan(beta L) = tanh(beta L),
//     the root found here;
//   - released in vacuum, a chain of two sections of different EI and a clump keeps its energy, kinetic plus
//     gravity's plus sum 1/2 kappa theta^2 over the joints, kappa as physics.md §11 defines it;
//   - the O(nu) sweep against the dense Newton-Euler reference, which adds the moments from the definition;
//   - the implicit stepper agrees with dopri5 on a tow of a stiff cable;
//   - the key's range; EI = 0 leaves the report's chain as it was (the goldens, Batch.ShippedScenarios...).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>

#include "chain_fixtures.h"
#include "core/config_error.h"
#include "core/dense_reference.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/chain/chain_jacobian.h"
#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
Environment vacuum(double gravity)
{
  Environment env;
  env.water_density = 0.0;
  env.gravity = gravity;
  return env;
}

NumericsParams tightDopri5()
{
  NumericsParams num;
  num.stepper = StepperType::kDopri5;
  num.abs_tol = num.rel_tol = 1e-10;
  num.max_step = 0.01;
  return num;
}

// A chain hanging down from the origin with a small lateral (x) offset of slope dx/ds = slope(s) at arc
// length s along the cable; the end body straight down; at rest.
ChainState bentChain(const ChainModel& model, const std::function<double(double)>& slope)
{
  const ChainGeometry g = model.initialGeometry();
  ChainState state;
  state.x.resize(3, g.jointCount());
  state.v.setZero(3, g.jointCount());
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  double s = 0.0;
  for (int e = 0; e < g.elementCount(); ++e)
  {
    const double d = g.elementLength(e);
    const double dx = e < g.segments ? slope(s + 0.5 * d) : 0.0;
    p += d * Eigen::Vector3d(dx, 0.0, -1.0).normalized();
    state.x.col(e) = p;
    s += d;
  }
  return state;
}

// The mean period [s] between upward zero crossings of q(t), sampled every dt over the given duration.
double measuredPeriod(Simulator& sim, const std::function<double(const ChainState&)>& q, double dt, double duration)
{
  std::vector<double> crossings;
  double t_prev = sim.time(), q_prev = q(sim.state());
  for (double t = sim.time() + dt; t <= duration; t += dt)
  {
    sim.advanceTo(t);
    const double q_now = q(sim.state());
    if (q_prev < 0.0 && q_now >= 0.0)
      crossings.push_back(t_prev + dt * q_prev / (q_prev - q_now));
    t_prev = t;
    q_prev = q_now;
  }
  EXPECT_GE(crossings.size(), 3u);
  if (crossings.size() < 2)
    return 0.0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

// A taut span: 10 m of 1 kg/m cable in 40 segments, hanging in vacuum from the fixed tow point with a
// 10 t end body whose CG is at the bail (so that the bail barely moves sideways: a pinned end, to 1e-4).
// Its first lateral mode, started from the sine, against the closed form at the mean tension.
double tautSpanPeriod(double bending_stiffness, double& closed_form)
{
  CableParams cable;
  cable.length = 10.0;
  cable.segments = 40;
  cable.mass_per_length = 1.0;
  cable.bending_stiffness = bending_stiffness;
  EndElementParams end;
  end.mass = 1.0e4;
  end.length = 0.5;
  end.cg_from_bail = end.cb_from_bail = 0.0;
  end.transverse_inertia = 10.0;
  const Environment env = vacuum(9.81);
  const NumericsParams num = tightDopri5();
  const auto model = test::makeModel(cable, end, env, num);
  const double L = cable.length, m = cable.mass_per_length;
  const double T = end.mass * env.gravity + 0.5 * m * env.gravity * L;  // the mean over the span (linear in s)
  const double k = kPi / L;
  closed_form = 2.0 * kPi / std::sqrt(k * k * (T + bending_stiffness * k * k) / m);

  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  // Small: the inextensible span shortens by (pi A)^2 / (4 L) as it bows, and the 10 t body's vertical
  // acceleration at twice the frequency (4 w^2 times that, 40 % of g at A = L/500) would modulate the tension.
  const double amplitude = 1e-4 * L;
  sim.reset(0.0, bentChain(*model, [&](double s) { return amplitude * k * std::cos(k * s); }));
  const int middle = cable.segments / 2 - 1;  // the joint at s = L/2
  return measuredPeriod(
      sim, [&](const ChainState& st) { return st.x(0, middle); }, closed_form / 200.0, 6.0 * closed_form);
}

TEST(BendingStiffness, ATautSpansFirstFrequencyIsTheBeamStrings)
{
  double string_form = 0.0, beam_form = 0.0;
  const double string_period = tautSpanPeriod(0.0, string_form);
  // EI (pi/L)^2 = T: the bending stiffness doubles w1^2.
  const double ei = (1.0e4 * 9.81 + 0.5 * 9.81 * 10.0) * 100.0 / (kPi * kPi);
  const double beam_period = tautSpanPeriod(ei, beam_form);
  std::printf("taut span: string %.6f s (closed form %.6f), with EI = %.4g N m^2 %.6f s (closed form %.6f)\n",
              string_period, string_form, ei, beam_period, beam_form);
  EXPECT_NEAR(string_period / string_form, 1.0, 1e-3);
  EXPECT_NEAR(beam_period / beam_form, 1.0, 1e-3);
  EXPECT_NEAR(string_period / beam_period, std::sqrt(2.0), 2e-3);
}

// The pinned-free beam's first flexural root of tan(x) = tanh(x) in (pi, 3 pi / 2), by bisection.
double pinnedFreeRoot()
{
  double lo = kPi + 1e-9, hi = 1.5 * kPi - 1e-9;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (std::tan(mid) - std::tanh(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(BendingStiffness, WithoutTensionAPinnedFreeChainBendsAtTheBeamsFrequency)
{
  // No gravity, so no tension: only the bending stiffness holds the shape. 10 m of 1 kg/m in 40 segments,
  // EI = 1000 N m^2, pinned at the tow point; the end body a speck (1e-6 of the cable's mass) at the free end.
  CableParams cable;
  cable.length = 10.0;
  cable.segments = 40;
  cable.mass_per_length = 1.0;
  cable.bending_stiffness = 1000.0;
  EndElementParams end;
  end.mass = 1e-5;
  end.length = 0.01;
  end.cg_from_bail = end.cb_from_bail = 0.0;
  end.transverse_inertia = 1e-12;
  const auto model = test::makeModel(cable, end, vacuum(0.0), tightDopri5());
  const double L = cable.length, beta = pinnedFreeRoot() / L;
  EXPECT_NEAR(beta * L, 3.9266, 1e-4);  // the tabulated root
  const double closed_form = 2.0 * kPi / (beta * beta * std::sqrt(cable.bending_stiffness / cable.mass_per_length));
  // The mode shape phi = sin(beta s) + (sin(beta L) / sinh(beta L)) sinh(beta s): its slope.
  const double r = std::sin(beta * L) / std::sinh(beta * L);
  auto phi = [&](double s) { return std::sin(beta * s) + r * std::sinh(beta * s); };
  const double amplitude = 0.01;  // [m]
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  sim.reset(0.0, bentChain(*model, [&](double s)
                           { return amplitude * beta * (std::cos(beta * s) + r * std::cosh(beta * s)); }));
  // The modal coordinate sum phi(s_j) x_j: blind to the rigid turn about the pin (orthogonal to phi).
  const double h = L / cable.segments;
  auto modal = [&](const ChainState& st)
  {
    double q = 0.0;
    for (int j = 0; j < cable.segments; ++j)
      q += phi((j + 1) * h) * st.x(0, j);
    return q;
  };
  const double period = measuredPeriod(sim, modal, closed_form / 200.0, 4.0 * closed_form);
  std::printf("pinned-free chain: first flexural period %.6f s, closed form %.6f s\n", period, closed_form);
  EXPECT_NEAR(period / closed_form, 1.0, 1e-3);
}

// Kinetic energy, gravity's potential and the joints' bending energy sum 1/2 kappa theta^2, in vacuum.
struct Energies
{
  double kinetic = 0.0, potential = 0.0;
};

Energies chainEnergies(const ChainModel& model, const EndElementParams& end, double gravity, const ChainState& state)
{
  const ChainGeometry g = model.initialGeometry();
  Energies out;
  Eigen::Vector3d x_f = Eigen::Vector3d::Zero(), v_f = Eigen::Vector3d::Zero(), s_prev = Eigen::Vector3d::Zero();
  for (int e = 0; e < g.elementCount(); ++e)
  {
    const double d = g.elementLength(e);
    const bool segment = e < g.segments;
    const double m = segment ? model.section(g.sectionOf(e)).cable.mass_per_length * d : end.mass;
    const double inertia = segment ? m * d * d / 12.0 : *end.transverse_inertia;
    const double cg = segment ? 0.5 : end.cg_from_bail / d;
    const Eigen::Vector3d x_a = state.x.col(e), v_a = state.v.col(e);
    const Eigen::Vector3d s = (x_a - x_f).normalized(), w = s.cross((v_a - v_f) / d);
    const Eigen::Vector3d v_g = v_f + cg * (v_a - v_f), x_g = x_f + cg * (x_a - x_f);
    out.kinetic += 0.5 * m * v_g.squaredNorm() + 0.5 * inertia * w.squaredNorm();
    out.potential += m * gravity * x_g.z();
    if (const JointBody* b = model.bodyAft(e, g))
    {
      out.kinetic += 0.5 * b->mass * v_a.squaredNorm();
      out.potential += b->mass * gravity * x_a.z();
    }
    if (segment && e > 0)
    {
      const double ei_f = model.section(g.sectionOf(e - 1)).cable.bending_stiffness;
      const double ei_a = model.section(g.sectionOf(e)).cable.bending_stiffness;
      const double kappa = 1.0 / (g.elementLength(e - 1) / (2.0 * ei_f) + d / (2.0 * ei_a));
      const double theta = std::acos(std::clamp(s_prev.dot(s), -1.0, 1.0));
      out.potential += 0.5 * kappa * theta * theta;
    }
    s_prev = s;
    x_f = x_a;
    v_f = v_a;
  }
  return out;
}

std::vector<CableParams> twoStiffSections()
{
  std::vector<CableParams> sections(2);
  sections[0].length = 3.0;
  sections[0].segments = 6;
  sections[0].mass_per_length = 2.0;
  sections[0].bending_stiffness = 40.0;
  sections[1].length = 4.0;
  sections[1].segments = 10;
  sections[1].mass_per_length = 0.5;
  sections[1].bending_stiffness = 6.0;
  return sections;
}

TEST(BendingStiffness, ReleasedInVacuumTheChainKeepsItsEnergyWithTheBendingEnergy)
{
  const NumericsParams num = []
  {
    NumericsParams n = tightDopri5();
    n.abs_tol = n.rel_tol = 1e-12;
    return n;
  }();
  EndElementParams end = test::endLikeSegment(twoStiffSections()[1]);
  end.mass = 1.5;
  end.transverse_inertia = end.mass * end.length * end.length / 12.0;
  JointBody clump;
  clump.joint = 10;  // at the sections' joint
  clump.mass = 2.0;
  const auto model = std::make_shared<ChainModel>(twoStiffSections(), std::vector<JointBody>{ clump },
                                                  std::make_shared<RigidEndElement>(end, num), vacuum(9.81), num);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  // Released bent (a bow in x) and spun about the vertical: the joints swing, bend and unbend in 3D.
  ChainState start = bentChain(*model, [](double s) { return 0.8 * std::sin(1.3 * s); });
  for (int j = 0; j < start.v.cols(); ++j)
    start.v.col(j) = Eigen::Vector3d(0.0, 0.4 * j / start.v.cols(), 0.0);
  sim.reset(0.0, start);
  const Energies e0 = chainEnergies(*model, end, 9.81, sim.state());
  double worst = 0.0, most_kinetic = e0.kinetic;
  for (int i = 1; i <= 100; ++i)
  {
    sim.advanceTo(i * 0.1);
    const Energies e = chainEnergies(*model, end, 9.81, sim.state());
    worst = std::max(worst, std::abs(e.kinetic + e.potential - e0.kinetic - e0.potential));
    most_kinetic = std::max(most_kinetic, e.kinetic);
  }
  std::printf("bending chain in vacuum: energy drift %.3g J over 10 s against %.3g J of kinetic energy\n", worst,
              most_kinetic);
  EXPECT_LT(worst, 1e-6 * most_kinetic);
  EXPECT_GT(most_kinetic, 1.0);  // it moved
}

TEST(BendingStiffness, TheChainSolveMatchesTheDenseReference)
{
  Environment env;
  env.current_W = Eigen::Vector3d(0.3, -0.2, 0.0);
  std::vector<CableParams> sections = twoStiffSections();
  sections[0].bending_stiffness = 5e3;
  JointBody clump;
  clump.joint = 4;
  clump.mass = 30.0;
  clump.drag_area = 0.05;
  const NumericsParams num;
  const auto model = std::make_shared<ChainModel>(sections, std::vector<JointBody>{ clump },
                                                  std::make_shared<RigidEndElement>(EndElementParams(), num), env, num);
  const ChainGeometry g = model->initialGeometry();
  const ChainData data = model->initialData(0.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial)
  {
    ShipEndState ship;
    ship.v_W = Eigen::Vector3d(1.5, 0.2 * u(rng), 0.0);
    ship.a_W = Eigen::Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.0);
    Eigen::Matrix3Xd x(3, g.jointCount()), v(3, g.jointCount());
    Eigen::Vector3d p = ship.p_W;
    for (int e = 0; e < g.elementCount(); ++e)
    {
      x.col(e) = p += g.elementLength(e) * Eigen::Vector3d(-1.0, 0.5 * u(rng), -0.6 + 0.4 * u(rng)).normalized();
      v.col(e) = ship.v_W + Eigen::Vector3d(u(rng), u(rng), u(rng));
    }
    const test::SweepDeviation d = test::sweepAgainstDense(*model, g, data, 0.0, ship, x, v);
    EXPECT_LT(d.accelerations, 1e-9) << "trial " << trial;
    EXPECT_LT(d.tensions, 1e-9) << "trial " << trial;
  }
}

// The implicit stepper's bending stiffness (addBendingStiffness) on a straight chain, against the bending
// energy's second derivative computed here by differences: never softer along any displacement (the claim
// that keeps the stage matrix from going indefinite), and stiffer by exactly the outer joints' term.
TEST(BendingStiffness, TheStageMatrixsBendingIsNeverSofterThanTheEnergys)
{
  CableParams cable;
  cable.length = 12.0;
  cable.segments = 12;
  cable.bending_stiffness = 50.0;
  const auto model = test::makeModel(cable, EndElementParams(), vacuum(0.0));
  const ChainGeometry g = model->initialGeometry();
  const Eigen::Vector3d first = Eigen::Vector3d::Zero(), dir = Eigen::Vector3d(1.0, -0.5, -2.0).normalized();
  Eigen::Matrix3Xd x(3, g.jointCount());
  for (int j = 0; j < g.jointCount(); ++j)
    x.col(j) = (j + 1) * dir;  // the end body 2 m: its joint's place does not matter for bending
  // The energy sum 1/2 (EI / l) theta^2 over the joints between segments, from the positions.
  auto energy = [&](const Eigen::Matrix3Xd& p)
  {
    double sum = 0.0;
    for (int i = 1; i < g.segments; ++i)
    {
      const Eigen::Vector3d s_f = (p.col(i - 1) - (i == 1 ? first : Eigen::Vector3d(p.col(i - 2)))).normalized();
      const Eigen::Vector3d s_a = (p.col(i) - p.col(i - 1)).normalized();
      const double theta = std::acos(std::clamp(s_f.dot(s_a), -1.0, 1.0));
      sum += 0.5 * cable.bending_stiffness / 1.0 * theta * theta;
    }
    return sum;
  };
  std::vector<ElementJacobian> J(static_cast<size_t>(g.segments));
  for (int e = 0; e < g.segments; ++e)
  {
    J[static_cast<size_t>(e)].dh_dx.setZero();
    addBendingStiffness(*model, g, first, x, e, J[static_cast<size_t>(e)]);
  }
  auto stageForm = [&](const Eigen::Matrix3Xd& d)
  {
    double q = 0.0;
    for (int e = 0; e < g.segments; ++e)
    {
      Vector6d joints;
      joints << (e == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(d.col(e - 1))), d.col(e);
      q -= joints.dot(J[static_cast<size_t>(e)].dh_dx * joints);
    }
    return q;
  };
  auto energyForm = [&](const Eigen::Matrix3Xd& d)
  {
    const double eps = 1e-4;  // theta is not smooth at 0, theta^2 is: the difference of E is exact to O(eps^2)
    return (energy(x + eps * d) + energy(x - eps * d) - 2.0 * energy(x)) / (eps * eps);
  };
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  double worst = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 200; ++trial)
  {
    Eigen::Matrix3Xd d = Eigen::Matrix3Xd::Zero(3, g.jointCount());
    for (int j = 0; j < g.segments; ++j)
      d.col(j) = Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    const double q_energy = energyForm(d), q_stage = stageForm(d);
    worst = std::min(worst, (q_stage - q_energy) / q_energy);
  }
  std::printf("bending in the stage matrix: stiffer than the energy's by at least %.2e (relative)\n", worst);
  EXPECT_GT(worst, -1e-5);
  // And by exactly what the move onto the diagonals adds: on a straight chain (unit segments) the spring at
  // joint i adds kappa |P (d_o - d_n)|^2 for its outer joints o, n (P across the axis): a rigid
  // translation costs nothing, a turn of the whole chain something.
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - dir * dir.transpose();
  for (int trial = 0; trial < 20; ++trial)
  {
    Eigen::Matrix3Xd d = Eigen::Matrix3Xd::Zero(3, g.jointCount());
    for (int j = 0; j < g.segments; ++j)
      d.col(j) = Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    double moved = 0.0;
    for (int i = 1; i < g.segments; ++i)
      moved += cable.bending_stiffness *
               (P * ((i == 1 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(d.col(i - 2))) - d.col(i))).squaredNorm();
    EXPECT_NEAR(stageForm(d), energyForm(d) + moved, 1e-5 * stageForm(d)) << "trial " << trial;
  }
}

TEST(BendingStiffness, RefusesOutOfRangeValuesNamingTheKey)
{
  const auto refusal = [](const std::string& yaml) { return test::configError(yaml); };
  for (const char* bad :
       { "cable: {bending_stiffness: -1.0}", "cable: {bending_stiffness: .nan}", "cable: {bending_stiffness: 2.0e9}" })
  {
    const std::string what = refusal(bad);
    EXPECT_NE(what.find("cable.bending_stiffness"), std::string::npos) << bad << ": " << what;
    EXPECT_NE(what.find("[0, 1000000000] [N m^2]"), std::string::npos) << bad << ": " << what;
  }
  const std::string what = refusal(
      "cable:\n  sections:\n    - {length: 300.0, segments: 30}\n    - {length: 200.0, segments: 20, "
      "bending_stiffness: -5.0}");
  EXPECT_NE(what.find("cable.sections[1].bending_stiffness"), std::string::npos) << what;
  EXPECT_EQ(refusal("cable: {bending_stiffness: 0.0}"), "(accepted)");
  EXPECT_EQ(refusal("cable: {bending_stiffness: 300.0, axial_stiffness: 1.0e8}"), "(accepted)");
}

}  // namespace
}  // namespace tow_sim
