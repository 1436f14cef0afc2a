// A winged depressor in line in the cable (docs/physics.md §11, (P49a)): in a steady tow the tensions above and
// below it differ by its weight in water and its wing's lift, worked out here from its attitude, and its axis lies
// along their mean (no moment about its centre); started there, the dynamics stay there; the configuration reads,
// writes back and refuses what it cannot be.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/chain_fixtures.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/simulation_config.h"

namespace tow_sim
{
namespace
{
// 100 m of cable in 20 segments, a 2 m depressor of 500 kg (0.05 m^3, its CG, CB and lift at the middle, no drag, a
// 1 m^2 wing of C_L lift), 50 m of cable in 10 segments, the plain end element.
std::shared_ptr<ChainModel> depressorTow(double lift, const NumericsParams& numerics = NumericsParams(),
                                         const Eigen::Vector3d& current_W = Eigen::Vector3d::Zero(),
                                         double lift_from_bail = 1.0)
{
  Environment env;
  env.current_W = current_W;
  CableParams upper, lower, wing;
  upper.length = 100.0;
  upper.segments = 20;
  lower.length = 50.0;
  lower.segments = 10;
  DepressorParams d;
  d.length = 2.0;
  d.mass = 500.0;
  d.displaced_volume = 0.05;
  d.cg_from_bail = d.cb_from_bail = 1.0;
  d.lift_from_bail = lift_from_bail;
  d.normal_drag_coefficient = d.tangential_drag_coefficient = 0.0;
  d.wing_area = 1.0;
  d.lift_coefficient = lift;
  wing.depressor = d;
  wing.length = 2.0;
  wing.segments = 1;
  return std::make_shared<ChainModel>(std::vector<CableParams>{ upper, wing, lower }, std::vector<JointBody>{},
                                      std::make_shared<RigidEndElement>(EndElementParams(), numerics), env, numerics);
}

constexpr int kDepressor = 20;  // its element: joints 20 (fore) and 21 (aft) of x_1 .. x_{nu+2}, tow point 0

Eigen::Matrix3Xd withTowPoint(const Eigen::Matrix3Xd& x)
{
  Eigen::Matrix3Xd joints(3, x.cols() + 1);
  joints << Eigen::Vector3d::Zero(), x;
  return joints;
}

TEST(Depressor, ItsTensionsDifferByItsWeightAndLiftAndItLiesAlongTheirMean)
{
  const Environment env;
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  double depth_without = 0.0;
  // Without lift; with it; with it in a cross current, which yaws the depressor and tilts its lift.
  // And with the lift acting 0.5 m aft of the centre: about the centre, (-l/2 s) x T_above + (l/2 s) x (-T_below)
  // + (l_L - l/2) s x L = 0, so the axis lies along T_above + T_below - (2 l_L / l - 1) L.
  const struct
  {
    double lift;
    Eigen::Vector3d current;
    double lift_from_bail;
  } cases[] = { { 0.0, Eigen::Vector3d::Zero(), 1.0 },
                { 1.0, Eigen::Vector3d::Zero(), 1.0 },
                { 1.0, { 0.0, 0.8, 0.0 }, 1.0 },
                { 1.0, Eigen::Vector3d::Zero(), 1.5 } };
  for (const auto& c : cases)
  {
    const double lift = c.lift;
    const auto model = depressorTow(lift, NumericsParams(), c.current, c.lift_from_bail);
    const EquilibriumResult eq = steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), u);
    const Eigen::Matrix3Xd x = withTowPoint(eq.state.x);
    const Eigen::Vector3d s = (x.col(kDepressor + 1) - x.col(kDepressor)).normalized();
    // The lift by hand: the water passes the body at -u; its part in the plane of symmetry (normal to the
    // horizontal y_b = z x s) gives 1/2 rho S C_L |w_p|^2, normal to w_p, on the side that points down.
    const Eigen::Vector3d y_b = Eigen::Vector3d::UnitZ().cross(s).normalized();
    const Eigen::Vector3d w = c.current - u, w_p = w - w.dot(y_b) * y_b;
    Eigen::Vector3d down = y_b.cross(w_p).normalized();
    if (down.z() > 0.0)
      down = -down;
    const Eigen::Vector3d L = 0.5 * env.water_density * 1.0 * lift * w_p.squaredNorm() * down;
    const double weight = (500.0 - env.water_density * 0.05) * env.gravity;
    const Eigen::Vector3d above = eq.tensions.col(kDepressor), below = eq.tensions.col(kDepressor + 1);
    const Eigen::Vector3d expected = weight * Eigen::Vector3d::UnitZ() - L;
    const double turn = std::acos(above.normalized().dot(below.normalized())) * 180.0 / kPi;
    const double misalignment = s.cross((above + below - (c.lift_from_bail - 1.0) * L).normalized()).norm();
    std::printf(
        "depressor, C_L %.0f, current %.1f m/s, yawed %.1f deg: T above %.2f N, below %.2f N, turned %.2f deg; jump "
        "(%.3f, %.3f, %.3f) N, by "
        "hand (%.3f, %.3f, %.3f) N; axis off the mean tension by %.1e rad; depth %.2f m\n",
        lift, c.current.norm(), std::atan2(s.y(), -s.x()) * 180.0 / kPi, above.norm(), below.norm(), turn,
        (above - below).x(), (above - below).y(), (above - below).z(), expected.x(), expected.y(), expected.z(),
        misalignment, -x.col(kDepressor).z());
    EXPECT_LT((above - below - expected).norm(), 1e-6 * above.norm());
    EXPECT_LT(misalignment, 1e-6);
    if (lift == 0.0)
    {
      depth_without = -x.col(kDepressor).z();
      continue;
    }
    EXPECT_LT(L.z(), -0.5 * L.norm());  // it presses down
    EXPECT_GT(L.norm(), 0.4 * weight);  // and nearly half its weight: the test sees the wing
    EXPECT_GT(turn, 5.0);               // the tension turns across it, as on a real depressor
    if (c.current.norm() == 0.0)
      EXPECT_GT(-x.col(kDepressor).z(), depth_without + 1.0);
    else  // yawed toward the flow across the track: its lift from the larger flow through the water
      EXPECT_GT(std::abs(s.y()), 0.05);
  }
}

