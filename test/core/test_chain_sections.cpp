// A chain of heterogeneous elements (docs/solver.md §11): cable sections of their own segment length, weight
// and drag, and point bodies at joints, against closed forms computed here from the parameters:
//   - the geometry: each segment's section and length, the cable out, with the winch's first segment and
//     for the ship side of a parted cable;
//   - hanging at rest, in vacuum and in water: no acceleration, each joint carries the weight in water of
//     what hangs below it, and the tension jumps by a body's (m - rho V) g at its joint;
//   - in vacuum, a chain whose first joint falls at g falls as a whole, with no tension (the bodies' inertia
//     and weight agree);
//   - a rod with a tip mass on a pivot, released level: the tip starts falling at g (m/2 + M)/(m/3 + M);
//   - towed along its axis without gravity: each tension is the tangential drag aft of it plus a body's
//     1/2 rho C_D A U^2;
//   - the body's drag derivative in elementJacobian against central differences of the solver's loads;
//   - random states of a chain of sections and bodies with the winch paying out, in a current: the O(nu)
//     sweep against the dense Newton-Euler reference (test/core/dense_reference.cpp), in which a body is part
//     of its segment's free body (its force and inertia at the aft joint, about the CG with their arm);
//   - released in vacuum and integrated by the simulator (dopri5, tight tolerances), the chain of sections
//     and bodies keeps its mechanical energy, computed here from positions and velocities.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "chain_fixtures.h"
#include "core/dense_reference.h"
#include "tow_sim/core/chain/chain_jacobian.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
constexpr double kG = 9.81;

// Three sections, forward to aft: 40 m in 4, 30 m in 6, 20 m in 2 segments, each of its own weight,
// diameter and drag.
std::vector<CableParams> threeSections()
{
  std::vector<CableParams> s(3);
  const double length[] = { 40.0, 30.0, 20.0 }, mass[] = { 2.0, 0.5, 1.2 }, diameter[] = { 0.03, 0.01, 0.02 };
  const int segments[] = { 4, 6, 2 };
  for (int i = 0; i < 3; ++i)
  {
    s[i].length = length[i];
    s[i].segments = segments[i];
    s[i].mass_per_length = mass[i];
    s[i].diameter = diameter[i];
  }
  return s;
}

std::shared_ptr<ChainModel> makeSectioned(const std::vector<CableParams>& sections,
                                          const std::vector<JointBody>& bodies, const Environment& env,
                                          const EndElementParams& end = EndElementParams())
{
  const NumericsParams num;
  return std::make_shared<ChainModel>(sections, bodies, std::make_shared<RigidEndElement>(end, num), env, num);
}

JointBody clump(int joint, double mass, double volume)
{
  JointBody b;
  b.joint = joint;
  b.mass = mass;
  b.displaced_volume = volume;
  return b;
}

// The chain hanging straight down from the origin: joints x_2 .. of the geometry's elements.
Eigen::Matrix3Xd hanging(const ChainGeometry& g)
{
  Eigen::Matrix3Xd x(3, g.elementCount());
  double depth = 0.0;
  for (int e = 0; e < g.elementCount(); ++e)
    x.col(e) = Eigen::Vector3d(0.0, 0.0, -(depth += g.elementLength(e)));
  return x;
}

TEST(ChainSections, EachSegmentHasItsSectionsLengthAndTheCableOutAddsUp)
{
  const auto model = makeSectioned(threeSections(), {}, Environment());
  ChainGeometry g = model->initialGeometry();
  EXPECT_EQ(model->segments(), 12);
  EXPECT_EQ(model->sectionCount(), 3);
  const int section[] = { 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 2, 2 };
  const double length[] = { 10.0, 5.0, 10.0 };
  for (int e = 0; e < 12; ++e)
  {
    EXPECT_EQ(g.sectionOf(e), section[e]) << e;
    EXPECT_DOUBLE_EQ(g.elementLength(e), length[section[e]]) << e;
    EXPECT_DOUBLE_EQ(model->segmentModel(e, g).mass, length[section[e]] * threeSections()[section[e]].mass_per_length);
  }
  EXPECT_DOUBLE_EQ(g.cableLength(), 90.0);
  EXPECT_EQ(g.aftSectionSegments(), 8);
  // The winch pays out the first section: two more segments there, the first 3.5 m long.
  g.segments = 14;
  g.first_length = 3.5;
  EXPECT_EQ(g.sectionOf(0), 0);
  EXPECT_EQ(g.sectionOf(5), 0);
  EXPECT_EQ(g.sectionOf(6), 1);
  EXPECT_EQ(g.sectionOf(12), 2);
  EXPECT_DOUBLE_EQ(g.cableLength(), 3.5 + 5 * 10.0 + 30.0 + 20.0);
  EXPECT_DOUBLE_EQ(model->firstSegment(g).mass, 3.5 * 2.0);
  // Parted at segment 7 (section 1): the ship side is segments 0 .. 6, seven aft of it.
  ChainGeometry ship_side = g;
  ship_side.segments = 7;
  ship_side.aft_segments = 7;
  ship_side.end_body = false;
  EXPECT_EQ(ship_side.sectionOf(5), 0);
  EXPECT_EQ(ship_side.sectionOf(6), 1);
  EXPECT_DOUBLE_EQ(ship_side.cableLength(), 3.5 + 5 * 10.0 + 5.0);
}

