// rostest: tow_nav_node behind tow_sim_node's simulated survey sensors (tow_nav.test, tow_nav_config.yaml).
// The test plays the clock (use_sim_time, 0.05 s steps at 4x real time) and the ship: 2 m/s east for 80 s, then
// a turn to port of 250 m radius, 200 s in all, in a current tow_nav_node does not know. It checks, against
// tow_sim_node's own vehicle/odom (the truth):
// - the estimate's error within the covariance it reports (NEES below chi-square(3)'s 99.9 % point at 95 % of
//   the instants; an error larger than the covariance allows fails, and so does a covariance so wide that the
//   position says little: sigma below 5 m after 150 s);
// - nav/fish/fix as the pose in latitude, longitude and altitude (about the sea surface), nav/layback and
//   nav/cross_track against the pose and the ship the test plays;
// - bad measurements sent among the good ones (a NaN depth, a depth below the seabed, a USBL fix 500 m off, a
//   ship fix 30 s in the past), each counted in the diagnostics, and no jump in the estimate.
#include <gtest/gtest.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/NavSatFix.h>
#include <GeographicLib/LocalCartesian.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "tow_sim/SensorValue.h"

namespace
{
constexpr double kT0 = 1000.0;                       // [s] the clock at the start
constexpr double kEnd = 200.0, kStep = 0.05;         // [s]
constexpr double kSpeed = 2.0, kTurnAt = 80.0;       // [m/s], [s]
constexpr double kRadius = 250.0;                    // [m] to port
constexpr double kChi2Point = 16.27;                 // chi-square, 3 degrees of freedom, 99.9 %
const Eigen::Vector3d kTowPoint_S(-20.0, 0.0, 0.0);  // [m] the configuration's default tow_point

// The ship at t [s] after the start: position (ENU) and yaw.
void shipAt(double t, Eigen::Vector3d& p, double& yaw)
{
  if (t <= kTurnAt)
  {
    p = Eigen::Vector3d(kSpeed * t, 0.0, 0.0);
    yaw = 0.0;
    return;
  }
  yaw = kSpeed * (t - kTurnAt) / kRadius;
  p = Eigen::Vector3d(kSpeed * kTurnAt + kRadius * std::sin(yaw), kRadius * (1.0 - std::cos(yaw)), 0.0);
}

struct Received
{
  std::mutex mutex;
  std::map<double, Eigen::Vector3d> vehicle;  // t after the start -> position
  std::vector<geometry_msgs::PoseWithCovarianceStamped> poses;
  std::vector<sensor_msgs::NavSatFix> fixes;
  std::map<double, double> layback, cross_track;
  std::map<std::string, std::string> diagnostics;  // the latest tow_nav values by key
  std::map<std::string, std::string> before;       // the same just before the bad measurements
};

bool vehicleAt(const Received& r, double t, Eigen::Vector3d& p)
{
  auto after = r.vehicle.lower_bound(t);
  if (after == r.vehicle.begin() || after == r.vehicle.end())
    return false;
  auto before = std::prev(after);
  const double w = (t - before->first) / (after->first - before->first);
  p = (1.0 - w) * before->second + w * after->second;
  return true;
}

Eigen::Vector3d positionOf(const geometry_msgs::PoseWithCovarianceStamped& m)
{
  return Eigen::Vector3d(m.pose.pose.position.x, m.pose.pose.position.y, m.pose.pose.position.z);
}

Eigen::Matrix3d covarianceOf(const geometry_msgs::PoseWithCovarianceStamped& m)
{
  Eigen::Matrix3d P;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      P(r, c) = m.pose.covariance[6 * r + c];
  return P;
}

double since(const ros::Time& stamp)
{
  return stamp.toSec() - kT0;
}

std::vector<ros::Subscriber> listen(ros::NodeHandle& nh, Received& r)
{
  std::vector<ros::Subscriber> subs;
  subs.push_back(nh.subscribe<nav_msgs::Odometry>("/vehicle/odom", 100,
                                                  [&r](const nav_msgs::Odometry::ConstPtr& m)
                                                  {
                                                    std::lock_guard<std::mutex> lock(r.mutex);
                                                    const auto& p = m->pose.pose.position;
                                                    r.vehicle[since(m->header.stamp)] = Eigen::Vector3d(p.x, p.y, p.z);
                                                  }));
  subs.push_back(nh.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
      "/nav/fish/pose", 100,
      [&r](const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& m)
      {
        std::lock_guard<std::mutex> lock(r.mutex);
        r.poses.push_back(*m);
      }));
  subs.push_back(nh.subscribe<sensor_msgs::NavSatFix>("/nav/fish/fix", 100,
                                                      [&r](const sensor_msgs::NavSatFix::ConstPtr& m)
                                                      {
                                                        std::lock_guard<std::mutex> lock(r.mutex);
                                                        r.fixes.push_back(*m);
                                                      }));
  for (const char* topic : { "/nav/layback", "/nav/cross_track" })
  {
    std::map<double, double>& into = std::string(topic) == "/nav/layback" ? r.layback : r.cross_track;
    subs.push_back(nh.subscribe<tow_sim::SensorValue>(topic, 100,
                                                      [&r, &into](const tow_sim::SensorValue::ConstPtr& m)
                                                      {
                                                        std::lock_guard<std::mutex> lock(r.mutex);
                                                        into[since(m->header.stamp)] = m->value;
                                                      }));
  }
  subs.push_back(
      nh.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 20,
                                                     [&r](const diagnostic_msgs::DiagnosticArray::ConstPtr& m)
                                                     {
                                                       std::lock_guard<std::mutex> lock(r.mutex);
                                                       for (const auto& status : m->status)
                                                         if (status.name.rfind("tow_nav", 0) == 0)
                                                           for (const auto& kv : status.values)
                                                             r.diagnostics[kv.key] = kv.value;
                                                     }));
  return subs;
}

