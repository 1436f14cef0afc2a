// The tow-point track rebuilt from samples: exact on a constant-acceleration path, continuous position,
// velocity and acceleration across samples, bounded extrapolation, rejected samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/ship_track.h"

namespace tow_sim
{
namespace
{
TEST(ShipTrack, ReproducesAConstantAccelerationPathExactly)
{
  const Eigen::Vector3d p0(1, 2, 0), v0(2, 0.5, 0), a(0.1, -0.2, 0);
  ShipTrack track;
  for (int i = 0; i <= 20; ++i)
  {
    const double t = 0.1 * i;
    ASSERT_TRUE(track.add(t, p0 + v0 * t + 0.5 * a * t * t, v0 + a * t));
  }
  for (double t = 0.1; t < 1.9; t += 0.0137)
  {
    const ShipEndState s = track(t);
    EXPECT_LT((s.p_W - (p0 + v0 * t + 0.5 * a * t * t)).norm(), 1e-9) << t;
    EXPECT_LT((s.v_W - (v0 + a * t)).norm(), 1e-9) << t;
    EXPECT_LT((s.a_W - a).norm(), 1e-9) << t;
  }
}

TEST(ShipTrack, TurningShipIsFollowedWithContinuousAcceleration)
{
  // A 2 m/s turn of radius 100 m sampled at 10 Hz.
  const double speed = 2.0, radius = 100.0, w = speed / radius;
  ShipTrack track;
  for (int i = 0; i <= 100; ++i)
  {
    const double t = 0.1 * i;
    track.add(t, radius * Eigen::Vector3d(std::sin(w * t), 1 - std::cos(w * t), 0),
              speed * Eigen::Vector3d(std::cos(w * t), std::sin(w * t), 0));
  }
  double worst_jump = 0.0;
  for (int k = 1; k < 90; ++k)
  {
    const double knot = 0.1 * k + 0.05;
    const ShipEndState before = track(knot - 1e-9), after = track(knot + 1e-9);
    worst_jump = std::max(worst_jump, (after.a_W - before.a_W).norm());
    const ShipEndState s = track(knot + 0.031);
    const double t = knot + 0.031;
    EXPECT_LT((s.p_W - radius * Eigen::Vector3d(std::sin(w * t), 1 - std::cos(w * t), 0)).norm(), 1e-6);
    EXPECT_NEAR(s.a_W.norm(), speed * speed / radius, 1e-4);
  }
  EXPECT_LT(worst_jump, 1e-6);
}

TEST(ShipTrack, ZeroOrStaleTwistDoesNotMakeTheTrackSwing)
{
  // A ship at 2 m/s whose odometry reports no velocity at all, at 20 Hz: the track must still move
  // smoothly at about 2 m/s instead of stopping at every sample.
  ShipTrack track;
  for (int i = 0; i <= 100; ++i)
    track.add(0.05 * i, Eigen::Vector3d(0.1 * i, 0, 0), Eigen::Vector3d::Zero());
  double worst_acceleration = 0.0;
  for (double t = 0.2; t < 4.8; t += 0.0071)
  {
    EXPECT_NEAR(track(t).v_W.x(), 2.0, 1e-9) << t;
    worst_acceleration = std::max(worst_acceleration, track(t).a_W.norm());
  }
  EXPECT_LT(worst_acceleration, 1e-6);
  // A burst of stale positions with fresh stamps: bounded velocities, no swing back and forth.
  ShipTrack burst;
  for (int i = 0; i < 20; ++i)
    burst.add(0.05 * i, Eigen::Vector3d(0.1 * i, 0, 0), Eigen::Vector3d(2, 0, 0));
  for (int i = 0; i < 50; ++i)  // 50 messages 10 ms apart, all at the position of the last one
    burst.add(1.0 + 0.01 * i, Eigen::Vector3d(1.9, 0, 0), Eigen::Vector3d(2, 0, 0));
  for (double t = 1.0; t < 1.49; t += 0.001)
    EXPECT_LT(burst(t).v_W.norm(), 2.5) << t;
}

TEST(ShipTrack, VelocitiesFromJitteryPositionsAreClampedToTheMaximumSpeed)
{
  // 2 m/s at 100 Hz with +-0.2 m of position noise (two samples up, two down) and no twist: the velocities
  // the positions give (central differences) reach 0.4 m / 0.02 s = 20 m/s across; with max_speed 5 m/s none
  // at a sample exceeds it.
  ShipTrack clamped(1.0, 400, 5.0), free(1.0, 400);
  for (int i = 0; i <= 200; ++i)
  {
    const Eigen::Vector3d p(0.02 * i, ((i / 2) % 2 ? 0.2 : -0.2), 0.0);
    clamped.add(0.01 * i, p, Eigen::Vector3d::Zero());
    free.add(0.01 * i, p, Eigen::Vector3d::Zero());
  }
  double fastest = 0.0, fastest_free = 0.0;
  for (int i = 1; i < 200; ++i)
  {
    fastest = std::max(fastest, clamped(0.01 * i).v_W.norm());
    fastest_free = std::max(fastest_free, free(0.01 * i).v_W.norm());
  }
  EXPECT_LE(fastest, 5.0 + 1e-12);
  EXPECT_GT(fastest, 4.9);        // clamped, not zeroed
  EXPECT_GT(fastest_free, 15.0);  // and the case matters
  EXPECT_THROW(ShipTrack(1.0, 400, 0.0), std::invalid_argument);
}

TEST(ShipTrack, DroppingThePastLeavesTheTrackFromThenOnUnchanged)
{
  // A turn sampled at 50 Hz: a twin that forgets everything before t = 5.05 s gives the same tow point,
  // to the bit, at 5.05 s and after, and keeps three samples or fewer before it.
  const double speed = 2.0, radius = 100.0, w = speed / radius;
  ShipTrack full(1.0, 100000), pruned(1.0, 100000);
  for (int i = 0; i <= 500; ++i)
  {
    const double t = 0.02 * i;
    const Eigen::Vector3d p(radius * std::sin(w * t), radius * (1 - std::cos(w * t)), 0);
    const Eigen::Vector3d v(speed * std::cos(w * t), speed * std::sin(w * t), 0);
    full.add(t, p, v);
    pruned.add(t, p, v);
  }
  pruned.dropBefore(5.05);
  EXPECT_LE(pruned.oldestTime(), 5.05);
  EXPECT_GT(pruned.oldestTime(), 5.0);
  for (double t = 5.05; t < 11.0; t += 0.0173)
  {
    EXPECT_EQ(pruned(t).p_W, full(t).p_W) << t;
    EXPECT_EQ(pruned(t).v_W, full(t).v_W) << t;
    EXPECT_EQ(pruned(t).a_W, full(t).a_W) << t;
  }
  pruned.dropBefore(1e9);  // past the newest sample: two stay, for the extrapolation
  EXPECT_EQ(pruned.newestTime(), full.newestTime());
  EXPECT_EQ(pruned(10.5).p_W, full(10.5).p_W);
}

TEST(ShipTrack, ExtrapolatesForABoundedTimeAndRejectsBadSamples)
{
  ShipTrack track(0.5);
  EXPECT_TRUE(track.add(0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0)));
  EXPECT_TRUE(track.add(1.0, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 0, 0)));
  EXPECT_NEAR(track(1.3).p_W.x(), 1.3, 1e-12);
  EXPECT_NEAR(track(5.0).p_W.x(), 1.5, 1e-12);                                     // held after 0.5 s
  EXPECT_FALSE(track.add(1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));  // duplicate stamp
  EXPECT_FALSE(track.add(0.5, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));  // reordered
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(track.add(2.0, Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d::Zero()));
  EXPECT_DOUBLE_EQ(track.newestTime(), 1.0);
}