TEST(ChainSections, HangingAtRestEachJointCarriesTheWeightInWaterBelowIt)
{
  for (const double density : { 0.0, 1025.0 })
  {
    Environment env;
    env.water_density = density;
    const std::vector<CableParams> sections = threeSections();
    const JointBody body = clump(8, 150.0, 0.02);  // 8 segments aft of it: between sections 0 and 1
    const auto model = makeSectioned(sections, { body }, env);
    ChainGeometry g = model->initialGeometry();
    g.end_body = false;  // no end body: the weights of the cable and the body alone
    const Eigen::Matrix3Xd x = hanging(g), v = Eigen::Matrix3Xd::Zero(3, x.cols());
    Eigen::Matrix3Xd a(3, x.cols()), T;
    ChainSolver solver;
    solver.solve(*model, g, model->initialData(), 0.0, ShipEndState(), x, v, a, &T);
    EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-9) << density;
    // The closed form: each segment's (m - rho pi D^2/4 d) g, the body's (m - rho V) g, summed from below.
    double below = 0.0;
    for (int e = g.segments - 1; e >= 0; --e)
    {
      const CableParams& c = sections[g.sectionOf(e)];
      const double d = g.elementLength(e);
      below += (c.mass_per_length - density * 0.25 * kPi * c.diameter * c.diameter) * d * kG;
      if (g.segments - 1 - e == body.joint)
        below += (body.mass - density * body.displaced_volume) * kG;
      EXPECT_NEAR(T(2, e), below, 1e-9 * below) << "density " << density << ", joint " << e + 1;
      EXPECT_LT(T.col(e).head<2>().norm(), 1e-9 * below);
    }
  }
}

TEST(ChainSections, InVacuumTheChainFallsAsAWholeWithNoTension)
{
  Environment vacuum;
  vacuum.water_density = 0.0;
  const auto model = makeSectioned(threeSections(), { clump(3, 80.0, 0.0), clump(10, 5.0, 0.0) }, vacuum);
  ChainGeometry g = model->initialGeometry();
  g.end_body = false;
  // Bent, every joint moving with the same velocity; the first joint falls at g.
  Eigen::Matrix3Xd x(3, g.segments), v(3, g.segments), a(3, g.segments), T;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int e = 0; e < g.segments; ++e)
    x.col(e) = p += g.elementLength(e) * Eigen::Vector3d(std::cos(0.4 * e), std::sin(0.3 * e), -0.5).normalized();
  ShipEndState first;
  first.v_W = Eigen::Vector3d(1.0, -2.0, 0.5);
  first.a_W = Eigen::Vector3d(0.0, 0.0, -kG);
  v.colwise() = first.v_W;
  ChainSolver solver;
  solver.solve(*model, g, model->initialData(), 0.0, first, x, v, a, &T);
  for (int e = 0; e < g.segments; ++e)
  {
    EXPECT_LT((a.col(e) - first.a_W).norm(), 1e-10) << e;
    EXPECT_LT(T.col(e).norm(), 1e-8) << e;
  }
}

