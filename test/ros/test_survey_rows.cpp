// A survey vessel's messages as tow_nav's rows (tow_sim/ros/survey_rows.h), without roscore: samples of one
// instant merge into a row released after `hold`; a USBL fix in the ship frame goes into the world frame with
// the ship's fixes and headings on both sides of its stamp, even when the later ones come after it (the inverse
// of what SurveySensors does, worked by hand here);
// a pressure becomes a depth; an AHRS quaternion its yaw, pitch and roll; bad and late messages are refused and
// counted.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>
#include <cmath>

#include "tow_sim/ros/survey_rows.h"

namespace
{
using namespace tow_sim;

SurveyRowSettings settings()
{
  SurveyRowSettings s;
  s.origin_from_first_fix = false;
  s.origin_latitude = 43.1;
  s.origin_longitude = 5.9;
  s.rho_g = 1000.0 * 10.0;
  s.usbl_latency = 1.0;
  return s;
}

sensor_msgs::NavSatFix fixAt(double t, double x, double y)
{
  sensor_msgs::NavSatFix f;
  f.header.stamp = ros::Time(100.0 + t);
  f.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
  GeographicLib::LocalCartesian(43.1, 5.9, 0.0).Reverse(x, y, 0.0, f.latitude, f.longitude, f.altitude);
  return f;
}

geometry_msgs::QuaternionStamped headingAt(double t, double yaw)
{
  geometry_msgs::QuaternionStamped h;
  h.header.stamp = ros::Time(100.0 + t);
  h.quaternion.z = std::sin(yaw / 2.0);
  h.quaternion.w = std::cos(yaw / 2.0);
  return h;
}

TEST(SurveyRows, SamplesMergeIntoRowsAndAUsblFixGoesIntoTheWorld)
{
  SurveyRows rows(settings());
  // The ship at (10, 20) then (12, 20) m, heading 90 deg (north), at t = 0 and 1 s.
  EXPECT_EQ(rows.fix(fixAt(0.0, 10.0, 20.0)), "");
  EXPECT_EQ(rows.heading(headingAt(0.0, M_PI / 2)), "");
  // At t = 0.5 s (the ship at (11, 20)) the fish is 100 m astern, 5 m to port and 40 m down. Astern of a ship
  // heading north is south and port is west: the world has it at (11 - 5, 20 - 100, -40).
  geometry_msgs::PointStamped usbl;
  usbl.header.stamp = ros::Time(100.5);
  usbl.header.frame_id = "ship";
  usbl.point.x = -100.0;
  usbl.point.y = 5.0;
  usbl.point.z = -40.0;
  EXPECT_EQ(rows.usbl(usbl), "");
  // The ship's next fix comes after the USBL fix (its stamp is past the newest one when it comes): it is placed
  // between the two, not at the older one.
  EXPECT_EQ(rows.fix(fixAt(1.0, 12.0, 20.0)), "");
  EXPECT_EQ(rows.heading(headingAt(1.0, M_PI / 2)), "");
  sensor_msgs::FluidPressure p;
  p.header.stamp = ros::Time(100.0);
  p.fluid_pressure = 101325.0 + 40.0 * 1000.0 * 10.0;
  rows.pressure(p);  // depth_source is depth: ignored
  tow_sim::SensorValue depth;
  depth.header.stamp = ros::Time(100.0);
  depth.value = 40.0;
  EXPECT_EQ(rows.depth(depth), "");
  EXPECT_TRUE(rows.release(ros::Time(101.0)).empty());  // nothing is 1.5 s old yet
  const std::vector<SurveyMeasurement> out = rows.releaseAll();
  ASSERT_EQ(out.size(), 3u);  // t = 0 (fix, heading, depth), 1 (fix, heading), 1.5 (the USBL, latency 1 s on)
  EXPECT_DOUBLE_EQ(out[0].t, 0.0);
  EXPECT_NEAR(out[0].ship_x, 10.0, 1e-6);
  EXPECT_NEAR(out[0].ship_y, 20.0, 1e-6);
  EXPECT_NEAR(out[0].ship_heading, M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(out[0].fish_depth, 40.0);
  EXPECT_DOUBLE_EQ(out[2].t, 1.5);
  EXPECT_NEAR(out[2].usbl_x, 11.0 - 5.0, 1e-6);
  EXPECT_NEAR(out[2].usbl_y, 20.0 - 100.0, 1e-6);
  EXPECT_DOUBLE_EQ(out[2].usbl_z, -40.0);
  EXPECT_EQ(rows.refused(), 0);
}

TEST(SurveyRows, PressureAndAttitude)
{
  SurveyRowSettings s = settings();
  s.depth_source = "pressure";
  SurveyRows rows(s);
  sensor_msgs::FluidPressure p;
  p.header.stamp = ros::Time(100.0);
  p.fluid_pressure = 101325.0 + 40.0 * 1000.0 * 10.0;
  EXPECT_EQ(rows.pressure(p), "");
  sensor_msgs::Imu imu;
  imu.header.stamp = ros::Time(100.0);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitX()));  // yaw 0.7, 0.1 nose down, port down
  imu.orientation.x = q.x(), imu.orientation.y = q.y(), imu.orientation.z = q.z(), imu.orientation.w = q.w();
  imu.orientation_covariance = { 1e-4, 0.0, 0.0, 0.0, 2e-4, 0.0, 0.0, 0.0, 0.0 };  // yaw's variance unknown
  EXPECT_EQ(rows.imu(imu), "");
  EXPECT_EQ(rows.attitudeVariance()[0], 1e-4);  // roll
  EXPECT_EQ(rows.attitudeVariance()[1], 2e-4);  // pitch
  EXPECT_TRUE(std::isnan(rows.attitudeVariance()[2]));
  const std::vector<SurveyMeasurement> out = rows.releaseAll();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].fish_depth, 40.0, 1e-9);
  EXPECT_NEAR(out[0].fish_heading, 0.7, 1e-12);
  EXPECT_NEAR(out[0].fish_pitch, 0.1, 1e-12);
  EXPECT_NEAR(out[0].fish_roll, -0.2, 1e-12);
}

