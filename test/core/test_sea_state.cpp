// The steady tow in an irregular sea in the frequency domain (sea_state.h; docs/physics.md §12, (P53a)) against
// the same sea in the time domain: a batch run of the scenario, whose ship heaves and pitches by the same RAOs
// in the very wave components the frequency domain sums, its outputs' standard deviations over 20 minutes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <vector>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/ship_response.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/sea_state.h"

namespace tow_sim
{
namespace
{
// 200 m of cable behind the generic vessel (its RAOs times rao_scale) in a long-crested JONSWAP sea. The waves' own
// loads on the cable near the surface are in the run, not in the frequency domain: a sea of a tenth the height
// behind a ship that moves ten times as much moves the tow point alike and makes them ten times smaller.
struct SeaCase
{
  double direction = kPi;  // [rad] the waves travel toward (world)
  double hs = 0.01;        // [m]
  double rao_scale = 10.0;
  Eigen::Vector3d tow_point_S = Eigen::Vector3d(-20.0, 0.0, 0.0);
  double speed = 2.0;        // [m/s]
  double heading = 0.0;      // [rad] the ship's
  double peak_period = 8.0;  // [s]
  // Not the generic vessel's but the same complex RAOs at every frequency and direction (heave [m/m], roll and
  // pitch [rad/m]): a ship that follows short waves too.
  std::optional<RaoValue> flat;
};

Scenario sea(const SeaCase& c)
{
  Scenario sc;
  sc.tow_point_S = c.tow_point_S;
  sc.start_heading = c.heading;
  sc.config.cable.length = 200.0;
  sc.config.cable.segments = 40;
  WaveParams& w = sc.config.environment.waves;
  w.type = WaveParams::Type::kJonswap;
  w.significant_height = c.hs;
  w.peak_period = c.peak_period;
  w.direction = c.direction;
  w.components = 60;
  w.seed = 3;
  prepareWaves(sc.config.environment);
  Manoeuvre straight;
  straight.type = Manoeuvre::Type::kStraight;
  straight.speed = c.speed;
  straight.duration = 1e4;
  sc.manoeuvres = { straight };
  sc.duration = 1500.0;
  if (c.flat)
  {
    sc.rao = std::make_shared<const RaoTable>(std::vector<double>{ 0.1, 10.0 }, std::vector<double>{ 0.0, 3.0 },
                                              std::vector<RaoValue>(4, *c.flat));
    return sc;
  }
  const RaoTable generic = RaoTable::genericVessel(sc.config.environment.gravity);
  std::vector<RaoValue> values;
  for (double d : generic.directions())
    for (double f : generic.frequencies())
    {
      RaoValue v = generic.at(f, d);
      v.heave *= c.rao_scale;
      v.roll *= c.rao_scale;
      v.pitch *= c.rao_scale;
      values.push_back(v);
    }
  sc.rao = std::make_shared<const RaoTable>(generic.frequencies(), generic.directions(), values);
  return sc;
}

// Over 300 s .. 1500 s every 0.5 s: the run's outputs (the vehicle's heave minus its depth, its surge and sway
// from the ship's reference point along and across the heading) and the frequency domain's sum of its
// components at the same instants, Re(H a e^{i psi}) with psi each component's phase at the ship (H conjugated
// where the ship overtakes the wave, as seaStateResponse wrote it).
struct Series
{
  std::vector<double> run[kSeaStateOutputs], sum[kSeaStateOutputs];
};

Series sample(const Scenario& sc, const SeaStateResponse& f)
{
  const WaveField sea(sc.config.environment.waves, sc.config.environment.gravity);
  StartedScenario started = startScenario(sc);
  Series out;
  for (double t = 300.0; t <= 1500.0 + 1e-9; t += 0.5)
  {
    started.run->advanceTo(t);
    const TowSnapshot s = started.run->snapshot();
    const double c = std::cos(s.ship.heading), n = std::sin(s.ship.heading);
    const Eigen::Vector3d cg = s.vehicle.p_cg_W - Eigen::Vector3d(s.ship.x, s.ship.y, 0.0);
    const double run[kSeaStateOutputs] = { s.tow_point.p_W.z(),      -s.depth, c * cg.x() + n * cg.y(),
                                           -n * cg.x() + c * cg.y(), s.pitch,  s.tension_ship,
                                           s.tension_vehicle };
    for (int j = 0; j < kSeaStateOutputs; ++j)
    {
      double sum = 0.0;
      for (size_t i = 0; i < f.components.size(); ++i)
      {
        const WaveComponent& w = sea.components()[i];
        const SeaStateComponent& fc = f.components[i];
        const double psi = w.omega * t - (w.kx * s.ship.x + w.ky * s.ship.y) + w.phase;
        const std::complex<double> h = fc.encounter_frequency < 0.0 ? std::conj(fc.outputs[j]) : fc.outputs[j];
        sum += (h * w.amplitude * std::polar(1.0, psi)).real();
      }
      out.run[j].push_back(run[j]);
      out.sum[j].push_back(sum);
    }
  }
  return out;
}

double mean(const std::vector<double>& v)
{
  double m = 0.0;
  for (double x : v)
    m += x / v.size();
  return m;
}

double deviation(const std::vector<double>& v)
{
  const double m = mean(v);
  double s = 0.0;
  for (double x : v)
    s += (x - m) * (x - m) / v.size();
  return std::sqrt(s);
}

// rms of the difference of the two series about their means, over the run's standard deviation.
double mismatch(const std::vector<double>& run, const std::vector<double>& sum)
{
  const double mr = mean(run), ms = mean(sum);
  double s = 0.0;
  for (size_t i = 0; i < run.size(); ++i)
    s += std::pow((run[i] - mr) - (sum[i] - ms), 2) / run.size();
  return std::sqrt(s) / deviation(run);
}

// Each output: the frequency domain's standard deviation within `spread` of the run's, and its sum of components
// within `shape` (rms of the difference over the run's standard deviation) of the run's series itself; a negative
// bound: not compared. The standard deviations differ by about 0.6 % from the 20 minutes' finite record alone
// (the tow point's, whose series agree to 1e-4, its small angles).
void compare(const char* sea, const Scenario& sc, const double (&spread)[kSeaStateOutputs],
             const double (&shape)[kSeaStateOutputs])
{
  const SeaStateResponse f = seaStateResponse(sc);
  const Series s = sample(sc, f);
  for (int j = 0; j < kSeaStateOutputs; ++j)
  {
    const double run = deviation(s.run[j]), m = mismatch(s.run[j], s.sum[j]);
    std::printf("sea state, %s: %-16s std %.6g frequency domain, %.6g run (%+.2f %%); series differ by %.2f %%\n", sea,
                SeaStateResponse::names[j], f.standard_deviation[j], run, 100.0 * (f.standard_deviation[j] / run - 1.0),
                100.0 * m);
    if (run < 1e-6)  // a long-crested head sea does not sway the tow: neither says it does
    {
      EXPECT_LT(f.standard_deviation[j], 1e-6) << SeaStateResponse::names[j];
      continue;
    }
    if (spread[j] >= 0.0)
    {
      EXPECT_NEAR(f.standard_deviation[j], run, spread[j] * run) << SeaStateResponse::names[j];
    }
    if (shape[j] >= 0.0)
    {
      EXPECT_LT(m, shape[j]) << SeaStateResponse::names[j];
    }
  }
}

// Small motions (the tow point heaving 4 cm rms): the linear limit. Outputs: tow point heave, vehicle heave, surge,
// sway, pitch, tensions at the ship and the vehicle.
TEST(SeaState, SmallMotionsInHeadAndBowQuarteringSeasAgreeWithTheTimeDomain)
{
  const double spread[kSeaStateOutputs] = { 0.015, 0.015, 0.015, 0.015, 0.015, 0.015, 0.015 };
  compare("head", sea(SeaCase()), spread, { 1e-4, 0.01, 0.025, 0.0, 0.01, 0.02, 0.02 });
  // The tow point 5 m to port and 3 m above the reference point: the ship's roll heaves and sways it, its pitch
  // surges it too. The vehicle barely follows a sway of the tow point (1e-4 m per m at 10 s, tow_sim_response
  // --input sway): its sway is the waves' own loads on the upper cable, which the frequency domain leaves out.
  // Not compared.
  SeaCase quartering;
  quartering.direction = 0.75 * kPi;
  quartering.tow_point_S = Eigen::Vector3d(-20.0, 5.0, 3.0);
  const double no_sway[kSeaStateOutputs] = { 0.015, 0.015, 0.015, -1.0, 0.015, 0.015, 0.015 };
  compare("bow quartering", sea(quartering), no_sway, { 1e-3, 0.01, 0.025, -1.0, 0.01, 0.02, 0.02 });
}

// A following sea of Tp 4 s overtaken by a ship at 4 m/s on a heading of 0.5 rad, the ship following even the short
// waves with a phase lag: the waves above 2.45 rad/s are slower than the ship, which meets them from astern (a
// negative encounter frequency: the ship's motion is conjugated), and they carry a good part of the tow point's
// heave. Near 2.45 rad/s the encounter periods are longer than the record, so the standard deviations are not
// compared; the series are (the vehicle's, as loosely as the slow waves' start from rest in the run demands).
TEST(SeaState, AnOvertakenFollowingSeaOnAnotherHeadingAgreesWithTheTimeDomain)
{
  SeaCase following;
  following.direction = following.heading = 0.5;
  following.speed = 4.0;
  following.peak_period = 4.0;
  following.hs = 0.02;
  following.flat = RaoValue{ std::polar(0.8, 0.6), std::polar(0.01, 0.3), std::polar(0.02, -0.4) };
  const Scenario sc = sea(following);
  const SeaStateResponse f = seaStateResponse(sc);
  double overtaken = 0.0;
  for (const SeaStateComponent& c : f.components)
    if (c.encounter_frequency < 0.0)
      overtaken += 0.5 * std::norm(c.outputs[0]) * c.amplitude * c.amplitude;
  std::printf("sea state, following: the overtaken waves give %.1f %% of the tow point's heave variance\n",
              100.0 * overtaken / std::pow(f.standard_deviation[0], 2));
  EXPECT_GT(overtaken, 0.1 * std::pow(f.standard_deviation[0], 2));
  const double none[kSeaStateOutputs] = { -1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0 };
  compare("following", sc, none, { 1e-3, 0.1, 0.1, -1.0, 0.1, 0.15, 0.1 });
}

// Hs 0.5 m behind the generic vessel (the tow point heaving 18 cm rms): the quadratic drag's nonlinearity and the
// waves' own loads on the upper cable show in the series; the standard deviations still agree.
TEST(SeaState, ARealSeaAgreesInItsStandardDeviations)
{
  SeaCase real;
  real.hs = 0.5;
  real.rao_scale = 1.0;
  compare("Hs 0.5 m", sea(real), { 0.015, 0.015, 0.015, 0.0, 0.015, 0.05, 0.015 },
          { 1e-4, 0.05, 0.15, 0.0, 0.05, 0.1, 0.1 });
}

}  // namespace
}  // namespace tow_sim