TEST(ChainSections, ARodWithATipMassReleasedLevelOnAPivot)
{
  // One segment of mass m, length L, a point mass M at its free end: I = m L^2/3 + M L^2 about the pivot,
  // the weights' moment (m/2 + M) g L, so the tip starts at a = g (m/2 + M)/(m/3 + M), and the pivot
  // carries (m + M) g - (m/2 + M) a.
  Environment vacuum;
  vacuum.water_density = 0.0;
  CableParams rod;
  rod.length = 10.0;
  rod.segments = 1;
  rod.mass_per_length = 3.0;
  const double m = 30.0, M = 45.0, L = 10.0;
  const auto model = makeSectioned({ rod }, { clump(0, M, 0.0) }, vacuum);
  ChainGeometry g = model->initialGeometry();
  g.end_body = false;
  Eigen::Matrix3Xd x(3, 1), v = Eigen::Matrix3Xd::Zero(3, 1), a(3, 1), T;
  x.col(0) = Eigen::Vector3d(-L, 0.0, 0.0);
  ChainSolver solver;
  solver.solve(*model, g, model->initialData(), 0.0, ShipEndState(), x, v, a, &T);
  const double tip = kG * (0.5 * m + M) / (m / 3.0 + M);
  EXPECT_LT((a.col(0) - Eigen::Vector3d(0.0, 0.0, -tip)).norm(), 1e-10 * tip);
  const double pivot = (m + M) * kG - (0.5 * m + M) * tip;
  EXPECT_LT((T.col(0) - Eigen::Vector3d(0.0, 0.0, pivot)).norm(), 1e-9 * m * kG);
}

TEST(ChainSections, TowedAlongItsAxisEachTensionIsTheDragAftOfIt)
{
  // No gravity, the flow along the chain: only the tangential drag c1 d U^2 of each segment (quadratic
  // law) and the bodies' 1/2 rho C_D A U^2 pull; the tension at a joint is their sum aft of it.
  Environment env;
  env.gravity = 0.0;
  std::vector<CableParams> sections = threeSections();
  const double c1[] = { 0.8, 0.3, 0.5 };
  for (int i = 0; i < 3; ++i)
  {
    sections[i].c1 = c1[i];
    sections[i].tangential_drag_model = TangentialDragModel::kQuadratic;
  }
  JointBody drogue = clump(2, 10.0, 0.01);
  drogue.drag_area = 0.4;
  const auto model = makeSectioned(sections, { drogue }, env);
  ChainGeometry g = model->initialGeometry();
  g.end_body = false;
  const double U = 2.5;
  ShipEndState ship;
  ship.v_W = Eigen::Vector3d(U, 0.0, 0.0);
  Eigen::Matrix3Xd x(3, g.segments), v(3, g.segments), a(3, g.segments), T;
  double along = 0.0;
  for (int e = 0; e < g.segments; ++e)
    x.col(e) = Eigen::Vector3d(-(along += g.elementLength(e)), 0.0, 0.0);
  v.colwise() = ship.v_W;
  ChainSolver solver;
  solver.solve(*model, g, model->initialData(), 0.0, ship, x, v, a, &T);
  EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-10);
  double aft = 0.0;
  for (int e = g.segments - 1; e >= 0; --e)
  {
    aft += c1[g.sectionOf(e)] * g.elementLength(e) * U * U;
    if (g.segments - 1 - e == drogue.joint)
      aft += 0.5 * env.water_density * drogue.drag_area * U * U;
    EXPECT_NEAR(T(0, e), aft, 1e-9 * aft) << "joint " << e + 1;
  }
}

TEST(ChainSections, TheBodysDragDerivativeMatchesCentralDifferencesOfTheSolversLoads)
{
  Environment env;
  env.current_W = Eigen::Vector3d(0.3, -0.2, 0.0);
  JointBody body = clump(9, 20.0, 0.05);
  body.drag_area = 0.6;
  const auto model = makeSectioned(threeSections(), { body }, env);
  const ChainGeometry g = model->initialGeometry();
  const ChainData data = model->initialData();
  const int e = g.segments - 1 - body.joint;  // the segment whose aft joint carries it
  Eigen::Matrix3Xd x = hanging(g), v(3, g.elementCount()), a(3, g.elementCount());
  for (int j = 0; j < v.cols(); ++j)
    v.col(j) = Eigen::Vector3d(1.2 + 0.1 * j, 0.4, -0.3 * std::sin(j));
  ShipEndState ship;
  ship.v_W = Eigen::Vector3d(1.0, 0.0, 0.0);
  ChainSolver solver;
  auto h_aft = [&](const Eigen::Matrix3Xd& vv)
  {
    solver.solve(*model, g, data, 0.0, ship, x, vv, a);
    return Eigen::Vector3d(solver.terms()[static_cast<size_t>(e)].h_a);
  };
  Eigen::Matrix3d differences;
  const double step = 1e-6;
  for (int i = 0; i < 3; ++i)
  {
    Eigen::Matrix3Xd plus = v, minus = v;
    plus(i, e) += step;
    minus(i, e) -= step;
    differences.col(i) = (h_aft(plus) - h_aft(minus)) / (2.0 * step);
  }
  const Eigen::Vector3d x_f = x.col(e - 1), v_f = v.col(e - 1);
  ElementJacobian J;
  elementJacobian(*model, e, 0.0, ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e)), g, data, 0.0, J);
  const Eigen::Matrix3d analytic = J.dh_dv.bottomRightCorner<3, 3>();
  EXPECT_LT((analytic - differences).norm(), 1e-6 * differences.norm());
  // The body's drag is most of the block (the test exercises its term).
  EXPECT_GT(body.forceVelocityJacobian(env, 0.0, x.col(e), v.col(e)).norm(), 0.5 * differences.norm());
}

