// A survey vessel's GNSS as ship odometry (GnssTrack): the lever arm taken out with the heading, and the
// alpha-beta trackers checked against their closed forms: no lag at constant velocity, the steady lag
// a dt^2 (1 - alpha) / beta (velocity a dt (alpha / beta - 1/2)) at constant acceleration, and the white-noise variance
// ratio of the position, (2 alpha^2 + 2 beta - 3 alpha beta) / (alpha (4 - 2 alpha - beta)) (Kalata, "The tracking
// index", IEEE Trans. AES 20(2), 1984).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/gnss_track.h"

namespace tow_sim
{
namespace
{
// The antenna's place for a ship frame at p_W with heading yaw (level ship).
Eigen::Vector3d antennaAt(const Eigen::Vector3d& p_W, double yaw, const Eigen::Vector3d& antenna_S)
{
  const double c = std::cos(yaw), s = std::sin(yaw);
  return p_W +
         Eigen::Vector3d(c * antenna_S.x() - s * antenna_S.y(), s * antenna_S.x() + c * antenna_S.y(), antenna_S.z());
}

GnssTrackParams withAntenna(const Eigen::Vector3d& antenna_S, double smoothing_time)
{
  GnssTrackParams p;
  p.antenna_S = antenna_S;
  p.smoothing_time = smoothing_time;
  return p;
}

TEST(GnssTrack, FollowsAConstantVelocityWithoutLagAndTakesOutTheLeverArm)
{
  // 2 m/s on a heading of 30 deg, fixes at 1 Hz, the antenna 12 m forward, 3 m to port, 15 m up.
  const Eigen::Vector3d antenna_S(12.0, 3.0, 15.0), v_W(2.0 * std::cos(kPi / 6), 2.0 * std::sin(kPi / 6), 0.0);
  GnssTrack track(withAntenna(antenna_S, 3.0));
  ShipEstimate e;
  for (int k = 0; k <= 120; ++k)
  {
    const Eigen::Vector3d p_W = Eigen::Vector3d(100.0, -50.0, 0.0) + v_W * k;
    e = track.update({ 1.0 * k, antennaAt(p_W, kPi / 6, antenna_S), kPi / 6 });
  }
  const Eigen::Vector3d p_end = Eigen::Vector3d(100.0, -50.0, 0.0) + v_W * 120.0;
  EXPECT_LT((e.p_W - p_end).norm(), 1e-6) << e.p_W.transpose();
  EXPECT_NEAR(e.v_S.x(), 2.0, 1e-6);  // surge, in ship axes
  EXPECT_NEAR(e.v_S.y(), 0.0, 1e-6);
  EXPECT_NEAR(e.yaw, kPi / 6, 1e-12);
  EXPECT_NEAR(e.p_W.z(), 0.0, 1e-12);  // use_altitude false: on the surface
}

TEST(GnssTrack, LagsAConstantAccelerationByTheClosedForm)
{
  const double dt = 0.5, tau = 2.0, a = 0.05;  // [s], [s], [m/s^2] along x
  GnssTrack track(withAntenna(Eigen::Vector3d::Zero(), tau));
  ShipEstimate e;
  for (int k = 0; k <= 400; ++k)
  {
    const double t = dt * k;
    e = track.update({ t, Eigen::Vector3d(0.5 * a * t * t, 0.0, 0.0), 0.0 });
  }
  double alpha = 0.0, beta = 0.0;
  GnssTrack::gains(dt, tau, alpha, beta);
  const double t = dt * 400;
  EXPECT_NEAR(0.5 * a * t * t - e.p_W.x(), a * dt * dt * (1.0 - alpha) / beta, 1e-9);
  EXPECT_NEAR(a * t - e.v_S.x(), a * dt * (alpha / beta - 0.5), 1e-9);  // and the velocity's
}

TEST(GnssTrack, SmoothsWhiteNoiseByTheVarianceRatioOfTheClosedForm)
{
  const double dt = 1.0, tau = 2.0, sigma = 1.5;
  GnssTrack track(withAntenna(Eigen::Vector3d::Zero(), tau));
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, sigma);
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < 200000; ++k)
  {
    const ShipEstimate e = track.update({ dt * k, Eigen::Vector3d(noise(rng), 0.0, 0.0), 0.0 });
    if (k < 100)
      continue;
    sum += e.p_W.x();
    sum2 += e.p_W.x() * e.p_W.x();
    ++n;
  }
  const double var = sum2 / n - (sum / n) * (sum / n);
  double alpha = 0.0, beta = 0.0;
  GnssTrack::gains(dt, tau, alpha, beta);
  const double ratio = (2 * alpha * alpha + 2 * beta - 3 * alpha * beta) / (alpha * (4 - 2 * alpha - beta));
  EXPECT_NEAR(var / (sigma * sigma), ratio, 0.03 * ratio);
  // By hand, alpha = 1 - exp(-1/2) = 0.39347, beta = alpha^2 / (2 - alpha) = 0.09636: the 2 s smoothing at
  // 1 Hz keeps 0.3169 of the noise's variance.
  EXPECT_NEAR(ratio, 0.3169, 1e-4);
}

