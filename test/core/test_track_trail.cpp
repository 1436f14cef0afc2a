// The drawn trails: spacing, age and size limits, and a restart.
#include <gtest/gtest.h>

#include <stdexcept>

#include "tow_sim/core/run/track_trail.h"

namespace tow_sim
{
namespace
{
TEST(TrackTrail, KeepsSpacedSamplesOverItsDuration)
{
  TrackTrail trail(100.0, 1.0);
  // 2 m/s for 300 s, sampled at 10 Hz: one sample kept per metre... every 0.5 s, 100 s of them.
  for (int i = 0; i <= 3000; ++i)
    trail.add(0.1 * i, Eigen::Vector3d(0.2 * i, 0.0, 0.0));
  const auto& s = trail.samples();
  ASSERT_FALSE(s.empty());
  EXPECT_NEAR(s.back().t, 300.0, 1e-9);
  EXPECT_GE(s.front().t, 200.0 - 1e-9);
  EXPECT_EQ(s.size(), 201u);  // 200 .. 300 s every 0.5 s
  for (size_t i = 1; i < s.size(); ++i)
    EXPECT_GE((s[i].p - s[i - 1].p).norm(), 1.0 - 1e-12);
}

TEST(TrackTrail, AStillPointKeepsOneSampleAndAClockGoingBackStartsAfresh)
{
  TrackTrail trail(100.0, 1.0);
  for (int i = 0; i < 50; ++i)
    trail.add(i, Eigen::Vector3d(5.0, 5.0, 0.0));
  EXPECT_EQ(trail.samples().size(), 1u);
  trail.add(10.0, Eigen::Vector3d(50.0, 5.0, 0.0));  // back in time
  ASSERT_EQ(trail.samples().size(), 1u);
  EXPECT_DOUBLE_EQ(trail.samples().front().t, 10.0);
}

TEST(TrackTrail, AtMostMaxPointsAndBadLimitsRefused)
{
  TrackTrail trail(1e6, 1.0, 10);
  for (int i = 0; i < 100; ++i)
    trail.add(i, Eigen::Vector3d(2.0 * i, 0.0, 0.0));
  EXPECT_EQ(trail.samples().size(), 10u);
  EXPECT_DOUBLE_EQ(trail.samples().back().t, 99.0);
  EXPECT_THROW(TrackTrail(0.0), std::invalid_argument);
  EXPECT_THROW(TrackTrail(10.0, 0.0), std::invalid_argument);
  EXPECT_THROW(TrackTrail(10.0, 1.0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace tow_sim
