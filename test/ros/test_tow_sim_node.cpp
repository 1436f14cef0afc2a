// rostest of tow_sim_node (the world: tow_sim_node_world.h): its topics and rates, tf, the fins' effect,
// the implicit stepper's stamps, the tow forces, diagnostics, markers, and bad odometry refused.
#include <iterator>

#include "tow_sim_node_world.h"

namespace tow_sim_test
{
namespace
{
TEST(TowSimNode, PublishesStateAndMarkersAtTheConfiguredRates)
{
  world->advance(2.0);
  int states0, markers0;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    states0 = world->rec_.state_count["base"];
    markers0 = world->rec_.marker_count["base"];
  }
  world->advance(10.0);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const int states = world->rec_.state_count["base"] - states0;
  const int markers = world->rec_.marker_count["base"] - markers0;
  std::printf("in 10 s of simulated time: %d cable/state, %d cable/markers (publish_rate 10 Hz); %d late steps\n",
              states, markers, world->lateSteps());
  // Lock-step: one publish tick per 0.1 s of clock, whatever the machine's load.
  EXPECT_NEAR(states, 100, 1);
  EXPECT_NEAR(markers, 100, 1);
  EXPECT_EQ(world->lateSteps(), 0);
  for (const char* name : kNodes)
  {
    const tow_sim::CableState& s = world->rec_.state[name];
    EXPECT_EQ(s.joints.size(), 22u) << name;  // nu + 2 joints, ship first
    EXPECT_EQ(s.tension.size(), 21u) << name;
    EXPECT_TRUE(allFinite(s)) << name;
    EXPECT_GT(s.tension_ship, 0.0) << name;
    EXPECT_EQ(s.header.frame_id, "odom");
  }
}

TEST(TowSimNode, TfToTheVehicleMatchesVehicleOdometry)
{
  tf2_ros::Buffer& buffer = world->tf_buffer_;
  world->advance(3.0);
  nav_msgs::Odometry odom;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    odom = world->rec_.odom["base"];
  }
  ASSERT_EQ(odom.child_frame_id, "base_vehicle");
  // The clock stands still between steps, so wait in wall time (a timeout in ROS time would never pass).
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(10.0);
  while (!buffer.canTransform("odom", "base_vehicle", odom.header.stamp) && ros::WallTime::now() < give_up)
    ros::WallDuration(0.01).sleep();
  const geometry_msgs::TransformStamped tf = buffer.lookupTransform("odom", "base_vehicle", odom.header.stamp);
  EXPECT_NEAR(tf.transform.translation.x, odom.pose.pose.position.x, 1e-9);
  EXPECT_NEAR(tf.transform.translation.y, odom.pose.pose.position.y, 1e-9);
  EXPECT_NEAR(tf.transform.translation.z, odom.pose.pose.position.z, 1e-9);
  EXPECT_NEAR(tf.transform.rotation.w, odom.pose.pose.orientation.w, 1e-9);
  EXPECT_NEAR(tf.transform.rotation.z, odom.pose.pose.orientation.z, 1e-9);
  EXPECT_LT(odom.pose.pose.position.z, -10.0);  // the vehicle is under water, astern of the ship
}

TEST(TowSimNode, ElevatorRaisesTheVehicleRudderMovesItToPort)
{
  for (int i = 0; i < 3; ++i)
  {
    world->command("elevator", 0.0, 0.3);
    world->command("rudder", 0.3, 0.0);
    world->advance(0.1);
  }
  world->advance(40.0);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const auto& base = world->rec_.state["base"];
  const auto& up = world->rec_.state["elevator"];
  const auto& port = world->rec_.state["rudder"];
  std::printf("after 40 s: depth base %.3f m, elevator %.3f m; diversion base %.3f m, rudder %.3f m\n",
              base.vehicle_depth, up.vehicle_depth, base.diversion, port.diversion);
  EXPECT_LT(up.vehicle_depth, base.vehicle_depth - 0.1);
  EXPECT_GT(port.diversion, base.diversion + 0.1);
}