nav_msgs::Odometry odometryAt(double t)
{
  Eigen::Vector3d p;
  double yaw = 0.0;
  shipAt(t, p, yaw);
  nav_msgs::Odometry odom;
  odom.header.stamp = ros::Time(kT0 + t);
  odom.header.frame_id = "odom";
  odom.child_frame_id = "ship";
  odom.pose.pose.position.x = p.x();
  odom.pose.pose.position.y = p.y();
  odom.pose.pose.orientation.z = std::sin(yaw / 2.0);
  odom.pose.pose.orientation.w = std::cos(yaw / 2.0);
  odom.twist.twist.linear.x = kSpeed;
  odom.twist.twist.angular.z = t > kTurnAt ? kSpeed / kRadius : 0.0;
  return odom;
}

// The bad measurements, each once, among the good ones.
struct Saboteur
{
  ros::Publisher depth, usbl, fix;
  GeographicLib::LocalCartesian origin{ 43.10, 5.90, 0.0 };

  void at(double t)
  {
    const ros::Time now(kT0 + t);
    tow_sim::SensorValue d;
    if (std::abs(t - 120.0) < 1e-6)  // no number
    {
      d.header.stamp = now + ros::Duration(0.013);
      d.value = std::nan("");
      depth.publish(d);
    }
    if (std::abs(t - 125.0) < 1e-6)  // 600 m below the seabed
    {
      d.header.stamp = now + ros::Duration(0.017);
      d.value = 1000.0;
      depth.publish(d);
    }
    if (std::abs(t - 130.0) < 1e-6)  // a USBL fix 500 m to port of the fish
    {
      geometry_msgs::PointStamped p;
      p.header.stamp = now - ros::Duration(1.0);
      p.header.frame_id = "ship";
      p.point.x = -170.0;
      p.point.y = 500.0;
      p.point.z = -60.0;
      usbl.publish(p);
    }
    if (std::abs(t - 135.0) < 1e-6)  // a ship fix 30 s in the past
    {
      Eigen::Vector3d s;
      double yaw = 0.0;
      shipAt(t - 30.0, s, yaw);
      sensor_msgs::NavSatFix f;
      f.header.stamp = now - ros::Duration(30.0);
      f.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
      origin.Reverse(s.x(), s.y(), 0.0, f.latitude, f.longitude, f.altitude);
      fix.publish(f);
    }
  }
};

