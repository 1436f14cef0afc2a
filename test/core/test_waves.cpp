// Linear waves (physics.md §9) against answers that do not come from waves.cpp: the dispersion relation and
// its limits, the Airy closed forms and the equations they solve (continuity, no rotation, the kinematic
// surface condition, d/dt), the Pierson-Moskowitz closed form, a generated sea's Hs and spectral peak from
// its own elevation record, the spreading function's mean cosine; then the loads (Morison) on a held
// segment and a neutrally buoyant, drag-free chain in a long wave moving with the water.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <vector>

#include "core/chain_fixtures.h"
#include "core/config_error.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/waves.h"
#include "tow_sim/core/vehicle/vehicle.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
namespace
{
constexpr double kG = 9.81;

WaveParams regular(double height, double period, double direction, double phase, double depth = 0.0)
{
  WaveParams w;
  w.type = WaveParams::Type::kRegular;
  w.height = height;
  w.period = period;
  w.direction = direction;
  w.phase = phase;
  w.water_depth = depth;
  return w;
}

TEST(Waves, WaveNumbersSolveTheDispersionRelationWithItsLimits)
{
  for (double period : { 2.0, 6.0, 10.0, 20.0 })
  {
    const double omega = 2.0 * kPi / period;
    // Deep water: omega^2 = g k, so a 10 s wave is g T^2 / (2 pi) = 156.13 m long.
    EXPECT_DOUBLE_EQ(waveNumber(omega, kG, 0.0), omega * omega / kG);
    for (double h : { 1.0, 5.0, 20.0, 100.0, 1000.0 })
    {
      const double k = waveNumber(omega, kG, h);
      EXPECT_NEAR(kG * k * std::tanh(k * h), omega * omega, 1e-12 * omega * omega) << period << " s, " << h << " m";
      if (k * h < 0.1)  // shallow water: the phase speed tends to sqrt(g h)
      {
        EXPECT_NEAR(omega / k, std::sqrt(kG * h), 0.01 * std::sqrt(kG * h));
      }
      if (k * h > 10.0)  // deep
      {
        EXPECT_NEAR(k, omega * omega / kG, 1e-8 * k);
      }
    }
  }
  EXPECT_NEAR(2.0 * kPi / waveNumber(2.0 * kPi / 10.0, kG, 0.0), 156.13, 0.01);
}

// Airy's closed forms, written out here: zeta = a cos(psi), psi = omega t - k (x cos th + y sin th) + phi;
// horizontal velocity a omega F_h cos(psi) along th, vertical -a omega F_v sin(psi).
struct Airy
{
  double a, omega, k, th, phi, h;
  double psi(const Eigen::Vector3d& p, double t) const
  {
    return omega * t - k * (p.x() * std::cos(th) + p.y() * std::sin(th)) + phi;
  }
  double fh(double z) const { return h > 0.0 ? std::cosh(k * (z + h)) / std::sinh(k * h) : std::exp(k * z); }
  double fv(double z) const { return h > 0.0 ? std::sinh(k * (z + h)) / std::sinh(k * h) : std::exp(k * z); }
  Eigen::Vector3d velocity(const Eigen::Vector3d& p, double t) const
  {
    const double u = a * omega * fh(p.z()) * std::cos(psi(p, t));
    return { u * std::cos(th), u * std::sin(th), -a * omega * fv(p.z()) * std::sin(psi(p, t)) };
  }
  Eigen::Vector3d acceleration(const Eigen::Vector3d& p, double t) const
  {
    const double du = -a * omega * omega * fh(p.z()) * std::sin(psi(p, t));
    return { du * std::cos(th), du * std::sin(th), -a * omega * omega * fv(p.z()) * std::cos(psi(p, t)) };
  }
};

TEST(Waves, RegularWaveKinematicsAreAirysDeepAndFinite)
{
  for (double depth : { 0.0, 15.0, 60.0 })
  {
    const WaveParams params = regular(3.0, 9.0, 0.7, 0.4, depth);
    const WaveField field(params, kG);
    ASSERT_EQ(field.components().size(), 1u);
    const double omega = 2.0 * kPi / 9.0;
    const Airy airy{ 1.5, omega, waveNumber(omega, kG, depth), 0.7, 0.4, depth };
    for (double z : { -1e-9, -2.0, -7.5, -14.0 })
      for (double t : { 0.0, 1.3, 4.0 })
      {
        const Eigen::Vector3d p(12.0, -5.0, z);
        const WaveKinematics w = field.kinematics(p, t);
        EXPECT_LT((w.velocity_W - airy.velocity(p, t)).norm(), 1e-12) << depth << " " << z << " " << t;
        EXPECT_LT((w.acceleration_W - airy.acceleration(p, t)).norm(), 1e-12) << depth << " " << z << " " << t;
        EXPECT_NEAR(field.elevation(p.x(), p.y(), t), 1.5 * std::cos(airy.psi(p, t)), 1e-12);
      }
  }
}

// The equations linear waves solve, by central differences of the field itself: incompressible and
// irrotational flow, the local acceleration the time derivative of the velocity, the surface moving with
// the water (w(z = 0) = d zeta / dt), and crests travelling toward `direction` at omega / k.
TEST(Waves, TheFieldSolvesTheLinearWaveEquations)
{
  WaveParams sea;
  sea.type = WaveParams::Type::kJonswap;
  sea.components = 20;
  sea.spreading = 4.0;
  sea.direction = -2.0;
  for (double depth : { 0.0, 30.0 })
  {
    sea.water_depth = depth;
    const WaveField field(sea, kG);
    const double e = 1e-4;
    const Eigen::Vector3d p(3.0, 4.0, -6.0);
    const double t = 17.0;
    auto v = [&](const Eigen::Vector3d& q, double tt) { return field.kinematics(q, tt).velocity_W; };
    Eigen::Matrix3d grad;  // grad(i, j) = d v_i / d x_j
    for (int j = 0; j < 3; ++j)
      grad.col(j) = (v(p + e * Eigen::Vector3d::Unit(j), t) - v(p - e * Eigen::Vector3d::Unit(j), t)) / (2.0 * e);
    const double scale = grad.norm();
    ASSERT_GT(scale, 1e-3);
    EXPECT_LT(std::abs(grad.trace()), 1e-6 * scale) << "divergence";
    EXPECT_LT((grad - grad.transpose()).norm(), 1e-6 * scale) << "curl";
    const Eigen::Vector3d dvdt = (v(p, t + e) - v(p, t - e)) / (2.0 * e);
    EXPECT_LT((dvdt - field.kinematics(p, t).acceleration_W).norm(), 1e-6 * dvdt.norm());
    const Eigen::Vector3d surface(p.x(), p.y(), -1e-12);
    const double dzeta_dt = (field.elevation(p.x(), p.y(), t + e) - field.elevation(p.x(), p.y(), t - e)) / (2.0 * e);
    EXPECT_NEAR(field.kinematics(surface, t).velocity_W.z(), dzeta_dt, 1e-6 * std::abs(dzeta_dt));
  }
  const WaveField one(regular(2.0, 7.0, 2.5, 0.0, 25.0), kG);
  const WaveComponent& c = one.components()[0];
  const double travelled = c.omega / c.k * 3.0;  // in 3 s
  EXPECT_NEAR(one.elevation(1.0 + travelled * std::cos(2.5), 2.0 + travelled * std::sin(2.5), 3.0),
              one.elevation(1.0, 2.0, 0.0), 1e-12);
}

TEST(Waves, NoWaveMotionAboveTheMeanSurfaceOrBelowTheBottom)
{
  const WaveField field(regular(4.0, 8.0, 0.0, 0.0, 20.0), kG);
  for (double z : { 0.0, 0.5, 3.0, -20.0, -25.0 })
  {
    const WaveKinematics w = field.kinematics(Eigen::Vector3d(0.0, 0.0, z), 1.0);
    EXPECT_EQ(w.velocity_W, Eigen::Vector3d::Zero()) << z;
    EXPECT_EQ(w.acceleration_W, Eigen::Vector3d::Zero()) << z;
  }
  EXPECT_TRUE(WaveField(WaveParams(), kG).components().empty());
}

TEST(Waves, JonswapWithoutPeakEnhancementIsThePiersonMoskowitzClosedForm)
{
  // gamma = 1: S = (5/16) Hs^2 omega_p^4 omega^-5 exp(-5/4 (omega_p/omega)^4), whose m0 is Hs^2/16 exactly.
  const double hs = 3.0, tp = 9.0, wp = 2.0 * kPi / tp;
  const JonswapSpectrum pm(hs, tp, 1.0);
  for (double x : { 0.6, 0.9, 1.0, 1.3, 2.0, 3.5 })
  {
    const double w = x * wp;
    const double closed = 5.0 / 16.0 * hs * hs * std::pow(wp, 4) * std::pow(w, -5) * std::exp(-1.25 * std::pow(x, -4));
    EXPECT_NEAR(pm(w), closed, 1e-6 * closed) << x;
  }
  // gamma multiplies the peak's shape by gamma there, before the scaling: the peak ratio with the same
  // m0 is gamma times the PM's m0 over JONSWAP's (1 - 0.287 ln gamma, Goda's fit, to about 1 %).
  const JonswapSpectrum js(hs, tp, 3.3);
  EXPECT_NEAR(js(wp) / pm(wp), 3.3 * (1.0 - 0.287 * std::log(3.3)), 0.02 * js(wp) / pm(wp));
}

// The generated sea itself: the elevation recorded at a point for three hours, its variance and its
// periodogram (a plain DFT here).
TEST(Waves, AJonswapSeaHasItsSignificantHeightAndItsPeakAtTp)
{
  WaveParams sea;
  sea.type = WaveParams::Type::kJonswap;
  sea.significant_height = 4.0;
  sea.peak_period = 10.0;
  sea.components = 200;
  sea.seed = 7;
  const WaveField field(sea, kG);
  double m0 = 0.0;
  for (const WaveComponent& c : field.components())
    m0 += 0.5 * c.amplitude * c.amplitude;
  std::printf("Hs from the components' m0: %.4f m (asked 4)\n", 4.0 * std::sqrt(m0));
  EXPECT_NEAR(4.0 * std::sqrt(m0), 4.0, 0.01 * 4.0);

  const double dt = 0.5;
  const int n = 21600;  // 3 h
  std::vector<double> zeta(n);
  double variance = 0.0;
  for (int i = 0; i < n; ++i)
  {
    zeta[i] = field.elevation(30.0, -40.0, i * dt);
    variance += zeta[i] * zeta[i] / n;
  }
  std::printf("Hs from the 3 h record: %.4f m\n", 4.0 * std::sqrt(variance));
  EXPECT_NEAR(4.0 * std::sqrt(variance), 4.0, 0.03 * 4.0);

  // Periodogram at the record's own frequencies 2 pi m / (n dt) from 0.5 to 2 omega_p, smoothed over
  // +-0.05 omega_p: its peak within 4 % of omega_p.
  const double wp = 2.0 * kPi / 10.0, df = 2.0 * kPi / (n * dt);
  const int first = static_cast<int>(0.5 * wp / df), last = static_cast<int>(2.0 * wp / df);
  std::vector<double> power;
  for (int m = first; m <= last; ++m)
  {
    const std::complex<double> step = std::polar(1.0, -m * df * dt);
    std::complex<double> sum = 0.0, turn = 1.0;
    for (int i = 0; i < n; ++i, turn *= step)
      sum += zeta[i] * turn;
    power.push_back(std::norm(sum));
  }
  const int half = static_cast<int>(0.05 * wp / df);
  int best = 0;
  double best_power = 0.0;
  for (int i = half; i + half < static_cast<int>(power.size()); ++i)
  {
    double smoothed = 0.0;
    for (int j = -half; j <= half; ++j)
      smoothed += power[i + j];
    if (smoothed > best_power)
    {
      best_power = smoothed;
      best = i;
    }
  }
  const double peak = (first + best) * df / wp;
  std::printf("spectral peak of the record at %.3f omega_p\n", peak);
  EXPECT_NEAR(peak, 1.0, 0.04);
}

TEST(Waves, SpreadingHasTheMeanCosineOfItsDistributionAndSeedsRepeat)
{
  // cos^{2s}(d/2) has E[cos d] = s / (s + 1).
  for (double s : { 1.0, 5.0, 20.0 })
  {
    WaveParams sea;
    sea.type = WaveParams::Type::kJonswap;
    sea.components = 2000;
    sea.spreading = s;
    sea.direction = 1.0;
    const WaveField field(sea, kG);
    double sum = 0.0;
    for (const WaveComponent& c : field.components())
      sum += std::cos(c.direction - 1.0);
    std::printf("s = %g: mean cosine %.4f (closed form %.4f)\n", s, sum / 2000.0, s / (s + 1.0));
    EXPECT_NEAR(sum / 2000.0, s / (s + 1.0), 0.02) << "s = " << s;
  }
  WaveParams sea;
  sea.type = WaveParams::Type::kJonswap;
  sea.spreading = 2.0;
  const WaveField a(sea, kG), b(sea, kG);
  sea.seed = 2;
  const WaveField c(sea, kG);
  EXPECT_EQ(a.elevation(5.0, 6.0, 100.0), b.elevation(5.0, 6.0, 100.0));
  EXPECT_NE(a.elevation(5.0, 6.0, 100.0), c.elevation(5.0, 6.0, 100.0));
}

TEST(Waves, BadParametersAreRefusedNamingTheKeyAndTheRange)
{
  const auto error = [](const std::string& yaml) { return test::configError(yaml); };
  std::string e = error("environment: {waves: {type: regular, height: -1}}");
  EXPECT_NE(e.find("environment.waves.height = -1"), std::string::npos) << e;
  EXPECT_NE(e.find("(0, 30] [m]"), std::string::npos) << e;
  e = error("environment: {waves: {type: jonswap, peak_period: 0.5}}");
  EXPECT_NE(e.find("environment.waves.peak_period = 0.5"), std::string::npos) << e;
  e = error("environment: {waves: {type: swell}}");
  EXPECT_NE(e.find("environment.waves.type: 'swell' must be 'none', 'regular' or 'jonswap'"), std::string::npos) << e;
  e = error("environment: {waves: {components: 0}}");
  EXPECT_NE(e.find("environment.waves.components = 0"), std::string::npos) << e;
  e = error("environment: {gravity: 0, waves: {type: regular}}");
  EXPECT_NE(e.find("environment.gravity = 0"), std::string::npos) << e;
  EXPECT_EQ(error("environment: {waves: {type: jonswap, significant_height: 6, spreading: 3}}"), "(accepted)");
}

// A segment crossing the mean surface sees the waves of its wet part's centre times the wet fraction: by
// hand from Airy for a segment half under water; none when above; continuous as it rises through z = 0.
TEST(Waves, TheSplashZoneFadesTheWavesInAndOutContinuously)
{
  Environment env;
  env.current_W = Eigen::Vector3d(0.3, 0.0, 0.0);
  env.waves = regular(2.0, 7.0, 0.5, 0.2);
  prepareWaves(env);
  const double omega = 2.0 * kPi / 7.0;
  const Airy airy{ 1.0, omega, omega * omega / kG, 0.5, 0.2, 0.0 };
  const double t = 3.3;
  // From (0, 0, -2) to (4, 0, 2): wet from eta = 0 to 0.5, its centre at (1, 0, -1).
  const WaveKinematics half = env.flowOver(Eigen::Vector3d(0, 0, -2), Eigen::Vector3d(4, 0, 2), t);
  const Eigen::Vector3d centre(1.0, 0.0, -1.0);
  EXPECT_LT((half.velocity_W - (0.5 * airy.velocity(centre, t) + env.current_W)).norm(), 1e-12);
  EXPECT_LT((half.acceleration_W - 0.5 * airy.acceleration(centre, t)).norm(), 1e-12);
  const WaveKinematics dry = env.flowOver(Eigen::Vector3d(0, 0, 0.5), Eigen::Vector3d(4, 0, 2), t);
  EXPECT_EQ(dry.velocity_W, env.current_W);
  EXPECT_EQ(dry.acceleration_W, Eigen::Vector3d::Zero());
  const WaveKinematics wet = env.flowOver(Eigen::Vector3d(0, 0, -3), Eigen::Vector3d(4, 0, -1), t);
  EXPECT_LT((wet.velocity_W - (airy.velocity(Eigen::Vector3d(2, 0, -2), t) + env.current_W)).norm(), 1e-12);
  double jump = 0.0;
  for (double z = -3.0; z <= 1.0; z += 0.01)
  {
    const Eigen::Vector3d a(0, 0, z), b(4, 0, z + 2.0), up(0, 0, 1e-6);
    const WaveKinematics lo = env.flowOver(a, b, t), hi = env.flowOver(a + up, b + up, t);
    jump = std::max(jump, (hi.acceleration_W - lo.acceleration_W).norm() / 1e-6);
  }
  std::printf("largest d(acceleration)/dz of a segment rising through the surface: %.3f 1/s^2\n", jump);
  EXPECT_LT(jump, 1.0);  // a switch would be ~ a omega^2 / 1e-6 = 8e5
}

// A cable segment held still in a regular wave: the drag of the water's velocity and the inertia of its
// acceleration, normal to the axis (Morison), the net weight, and no moment for a uniform segment.
TEST(Waves, AHeldSegmentFeelsMorisonsForce)
{
  CableParams cable;
  cable.tangential_drag_coefficient = 0.0;
  Environment env;
  env.waves = regular(3.0, 8.0, 0.3, 0.0);
  prepareWaves(env);
  const CableSegmentModel seg = CableSegmentModel::fromParams(cable, env, NumericsParams());
  const Eigen::Vector3d s = Eigen::Vector3d(1.0, 0.2, -0.5).normalized();
  const Eigen::Vector3d x_f(0.0, 0.0, -3.0), x_a = x_f + seg.length * s;
  const ElementKinematics k = ElementKinematics::fromJoints(x_f, x_a, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const double omega = 2.0 * kPi / 8.0;
  const Airy airy{ 1.5, omega, omega * omega / kG, 0.3, 0.0, 0.0 };
  const double rho = env.water_density, area = kPi * cable.diameter * cable.diameter / 4.0;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - s * s.transpose();
  for (double t : { 0.0, 2.1, 5.0 })
  {
    BodyDynamics out;
    cableSegmentDynamics(seg, t, k, env, out);
    const Eigen::Vector3d centre = 0.5 * (x_f + x_a);
    const Eigen::Vector3d u_n = -(P * airy.velocity(centre, t));  // the segment's velocity through the water
    const Eigen::Vector3d expected =
        -0.5 * rho * cable.normal_drag_coefficient * cable.diameter * seg.length * u_n.norm() * u_n +
        (1.0 + cable.added_mass_coefficient) * rho * area * seg.length * (P * airy.acceleration(centre, t)) -
        (cable.mass_per_length - rho * area) * kG * seg.length * Eigen::Vector3d::UnitZ();
    EXPECT_LT((out.wrench.head<3>() - expected).norm(), 1e-9 * expected.norm()) << t;
    EXPECT_LT(out.wrench.tail<3>().norm(), 1e-9) << t;
  }
}

// Neutrally buoyant and without drag, a chain moving with the water is accelerated with it: m = rho A d,
// so m a_w = (Froude-Krylov + added mass) a_w - e a_w on each element. In a wave 5.6 km long (T = 60 s) the
// chain is short, and every joint's acceleration is the water's at it to O(k L) = 1 %. Without the
// Froude-Krylov term the normal acceleration would be e / (m + e) = half of it; in calm water, none.
double neutralChainAccelerationError(const std::function<std::shared_ptr<const EndBody>(const CableParams&)>& end_body)
{
  CableParams cable;
  cable.segments = 4;
  cable.length = 8.0;
  cable.diameter = 0.05;
  Environment env;
  cable.mass_per_length = env.water_density * kPi * cable.diameter * cable.diameter / 4.0;
  cable.normal_drag_coefficient = 0.0;
  cable.tangential_drag_coefficient = 0.0;
  const double period = 60.0, omega = 2.0 * kPi / period, k = omega * omega / kG, a = 1.0;
  env.waves = regular(2.0 * a, period, 0.4, 0.0);
  auto model = std::make_shared<ChainModel>(cable, end_body(cable), env, NumericsParams());
  const WaveField& field = *model->environment().wave_field;
  const Eigen::Vector3d tow(20.0, -10.0, -30.0);
  double worst = 0.0;
  for (const Eigen::Vector3d& dir :
       { Eigen::Vector3d(1.0, 0.3, 0.0), Eigen::Vector3d(-0.2, 1.0, 0.1), Eigen::Vector3d(0.1, 0.2, -1.0) })
    for (double t : { 0.0, 11.0, 23.0, 41.0 })
    {
      auto ship = [&](double tt)
      {
        const WaveKinematics w = field.kinematics(tow, tt);
        return ShipEndState{ tow, w.velocity_W, w.acceleration_W };
      };
      Simulator sim(model, ship);
      ChainState state = straightChain(*model, tow, dir.normalized(), Eigen::Vector3d::Zero());
      for (int j = 0; j < model->jointCount(); ++j)
        state.v.col(j) = field.kinematics(state.x.col(j), t).velocity_W;
      sim.reset(t, state);
      const double scale = a * omega * omega * std::exp(k * tow.z());
      for (int j = 0; j < model->jointCount(); ++j)
        worst = std::max(
            worst, (sim.accelerations().col(j) - field.kinematics(state.x.col(j), t).acceleration_W).norm() / scale);
    }
  return worst;
}

TEST(Waves, ANeutrallyBuoyantDragFreeChainMovingWithTheWaterIsAcceleratedWithIt)
{
  const double rigid = neutralChainAccelerationError(
      [](const CableParams& cable)
      { return std::make_shared<RigidEndElement>(test::endLikeSegment(cable), NumericsParams()); });
  // The towed vehicle without drag or fin loads, its CB at its CG and as heavy as the water it displaces.
  VehicleParams v;
  v.mass = 1025.0 * v.displaced_volume;
  v.cb_from_bail = v.cg_from_bail;
  v.c1 = v.c2 = 0.0;
  for (FinPairParams* fin : { &v.rudder, &v.elevator })
    fin->lift_constant = fin->drag_constant = 0.0;
  auto vehicle = [&](const VehicleParams& p)
  { return [p](const CableParams&) { return std::make_shared<Vehicle>(p); }; };
  const double approach_a = neutralChainAccelerationError(vehicle(v));
  v.added_mass_approach = AddedMassApproach::kB;
  v.prolate_spheroid = ProlateSpheroid();
  const double approach_b = neutralChainAccelerationError(vehicle(v));
  std::printf(
      "largest difference of a joint's acceleration from the water's, of a omega^2 e^{kz}: rigid end %.4f, "
      "vehicle A %.4f, B %.4f\n",
      rigid, approach_a, approach_b);
  EXPECT_LT(rigid, 0.02);
  EXPECT_LT(approach_a, 0.02);
  EXPECT_LT(approach_b, 0.02);
}

// The rows of a batch run's timeseries.csv (blank cells as 0), its header left out.
std::vector<std::vector<double>> seriesRows(const std::string& csv)
{
  std::vector<std::vector<double>> rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line))
  {
    std::vector<double> c;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ','))
      c.push_back(cell.empty() ? 0.0 : std::stod(cell));
    rows.push_back(c);
  }
  return rows;
}