TEST(GnssTrack, ATurnOnTheSpotLeavesTheShipWhereItIsThroughPlusMinusPi)
{
  // The ship turns about its own origin at 3 deg/s; the antenna 20 m ahead sweeps a circle.
  const Eigen::Vector3d antenna_S(20.0, 0.0, 0.0), origin(5.0, 7.0, 0.0);
  const double rate = 3.0 * kPi / 180.0;
  GnssTrack track(withAntenna(antenna_S, 2.0));
  ShipEstimate e;
  double worst = 0.0;
  for (int k = 0; k <= 600; ++k)  // 300 s: 900 deg, through +-pi three times
  {
    const double t = 0.5 * k, yaw = std::remainder(rate * t, 2.0 * kPi);
    e = track.update({ t, antennaAt(origin, yaw, antenna_S), yaw });
    if (k > 200)  // the start from rest has died out
    {
      worst = std::max(worst, (e.p_W - origin).norm());
      EXPECT_NEAR(e.yaw_rate, rate, 1e-6) << t;
      EXPECT_NEAR(e.yaw, rate * t, 1e-6) << t;  // unwrapped: continuous
    }
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(GnssTrack, RefusesAStaleFixAndKeepsItsTrack)
{
  GnssTrack track(withAntenna(Eigen::Vector3d::Zero(), 1.0));
  track.update({ 1.0, Eigen::Vector3d(1, 0, 0), 0.0 });
  const ShipEstimate before = track.update({ 2.0, Eigen::Vector3d(2, 0, 0), 0.0 });
  try
  {
    track.update({ 2.0, Eigen::Vector3d(50, 0, 0), 0.0 });
    ADD_FAILURE() << "a fix at the previous fix's stamp was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("is not after the previous fix's 2 s"), std::string::npos) << e.what();
  }
  EXPECT_THROW(track.update({ 3.0, Eigen::Vector3d(NAN, 0, 0), 0.0 }), std::invalid_argument);
  const ShipEstimate after = track.update({ 3.0, Eigen::Vector3d(3, 0, 0), 0.0 });
  double alpha = 0.0, beta = 0.0;
  GnssTrack::gains(1.0, 1.0, alpha, beta);
  const double predicted = before.p_W.x() + before.v_S.x();  // untouched by the refused fixes
  EXPECT_NEAR(after.p_W.x(), predicted + alpha * (3.0 - predicted), 1e-12);
}

TEST(GnssTrack, RefusesParametersOutOfRangeNamingThem)
{
  GnssTrackParams p;
  p.smoothing_time = -1.0;
  try
  {
    validate(p, "/gnss_ship/");
    ADD_FAILURE();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("/gnss_ship/smoothing_time = -1 must be in [0, 600] [s]"), std::string::npos)
        << e.what();
  }
  p.smoothing_time = 1.0;
  p.antenna_S.x() = NAN;
  EXPECT_THROW(validate(p, ""), std::invalid_argument);
}

}  // namespace
}  // namespace tow_sim