// A depressor hanging steeply across the flow (its axis 68 degrees below the horizontal, as a heavy one on a short
// bridle does) in a flow that tilts from horizontal to 45 degrees upward, through the direction normal to its
// axis (21.8 degrees): the lift stays 1/2 rho S C_L U^2 normal to the flow and pointing down, (-sin b, 0, -cos b)
// for a flow U (-cos b, 0, sin b), and so continuous. ((P49a) once took the side against the axis' upward normal,
// which flipped the lift there: a jump of twice the lift that a steep depressor heaving in a sea crossed.)
TEST(Depressor, ItsLiftPointsDownAndTurnsSmoothlyThroughTheFlowNormalToItsAxis)
{
  DepressorParams p;
  p.length = 2.0;
  p.wing_area = 1.0;
  p.lift_coefficient = 1.0;
  const Depressor depressor(p, NumericsParams());
  const Eigen::Vector3d s = Eigen::Vector3d(-std::cos(68.0 * kPi / 180.0), 0.0, -std::sin(68.0 * kPi / 180.0));
  const ElementKinematics k =
      ElementKinematics::fromJoints(Eigen::Vector3d::Zero(), 2.0 * s, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const double rho = 1025.0, speed = 2.0, full = 0.5 * rho * 1.0 * 1.0 * speed * speed;
  double worst = 0.0, largest_step = 0.0;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (int i = 0; i <= 900; ++i)
  {
    const double b = 0.05 * i * kPi / 180.0;  // the flow's upward tilt, 0 .. 45 degrees
    const Eigen::Vector3d flow = speed * Eigen::Vector3d(-std::cos(b), 0.0, std::sin(b));  // the body at rest
    const Eigen::Vector3d lift = depressor.lift(k, flow, rho);
    worst = std::max(worst, (lift - full * Eigen::Vector3d(-std::sin(b), 0.0, -std::cos(b))).norm());
    if (i > 0)
      largest_step = std::max(largest_step, (lift - previous).norm());
    previous = lift;
  }
  std::printf("lift through the axis-normal flow: largest error %.2e N of %.0f N; largest change per 0.05 deg %.3f N\n",
              worst, full, largest_step);
  EXPECT_LT(worst, 1e-9 * full);
  EXPECT_LT(largest_step, 1e-3 * full);  // 0.05 degrees turn it by 8.7e-4 of itself
}

TEST(Depressor, StartedAtItsEquilibriumTheTowStaysThere)
{
  for (StepperType stepper : { StepperType::kDopri5, StepperType::kImplicit })
  {
    NumericsParams numerics;
    numerics.stepper = stepper;
    const auto model = depressorTow(1.0, numerics);
    const Eigen::Vector3d u(2.0, 0.0, 0.0);
    const EquilibriumResult eq = steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), u);
    Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), u));
    sim.reset(0.0, eq.state);
    const Eigen::Matrix3Xd start = sim.jointPositions().colwise() - sim.shipEnd().p_W;
    double worst = 0.0;
    for (int i = 1; i <= 30; ++i)
    {
      sim.advanceTo(i * 1.0);
      const Eigen::Matrix3Xd now = sim.jointPositions().colwise() - sim.shipEnd().p_W;
      worst = std::max(worst, (now - start).colwise().norm().maxCoeff());
    }
    std::printf("depressor tow started at equilibrium (%s): largest joint motion in 30 s %.2e m\n",
                stepper == StepperType::kDopri5 ? "dopri5" : "implicit", worst);
    EXPECT_LT(worst, 1e-4);
  }
}