TEST(SurveyRows, BadAndLateMessagesAreRefusedAndCounted)
{
  SurveyRows rows(settings());
  tow_sim::SensorValue depth;
  depth.header.stamp = ros::Time(100.0);
  depth.value = std::nan("");
  EXPECT_NE(rows.depth(depth).find("value = nan"), std::string::npos);
  geometry_msgs::PointStamped usbl;
  usbl.header.stamp = ros::Time(100.0);
  usbl.header.frame_id = "base_link";
  EXPECT_NE(rows.usbl(usbl).find("header.frame_id"), std::string::npos);
  usbl.header.frame_id = "ship";
  usbl.point.y = std::nan("");
  EXPECT_NE(rows.usbl(usbl).find("point.y = nan"), std::string::npos);
  usbl.point.y = 0.0;
  EXPECT_EQ(rows.usbl(usbl), "");  // taken; placed when its row is due, and there is no ship fix around it
  EXPECT_EQ(rows.refused(), 3);
  depth.value = 30.0;
  depth.header.stamp = ros::Time(110.0);
  EXPECT_EQ(rows.depth(depth), "");
  EXPECT_EQ(rows.release(ros::Time(112.0)).size(), 1u);
  EXPECT_EQ(rows.unplaced(), 1);
  EXPECT_EQ(rows.refused(), 4);
  depth.header.stamp = ros::Time(109.0);  // before the row released
  EXPECT_EQ(rows.depth(depth), "");
  EXPECT_EQ(rows.late(), 1);
  EXPECT_TRUE(rows.releaseAll().empty());
}
}  // namespace
