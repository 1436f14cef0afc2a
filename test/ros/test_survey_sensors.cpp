// rostest: tow_sim_node's survey sensors (docs/survey.md, "In tow_sim_node"), noiseless (survey_config.yaml).
// The test plays a ship at 2 m/s on a heading of 60 deg from east and checks over 25 s:
// - the GNSS fix against the ship's track, converted back with GeographicLib about the configured origin;
// - the heading against the track's;
// - the cable counter against the cable's length;
// - the depth and the pressure against the node's own vehicle/odom at the same stamp (interpolated);
// - the AHRS's yaw against vehicle/odom's;
// - the USBL fix, in the ship frame, against vehicle/odom put into that frame.
// It also checks each topic's rate, the USBL's latency (its stamp 1 s before it arrives, plus the node's
// 0.2 s odometry delay), and that there is no altimeter without a seabed.
#include <gtest/gtest.h>

#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/Range.h>
#include <GeographicLib/LocalCartesian.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <vector>

#include "tow_sim/SensorValue.h"

namespace
{
constexpr double kSpeed = 2.0, kYaw = M_PI / 3;  // [m/s], [rad] from east toward north

Eigen::Vector3d truth(double t)  // the ship at t [s] after the start, ENU [m]
{
  return Eigen::Vector3d(30.0, -20.0, 0.0) + kSpeed * t * Eigen::Vector3d(std::cos(kYaw), std::sin(kYaw), 0.0);
}

double yawOf(const geometry_msgs::Quaternion& q)
{
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

struct Received
{
  std::mutex mutex;
  std::map<ros::Time, nav_msgs::Odometry> vehicle;
  std::vector<sensor_msgs::NavSatFix> fixes;
  std::vector<geometry_msgs::QuaternionStamped> headings;
  std::vector<tow_sim::SensorValue> cable_out, tension, depth;
  std::vector<sensor_msgs::FluidPressure> pressure;
  std::vector<sensor_msgs::Imu> imu;
  std::vector<std::pair<ros::Time, geometry_msgs::PointStamped>> usbl;  // with the time it came
  int altitudes = 0;
  ros::Time start;  // the ship's track begins
};

Eigen::Vector3d shipAt(const Received& r, const ros::Time& stamp)
{
  return truth((stamp - r.start).toSec());
}

// vehicle/odom's position and yaw at stamp, linear between the two around it (false outside them).
bool vehicleAt(const Received& r, const ros::Time& stamp, Eigen::Vector3d& p, double& yaw)
{
  auto after = r.vehicle.lower_bound(stamp);
  if (after == r.vehicle.begin() || after == r.vehicle.end())
    return false;
  auto before = std::prev(after);
  const double w = (stamp - before->first).toSec() / (after->first - before->first).toSec();
  auto at = [](const nav_msgs::Odometry& o)
  { return Eigen::Vector3d(o.pose.pose.position.x, o.pose.pose.position.y, o.pose.pose.position.z); };
  p = (1.0 - w) * at(before->second) + w * at(after->second);
  const double y0 = yawOf(before->second.pose.pose.orientation), y1 = yawOf(after->second.pose.pose.orientation);
  yaw = y0 + w * std::remainder(y1 - y0, 2.0 * M_PI);
  return true;
}

template <class M>
ros::Subscriber keep(ros::NodeHandle& nh, const std::string& topic, Received& r, std::vector<M>& into)
{
  return nh.subscribe<M>(topic, 100,
                         [&r, &into](const typename M::ConstPtr& m)
                         {
                           std::lock_guard<std::mutex> lock(r.mutex);
                           into.push_back(*m);
                         });
}

// The ship's sensors: the fix (about the origin of survey_config.yaml), the heading, the counter, the load cell.
void checkShip(const Received& r, const ros::Time& start)
{
  const GeographicLib::LocalCartesian origin(43.10, 5.90, 0.0);
  double worst_fix = 0.0;
  for (const sensor_msgs::NavSatFix& f : r.fixes)
  {
    double x = 0.0, y = 0.0, z = 0.0;
    origin.Forward(f.latitude, f.longitude, f.altitude, x, y, z);
    worst_fix = std::max(worst_fix, (Eigen::Vector2d(x, y) - truth((f.header.stamp - start).toSec()).head<2>()).norm());
    EXPECT_EQ(f.header.frame_id, "ship");
    EXPECT_EQ(f.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN);
  }
  double worst_heading = 0.0;
  for (const geometry_msgs::QuaternionStamped& h : r.headings)
    worst_heading = std::max(worst_heading, std::abs(std::remainder(yawOf(h.quaternion) - kYaw, 2.0 * M_PI)));
  std::printf("%zu fixes (worst %.4f m off the track), %zu headings (worst %.2e rad), %zu counts, %zu tensions\n",
              r.fixes.size(), worst_fix, r.headings.size(), worst_heading, r.cable_out.size(), r.tension.size());
  EXPECT_GE(r.fixes.size(), 18u);  // 1 Hz over the ~24 s the cable is out
  EXPECT_LE(r.fixes.size(), 27u);
  EXPECT_LT(worst_fix, 0.1);
  EXPECT_GE(r.headings.size(), 180u);  // 10 Hz
  EXPECT_LT(worst_heading, 1e-6);
  EXPECT_GE(r.cable_out.size(), 18u);
  for (const tow_sim::SensorValue& c : r.cable_out)
    EXPECT_NEAR(c.value, 150.0, 1e-9);
  EXPECT_GE(r.tension.size(), 180u);
  for (const tow_sim::SensorValue& t : r.tension)
    EXPECT_TRUE(std::isfinite(t.value) && t.value > 0.0);
}

// The fish's sensors against the node's own vehicle/odom at their stamps.
void checkFish(const Received& r)
{
  Eigen::Vector3d p;
  double yaw = 0.0, worst_depth = 0.0, worst_yaw = 0.0, worst_usbl = 0.0, latency_lo = 1e9, latency_hi = 0.0;
  int compared = 0;
  for (const tow_sim::SensorValue& d : r.depth)
    if (vehicleAt(r, d.header.stamp, p, yaw))
      worst_depth = std::max(worst_depth, std::abs(d.value + p.z())), ++compared;
  for (size_t i = 0; i < r.pressure.size() && i < r.depth.size(); ++i)
    EXPECT_NEAR(r.pressure[i].fluid_pressure, 101325.0 + 1025.0 * 9.81 * r.depth[i].value, 1e-6);
  for (const sensor_msgs::Imu& m : r.imu)
    if (vehicleAt(r, m.header.stamp, p, yaw))
      worst_yaw = std::max(worst_yaw, std::abs(std::remainder(yawOf(m.orientation) - yaw, 2.0 * M_PI)));
  for (const auto& [came, u] : r.usbl)
  {
    latency_lo = std::min(latency_lo, (came - u.header.stamp).toSec());
    latency_hi = std::max(latency_hi, (came - u.header.stamp).toSec());
    if (!vehicleAt(r, u.header.stamp, p, yaw))
      continue;
    const Eigen::Vector3d in_ship(u.point.x, u.point.y, u.point.z);
    const Eigen::Vector3d ship = shipAt(r, u.header.stamp);
    const Eigen::Vector3d world = ship + Eigen::AngleAxisd(kYaw, Eigen::Vector3d::UnitZ()) * in_ship;
    worst_usbl = std::max(worst_usbl, (world - p).norm());
  }
  std::printf(
      "%zu depths (%d compared, worst %.3f m), %zu AHRS (worst yaw %.4f rad), %zu USBL fixes (worst %.3f m, "
      "latency %.2f .. %.2f s), %d altitudes\n",
      r.depth.size(), compared, worst_depth, r.imu.size(), worst_yaw, r.usbl.size(), worst_usbl, latency_lo, latency_hi,
      r.altitudes);
  EXPECT_GE(compared, 15);
  EXPECT_LT(worst_depth, 0.2);
  EXPECT_EQ(r.pressure.size(), r.depth.size());
  EXPECT_GE(r.imu.size(), 150u);
  EXPECT_LT(worst_yaw, 0.01);
  EXPECT_GE(r.usbl.size(), 15u);
  EXPECT_LT(worst_usbl, 0.3);
  EXPECT_GE(latency_lo, 1.0);  // its stamp is the instant it measures, 1 s before it comes
  EXPECT_LT(latency_hi, 2.0);
  EXPECT_EQ(r.altitudes, 0);  // no seabed, no altimeter
}

void checkAgainstTruth(const Received& r, const ros::Time& start)
{
  checkShip(r, start);
  checkFish(r);
}

TEST(SurveySensors, EachTopicAgreesWithTheTruthAtItsRate)
{
  ros::NodeHandle nh;
  Received r;
  std::vector<ros::Subscriber> subs = {
    keep(nh, "/survey/ship/fix", r, r.fixes),      keep(nh, "/survey/ship/heading", r, r.headings),
    keep(nh, "/survey/cable_out", r, r.cable_out), keep(nh, "/survey/tension", r, r.tension),
    keep(nh, "/survey/fish/depth", r, r.depth),    keep(nh, "/survey/fish/pressure", r, r.pressure),
    keep(nh, "/survey/fish/imu", r, r.imu),
  };
  subs.push_back(nh.subscribe<nav_msgs::Odometry>("/vehicle/odom", 100,
                                                  [&r](const nav_msgs::Odometry::ConstPtr& m)
                                                  {
                                                    std::lock_guard<std::mutex> lock(r.mutex);
                                                    r.vehicle[m->header.stamp] = *m;
                                                  }));
  subs.push_back(nh.subscribe<geometry_msgs::PointStamped>("/survey/usbl", 10,
                                                           [&r](const geometry_msgs::PointStamped::ConstPtr& m)
                                                           {
                                                             std::lock_guard<std::mutex> lock(r.mutex);
                                                             r.usbl.emplace_back(ros::Time::now(), *m);
                                                           }));
  subs.push_back(nh.subscribe<sensor_msgs::Range>("/survey/fish/altitude", 10,
                                                  [&r](const sensor_msgs::Range::ConstPtr&)
                                                  {
                                                    std::lock_guard<std::mutex> lock(r.mutex);
                                                    ++r.altitudes;
                                                  }));
  ros::Publisher odom_pub = nh.advertise<nav_msgs::Odometry>("/ship/odom", 10);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
  while (odom_pub.getNumSubscribers() == 0 && ros::WallTime::now() < deadline)
    ros::WallDuration(0.05).sleep();
  const ros::Time start = ros::Time::now();
  {
    std::lock_guard<std::mutex> lock(r.mutex);
    r.start = start;
  }
  nav_msgs::Odometry odom;
  odom.header.frame_id = "odom";
  odom.child_frame_id = "ship";
  odom.pose.pose.orientation.z = std::sin(kYaw / 2);
  odom.pose.pose.orientation.w = std::cos(kYaw / 2);
  odom.twist.twist.linear.x = kSpeed;
  for (int k = 0; k < 250; ++k)  // 25 s at 10 Hz
  {
    odom.header.stamp = ros::Time::now();
    const Eigen::Vector3d p = truth((odom.header.stamp - start).toSec());
    odom.pose.pose.position.x = p.x();
    odom.pose.pose.position.y = p.y();
    odom_pub.publish(odom);
    ros::WallDuration(0.1).sleep();
  }
  spinner.stop();
  std::lock_guard<std::mutex> lock(r.mutex);
  checkAgainstTruth(r, start);
}

}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_survey_sensors");
  return RUN_ALL_TESTS();
}