// The default implicit stepper's node (base) integrates in its own steps, past the clock, and publishes
// outputs interpolated at the clock's time: the same stamps as the dopri5 node beside it, which ends a
// step at each physics tick, and the same tow.
TEST(TowSimNode, TheImplicitStepperPublishesAtTheClockFromItsOwnSteps)
{
  world->advance(20.0);
  // Both nodes stamp their outputs with the clock's time at their tick. The clock goes out every 10 ms and
  // a node under load may skip some of it (roscpp keeps one /clock message), so the two nodes' stamps need
  // not coincide (CI once saw none in common among the last 100): compare the base node at its latest stamp
  // within the dopri5 node's, against dopri5's outputs interpolated linearly between its two stamps around it
  // (at most 0.25 s apart; the same stamp when both published at it). It must be recent.
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const auto& dopri5_kept = world->rec_.state_by_stamp["dopri5"];
  const auto& implicit_kept = world->rec_.state_by_stamp["base"];
  ASSERT_FALSE(dopri5_kept.empty());
  ASSERT_FALSE(implicit_kept.empty());
  auto common = implicit_kept.rbegin();
  auto before = dopri5_kept.end(), after = dopri5_kept.end();
  for (; common != implicit_kept.rend(); ++common)
  {
    after = dopri5_kept.lower_bound(common->first);
    if (after == dopri5_kept.end() || (after->first != common->first && after == dopri5_kept.begin()))
      continue;
    before = after->first == common->first ? after : std::prev(after);
    if ((after->first - before->first).toSec() <= 0.25)
      break;
  }
  ASSERT_NE(common, implicit_kept.rend()) << "no stamp of the base node within 0.25 s stamps of the dopri5 node";
  EXPECT_LT((implicit_kept.rbegin()->first - common->first).toSec(), 1.0) << "the compared stamp is old";
  const double span = (after->first - before->first).toSec();
  const double w = span > 0.0 ? (common->first - before->first).toSec() / span : 0.0;
  auto at = [&](double tow_sim::CableState::*field)
  { return (1.0 - w) * before->second.*field + w * after->second.*field; };
  const auto& implicit = common->second;
  const double depth = at(&tow_sim::CableState::vehicle_depth), tension = at(&tow_sim::CableState::tension_ship);
  std::printf(
      "implicit vs dopri5 node at %.3f s (latest %.3f s; dopri5 %.3f .. %.3f s): depth %.4f vs %.4f m, "
      "tension %.2f vs %.2f N\n",
      common->first.toSec(), implicit_kept.rbegin()->first.toSec(), before->first.toSec(), after->first.toSec(),
      implicit.vehicle_depth, depth, implicit.tension_ship, tension);
  EXPECT_NEAR(implicit.vehicle_depth, depth, 1e-3 * depth);
  EXPECT_NEAR(implicit.tension_ship, tension, 5e-3 * tension);
  EXPECT_NEAR(implicit.layback, at(&tow_sim::CableState::layback), 1e-3 * at(&tow_sim::CableState::layback));
  EXPECT_TRUE(allFinite(implicit));
}

