// rostest: ship_motion_node in regular waves (test/ros/waves_config.yaml) and tow_sim_node towing in them,
// in real time. Over ~duration (25 s; make soak: 600 s in an irregular sea): the ship heaves, rolls and
// pitches (the generic vessel, head-and-beam seas); the cable's first joint, the tow point, is at every
// cable/state stamp the lever arm p + Rz Ry Rx r_tow of the odometry's full pose (interpolated between its
// 20 Hz messages), written out here; the tension at the ship swings (the ship's heave and the waves on the
// cable together: this does not tell them apart; the waves' loads are checked in test_waves); nothing is NaN.
#include <gtest/gtest.h>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <vector>

#include "tow_sim/CableState.h"

namespace
{
const Eigen::Vector3d kTowPoint(-20.0, 1.5, 3.0);  // [m] ship frame, as the launch file sets it

struct Pose
{
  Eigen::Vector3d p;
  Eigen::Quaterniond q;
};

TEST(ShipInWaves, TheTowPointIsTheLeverArmOfTheShipsFullPoseAndTheCableFeelsTheWaves)
{
  ros::NodeHandle nh;
  std::mutex mutex;
  std::map<double, Pose> odometry;  // by stamp [s]
  std::vector<std::pair<double, Eigen::Vector3d>> tow_points;
  std::vector<double> tensions;
  bool finite = true;
  ros::Subscriber odom_sub = nh.subscribe<nav_msgs::Odometry>(
      "/ship/odom", 100,
      [&](const nav_msgs::Odometry::ConstPtr& m)
      {
        const auto& p = m->pose.pose;
        std::lock_guard<std::mutex> lock(mutex);
        odometry[m->header.stamp.toSec()] =
            Pose{ Eigen::Vector3d(p.position.x, p.position.y, p.position.z),
                  Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z) };
      });
  ros::Subscriber state_sub =
      nh.subscribe<tow_sim::CableState>("/cable/state", 100,
                                        [&](const tow_sim::CableState::ConstPtr& m)
                                        {
                                          std::lock_guard<std::mutex> lock(mutex);
                                          if (m->joints.empty())
                                            return;
                                          const Eigen::Vector3d first(m->joints[0].x, m->joints[0].y, m->joints[0].z);
                                          finite = finite && first.allFinite() && std::isfinite(m->tension_ship);
                                          tow_points.emplace_back(m->header.stamp.toSec(), first);
                                          tensions.push_back(m->tension_ship);
                                        });
  double duration = 25.0;
  ros::NodeHandle("~").param("duration", duration, duration);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::WallDuration(duration).sleep();
  spinner.stop();

  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_GT(odometry.size(), static_cast<size_t>(12.0 * duration));   // 20 Hz
  ASSERT_GT(tow_points.size(), static_cast<size_t>(4.0 * duration));  // 10 Hz
  EXPECT_TRUE(finite);
  double z_min = 1e9, z_max = -1e9, roll_max = 0.0, pitch_max = 0.0;
  for (const auto& [t, pose] : odometry)
  {
    const Eigen::Matrix3d R = pose.q.toRotationMatrix();
    z_min = std::min(z_min, pose.p.z());
    z_max = std::max(z_max, pose.p.z());
    roll_max = std::max(roll_max, std::abs(std::atan2(R(2, 1), R(2, 2))));
    pitch_max = std::max(pitch_max, std::abs(std::asin(R(2, 0))));
  }
  std::printf("ship heave %.2f .. %.2f m, |roll| up to %.4f rad, |pitch| up to %.4f rad\n", z_min, z_max, roll_max,
              pitch_max);
  EXPECT_GT(z_max - z_min, 0.5);
  EXPECT_GT(roll_max, 0.005);
  EXPECT_GT(pitch_max, 0.005);

  // The lever arm of the two odometry poses around each stamp, interpolated.
  auto lever = [](const Pose& pose) { return Eigen::Vector3d(pose.p + pose.q.toRotationMatrix() * kTowPoint); };
  double worst = 0.0;
  int compared = 0;
  for (const auto& [t, x1] : tow_points)
  {
    const auto after = odometry.upper_bound(t);
    if (after == odometry.begin() || after == odometry.end())
      continue;
    const auto before = std::prev(after);
    const double w = (t - before->first) / (after->first - before->first);
    const Eigen::Vector3d expected = (1.0 - w) * lever(before->second) + w * lever(after->second);
    worst = std::max(worst, (x1 - expected).norm());
    ++compared;
  }
  std::printf("tow point vs the odometry's lever arm: largest difference %.2e m over %d states\n", worst, compared);
  EXPECT_GT(compared, 100);
  EXPECT_LT(worst, 0.01);

  const auto [lo, hi] = std::minmax_element(tensions.begin() + tensions.size() / 2, tensions.end());
  std::printf("tension at the ship over the last half: %.0f .. %.0f N\n", *lo, *hi);
  EXPECT_GT(*hi - *lo, 0.1 * *hi);
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ship_in_waves");
  return RUN_ALL_TESTS();
}
