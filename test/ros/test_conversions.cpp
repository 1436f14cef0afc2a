// The node's conversions between messages and the core's types, without roscore: odometry into the live
// run's input, snapshots into cable/state, vehicle/odom and the tow forces, and the tension colours. The
// expected values are worked by hand from the frames' definitions (REP-103, REP-105).
#include <gtest/gtest.h>

#include <cmath>

#include "tow_sim/config/config.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/ros/conversions.h"
#include "tow_sim/ros/gnss_ship_node.h"
#include "tow_sim/ros/markers.h"

namespace tow_sim
{
namespace
{
// A two-segment snapshot: joints along -x, the vehicle yawed 90 degrees (its x axis along world +y).
TowSnapshot snapshot()
{
  TowSnapshot s;
  s.segments = 2;
  s.joints.resize(3, 3);
  s.joints << 0.0, -10.0, -20.0, 0.0, 0.0, 0.0, 0.0, -1.0, -2.0;
  s.tensions.resize(3, 3);
  s.tensions << 100.0, 90.0, 80.0, 0.0, 0.0, 0.0, -50.0, -40.0, -30.0;
  s.slack = { false, false, true };
  s.vehicle.p_cg_W = Eigen::Vector3d(-21.0, 0.0, -2.0);
  s.vehicle.v_cg_W = Eigen::Vector3d(0.0, 2.0, 0.0);
  s.vehicle.omega_W = Eigen::Vector3d(0.0, 0.0, 0.1);
  s.attitude = Eigen::Quaterniond(Eigen::AngleAxisd(kHalfPi, Eigen::Vector3d::UnitZ()));
  return s;
}

std_msgs::Header header()
{
  std_msgs::Header h;
  h.stamp.fromSec(12.5);
  h.frame_id = "odom";
  return h;
}

TEST(Conversions, OdometryBecomesTheLiveRunsInputFieldByField)
{
  nav_msgs::Odometry m;
  m.header.frame_id = "odom";
  m.pose.pose.position.x = 1.0;
  m.pose.pose.position.y = 2.0;
  m.pose.pose.position.z = 3.0;
  m.pose.pose.orientation.w = 0.5;
  m.pose.pose.orientation.x = 0.1;
  m.pose.pose.orientation.y = 0.2;
  m.pose.pose.orientation.z = 0.3;
  m.twist.twist.linear.x = 4.0;
  m.twist.twist.linear.y = 5.0;
  m.twist.twist.linear.z = 6.0;
  m.twist.twist.angular.x = 7.0;
  m.twist.twist.angular.y = 8.0;
  m.twist.twist.angular.z = 9.0;
  const OdometryInput in = ros_conv::toOdometryInput(m);
  EXPECT_EQ(in.frame_id, "odom");
  EXPECT_EQ(in.p_W, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(in.q_wxyz, Eigen::Vector4d(0.5, 0.1, 0.2, 0.3));  // w first, as sent (not normalised here)
  EXPECT_EQ(in.v_S, Eigen::Vector3d(4.0, 5.0, 6.0));          // the ship frame's, as REP-105 has it
  EXPECT_EQ(in.w_S, Eigen::Vector3d(7.0, 8.0, 9.0));
}

TEST(Conversions, CableStateCarriesTheJointsAndEachTensionsSizeAndVector)
{
  const tow_sim::CableState c = ros_conv::toCableState(snapshot(), header());
  ASSERT_EQ(c.joints.size(), 3u);
  EXPECT_EQ(c.joints[2].x, -20.0);
  EXPECT_EQ(c.joints[2].z, -2.0);
  ASSERT_EQ(c.tension.size(), 3u);
  EXPECT_DOUBLE_EQ(c.tension[0], std::hypot(100.0, 50.0));
  EXPECT_EQ(c.tension_vector[1].z, -40.0);
  EXPECT_EQ(c.slack, (std::vector<uint8_t>{ 0, 0, 1 }));
  EXPECT_EQ(c.header.frame_id, "odom");
}

// vehicle/odom: the twist in the vehicle's own axes. Yawed 90 degrees, the world's +y is its forward x,
// and a yaw rate about world z is one about its z.
TEST(Conversions, VehicleOdometryHasItsTwistInTheVehicleFrame)
{
  const nav_msgs::Odometry o = ros_conv::toVehicleOdometry(snapshot(), header(), "fish");
  EXPECT_EQ(o.child_frame_id, "fish");
  EXPECT_EQ(o.pose.pose.position.x, -21.0);
  EXPECT_NEAR(o.twist.twist.linear.x, 2.0, 1e-12);
  EXPECT_NEAR(o.twist.twist.linear.y, 0.0, 1e-12);
  EXPECT_NEAR(o.twist.twist.angular.z, 0.1, 1e-12);
  EXPECT_NEAR(o.pose.pose.orientation.z, std::sin(kPi / 4.0), 1e-12);
}

// The ship feels -T_1 (the cable pulls it aft and down here); after a parting, the pull of the cable left
// on it, none when none is left.
TEST(Conversions, TheShipFeelsMinusT1AndAfterAPartingWhatHangsFromIt)
{
  TowSnapshot s = snapshot();
  geometry_msgs::WrenchStamped w = ros_conv::toShipTowForce(s, header());
  EXPECT_EQ(w.wrench.force.x, -100.0);
  EXPECT_EQ(w.wrench.force.z, 50.0);
  EXPECT_EQ(w.wrench.torque.x, 0.0);
  s.parted = true;
  w = ros_conv::toShipTowForce(s, header());
  EXPECT_EQ(w.wrench.force.x, 0.0);
  s.ship_side_tensions = Eigen::Matrix3Xd::Zero(3, 1);
  s.ship_side_tensions.col(0) = Eigen::Vector3d(0.0, 0.0, 30.0);
  w = ros_conv::toShipTowForce(s, header());
  EXPECT_EQ(w.wrench.force.z, -30.0);
}

// The pull on the vehicle, T_{nu+1} at the bail, in the vehicle frame with its moment about the CG: the bail
// 1 m ahead of the CG along world x (the vehicle's -y), the pull (80, 0, -30) N in the world.
TEST(Conversions, TheVehicleFeelsTheLastTensionWithItsMomentAboutTheCG)
{
  const geometry_msgs::WrenchStamped w = ros_conv::toVehicleTowForce(snapshot(), header(), "fish");
  EXPECT_EQ(w.header.frame_id, "fish");
  // World (80, 0, -30) in axes x = world y, y = world -x, z = world z: (0, -80, -30).
  EXPECT_NEAR(w.wrench.force.x, 0.0, 1e-12);
  EXPECT_NEAR(w.wrench.force.y, -80.0, 1e-12);
  EXPECT_NEAR(w.wrench.force.z, -30.0, 1e-12);
  // Arm (1, 0, 0) x force (80, 0, -30) = (0, 30, 0) in the world; in the vehicle axes (30, 0, 0).
  EXPECT_NEAR(w.wrench.torque.x, 30.0, 1e-12);
  EXPECT_NEAR(w.wrench.torque.y, 0.0, 1e-12);
}

TEST(Conversions, TensionColoursRunBlueGreenRedAndMagentaForSlack)
{
  auto rgb = [](double t, bool slack)
  {
    const std_msgs::ColorRGBA c = ros_conv::tensionColor(t, 1000.0, slack);
    return Eigen::Vector4d(c.r, c.g, c.b, c.a);
  };
  EXPECT_EQ(rgb(0.0, false), Eigen::Vector4d(0, 0, 1, 1));
  EXPECT_EQ(rgb(500.0, false), Eigen::Vector4d(0, 1, 0, 1));
  EXPECT_EQ(rgb(1000.0, false), Eigen::Vector4d(1, 0, 0, 1));
  EXPECT_EQ(rgb(5000.0, false), Eigen::Vector4d(1, 0, 0, 1));
  EXPECT_EQ(rgb(250.0, false), Eigen::Vector4d(0, 0.5, 0.5, 1));
  EXPECT_EQ(rgb(500.0, true), Eigen::Vector4d(1, 0, 1, 1));
}

// cable.sections and cable.bodies as the parameter server holds them (rosparam load of a YAML file: lists of
// structs, integers where the file wrote no decimal point) reach the configuration loader intact.
TEST(Conversions, CableSectionsAndBodiesFromTheParameterServer)
{
  XmlRpc::XmlRpcValue tree, cable, upper, lower, clump;
  upper["length"] = 400;
  upper["segments"] = 40;
  lower["length"] = 150.0;
  lower["segments"] = 30;
  lower["diameter"] = 0.012;
  clump["at"] = 400;
  clump["mass"] = 500.0;
  clump["drag_area"] = 0.3;
  cable["diameter"] = 0.017;
  cable["sections"][0] = upper;
  cable["sections"][1] = lower;
  cable["bodies"][0] = clump;
  tree["cable"] = cable;
  const SimulationConfig c = loadConfig(ros_conv::toYaml(tree), "/tow_sim/");
  ASSERT_EQ(c.sections.size(), 2u);
  EXPECT_EQ(c.sections[0].length, 400.0);
  EXPECT_EQ(c.sections[0].diameter, 0.017);
  EXPECT_EQ(c.sections[1].segments, 30);
  EXPECT_EQ(c.sections[1].diameter, 0.012);
  EXPECT_EQ(c.cable.length, 550.0);
  ASSERT_EQ(c.bodies.size(), 1u);
  EXPECT_EQ(jointBodies(c).front().joint, 30);
  EXPECT_EQ(c.bodies[0].body.mass, 500.0);
}

// Sections and point bodies in cable/state (each segment's section; each body's joint and pull above, 0 and
// -1 once off the vehicle side) and in the markers (a strip a section, of its own width; a sphere a body,
// yellow when it floats).
TEST(Conversions, SectionsAndBodiesInCableStateAndMarkers)
{
  TowSnapshot s = snapshot();
  s.segment_section = { 0, 1 };
  s.bodies.resize(2);
  s.bodies[0].joint = 1;
  s.bodies[0].p_W = s.joints.col(1);
  s.bodies[0].tension_above = Eigen::Vector3d(0.0, 3.0, 4.0);
  s.bodies[1].joint = -1;
  const tow_sim::CableState c = ros_conv::toCableState(s, header());
  EXPECT_EQ(c.section, (std::vector<uint16_t>{ 0, 1 }));
  EXPECT_EQ(c.body_joint, (std::vector<int32_t>{ 1, -1 }));
  EXPECT_EQ(c.body_tension_above, (std::vector<double>{ 5.0, 0.0 }));

  SimulationConfig config;
  config.sections = { CableParams(), CableParams() };
  config.sections[1].diameter = 2.0 * config.sections[0].diameter;
  config.bodies.resize(2);
  config.bodies[0].body.mass = 100.0;
  config.bodies[0].body.displaced_volume = 0.01;  // a clump
  config.bodies[1].body.displaced_volume = 0.5;   // a float
  const CableLook look = cableLook(config, 0.1);
  EXPECT_EQ(look.section_widths, (std::vector<double>{ 0.1, 0.2 }));
  EXPECT_EQ(look.body_floats, (std::vector<bool>{ false, true }));
  EXPECT_NEAR(look.body_diameters[1], std::cbrt(6.0 * 0.5 / kPi), 1e-12);
  EXPECT_NEAR(look.body_diameters[0], 0.3, 1e-12);  // at least three line widths
  const visualization_msgs::MarkerArray markers =
      makeMarkers(s, VehicleParams(), nullptr, NodeParams(), header(), MarkerTrails(), look);
  std::vector<const visualization_msgs::Marker*> strips, spheres;
  for (const visualization_msgs::Marker& m : markers.markers)
  {
    if (m.ns == "cable")
      strips.push_back(&m);
    if (m.ns == "cable_bodies")
      spheres.push_back(&m);
  }
  ASSERT_EQ(strips.size(), 2u);
  EXPECT_EQ(strips[0]->points.size(), 2u);  // x_1 .. x_2
  EXPECT_EQ(strips[1]->points.size(), 2u);  // x_2 .. the bail x_3
  EXPECT_EQ(strips[1]->scale.x, 0.2);
  EXPECT_EQ(strips[1]->points[0].x, -10.0);
  ASSERT_EQ(spheres.size(), 2u);
  EXPECT_EQ(spheres[0]->pose.position.x, -10.0);
  EXPECT_EQ(spheres[0]->action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(spheres[1]->action, visualization_msgs::Marker::DELETE);
}

// The vehicle drawn vehicle_marker_scale times its size keeps its hull's centre and the fins' directions
// from it (their distances scale), turns half transparent, and its label says so; the view frame sits
// midway between the tow point and the vehicle's CG with the world's axes.
TEST(Conversions, TheEnlargedVehicleKeepsItsCentreAndTheViewFrameIsMidway)
{
  TowSnapshot s = snapshot();
  s.joints.conservativeResize(3, 4);  // the tail point after the bail: the vehicle along -x
  s.joints.col(3) = s.joints.col(2) + Eigen::Vector3d(-VehicleParams().tail_from_bail, 0.0, 0.0);
  s.attitude = Eigen::Quaterniond(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitZ()));
  s.tow_point.p_W = Eigen::Vector3d(4.0, 2.0, 0.0);
  auto find = [](const visualization_msgs::MarkerArray& a, const std::string& ns, int id)
  {
    for (const visualization_msgs::Marker& m : a.markers)
      if (m.ns == ns && m.id == id)
        return m;
    ADD_FAILURE() << ns << " " << id;
    return visualization_msgs::Marker();
  };
  NodeParams one, ten;
  ten.vehicle_marker_scale = 10.0;
  const auto a = makeMarkers(s, VehicleParams(), nullptr, one, header());
  const auto b = makeMarkers(s, VehicleParams(), nullptr, ten, header());
  const auto hull1 = find(a, "vehicle", 0), hull10 = find(b, "vehicle", 0);
  EXPECT_NEAR(hull10.pose.position.x, hull1.pose.position.x, 1e-12);
  EXPECT_NEAR(hull10.scale.x, 10.0 * hull1.scale.x, 1e-12);
  EXPECT_NEAR(hull10.scale.y, 10.0 * one.vehicle_diameter, 1e-12);
  EXPECT_EQ(hull1.color.a, 1.0);
  EXPECT_EQ(hull10.color.a, 0.5);
  const auto fin1 = find(a, "vehicle", 3), fin10 = find(b, "vehicle", 3);
  EXPECT_NEAR(fin10.pose.position.x - hull1.pose.position.x, 10.0 * (fin1.pose.position.x - hull1.pose.position.x),
              1e-9);
  EXPECT_NEAR(fin10.pose.position.y - hull1.pose.position.y, 10.0 * (fin1.pose.position.y - hull1.pose.position.y),
              1e-9);
  EXPECT_EQ(find(a, "labels", 1).text.find("drawn"), std::string::npos);
  EXPECT_NE(find(b, "labels", 1).text.find("(drawn x10)"), std::string::npos);
  EXPECT_EQ(find(b, "ship", 2).type, visualization_msgs::Marker::CUBE);  // the hull above the water

  const geometry_msgs::TransformStamped view = ros_conv::toViewTransform(s, header(), "tow_view");
  EXPECT_EQ(view.child_frame_id, "tow_view");
  EXPECT_EQ(view.header.frame_id, "odom");
  EXPECT_NEAR(view.transform.translation.x, 0.5 * (4.0 - 21.0), 1e-12);
  EXPECT_NEAR(view.transform.translation.y, 1.0, 1e-12);
  EXPECT_NEAR(view.transform.translation.z, -1.0, 1e-12);
  EXPECT_EQ(view.transform.rotation.w, 1.0);
}

// gnss_ship_node's message checks: a heading as a quaternion about z, from east (REP-103) or from north
// clockwise (a gyrocompass's, as some GNSS drivers put it in the quaternion's yaw); a fix refused naming
// its field.
TEST(Conversions, GnssHeadingConventionsAndRefusedFixes)
{
  geometry_msgs::QuaternionStamped h;
  const double psi = 30.0 * kPi / 180.0;  // the quaternion's yaw
  h.quaternion.z = std::sin(psi / 2);
  h.quaternion.w = std::cos(psi / 2);
  EXPECT_NEAR(ros_conv::headingYaw(h, "enu"), psi, 1e-12);
  EXPECT_NEAR(ros_conv::headingYaw(h, "compass"), 60.0 * kPi / 180.0, 1e-12);  // N30E is 60 deg from east
  h.quaternion.z = std::sin(kPi / 4), h.quaternion.w = std::cos(kPi / 4);      // compass 90: due east
  EXPECT_NEAR(ros_conv::headingYaw(h, "compass"), 0.0, 1e-12);
  h.quaternion.z = std::sin(kPi / 2 + 0.1), h.quaternion.w = std::cos(kPi / 2 + 0.1);  // compass 180 + 11.5 deg
  EXPECT_NEAR(ros_conv::headingYaw(h, "compass"), -kPi / 2 - 0.2, 1e-12);
  h.quaternion.w = 2.0;
  EXPECT_THROW(ros_conv::headingYaw(h, "enu"), std::invalid_argument);

  sensor_msgs::NavSatFix fix;
  fix.latitude = 43.1, fix.longitude = 5.9;
  EXPECT_EQ(ros_conv::fixProblem(fix), "");
  fix.status.status = sensor_msgs::NavSatStatus::STATUS_NO_FIX;
  EXPECT_NE(ros_conv::fixProblem(fix).find("status.status = -1 (no fix)"), std::string::npos);
  fix.status.status = sensor_msgs::NavSatStatus::STATUS_GBAS_FIX;
  fix.longitude = 181.0;
  EXPECT_EQ(ros_conv::fixProblem(fix), "longitude = 181 must be finite, in [-180, 180] [deg]");
  fix.longitude = 5.9, fix.altitude = NAN;
  EXPECT_NE(ros_conv::fixProblem(fix).find("altitude = nan"), std::string::npos);
}

}  // namespace
}  // namespace tow_sim