// The cable's forces out: on the ship -T_1 at the tow point (world frame), on the vehicle T_{nu+1} at the
// bail in the vehicle frame with its moment about the CG; checked against cable/state and vehicle/odom of
// the same stamp (the elevator node's vehicle is pitched by its fins).
TEST(TowSimNode, PublishesTheTowForcesOnShipAndVehicle)
{
  world->advance(1.0);
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(5.0);
  for (const char* node : { "base", "elevator" })
  {
    const std::string n = node;
    tow_sim::CableState state;
    nav_msgs::Odometry odom;
    geometry_msgs::WrenchStamped ship, vehicle;
    for (bool found = false; !found;)
    {
      {
        std::lock_guard<std::mutex> lock(world->rec_.mutex);
        state = world->rec_.state[n];
        const ros::Time stamp = state.header.stamp;
        found = world->rec_.ship_force[n].count(stamp) && world->rec_.vehicle_force[n].count(stamp) &&
                world->rec_.odom_by_stamp[n].count(stamp);
        if (found)
        {
          ship = world->rec_.ship_force[n][stamp];
          vehicle = world->rec_.vehicle_force[n][stamp];
          odom = world->rec_.odom_by_stamp[n][stamp];
        }
      }
      ASSERT_TRUE(found || ros::WallTime::now() < give_up) << n << ": no forces stamped as the state";
      if (!found)
        ros::WallDuration(0.01).sleep();
    }
    const auto vec = [](const geometry_msgs::Vector3& v) { return Eigen::Vector3d(v.x, v.y, v.z); };
    const auto point = [](const geometry_msgs::Point& p) { return Eigen::Vector3d(p.x, p.y, p.z); };
    const size_t bail = state.tension_vector.size() - 1;
    const Eigen::Vector3d T1 = vec(state.tension_vector.front()), Tb = vec(state.tension_vector[bail]);
    const Eigen::Quaterniond q(odom.pose.pose.orientation.w, odom.pose.pose.orientation.x, odom.pose.pose.orientation.y,
                               odom.pose.pose.orientation.z);
    const Eigen::Vector3d force_W = q * vec(vehicle.wrench.force), torque_W = q * vec(vehicle.wrench.torque);
    const Eigen::Vector3d arm_W = point(state.joints[bail]) - point(odom.pose.pose.position);
    std::printf("%s: ship tow force %.2f N (T_1 %.2f N), vehicle %.2f N (bail %.2f N), moment about the CG %.2f N m\n",
                node, vec(ship.wrench.force).norm(), state.tension_ship, force_W.norm(), state.tension_vehicle,
                torque_W.norm());
    EXPECT_EQ(ship.header.frame_id, "odom");
    EXPECT_EQ(vehicle.header.frame_id, n + "_vehicle");
    EXPECT_LT((vec(ship.wrench.force) + T1).norm(), 1e-9 * T1.norm());
    EXPECT_LT(vec(ship.wrench.torque).norm(), 1e-12);
    EXPECT_LT((force_W - Tb).norm(), 1e-6 * Tb.norm());
    EXPECT_NEAR(force_W.norm(), state.tension_vehicle, 1e-6 * state.tension_vehicle);
    EXPECT_LT((torque_W - arm_W.cross(Tb)).norm(), 1e-6 * std::max(1.0, arm_W.norm() * Tb.norm()));
    EXPECT_GT(arm_W.norm(), 0.01);  // the bail is not at the CG: the moment is a real check
  }
}

// cable.safe_working_load (winch node: 500 N) and cable.breaking_load (rudder node: 800 N) against tows of
// ~900 N: diagnostics WARN and ERROR with the largest tension; the base node, without limits, neither.
TEST(TowSimNode, TensionLimitsShowInDiagnostics)
{
  auto diagnostic = [](const std::string& node, const std::string& key)
  {
    for (const auto& kv : world->rec_.diagnostics)
      if (kv.first.find(node + "/tow_sim") != std::string::npos && kv.first.find(key) != std::string::npos)
        return kv.second;
    return std::string();
  };
  std::string winch, rudder, base;
  for (int i = 0; i < 20; ++i)
  {
    world->advance(0.5);
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    winch = diagnostic("winch", "/summary");
    rudder = diagnostic("rudder", "/summary");
    base = diagnostic("base", "/summary");
    if (winch.find("safe working load") != std::string::npos && rudder.find("breaking load") != std::string::npos)
      break;
  }
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const double winch_largest = std::atof(diagnostic("winch", "largest tension [N]").c_str());
  const double rudder_largest = std::atof(diagnostic("rudder", "largest tension [N]").c_str());
  std::printf("tension limits: winch '%s' (%.0f N), rudder '%s' (%.0f N), base '%s'\n", winch.c_str(), winch_largest,
              rudder.c_str(), rudder_largest, base.c_str());
  EXPECT_NE(winch.find("above the safe working load"), std::string::npos) << winch;
  EXPECT_NE(rudder.find("above the breaking load"), std::string::npos) << rudder;
  EXPECT_GT(winch_largest, 500.0);
  EXPECT_GT(rudder_largest, 800.0);
  EXPECT_EQ(base.find("load"), std::string::npos) << base;
  EXPECT_EQ(diagnostic("base", "safe working load [N]"), "0");
}