Received& played()
{
  static Received r;
  static bool done = false;
  if (done)
    return r;
  done = true;
  ros::NodeHandle nh;
  std::vector<ros::Subscriber> subs = listen(nh, r);
  ros::Publisher clock = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  ros::Publisher odom = nh.advertise<nav_msgs::Odometry>("/ship/odom", 50);
  Saboteur bad{ nh.advertise<tow_sim::SensorValue>("/survey/fish/depth", 10),
                nh.advertise<geometry_msgs::PointStamped>("/survey/usbl", 10),
                nh.advertise<sensor_msgs::NavSatFix>("/survey/ship/fix", 10) };
  ros::WallDuration(2.0).sleep();  // the nodes connect
  for (int k = 0; k * kStep <= kEnd + 1e-9 && ros::ok(); ++k)
  {
    const double t = k * kStep;
    rosgraph_msgs::Clock c;
    c.clock = ros::Time(kT0 + t);
    clock.publish(c);
    odom.publish(odometryAt(t));
    if (std::abs(t - 119.0) < 1e-6)
    {
      std::lock_guard<std::mutex> lock(r.mutex);
      r.before = r.diagnostics;
    }
    bad.at(t);
    ros::WallDuration(kStep / 4.0).sleep();
  }
  ros::WallDuration(1.0).sleep();
  return r;
}
}  // namespace

TEST(TowNavNode, TheEstimateIsWithinTheCovarianceItReports)
{
  Received& r = played();
  std::lock_guard<std::mutex> lock(r.mutex);
  ASSERT_GT(r.vehicle.size(), 1000u) << "tow_sim_node's vehicle/odom did not come";
  ASSERT_GT(r.poses.size(), 500u) << "tow_nav_node published too few estimates";
  int compared = 0, inside = 0;
  double sum_e2 = 0.0, largest = 0.0, widest = 0.0, widest_at = 0.0;
  for (const auto& pose : r.poses)
  {
    const double t = since(pose.header.stamp);
    Eigen::Vector3d truth;
    if (t < 50.0 || !vehicleAt(r, t, truth))  // 30 s for the model to settle after it starts at 20 s
      continue;
    const Eigen::Vector3d e = positionOf(pose) - truth;
    const Eigen::Matrix3d P = covarianceOf(pose);
    const double nees = e.dot(P.ldlt().solve(e));
    ++compared;
    inside += nees <= kChi2Point;
    sum_e2 += e.head<2>().squaredNorm();
    largest = std::max(largest, e.head<2>().norm());
    if (t >= 150.0 && std::sqrt(std::max(P(0, 0), P(1, 1))) > widest)  // after six analyses with USBL
      widest = std::sqrt(std::max(P(0, 0), P(1, 1))), widest_at = t;
  }
  ASSERT_GT(compared, 500);
  const double rms = std::sqrt(sum_e2 / compared);
  std::printf(
      "tow_nav_node: %d estimates against vehicle/odom: horizontal RMS %.2f m, largest %.2f m, %.1f %% "
      "with NEES <= %.2f, widest sigma after 150 s %.2f m at t = %.1f s\n",
      compared, rms, largest, 100.0 * inside / compared, kChi2Point, widest, widest_at);
  EXPECT_GE(inside, 0.95 * compared) << "the error is larger than the covariance it reports allows";
  EXPECT_LT(widest, 5.0) << "a covariance this wide says little about the position";
  EXPECT_LT(rms, 10.0);  // on a 200 m cable; a fish put at the ship, or on the wrong side, is 150 m off
}