TEST(ChainSections, RandomStatesMatchTheDenseReference)
{
  Environment env;
  env.current_W = Eigen::Vector3d(0.4, -0.3, 0.05);
  JointBody clump_body = clump(8, 300.0, 0.03), float_body = clump(3, 5.0, 0.2);
  clump_body.drag_area = 0.5;
  float_body.drag_area = 0.2;
  float_body.added_mass = 150.0;
  const auto model = makeSectioned(threeSections(), { clump_body, float_body }, env);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial)
  {
    const ChainData data = model->initialData();
    ChainGeometry g = model->initialGeometry();
    g.segments += trial % 3;  // the winch has paid out 0, 1 or 2 more of the first section's segments
    g.first_length = g.nominal_length * (0.6 + 0.3 * (u(rng) + 1.0));
    g.first_rate = 0.8 * u(rng);
    g.first_acceleration = 0.1 * u(rng);
    ShipEndState ship;
    ship.v_W = Eigen::Vector3d(2.0 + u(rng), u(rng), 0.2 * u(rng));
    ship.a_W = 0.3 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    Eigen::Matrix3Xd x(3, g.elementCount()), v(3, g.elementCount());
    Eigen::Vector3d p = ship.p_W;
    for (int e = 0; e < g.elementCount(); ++e)
    {
      x.col(e) = p += g.elementLength(e) * Eigen::Vector3d(-1.0, 0.4 * u(rng), -0.6 + 0.3 * u(rng)).normalized();
      v.col(e) = ship.v_W + Eigen::Vector3d(u(rng), u(rng), u(rng));
    }
    const test::SweepDeviation d = test::sweepAgainstDense(*model, g, data, 0.0, ship, x, v);
    EXPECT_LT(d.accelerations, 1e-9) << "trial " << trial;
    EXPECT_LT(d.tensions, 1e-9) << "trial " << trial;
  }
}

// Kinetic plus potential energy in vacuum: each segment 1/2 m |v_G|^2 + 1/2 (m d^2/12) |w|^2 + m g z_G with
// m its section's mass per length times d, each point body 1/2 M |v|^2 + M g z, the end body like a segment.
double sectionedEnergy(const ChainModel& model, const EndElementParams& end, const ChainState& state)
{
  const ChainGeometry g = model.initialGeometry();
  double energy = 0.0;
  Eigen::Vector3d x_f = Eigen::Vector3d::Zero(), v_f = Eigen::Vector3d::Zero();
  for (int e = 0; e < g.elementCount(); ++e)
  {
    const double d = g.elementLength(e);
    const double m = e < g.segments ? model.section(g.sectionOf(e)).cable.mass_per_length * d : end.mass;
    const Eigen::Vector3d x_a = state.x.col(e), v_a = state.v.col(e);
    const Eigen::Vector3d v_g = 0.5 * (v_f + v_a), w = (x_a - x_f).normalized().cross((v_a - v_f) / d);
    energy += 0.5 * m * v_g.squaredNorm() + 0.5 * (m * d * d / 12.0) * w.squaredNorm() + m * kG * 0.5 * (x_f + x_a).z();
    if (const JointBody* b = model.bodyAft(e, g))
      energy += 0.5 * b->mass * v_a.squaredNorm() + b->mass * kG * x_a.z();
    x_f = x_a;
    v_f = v_a;
  }
  return energy;
}