TEST(Depressor, TheConfigurationReadsWritesBackAndRefusesWhatItCannotBe)
{
  const std::string yaml = R"(cable:
  sections:
    - {length: 300.0, segments: 30}
    - depressor: {length: 2.5, mass: 800.0, displaced_volume: 0.1, wing_area: 1.2, lift_coefficient: 0.9,
                  lift_from_bail: 1.1, cg_from_bail: 1.3, cb_from_bail: 1.2}
    - {length: 100.0, segments: 20, mass_per_length: 0.4}
)";
  const SimulationConfig config = loadConfig(YAML::Load(yaml));
  ASSERT_EQ(config.sections.size(), 3u);
  ASSERT_TRUE(config.sections[1].depressor.has_value());
  EXPECT_EQ(config.sections[1].segments, 1);
  EXPECT_DOUBLE_EQ(config.sections[1].length, 2.5);
  EXPECT_DOUBLE_EQ(config.cable.length, 402.5);
  EXPECT_DOUBLE_EQ(config.sections[1].depressor->wing_area, 1.2);
  const SimulationConfig again = loadConfig(toYaml(config));
  ASSERT_TRUE(again.sections[1].depressor.has_value());
  EXPECT_DOUBLE_EQ(again.sections[1].depressor->lift_from_bail, 1.1);
  EXPECT_DOUBLE_EQ(again.sections[1].depressor->cg_from_bail, 1.3);
  const struct
  {
    std::string yaml, words;
  } refusals[] = {
    { "cable:\n  sections:\n    - depressor: {length: 2.0}\n    - {length: 100.0, segments: 10}\n",
      "the first section is the cable" },
    { "cable:\n  sections:\n    - {length: 100.0, segments: 10}\n    - {depressor: {length: 2.0}, segments: 3}\n",
      "cable.sections[1].segments" },
    { "cable:\n  sections:\n    - {length: 100.0, segments: 10}\n    - depressor: {length: 2.0, lift_from_bail: 3.0}\n",
      "cable.sections[1].depressor.lift_from_bail" },
    { "cable:\n  sections:\n    - {length: 100.0, segments: 10}\n    - depressor: {length: 2.0, wing_aera: 1.0}\n",
      "wing_area" },
    { "cable:\n  axial_stiffness: 1.0e8\n  sections:\n    - {length: 100.0, segments: 10}\n    - depressor: {length: "
      "2.0}\n",
      "not in an elastic cable" },
  };
  for (const auto& r : refusals)
  {
    try
    {
      const SimulationConfig c = loadConfig(YAML::Load(r.yaml));
      ChainModel(cableSections(c), jointBodies(c), std::make_shared<RigidEndElement>(EndElementParams(), c.numerics),
                 c.environment, c.numerics);
      ADD_FAILURE() << "accepted:\n" << r.yaml;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(r.words), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace tow_sim
