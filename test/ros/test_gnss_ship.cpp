// rostest: gnss_ship_node turns a survey vessel's GNSS into ship/odom, and tow_sim_node tows behind it.
// The vessel steams at 2 m/s on a heading of 60 deg from east (ENU), its antenna 10 m forward, 2 m to
// starboard and 12 m up; its fixes (latitude, longitude, altitude) are made here with GeographicLib's
// Geodesic direct problem from the origin, not the node's LocalCartesian, and published at 5 Hz with the
// heading. Checked: the ship frame's origin and velocity on ship/odom against the truth, the heading;
// fixes without a fix, with NaN latitude or an old stamp change nothing; tow_sim_node follows (cable/state).
#include <gtest/gtest.h>

#include <geometry_msgs/QuaternionStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/NavSatFix.h>
#include <GeographicLib/Geodesic.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "tow_sim/CableState.h"

namespace
{
constexpr double kLat0 = 43.10, kLon0 = 5.90, kAlt0 = 48.0;  // the origin, as gnss_ship.test configures it
constexpr double kSpeed = 2.0, kYaw = M_PI / 3;              // [m/s], [rad] from east toward north
const Eigen::Vector3d kAntenna(10.0, -2.0, 12.0);            // [m] ship frame

// The ship frame's origin at time t [s] after the start, ENU [m].
Eigen::Vector3d truth(double t)
{
  return Eigen::Vector3d(30.0, -20.0, 0.0) + kSpeed * t * Eigen::Vector3d(std::cos(kYaw), std::sin(kYaw), 0.0);
}

// The antenna's fix for the ship at t: east/north offsets as a geodesic from the origin.
sensor_msgs::NavSatFix fixAt(double t, const ros::Time& stamp)
{
  const Eigen::Vector3d a = truth(t) + Eigen::AngleAxisd(kYaw, Eigen::Vector3d::UnitZ()) * kAntenna;
  const double distance = std::hypot(a.x(), a.y()), azimuth = std::atan2(a.x(), a.y()) * 180.0 / M_PI;
  sensor_msgs::NavSatFix fix;
  fix.header.stamp = stamp;
  fix.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
  GeographicLib::Geodesic::WGS84().Direct(kLat0, kLon0, azimuth, distance, fix.latitude, fix.longitude);
  fix.altitude = kAlt0 + a.z();
  return fix;
}

TEST(GnssShip, TheShipFollowsItsFixesAndHeadingAndTheCableFollowsTheShip)
{
  ros::NodeHandle nh;
  std::mutex mutex;
  nav_msgs::Odometry last;
  int odom_count = 0, states = 0;
  ros::Subscriber odom_sub = nh.subscribe<nav_msgs::Odometry>("/ship/odom", 50,
                                                              [&](const nav_msgs::Odometry::ConstPtr& m)
                                                              {
                                                                std::lock_guard<std::mutex> lock(mutex);
                                                                last = *m;
                                                                ++odom_count;
                                                              });
  ros::Subscriber state_sub = nh.subscribe<tow_sim::CableState>("/cable/state", 50,
                                                                [&](const tow_sim::CableState::ConstPtr& m)
                                                                {
                                                                  std::lock_guard<std::mutex> lock(mutex);
                                                                  states += std::isfinite(m->tension_ship) ? 1 : 0;
                                                                });
  ros::Publisher fix_pub = nh.advertise<sensor_msgs::NavSatFix>("/ship/fix", 10);
  ros::Publisher heading_pub = nh.advertise<geometry_msgs::QuaternionStamped>("/ship/heading", 10);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
  while ((fix_pub.getNumSubscribers() == 0 || heading_pub.getNumSubscribers() == 0) && ros::WallTime::now() < deadline)
    ros::WallDuration(0.05).sleep();
  const ros::Time start = ros::Time::now();
  geometry_msgs::QuaternionStamped heading;
  heading.quaternion.z = std::sin(kYaw / 2);
  heading.quaternion.w = std::cos(kYaw / 2);
  int bad_sent = 0;
  for (int k = 0; k < 100; ++k)  // 20 s at 5 Hz
  {
    const ros::Time now = ros::Time::now();
    heading.header.stamp = now;
    heading_pub.publish(heading);
    ros::WallDuration(0.01).sleep();
    fix_pub.publish(fixAt((now - start).toSec(), now));
    if (k % 10 == 5)  // a bad fix among the good: each must change nothing
    {
      sensor_msgs::NavSatFix bad = fixAt((now - start).toSec(), now + ros::Duration(0.05));
      if (k % 30 == 5)
        bad.status.status = sensor_msgs::NavSatStatus::STATUS_NO_FIX, bad.latitude += 0.01;
      else if (k % 30 == 15)
        bad.latitude = NAN;
      else
        bad.header.stamp = now - ros::Duration(0.5), bad.longitude += 0.01;  // older than the last good one
      fix_pub.publish(bad);
      ++bad_sent;
    }
    ros::WallDuration(0.19).sleep();
  }
  ros::WallDuration(0.5).sleep();
  spinner.stop();

  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_GT(odom_count, 80);
  EXPECT_EQ(last.header.frame_id, "odom");
  EXPECT_EQ(last.child_frame_id, "ship");
  const double t = (last.header.stamp - start).toSec();
  const Eigen::Vector3d p(last.pose.pose.position.x, last.pose.pose.position.y, last.pose.pose.position.z);
  const auto& q = last.pose.pose.orientation;
  const double yaw = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
  std::printf(
      "ship at %.3f s: (%.3f, %.3f, %.3f) m, truth (%.3f, %.3f, %.3f) m; surge %.4f m/s, sway %.4f m/s, "
      "yaw %.5f rad; %d bad fixes sent; %d cable states\n",
      t, p.x(), p.y(), p.z(), truth(t).x(), truth(t).y(), truth(t).z(), last.twist.twist.linear.x,
      last.twist.twist.linear.y, yaw, bad_sent, states);
  EXPECT_LT((p - truth(t)).norm(), 0.05);  // a 2 m/s track, 1 s smoothing: no lag once settled
  EXPECT_NEAR(last.twist.twist.linear.x, kSpeed, 0.02);
  EXPECT_NEAR(last.twist.twist.linear.y, 0.0, 0.02);
  EXPECT_NEAR(yaw, kYaw, 1e-6);
  EXPECT_GT(states, 20);  // tow_sim_node tows behind it
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_gnss_ship");
  return RUN_ALL_TESTS();
}