// The ship's pose between odometry samples takes the shorter way round through +-pi, and past the newest
// sample goes on at the last two samples' rates for at most max_extrapolation (as the tow point does).
TEST(ShipHistory, PoseWrapsThroughPiAndExtrapolatesLikeTheTrack)
{
  ShipHistory ship(1.0, 100);
  auto pose = [](double x, double heading)
  {
    ShipPose p;
    p.x = x;
    p.heading = heading;
    p.speed = 2.0;
    return p;
  };
  const double pi = kPi;
  ship.add(0.0, Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(2.0, 0.0, 0.0), pose(0.0, pi - 0.1));
  ship.add(1.0, Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d(2.0, 0.0, 0.0), pose(2.0, -pi + 0.1));
  EXPECT_NEAR(std::remainder(ship.pose(0.5).heading - pi, 2.0 * pi), 0.0, 1e-12);  // not 0
  EXPECT_NEAR(ship.pose(0.5).x, 1.0, 1e-12);
  EXPECT_NEAR(ship.pose(1.5).x, 3.0, 1e-12);  // on at 2 m/s
  EXPECT_NEAR(std::remainder(ship.pose(1.5).heading - (-pi + 0.2), 2.0 * pi), 0.0, 1e-12);
  EXPECT_NEAR(ship.pose(5.0).x, 4.0, 1e-12);   // held after max_extrapolation (1 s)
  EXPECT_NEAR(ship.pose(-1.0).x, 0.0, 1e-12);  // before the oldest: the oldest
}

}  // namespace
}  // namespace tow_sim