// A tow in an irregular head sea with the ship heaving and pitching (the generic vessel): no divergence,
// the segment lengths held (the largest error a step leaves before projection small), the tension at the
// ship positive and swinging about its calm-water value, the vehicle's depth bounded. 600 s here;
// TOW_SIM_SEAWAY_SECONDS=3600 (make soak) runs the hour.
TEST(Waves, AnIrregularSeaTowStaysBounded)
{
  const char* env = std::getenv("TOW_SIM_SEAWAY_SECONDS");
  const double seconds = env ? std::atof(env) : 600.0;
  const Scenario sc = loadScenario(YAML::Load(R"(
cable: {length: 300.0, segments: 30}
environment:
  waves: {type: jonswap, significant_height: 5.0, peak_period: 9.0, direction: 2.8, spreading: 4, seed: 3}
ship: {manoeuvres: [{type: straight, speed: 2.0, duration: 1.0e5}]}
simulation: {duration: )" + std::to_string(seconds) +
                                              R"(, output_interval: 1.0, shape_interval: 1.0e5}
)"));
  std::ostringstream series, shapes;
  BatchResult result;
  ASSERT_NO_THROW(runScenario(sc, series, shapes, result));
  EXPECT_EQ(result.t_reached, seconds);
  double t_lo = 1e9, t_hi = 0.0, depth_lo = 1e9, depth_hi = 0.0, worst_length = 0.0, sum = 0.0;
  int rows = 0;
  for (const std::vector<double>& c : seriesRows(series.str()))
  {
    if (c[0] < 60.0)  // the waves switch on at t = 0
      continue;
    t_lo = std::min(t_lo, c[15]);
    t_hi = std::max(t_hi, c[15]);
    depth_lo = std::min(depth_lo, c[11]);
    depth_hi = std::max(depth_hi, c[11]);
    worst_length = std::max(worst_length, c[20]);
    sum += c[15];
    ++rows;
  }
  std::printf(
      "%.0f s in Hs 5 m: tension at the ship %.0f .. %.0f N (mean %.0f), depth %.1f .. %.1f m, largest "
      "length error before projection %.1e\n",
      seconds, t_lo, t_hi, sum / rows, depth_lo, depth_hi, worst_length);
  EXPECT_GT(t_lo, 0.0);
  EXPECT_GT(t_hi - t_lo, 200.0);  // the sea loads the cable
  EXPECT_LT(depth_hi - depth_lo, 10.0);
  EXPECT_LT(worst_length, 1e-3);
}

// The batch's per-interval tension extremes (over the accepted steps' ends) catch what a sample per output
// interval misses. In a regular 9 s wave with steps of at most 0.05 s (numerics.max_step), against the same
// run written every 0.05 s, each 2 s interval's extremes agree with the fine samples' within 1 % of the
// tension's swing, and they are wider than the change between the 2 s samples.
TEST(Waves, TheBatchsTensionExtremesCatchPeaksBetweenOutputs)
{
  auto run = [](double interval)
  {
    const Scenario sc = loadScenario(YAML::Load(R"(
cable: {length: 200.0, segments: 20}
environment: {waves: {type: regular, height: 3.0, period: 9.0, direction: 3.1}}
numerics: {max_step: 0.05}
ship: {manoeuvres: [{type: straight, speed: 2.0, duration: 1.0e5}]}
simulation: {duration: 120, output_interval: )" +
                                                std::to_string(interval) + R"(, shape_interval: 1.0e5}
)"));
    std::ostringstream series, shapes;
    BatchResult result;
    runScenario(sc, series, shapes, result);
    return seriesRows(series.str());
  };
  const auto coarse = run(2.0), fine = run(0.05);
  double worst = 0.0, swing = 0.0, wider = 0.0;
  for (size_t i = 10; i < coarse.size(); ++i)
  {
    const double t = coarse[i][0];
    double lo = 1e9, hi = -1e9;
    for (const auto& r : fine)
      if (r[0] > t - 2.0 + 1e-9 && r[0] < t + 1e-9)
      {
        lo = std::min(lo, r[15]);
        hi = std::max(hi, r[15]);
      }
    worst = std::max({ worst, std::abs(coarse[i][26] - lo), std::abs(coarse[i][27] - hi) });
    swing = std::max(swing, hi - lo);
    wider += (coarse[i][27] - coarse[i][26]) - std::abs(coarse[i][15] - coarse[i - 1][15]);
  }
  std::printf("tension extremes per 2 s vs 0.05 s samples: largest difference %.1f N (largest swing in 2 s %.0f N)\n",
              worst, swing);
  EXPECT_LT(worst, 0.01 * swing);
  EXPECT_GT(wider, 0.0);
}

}  // namespace
}  // namespace tow_sim