// What rviz shows besides the cable: the ship's hull outline at its odometry pose and the tow point
// (ns "ship"), and the trails of the ship and the vehicle (ns "trails") ending where they are now.
TEST(TowSimNode, MarkersShowTheShipAndTheTrails)
{
  world->advance(2.0);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const visualization_msgs::MarkerArray& array = world->rec_.markers["base"];
  auto find = [&](const std::string& ns, int id) -> const visualization_msgs::Marker*
  {
    for (const auto& m : array.markers)
      if (m.ns == ns && m.id == id)
        return &m;
    return nullptr;
  };
  const visualization_msgs::Marker *hull = find("ship", 0), *tow_point = find("ship", 1);
  const visualization_msgs::Marker *ship_trail = find("trails", 0), *vehicle_trail = find("trails", 1);
  ASSERT_TRUE(hull && tow_point && ship_trail && vehicle_trail);
  const double t = hull->header.stamp.toSec(), ship_x = 2.0 * (t - 100.0);  // the test's ship
  std::printf("markers at t = %.1f s: hull bow at x = %.3f (ship %.3f), %zu ship and %zu vehicle trail points\n", t,
              hull->points[2].x, ship_x, ship_trail->points.size(), vehicle_trail->points.size());
  ASSERT_EQ(hull->points.size(), 6u);                   // a closed outline
  EXPECT_NEAR(hull->points[2].x, ship_x + 30.0, 1e-6);  // the bow, half the default 60 m ahead
  EXPECT_NEAR(hull->points[2].y, 0.0, 1e-9);
  EXPECT_NEAR(tow_point->pose.position.x, ship_x - 20.0, 1e-6);
  EXPECT_GT(ship_trail->points.size(), 20u);  // over 40 m of track, a point per metre
  EXPECT_NEAR(ship_trail->points.back().x, ship_x, 1e-6);
  EXPECT_LT(ship_trail->points.front().x, ship_x - 20.0);
  EXPECT_LT(vehicle_trail->points.back().z, -10.0);  // under water
}

TEST(TowSimNode, RejectsBadOdometryAndKeepsRunning)
{
  nav_msgs::Odometry good = world->shipOdometry();
  auto send = [&](nav_msgs::Odometry m)
  {
    m.header.stamp = ros::Time(world->time_ + 0.001);
    world->robust_odom_pub_.publish(m);
    ros::WallDuration(0.05).sleep();
  };
  nav_msgs::Odometry bad = good;
  bad.pose.pose.position.x = std::numeric_limits<double>::quiet_NaN();
  send(bad);
  bad = good;
  bad.pose.pose.orientation.w = 0.0;  // zero quaternion
  send(bad);
  bad = good;
  bad.pose.pose.position.y += 5000.0;  // a jump of kilometres
  send(bad);
  bad = good;
  bad.header.frame_id = "map";
  send(bad);
  bad = good;
  bad.header.stamp = ros::Time(world->time_ - 50.0);  // backwards in time
  world->robust_odom_pub_.publish(bad);
  ros::WallDuration(0.05).sleep();
  bad = good;
  bad.header.stamp = ros::TIME_MAX;  // 136 years ahead: ros::Time arithmetic on it throws
  world->robust_odom_pub_.publish(bad);
  ros::WallDuration(0.05).sleep();
  world->advance(5.0);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const auto& robust = world->rec_.state["robust"];
  const auto& base = world->rec_.state["base"];
  EXPECT_TRUE(allFinite(robust));
  EXPECT_NEAR(robust.vehicle_depth, base.vehicle_depth, 0.5);  // unharmed: it follows the good odometry
  EXPECT_NEAR(robust.joints[0].y, 0.0, 1e-6);                  // the kilometre jump never got in
  bool found = false;
  for (const auto& kv : world->rec_.diagnostics)
    if (kv.first.find("robust") != std::string::npos && kv.first.find("rejected messages") != std::string::npos)
    {
      std::printf("%s = %s\n", kv.first.c_str(), kv.second.c_str());
      found = std::atoi(kv.second.c_str()) >= 6;
    }
  EXPECT_TRUE(found) << "the robust node's diagnostics do not report the 6 rejected odometry messages";
}

}  // namespace
}  // namespace tow_sim_test
