// Ship odometry checks: each kind of bad message has its defined refusal; a good one gives the tow point.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/odometry_check.h"

namespace tow_sim
{
namespace
{
OdometryInput good(double t)
{
  OdometryInput in;
  in.t = t;
  in.frame_id = "odom";
  in.p_W = Eigen::Vector3d(2.0 * t, 0.0, 0.0);
  in.v_S = Eigen::Vector3d(2.0, 0.0, 0.0);
  return in;
}

TEST(OdometryCheck, GivesTheTowPointOfAGoodMessage)
{
  ShipTrack track;
  OdometryInput in = good(1.0);
  // Heading north (90 deg), turning at 0.01 rad/s: the tow point 20 m astern lies 20 m south and
  // moves with the ship plus w x r.
  in.q_wxyz = Eigen::Vector4d(std::cos(kPi / 4), 0, 0, std::sin(kPi / 4));
  in.w_S = Eigen::Vector3d(0, 0, 0.01);
  const OdometryResult r = checkOdometry(in, OdometryLimits(), track, 1.0);
  ASSERT_TRUE(r.accepted) << r.reason;
  EXPECT_LT((r.tow_p_W - Eigen::Vector3d(2.0, -20.0, 0.0)).norm(), 1e-12);
  EXPECT_LT((r.tow_v_W - Eigen::Vector3d(0.2, 2.0, 0.0)).norm(), 1e-12);
}

TEST(OdometryCheck, RefusesEachKindOfBadMessage)
{
  ShipTrack track;
  const OdometryLimits limits;
  OdometryResult first = checkOdometry(good(1.0), limits, track, 1.0);
  ASSERT_TRUE(first.accepted);
  track.add(1.0, first.tow_p_W, first.tow_v_W);
  auto refused = [&](OdometryInput in, const std::string& needle)
  {
    const OdometryResult r = checkOdometry(in, limits, track, 2.0);
    EXPECT_FALSE(r.accepted) << needle;
    EXPECT_NE(r.reason.find(needle), std::string::npos) << r.reason;
  };
  OdometryInput in = good(1.5);
  in.frame_id = "map";
  refused(in, "header.frame_id = 'map'");
  in = good(1.5);
  in.p_W.x() = std::numeric_limits<double>::quiet_NaN();
  refused(in, "not finite");
  in = good(1.5);
  in.q_wxyz.setZero();
  refused(in, "orientation has norm 0");
  in = good(1.5);
  in.q_wxyz = Eigen::Vector4d(1.5, 0, 0, 0);
  refused(in, "orientation has norm 1.5");
  refused(good(1.0), "not after the previous");         // duplicate
  refused(good(1.0 + 1e-9), "not after the previous");  // as good as one (1 us at least)
  {
    ShipTrack none;  // a stamp 1e10 s from the origin would overflow the track's pieces
    const OdometryResult far = checkOdometry(good(-1e10), limits, none, -1e10);
    EXPECT_FALSE(far.accepted);
    EXPECT_NE(far.reason.find("beyond +-1e9 s"), std::string::npos) << far.reason;
  }
  refused(good(0.5), "not after the previous");  // reordered
  refused(good(5.0), "in the future");
  ShipTrack empty;  // even the first message: a stamp from another clock would start the cable there
  const OdometryResult ancient = checkOdometry(good(1.0), limits, empty, 1.0 + limits.max_age + 0.5);
  EXPECT_FALSE(ancient.accepted);
  EXPECT_NE(ancient.reason.find("s in the past (more than max_odom_age"), std::string::npos) << ancient.reason;
  EXPECT_TRUE(checkOdometry(good(1.0), limits, empty, 1.0 + limits.max_age - 0.5).accepted);
  in = good(1.5);
  in.v_S.x() = 40.0;
  refused(in, "exceeds max_ship_speed");
  in = good(1.5);
  in.p_W.y() = 3000.0;
  refused(in, "jumped");
  ShipTrack none;
  in = good(1.5);
  in.p_W.x() = 2e7;  // 20 000 km: joints could no longer be told apart in double precision
  const OdometryResult far = checkOdometry(in, limits, none, 2.0);
  EXPECT_FALSE(far.accepted);
  EXPECT_NE(far.reason.find("pose.pose.position has a component beyond"), std::string::npos) << far.reason;
  // Nearly unit quaternions are normalised and accepted.
  in = good(1.5);
  in.q_wxyz = Eigen::Vector4d(1.005, 0, 0, 0);
  const OdometryResult r = checkOdometry(in, limits, track, 2.0);
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_NEAR(r.q_WS.norm(), 1.0, 1e-15);
}

// A GPS driver's (0, 0, 0) first, then the real track 1 km away: every real message is refused as a
// jump until `needed` consistent ones in a row say the ship is there; a lone outlier does not count.
TEST(OdometryCheck, ReacquiresATrackThatStaysElsewhere)
{
  const OdometryLimits limits;
  ShipTrack track;
  OdometryInput first = good(0.0);
  first.p_W.setZero();
  OdometryResult r = checkOdometry(first, limits, track, 0.0);
  ASSERT_TRUE(r.accepted) << r.reason;
  track.add(0.0, r.tow_p_W, r.tow_v_W);
  TrackReacquisition reacquire(5);
  const Eigen::Vector3d offset(1000.0, 500.0, 0.0);
  int refused = 0;
  bool again = false;
  for (int i = 1; i <= 10 && !again; ++i)
  {
    OdometryInput real = good(0.1 * i);
    real.p_W += offset;
    r = checkOdometry(real, limits, track, real.t);
    ASSERT_FALSE(r.accepted);
    ASSERT_TRUE(r.jumped) << r.reason;
    again = reacquire.jumped(real.t, r.tow_p_W, limits);
    refused += again ? 0 : 1;
  }
  EXPECT_TRUE(again);
  EXPECT_EQ(refused, 4);  // the fifth consistent message re-acquires
  // Outliers that disagree with each other never add up.
  TrackReacquisition outliers(3);
  for (int i = 0; i < 10; ++i)
    EXPECT_FALSE(outliers.jumped(0.1 * i, Eigen::Vector3d(i % 2 ? 1000.0 : -1000.0, 0.0, 0.0), limits));
  // A refusal for another reason is not a jump.
  OdometryInput nan = good(2.0);
  nan.v_S.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(checkOdometry(nan, limits, track, 2.0).jumped);
}

}  // namespace
}  // namespace tow_sim