TEST(ChainSections, ReleasedInVacuumTheChainKeepsItsEnergy)
{
  Environment vacuum;
  vacuum.water_density = 0.0;
  NumericsParams num;
  num.stepper = StepperType::kDopri5;
  num.abs_tol = num.rel_tol = 1e-12;
  num.max_step = 0.05;
  std::vector<CableParams> sections = threeSections();
  for (CableParams& c : sections)
    c.length /= 10.0;  // 9 m of cable: a quick swing
  EndElementParams end = test::endLikeSegment(sections[2]);
  end.mass = 2.0;
  end.transverse_inertia = end.mass * end.length * end.length / 12.0;
  const auto model =
      std::make_shared<ChainModel>(sections, std::vector<JointBody>{ clump(8, 3.0, 0.0), clump(1, 1.0, 0.0) },
                                   std::make_shared<RigidEndElement>(end, num), vacuum, num);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  ChainState start =
      straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.0, -0.577), Eigen::Vector3d::Zero());
  for (int j = 0; j < start.v.cols(); ++j)
    start.v.col(j) = Eigen::Vector3d(0.0, 0.3 * j / start.v.cols(), 0.0);
  sim.reset(0.0, start);
  const double e0 = sectionedEnergy(*model, end, sim.state());
  double worst = 0.0;
  for (int i = 1; i <= 20; ++i)
  {
    sim.advanceTo(i * 1.0);
    worst = std::max(worst, std::abs(sectionedEnergy(*model, end, sim.state()) - e0) / std::abs(e0));
  }
  std::printf("sections and bodies in vacuum: largest relative energy drift over 20 s %.3g\n", worst);
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT((sim.state().x - start.x).norm(), 1.0);  // it did swing
}

TEST(ChainSections, TheWinchPaysOutTheFirstSectionOnly)
{
  // 40 m of the first section and 50 m aft of it: a winch from 60 to 200 m of cable out holds the first
  // section between 10 and 150 m. Paying out lengthens it alone; the sections aft keep their segments.
  const auto model = makeSectioned(threeSections(), { clump(8, 150.0, 0.02) }, Environment());
  WinchParams winch;
  winch.enabled = true;
  winch.min_length = 60.0;
  winch.max_length = 200.0;
  ShipMotion ship = constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.5, 0.0, 0.0));
  Simulator sim(model, ship, winch);
  sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -1.0), ship(0.0).v_W));
  sim.setWinchCommand(1.0);
  sim.advanceTo(30.0);
  const ChainGeometry& g = sim.geometry();
  EXPECT_GT(sim.cableLength(), 110.0);
  EXPECT_NEAR(g.cableLength(), sim.cableLength(), 1e-9 * sim.cableLength());
  EXPECT_EQ(g.segments - g.aftSectionSegments(), g.segments - 8);
  EXPECT_GT(g.segments, 12 + 1);  // the first section split
  for (int e = g.segments - 8; e < g.segments; ++e)
    EXPECT_DOUBLE_EQ(g.elementLength(e), e < g.segments - 2 ? 5.0 : 10.0) << e;
  EXPECT_EQ(g.sectionOf(g.segments - 9), 0);
  EXPECT_EQ(g.sectionOf(g.segments - 8), 1);
  // A least cable out that would haul in the sections aft of the first is refused by name.
  winch.min_length = 45.0;
  try
  {
    Simulator refused(model, ship, winch);
    ADD_FAILURE() << "accepted a winch.min_length inside the sections aft of the first";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("winch.min_length"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sections aft of the first"), std::string::npos) << e.what();
  }
}

TEST(ChainSections, BadSectionsAndBodiesAreRefusedByName)
{
  std::vector<CableParams> sections = threeSections();
  sections[1].axial_stiffness = 1e6;
  EXPECT_THROW(
      {
        try
        {
          makeSectioned(sections, {}, Environment());
        }
        catch (const std::invalid_argument& e)
        {
          EXPECT_NE(std::string(e.what()).find("cable.sections[1].axial_stiffness"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
  auto message = [](const std::vector<CableParams>& s, const JointBody& b)
  {
    try
    {
      makeSectioned(s, { b }, Environment());
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(threeSections(), clump(12, 1.0, 0.0)).find("cable.bodies[0].joint = 12 must be in 0 .. 11"),
            std::string::npos);
  EXPECT_NE(message(threeSections(), clump(3, -1.0, 0.0)).find("cable.bodies[0].mass"), std::string::npos);
  std::vector<CableParams> bad = threeSections();
  bad[2].diameter = -1.0;
  EXPECT_NE(message(bad, clump(0, 1.0, 0.0)).find("cable.sections[2].diameter"), std::string::npos);
  EXPECT_THROW(makeSectioned({}, {}, Environment()), std::invalid_argument);
}

}  // namespace
}  // namespace tow_sim