TEST(TowNavNode, TheFixLaybackAndCrossTrackAgreeWithThePose)
{
  Received& r = played();
  std::lock_guard<std::mutex> lock(r.mutex);
  ASSERT_EQ(r.fixes.size(), r.poses.size());
  ASSERT_FALSE(r.poses.empty());
  const GeographicLib::LocalCartesian origin(43.10, 5.90, 0.0);
  int checked = 0;
  for (size_t i = 0; i < r.poses.size(); ++i)
  {
    const Eigen::Vector3d p = positionOf(r.poses[i]);
    const double t = since(r.poses[i].header.stamp);
    // Latitude and longitude of the pose's point on the origin's tangent plane; the altitude is the origin's
    // (0 here, the sea surface) plus its z, without the plane's rise above the ellipsoid.
    Eigen::Vector3d from_fix;
    origin.Forward(r.fixes[i].latitude, r.fixes[i].longitude, 0.0, from_fix.x(), from_fix.y(), from_fix.z());
    EXPECT_LT((from_fix - p).head<2>().norm(), 1e-3) << "at t = " << t;
    EXPECT_NEAR(r.fixes[i].altitude, p.z(), 1e-9) << "at t = " << t;
    EXPECT_NEAR(r.fixes[i].position_covariance[0], r.poses[i].pose.covariance[0], 1e-9);
    if (t < 50.0 || !r.layback.count(t) || !r.cross_track.count(t))
      continue;
    Eigen::Vector3d ship;
    double yaw = 0.0;
    shipAt(t, ship, yaw);
    const Eigen::Vector2d forward(std::cos(yaw), std::sin(yaw)), port(-std::sin(yaw), std::cos(yaw));
    const Eigen::Vector2d behind =
        (ship + Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * kTowPoint_S - p).head<2>();
    // The node's ship is its smoothed GNSS track (0.5 m noise): metres, not the tens a wrong sign would give.
    EXPECT_NEAR(r.layback.at(t), behind.dot(forward), 3.0) << "at t = " << t;
    EXPECT_NEAR(r.cross_track.at(t), -behind.dot(port), 3.0) << "at t = " << t;
    ++checked;
  }
  EXPECT_GT(checked, 500);
}

TEST(TowNavNode, BadMeasurementsAreCountedAndTheEstimateDoesNotJump)
{
  Received& r = played();
  std::lock_guard<std::mutex> lock(r.mutex);
  // Each counter's rise over the bad measurements (the diagnostics come once a second of the clock).
  auto rise = [&r](const std::string& key)
  {
    if (!r.diagnostics.count(key) || !r.before.count(key))
      return -1L;
    return std::stol(r.diagnostics.at(key)) - std::stol(r.before.at(key));
  };
  EXPECT_EQ(rise("messages refused (bad field)") - rise("USBL fixes without a ship pose around them"), 1)
      << "the NaN depth";
  EXPECT_EQ(rise("depths rejected (below the seabed)"), 1);
  EXPECT_EQ(rise("USBL fixes rejected (gate)"), 1) << "the fix 500 m off";
  EXPECT_GE(rise("messages late (after their row)"), 1) << "the fix 30 s in the past";
  double largest = 0.0, at = 0.0;
  for (size_t i = 1; i < r.poses.size(); ++i)
  {
    const double dt = since(r.poses[i].header.stamp) - since(r.poses[i - 1].header.stamp);
    ASSERT_GT(dt, 0.0) << "estimates out of time order";
    const double step = (positionOf(r.poses[i]) - positionOf(r.poses[i - 1])).head<2>().norm() - kSpeed * 1.5 * dt;
    if (step > largest)
      largest = step, at = since(r.poses[i].header.stamp);
  }
  std::printf("tow_nav_node: the largest step beyond 1.5 x the ship's speed: %.2f m at t = %.1f s\n", largest, at);
  EXPECT_LT(largest, 1.0) << "the estimate jumped at t = " << at;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_tow_nav");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
