// Hard but legal regimes: the ship reversing over its cable, tow speeds 0 to 10 m/s, currents from
// every direction, 1 and 2000 segments, very light and very heavy vehicles, odometry at 1 Hz and 200 Hz,
// and a two-hour soak with random manoeuvres and commands.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/vehicle/vehicle.h"
#include "tow_sim/scenario/scenario.h"
#include "tow_sim/scenario/ship_path.h"

namespace tow_sim
{
namespace
{

struct Tow
{
  std::shared_ptr<Vehicle> vehicle;
  std::shared_ptr<ChainModel> model;
};

Tow makeTow(double length, int segments, const VehicleParams& vp = VehicleParams(),
            const Eigen::Vector3d& current = Eigen::Vector3d::Zero(), const NumericsParams& numerics = NumericsParams())
{
  CableParams cable;
  cable.length = length;
  cable.segments = segments;
  Environment env;
  env.current_W = current;
  Tow tow;
  tow.vehicle = std::make_shared<Vehicle>(vp);
  tow.model = std::make_shared<ChainModel>(cable, tow.vehicle, env, numerics);
  return tow;
}

// Runs `duration` from the steady tow at `speed` along +x; returns the largest joint motion relative
// to the ship (how far it left the equilibrium) and checks the state stays finite with its lengths.
double runFromEquilibrium(const Tow& tow, double speed, double duration)
{
  const Eigen::Vector3d u(speed, 0.0, 0.0);
  Simulator sim(tow.model, constantVelocityShip(Eigen::Vector3d::Zero(), u));
  const EquilibriumResult eq = steadyTowEquilibrium(*tow.model, 0.0, Eigen::Vector3d::Zero(), u);
  sim.reset(0.0, eq.state);
  const Eigen::Matrix3Xd start = sim.jointPositions();
  sim.advanceTo(duration);
  EXPECT_TRUE(sim.state().x.allFinite() && sim.state().v.allFinite() && sim.tensions().allFinite());
  EXPECT_LT(sim.lengthError(), 1e-9);
  return ((sim.jointPositions().colwise() - sim.shipEnd().p_W) - (start.colwise() - Eigen::Vector3d::Zero()))
      .colwise()
      .norm()
      .maxCoeff();
}

TEST(HardRegimes, TowSpeedsFromZeroToTenMetresPerSecond)
{
  for (double speed : { 0.0, 0.5, 2.0, 5.0, 10.0 })
  {
    const double drift = runFromEquilibrium(makeTow(200.0, 40), speed, 20.0);
    std::printf("speed %4.1f m/s: largest joint drift from the equilibrium in 20 s %.2e m\n", speed, drift);
    EXPECT_LT(drift, 1e-6) << speed;  // measured at most 1.7e-8 m
  }
}

TEST(HardRegimes, CurrentFromEveryDirection)
{
  for (int k = 0; k < 8; ++k)
  {
    const double a = k * kPi / 4;
    const Tow tow = makeTow(200.0, 40, VehicleParams(), Eigen::Vector3d(std::cos(a), std::sin(a), 0.0));
    const double drift = runFromEquilibrium(tow, 2.0, 20.0);
    std::printf("current towards %3d deg: drift from the equilibrium in 20 s %.2e m\n", k * 45, drift);
    EXPECT_LT(drift, 1e-6) << "current towards " << k * 45 << " deg";
  }
}

TEST(HardRegimes, OneAndTwoThousandSegments)
{
  const double one = runFromEquilibrium(makeTow(100.0, 1), 2.0, 60.0);
  const double many = runFromEquilibrium(makeTow(500.0, 2000), 2.0, 0.5);
  std::printf("1 segment: drift from the equilibrium in 60 s %.2e m; 2000 segments, in 0.5 s %.2e m\n", one, many);
  EXPECT_LT(one, 1e-6);
  EXPECT_LT(many, 1e-6);
}

TEST(HardRegimes, VeryLightAndVeryHeavyVehicles)
{
  VehicleParams light;
  light.mass = 5.0;
  light.displaced_volume = 0.004;
  light.inertia_B = Eigen::Vector3d(0.02, 0.6, 0.6).asDiagonal();
  light.added_mass_a = 5.0;
  VehicleParams heavy;
  heavy.mass = 20000.0;
  heavy.displaced_volume = 5.0;
  heavy.inertia_B = Eigen::Vector3d(200.0, 7000.0, 7000.0).asDiagonal();
  for (const VehicleParams& p : { light, heavy })
  {
    const double drift = runFromEquilibrium(makeTow(300.0, 50, p), 2.0, 60.0);
    std::printf("vehicle of %.0f kg: drift from the equilibrium in 60 s %.2e m\n", p.mass, drift);
    EXPECT_LT(drift, 1e-6);  // measured at most 5e-9 m
  }
}

TEST(HardRegimes, ShipReversingOverItsOwnCable)
{
  Scenario sc = loadScenario(YAML::Load(R"(
ship:
  manoeuvres:
    - {type: straight, speed: 2.0, duration: 30}
    - {type: speed_change, to_speed: -1.0, duration: 30}
    - {type: straight, speed: -1.0, duration: 400}
simulation: {duration: 240}
)"));
  const ShipHistory path = buildShipPath(sc);
  const Tow tow = makeTow(100.0, 20);
  Simulator sim(tow.model, [&path](double t) { return path.towPoint(t); });
  const ShipEndState s0 = path.towPoint(0.0);
  sim.reset(0.0, steadyTowEquilibrium(*tow.model, 0.0, s0.p_W, s0.v_W).state);
  int slack_samples = 0, slack_while_towing = 0;
  for (int i = 1; i <= 240; ++i)
  {
    ASSERT_NO_THROW(sim.advanceTo(i * 1.0)) << "t = " << i;
    ASSERT_TRUE(sim.state().x.allFinite() && sim.tensions().allFinite());
    const std::vector<bool> slack = slackFlags(sim.jointPositions(), sim.tensions());
    const int count = static_cast<int>(std::count(slack.begin(), slack.end(), true));
    slack_samples += count;
    if (i <= 30)
      slack_while_towing += count;
  }
  const Eigen::Matrix3Xd joints = sim.jointPositions();
  std::printf(
      "ship reversing: vehicle %.1f m ahead of the tow point after 240 s; %d slack joint samples (%d while "
      "still towing ahead)\n",
      joints(0, joints.cols() - 1) - joints(0, 0), slack_samples, slack_while_towing);
  EXPECT_LT(sim.lengthError(), 1e-9);
  // Backing onto its own cable the ship pushes it: the rigid links carry compression, and the slack flags
  // (what cable/state.slack publishes) say so; towing ahead, none is slack.
  EXPECT_GT(slack_samples, 0);
  EXPECT_EQ(slack_while_towing, 0);
  // The ship backed over its cable: the vehicle now trails ahead of the tow point (the ship moves -x).
  EXPECT_GT(joints(0, joints.cols() - 1), joints(0, 0));
}

// The tow point rebuilt from odometry sampled at 1 Hz and at 200 Hz against the exact path.
TEST(HardRegimes, OdometryAtOneAndTwoHundredHertz)
{
  const double speed = 2.0, radius = 150.0, w = speed / radius;
  auto exact = [=](double t)
  {
    ShipEndState s;
    s.p_W = radius * Eigen::Vector3d(std::sin(w * t), 1.0 - std::cos(w * t), 0.0);
    s.v_W = speed * Eigen::Vector3d(std::cos(w * t), std::sin(w * t), 0.0);
    s.a_W = speed * w * Eigen::Vector3d(-std::sin(w * t), std::cos(w * t), 0.0);
    return s;
  };
  // dopri5 at 1e-7, whose error is far below the gaps measured: they are the track's.
  NumericsParams numerics;
  numerics.stepper = StepperType::kDopri5;
  auto vehicleAfter = [&](const ShipMotion& ship)
  {
    const Tow tow = makeTow(200.0, 40, VehicleParams(), Eigen::Vector3d::Zero(), numerics);
    Simulator sim(tow.model, ship);
    sim.reset(0.0, steadyTowEquilibrium(*tow.model, 0.0, ship(0.0).p_W, ship(0.0).v_W).state);
    sim.advanceTo(120.0);
    return Eigen::Vector3d(sim.state().x.col(tow.model->segments()));
  };
  const Eigen::Vector3d reference = vehicleAfter(exact);
  for (double rate : { 1.0, 200.0 })
  {
    auto track = std::make_shared<ShipTrack>(1.0, 30000);
    for (int i = 0; i <= static_cast<int>(130 * rate); ++i)
      track->add(i / rate, exact(i / rate).p_W, exact(i / rate).v_W);
    const double gap = (vehicleAfter([track](double t) { return (*track)(t); }) - reference).norm();
    std::printf("odometry at %.0f Hz: vehicle %.2e m from the exact-path run after 120 s\n", rate, gap);
    EXPECT_LT(gap, rate < 2.0 ? 1e-6 : 1e-8);  // measured 1.6e-8 m and 5.5e-10 m
  }
}

long residentKilobytes()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0)
      return std::stol(line.substr(6));
  return -1;
}

// Two hours of random manoeuvres and fin commands: no divergence, lengths held, flat memory.
TEST(HardRegimes, TwoHourSoakWithRandomManoeuvresAndCommands)
{
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Scenario sc;
  sc.duration = 7200.0;
  double t = 0.0;
  while (t < sc.duration + 100.0)
  {
    Manoeuvre m;
    const double pick = u(rng);
    m.speed = 0.5 + 3.0 * u(rng);
    if (pick < 0.4)
    {
      m.type = Manoeuvre::Type::kStraight;
      m.duration = 60.0 + 240.0 * u(rng);
    }
    else if (pick < 0.6)
    {
      m.type = Manoeuvre::Type::kSpeedChange;
      m.to_speed = m.speed;
      m.duration = 30.0 + 60.0 * u(rng);
    }
    else
    {
      m.type = Manoeuvre::Type::kTurn;
      m.radius = 100.0 + 300.0 * u(rng);
      m.angle = kPi * u(rng);
      m.direction = u(rng) < 0.5 ? 1 : -1;
      m.duration = m.angle * m.radius / m.speed;
    }
    t += m.duration;
    sc.manoeuvres.push_back(m);
  }
  const ShipHistory path = buildShipPath(sc);
  const Tow tow = makeTow(300.0, 50);
  Simulator sim(tow.model, [&path](double time) { return path.towPoint(time); });
  const ShipEndState s0 = path.towPoint(0.0);
  sim.reset(0.0, steadyTowEquilibrium(*tow.model, 0.0, s0.p_W, s0.v_W).state);
  long rss_after_warmup = 0;
  double worst_length = 0.0;
  for (int minute = 1; minute <= 120; ++minute)
  {
    sim.command(0.4 * (u(rng) - 0.5), 0.4 * (u(rng) - 0.5), 200.0 * u(rng));
    ASSERT_NO_THROW(sim.advanceTo(minute * 60.0)) << "minute " << minute;
    worst_length = std::max(worst_length, sim.lengthError());
    if (minute == 10)
      rss_after_warmup = residentKilobytes();
  }
  const long rss_end = residentKilobytes();
  std::printf("2 h soak: largest length error %.2e; resident memory %ld kB after 10 min, %ld kB after 2 h\n",
              worst_length, rss_after_warmup, rss_end);
  EXPECT_LT(worst_length, 1e-9);
  EXPECT_LT(rss_end - rss_after_warmup, 1024);  // flat: less than 1 MB growth
}

}  // namespace
}  // namespace tow_sim
