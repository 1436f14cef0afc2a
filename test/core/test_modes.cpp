// Natural modes (modes.h) against closed forms: a uniform chain hanging in still water (Bessel's zeros, with
// the added mass and the buoyancy) and a heavy body swinging on a light cable in vacuum (the two-degree-of-
// freedom pendulum of a string and a rigid body).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "chain_fixtures.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/analysis/modes.h"
#include "tow_sim/core/chain/chain_state.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/scenario/ship_path.h"
#include "tow_sim/scenario/towing_chart.h"

namespace tow_sim
{
namespace
{
// Every mode (naturalModes, dense) with count 0, else the count lowest (lowestModes, by Arnoldi).
std::vector<Mode> hangingModes(const CableParams& cable, const EndElementParams& end, const Environment& env,
                               std::size_t count = 0)
{
  const auto model = test::makeModel(cable, end, env);
  const ChainState state =
      straightChain(*model, Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  if (count > 0)
    return lowestModes(*model, model->initialGeometry(), model->initialData(0.0), 0.0, ShipEndState(), state.x, state.v,
                       count);
  return naturalModes(*model, model->initialGeometry(), model->initialData(0.0), 0.0, ShipEndState(), state.x, state.v);
}
}  // namespace

TEST(Modes, AChainHangingInStillWaterSwingsAtBesselsFrequenciesWithAddedMassAndBuoyancy)
{
  CableParams cable;
  cable.segments = 80;
  cable.length = 80.0;
  cable.diameter = 0.05;
  cable.mass_per_length = 4.0;
  cable.added_mass_coefficient = 1.0;
  cable.normal_drag_coefficient = 0.0;  // drag would damp the swing; its linear part is zero at rest anyway
  cable.tangential_drag_coefficient = 0.0;
  const EndElementParams end = test::endLikeSegment(cable);  // the 81st segment
  Environment env;
  // Both ways: every mode of the dense eigenproblem, and the lowest six by Arnoldi on the joints' amplitudes.
  for (const std::size_t count : { std::size_t(0), std::size_t(6) })
  {
    SCOPED_TRACE(count == 0 ? "dense" : "lowestModes");
    const std::vector<Mode> modes = hangingModes(cable, end, env, count);
    ASSERT_EQ(modes.size(), count == 0 ? 2u * 81u : count);
    // Transverse motion of a continuous chain: (mu + mu_a) y'' = d/dz (w z dy/dz), w = (mu - rho A) g.
    const double area = 0.25 * kPi * cable.diameter * cable.diameter, L = 81.0;
    const double w = (cable.mass_per_length - env.water_density * area) * env.gravity;
    const double inertia = cable.mass_per_length + cable.added_mass_coefficient * env.water_density * area;
    const double zeros[] = { 2.404825557695773, 5.520078110286311, 8.653727912911013 };
    for (int k = 0; k < 3; ++k)
    {
      const double expected = 0.5 * zeros[k] * std::sqrt(w / (inertia * L));
      // Each mode twice, in two planes (the vertical chain has no preferred one).
      const double a = modes[2 * k].frequency, b = modes[2 * k + 1].frequency;
      std::printf("hanging mode %d: %.6f and %.6f rad/s, Bessel %.6f rad/s (%.2e)\n", k + 1, a, b, expected,
                  a / expected - 1.0);
      EXPECT_NEAR(a / expected, 1.0, 2e-3) << k;
      EXPECT_NEAR(b / a, 1.0, 1e-9) << k;
      EXPECT_NEAR(modes[2 * k].damping_ratio, 0.0, 1e-9) << k;
      EXPECT_NEAR(2.0 * kPi / modes[2 * k].period, a, 1e-9 * a) << k;
    }
    // The first mode's shape: the largest displacement 1, at the tail; the joint below the tow point hardly moves.
    const Eigen::Matrix3Xd& shape = modes[0].shape;
    EXPECT_NEAR(shape.cwiseAbs().maxCoeff(), 1.0, 1e-9);
    const Eigen::VectorXd moved = shape.colwise().norm();
    EXPECT_EQ(std::max_element(moved.data(), moved.data() + moved.size()) - moved.data(), moved.size() - 1);
    EXPECT_LT(moved(0), 0.05 * moved(moved.size() - 1));
  }
}

TEST(Modes, AHeavyBodyOnALightCableSwingsAsTheTwoDegreeOfFreedomPendulum)
{
  CableParams cable;
  cable.segments = 20;
  cable.length = 10.0;
  cable.mass_per_length = 1e-4;  // 1 g of cable under a 100 kg body: its mass moves the modes by ~1e-5
  EndElementParams end;
  end.mass = 100.0;
  end.length = 1.0;
  end.cg_from_bail = end.cb_from_bail = 0.5;
  end.displaced_volume = 0.0;
  end.transverse_inertia = 2.0;
  Environment env;
  env.water_density = 0.0;
  for (const std::size_t count : { std::size_t(0), std::size_t(6) })  // dense, and Arnoldi's lowest six
  {
    SCOPED_TRACE(count == 0 ? "dense" : "lowestModes");
    const std::vector<Mode> modes = hangingModes(cable, end, env, count);
    // The string of length L and the body (mass M, CG c below the bail, inertia I about it), by Lagrange:
    // M = [[M L^2, M L c], [M L c, M c^2 + I]], K = diag(M g L, M g c).
    const double M = end.mass, L = cable.length, c = end.cg_from_bail, I = *end.transverse_inertia, g = env.gravity;
    Eigen::Matrix2d mass, stiffness;
    mass << M * L * L, M * L * c, M * L * c, M * c * c + I;
    stiffness << M * g * L, 0.0, 0.0, M * g * c;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> pendulum(stiffness, mass);
    for (int k = 0; k < 2; ++k)
    {
      const double expected = std::sqrt(pendulum.eigenvalues()(k));
      const double a = modes[2 * k].frequency, b = modes[2 * k + 1].frequency;
      std::printf("pendulum mode %d: %.6f and %.6f rad/s, closed form %.6f rad/s (%.2e)\n", k + 1, a, b, expected,
                  a / expected - 1.0);
      EXPECT_NEAR(a / expected, 1.0, 1e-4) << k;
      EXPECT_NEAR(b / expected, 1.0, 1e-4) << k;
    }
    EXPECT_EQ(modes[2].dominant.rfind("vehicle", 0), 0u) << modes[2].dominant;  // the body's own swing
    // The light cable's own modes are far above: a string of 1 g under the body's weight.
    EXPECT_GT(modes[4].frequency, 20.0 * modes[2].frequency);
  }
}

// A body hung at its CG (bail, CG and CB at one station) has no stiffness in its swing about the bail: a mode of
// zero frequency, about which shift-invert Arnoldi has nothing to invert. lowestModes then gives the dense solve's.
TEST(Modes, AModeOfZeroFrequencyFallsBackToTheDenseSolve)
{
  CableParams cable;
  cable.segments = 20;
  cable.length = 10.0;
  EndElementParams end;
  end.mass = 100.0;
  end.length = 1.0;
  end.cg_from_bail = end.cb_from_bail = 0.0;
  end.displaced_volume = 0.0;
  end.transverse_inertia = 2.0;
  Environment env;
  env.water_density = 0.0;
  const std::vector<Mode> dense = hangingModes(cable, end, env), lowest = hangingModes(cable, end, env, 6);
  ASSERT_EQ(lowest.size(), 6u);
  EXPECT_LT(lowest.front().frequency, 1e-6);  // the body's free swing
  for (size_t k = 0; k < lowest.size(); ++k)
    EXPECT_EQ(lowest[k].frequency, dense[k].frequency) << k;
}

// lowestModes (shift-invert Arnoldi on the joints' amplitudes, each element linearised alone) against naturalModes
// (angle coordinates differenced through the whole solve, the dense eigenproblem): the ten lowest modes of a steady
// tow in a cross current and of a two-part tow (sections, a clump, a float, a winged depressor), whose modes are
// apart (a hanging chain's come in equal pairs, whose shapes are not unique).
TEST(Modes, TheLowestModesByArnoldiAreTheDenseOnes)
{
  SimulationConfig cross = test::shortTightTow();
  cross.cable.segments = 30;
  const SimulationConfig two_part = loadConfig(YAML::Load(test::kSmallTwoPartTow));
  const std::pair<const SimulationConfig*, double> cases[] = { { &cross, 0.5 }, { &two_part, 1.5 } };
  for (const auto& [config, speed] : cases)
  {
    const Eigen::Vector3d current(0.1, 0.3, 0.0);
    const std::vector<Mode> dense = steadyTowModes(*config, speed, config->cable.length, current);
    const std::vector<Mode> lowest = steadyTowModes(*config, speed, config->cable.length, current, 10);
    ASSERT_EQ(lowest.size(), 10u);
    for (size_t k = 0; k < lowest.size(); ++k)
    {
      std::printf("mode %zu: %.6f rad/s, damping ratio %.6f, %s (dense: %.6f, %.6f, %s)\n", k + 1, lowest[k].frequency,
                  lowest[k].damping_ratio, lowest[k].dominant.c_str(), dense[k].frequency, dense[k].damping_ratio,
                  dense[k].dominant.c_str());
      EXPECT_NEAR(lowest[k].frequency / dense[k].frequency, 1.0, 1e-6) << k;
      EXPECT_NEAR(lowest[k].damping_ratio, dense[k].damping_ratio, 1e-6) << k;
      EXPECT_EQ(lowest[k].period == dense[k].period || std::abs(lowest[k].period / dense[k].period - 1.0) < 1e-6, true)
          << k << ": " << lowest[k].period << " against " << dense[k].period;
      EXPECT_EQ(lowest[k].dominant, dense[k].dominant) << k;
      EXPECT_LT((lowest[k].shape - dense[k].shape).cwiseAbs().maxCoeff(), 1e-5) << k;
    }
  }
}

// The damping too, against the dynamics themselves: the steady tow at 0.2 m/s started with the vehicle turned
// along its lightly damped yaw mode rings at that mode's period and decays at its damping ratio (dopri5 at 1e-9,
// the successive peaks of the tail's sideways offset from the bail).
TEST(Modes, TheSteadyTowsVehicleYawModeRingsAtItsPeriodAndDampingInAFreeDecay)
{
  const SimulationConfig config = test::shortTightTow();
  const double speed = 0.2;
  // The lowest 20 by Arnoldi (lowestModes): the yaw mode is among them.
  const std::vector<Mode> modes = steadyTowModes(config, speed, config.cable.length, Eigen::Vector3d::Zero(), 20);
  const auto yaw_mode = std::find_if(
      modes.begin(), modes.end(), [](const Mode& m) { return m.dominant == "vehicle yaw" && std::isfinite(m.period); });
  ASSERT_NE(yaw_mode, modes.end());
  ASSERT_LT(yaw_mode->damping_ratio, 0.2);  // lightly damped: several peaks to measure

  const TowSnapshot eq = steadyTow(config, speed, config.cable.length, Eigen::Vector3d::Zero());
  const auto ship = straightShip(speed, -2.0, 100.0);
  InitialShape initial;
  initial.type = InitialShape::Type::kPoints;
  initial.points = eq.joints.rightCols(eq.joints.cols() - 1) + 0.005 * yaw_mode->shape;
  TowRun run(config, ship, initial);
  ASSERT_EQ(run.start(0.0), "");
  std::vector<double> t, yaw;
  for (int k = 0; k <= 1200; ++k)
  {
    run.advanceTo(0.05 * k);
    t.push_back(0.05 * k);
    const TowSnapshot s = run.snapshot();  // the tail's sideways offset from the bail (the yaw angle is ill-posed:
    const Eigen::Index tail = s.joints.cols() - 1;  // the body hangs steeply at this speed)
    yaw.push_back(s.joints(1, tail) - s.joints(1, tail - 1));
  }
  std::vector<double> peak_t, peak;
  for (size_t i = 1; i + 1 < yaw.size(); ++i)
    if (yaw[i] > yaw[i - 1] && yaw[i] >= yaw[i + 1] && yaw[i] > 0.0)
    {
      // the parabola through the three samples: its vertex
      const double d = yaw[i - 1] - 2.0 * yaw[i] + yaw[i + 1], u = 0.5 * (yaw[i - 1] - yaw[i + 1]) / d;
      peak_t.push_back(t[i] + u * 0.05);
      peak.push_back(yaw[i] - 0.25 * (yaw[i - 1] - yaw[i + 1]) * u);
    }
  ASSERT_GE(peak.size(), 4u);
  const double period = (peak_t[3] - peak_t[1]) / 2.0;  // from the second peak on: the faster modes have gone
  const double delta = std::log(peak[1] / peak[3]) / 2.0;
  const double zeta = delta / std::sqrt(4.0 * kPi * kPi + delta * delta);
  std::printf("vehicle yaw mode: period %.4f s, damping ratio %.4f; free decay: %.4f s, %.4f\n", yaw_mode->period,
              yaw_mode->damping_ratio, period, zeta);
  // 5 mm at the tail: the swing's speed stays well under the flow's, whose drag the modes linearise (at 5 cm
  // the quadratic drag already shifts the damping by 5 %).
  EXPECT_NEAR(period / yaw_mode->period, 1.0, 5e-3);
  EXPECT_NEAR(zeta / yaw_mode->damping_ratio, 1.0, 0.02);
}

namespace
{
// 100 m of elastic cable (2 kg/m, EA 1e6 N, the axial damping c [N s]) in 50 segments.
CableParams hangingElasticCable(double damping)
{
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 50;
  cable.mass_per_length = 2.0;
  cable.axial_stiffness = 1e6;
  cable.axial_damping = damping;
  return cable;
}

// Its modes hanging in vacuum from the tow point, an end body of end_mass [kg], stretched to rest by its weight.
std::vector<Mode> elasticHangingModes(const CableParams& cable, double end_mass)
{
  EndElementParams end;
  end.mass = end_mass;
  Environment env;
  env.water_density = 0.0;
  const auto model = test::makeModel(cable, end, env);
  const EquilibriumResult eq = steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  return naturalModes(*model, model->initialGeometry(), model->initialData(0.0), 0.0, ShipEndState(), eq.state.x,
                      eq.state.v);
}
}  // namespace

// A bar fixed at the top with a mass M at its lower end vibrates along its length at beta L tan(beta L) = mu L / M,
// omega = beta sqrt(EA / mu) (the bar's mass mu L; axial waves do not feel the static tension of a linear spring).
// An elastic cable hanging in vacuum from its tow point, its end body M, stretched to rest by its own weight.
TEST(Modes, AnElasticCableHangingInVacuumStretchesAtTheBarsFrequencies)
{
  const CableParams cable = hangingElasticCable(0.0);
  const double end_mass = 100.0;
  const std::vector<Mode> modes = elasticHangingModes(cable, end_mass);
  std::vector<double> axial;
  for (const Mode& m : modes)
    if (m.dominant == "axial")
      axial.push_back(m.frequency);
  ASSERT_GE(axial.size(), 2u);
  const double ratio = cable.mass_per_length * cable.length / end_mass, c = std::sqrt(1e6 / cable.mass_per_length);
  for (int k = 0; k < 2; ++k)
  {
    double lo = k * kPi + 1e-9, hi = k * kPi + 0.5 * kPi - 1e-9;  // the root of x tan x = ratio in this branch
    for (int i = 0; i < 200; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      (mid * std::tan(mid) < ratio ? lo : hi) = mid;
    }
    const double expected = 0.5 * (lo + hi) * c / cable.length;
    std::printf("axial mode %d: %.6f rad/s, the bar's %.6f rad/s (%.2e)\n", k + 1, axial[k], expected,
                axial[k] / expected - 1.0);
    EXPECT_NEAR(axial[k] / expected, 1.0, 1e-3) << k;
  }
  // The pendulum's swing is far slower and not axial; the cable hangs straight, so nothing couples.
  EXPECT_NE(modes.front().dominant, "axial");
}

// With axial damping c (T = EA eps + c eps') the damping is proportional to the stiffness, as in a Kelvin-Voigt bar:
// each axial mode's damping ratio is c omega / (2 EA), whatever the tip mass.
TEST(Modes, AnElasticCablesAxialDampingIsKelvinVoigts)
{
  const CableParams cable = hangingElasticCable(1e4);
  const std::vector<Mode> modes = elasticHangingModes(cable, 100.0);
  int checked = 0;
  for (const Mode& m : modes)
    if (m.dominant == "axial" && checked < 2)
    {
      const double expected = cable.axial_damping * m.frequency / (2.0 * *cable.axial_stiffness);
      std::printf("axial mode at %.4f rad/s: damping ratio %.6f, Kelvin-Voigt %.6f\n", m.frequency, m.damping_ratio,
                  expected);
      EXPECT_NEAR(m.damping_ratio / expected, 1.0, 1e-3);
      ++checked;
    }
  EXPECT_EQ(checked, 2);
}

// A stiff elastic cable answers the ship's heave as the rigid chain does: the response converges as 1/EA.
TEST(Modes, AStiffElasticCablesResponseIsTheRigidChains)
{
  SimulationConfig rigid = test::shortTightTow(), stiff = rigid;
  stiff.cable.axial_stiffness = 1e10;
  const std::vector<double> periods = { 5.0, 10.0 };
  const auto a = steadyTowResponse(rigid, 2.0, 200.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), periods);
  const auto b = steadyTowResponse(stiff, 2.0, 200.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), periods);
  for (size_t i = 0; i < periods.size(); ++i)
  {
    std::printf("heave response at %.0f s: rigid %.6f m/m, %.4f N/m at the ship; EA 1e10 %.6f m/m, %.4f N/m\n",
                periods[i], std::abs(a[i].heave), std::abs(a[i].tension_ship), std::abs(b[i].heave),
                std::abs(b[i].tension_ship));
    EXPECT_LT(std::abs(b[i].heave - a[i].heave), 1e-3 * std::abs(a[i].heave)) << periods[i];
    EXPECT_LT(std::abs(b[i].pitch - a[i].pitch), 1e-3 * std::abs(a[i].pitch)) << periods[i];
    EXPECT_LT(std::abs(b[i].tension_ship - a[i].tension_ship), 1e-3 * std::abs(a[i].tension_ship)) << periods[i];
    EXPECT_LT(std::abs(b[i].tension_vehicle - a[i].tension_vehicle), 1e-3 * std::abs(a[i].tension_vehicle))
        << periods[i];
  }
}

}  // namespace tow_sim
