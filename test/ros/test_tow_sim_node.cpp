// rostest of tow_sim_node. The test plays the ship and the clock (use_sim_time): six nodes get the same
// odometry, so the only differences between them are the commands and parameters. The clock moves in
// steps of 0.1 s, and the next step waits until every node has published its cable/state for this one
// (lock-step), so what the nodes see and the message counts do not depend on how fast or loaded the
// machine is.
#include <gtest/gtest.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <std_msgs/Float64.h>

#include "tow_sim/CableState.h"
#include "tow_sim/CurrentProfile.h"
#include "tow_sim/FinCommand.h"
#include "tow_sim/PlanCableOut.h"
#include "tow_sim/StateFile.h"
#include "tow_sim/config/config.h"
#include "tow_sim/scenario/towing_chart.h"

namespace
{
const char* const kNodes[] = { "base", "elevator", "rudder", "robust", "unstable", "winch", "dopri5", "gps" };
// The gps node's ship: the same track 1 km east and 500 m north, after a first fix at (0, 0, 0).
const double kGpsOffsetX = 1000.0, kGpsOffsetY = 500.0;

bool allFinite(const tow_sim::CableState& s);

struct Recorder
{
  std::mutex mutex;
  std::map<std::string, tow_sim::CableState> state;
  std::map<std::string, std::map<ros::Time, tow_sim::CableState>> state_by_stamp;  // the last 100 per node
  std::map<std::string, nav_msgs::Odometry> odom;
  std::map<std::string, std::map<ros::Time, nav_msgs::Odometry>> odom_by_stamp;  // the last 100 per node
  std::map<std::string, std::map<ros::Time, geometry_msgs::WrenchStamped>> ship_force, vehicle_force;  // last 100
  std::map<std::string, visualization_msgs::MarkerArray> markers;  // the last array per node
  std::map<std::string, int> state_count, marker_count, non_finite_states;
  std::map<std::string, std::string> diagnostics;  // "<node>/<key>" -> value
};

class World
{
public:
  World()
  {
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/ship/odom", 50);
    robust_odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/robust/ship/odom", 50);
    gps_odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/gps/ship/odom", 50);
    for (const char* name : kNodes)
    {
      const std::string n = name;
      subs_.push_back(nh_.subscribe<tow_sim::CableState>("/" + n + "/cable/state", 50,
                                                         [this, n](const tow_sim::CableState::ConstPtr& m)
                                                         {
                                                           std::lock_guard<std::mutex> lock(rec_.mutex);
                                                           rec_.state[n] = *m;
                                                           ++rec_.state_count[n];
                                                           auto& kept = rec_.state_by_stamp[n];
                                                           kept[m->header.stamp] = *m;
                                                           if (kept.size() > 100)
                                                             kept.erase(kept.begin());
                                                           if (!allFinite(*m))
                                                             ++rec_.non_finite_states[n];
                                                         }));
      subs_.push_back(nh_.subscribe<nav_msgs::Odometry>("/" + n + "/vehicle/odom", 50,
                                                        [this, n](const nav_msgs::Odometry::ConstPtr& m)
                                                        {
                                                          std::lock_guard<std::mutex> lock(rec_.mutex);
                                                          rec_.odom[n] = *m;
                                                          auto& kept = rec_.odom_by_stamp[n];
                                                          kept[m->header.stamp] = *m;
                                                          if (kept.size() > 100)
                                                            kept.erase(kept.begin());
                                                        }));
      subs_.push_back(
          nh_.subscribe<visualization_msgs::MarkerArray>("/" + n + "/cable/markers", 5,
                                                         [this, n](const visualization_msgs::MarkerArray::ConstPtr& m)
                                                         {
                                                           std::lock_guard<std::mutex> lock(rec_.mutex);
                                                           rec_.markers[n] = *m;
                                                           ++rec_.marker_count[n];
                                                         }));
      for (const char* topic : { "ship/tow_force", "vehicle/tow_force" })
      {
        const bool ship = std::string(topic) == "ship/tow_force";
        subs_.push_back(
            nh_.subscribe<geometry_msgs::WrenchStamped>("/" + n + "/" + topic, 50,
                                                        [this, n, ship](const geometry_msgs::WrenchStamped::ConstPtr& m)
                                                        {
                                                          std::lock_guard<std::mutex> lock(rec_.mutex);
                                                          auto& kept = (ship ? rec_.ship_force : rec_.vehicle_force)[n];
                                                          kept[m->header.stamp] = *m;
                                                          if (kept.size() > 100)
                                                            kept.erase(kept.begin());
                                                        }));
      }
      fin_pubs_[n] = nh_.advertise<tow_sim::FinCommand>("/" + n + "/fins/command", 5);
    }
    subs_.push_back(
        nh_.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 50,
                                                        [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m)
                                                        {
                                                          std::lock_guard<std::mutex> lock(rec_.mutex);
                                                          for (const auto& status : m->status)
                                                          {
                                                            rec_.diagnostics[status.name + "/summary"] = status.message;
                                                            for (const auto& kv : status.values)
                                                              rec_.diagnostics[status.name + "/" + kv.key] = kv.value;
                                                          }
                                                        }));
    spinner_.start();
    publishClock();
    // Wait until every node listens to the ship before the first odometry, so all start alike.
    const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(60.0);
    while ((odom_pub_.getNumSubscribers() < 5 || robust_odom_pub_.getNumSubscribers() < 1 ||
            gps_odom_pub_.getNumSubscribers() < 1 || clock_pub_.getNumSubscribers() < 6) &&
           ros::WallTime::now() < give_up)
      ros::WallDuration(0.05).sleep();
    // Each node starts at the first odometry: tick until every one has published (not a lock-step yet).
    while (ros::WallTime::now() < give_up)
    {
      {
        std::lock_guard<std::mutex> lock(rec_.mutex);
        bool all = true;
        for (const char* name : kNodes)
          all = all && rec_.state_count[name] > 0;
        // and the gps node has re-acquired its ship on the real track (1 km east)
        const auto& gps = rec_.state["gps"];
        all = all && !gps.joints.empty() && gps.joints[0].x > 500.0;
        if (all)
          break;
      }
      time_ += 0.01;
      publishClock();
      if (++tick_ % 5 == 0)
      {
        odom_pub_.publish(shipOdometry());
        robust_odom_pub_.publish(shipOdometry());
        publishGps();
      }
      ros::WallDuration(0.01).sleep();
    }
  }

  // Advances the clock by `seconds` in steps of 0.1 s (ten clock ticks of 10 ms, the ship towing at 2 m/s
  // along +x with its odometry at 20 Hz); after each step it waits until every node has published a
  // cable/state (publish_rate 10 Hz: once per step), at most `wait` of wall time, else the step counts as late.
  void advance(double seconds, double wait = 10.0)
  {
    const int steps = static_cast<int>(std::round(seconds / 0.1));
    for (int i = 0; i < steps; ++i)
    {
      std::map<std::string, int> before;
      {
        std::lock_guard<std::mutex> lock(rec_.mutex);
        before = rec_.state_count;
      }
      for (int tick = 0; tick < 10; ++tick)
      {
        time_ += 0.01;
        publishClock();
        if (++tick_ % 5 == 0)
        {
          nav_msgs::Odometry odom = shipOdometry();
          odom_pub_.publish(odom);
          robust_odom_pub_.publish(odom);
          publishGps();
        }
      }
      waitForEveryNode(before, wait);
    }
  }

  int lateSteps() const { return late_steps_; }
  nav_msgs::Odometry shipOdometry() const
  {
    nav_msgs::Odometry odom;
    odom.header.stamp = ros::Time(time_);
    odom.header.frame_id = "odom";
    odom.child_frame_id = "ship";
    odom.pose.pose.position.x = 2.0 * (time_ - 100.0);
    odom.pose.pose.orientation.w = 1.0;
    odom.twist.twist.linear.x = 2.0;
    return odom;
  }

  // The gps node's odometry: (0, 0, 0) first (a driver before its fix), then the ship's track offset.
  void publishGps()
  {
    nav_msgs::Odometry odom = shipOdometry();
    bool started;
    {
      std::lock_guard<std::mutex> lock(rec_.mutex);
      started = rec_.state_count["gps"] > 0;
    }
    gps_fixed_ = gps_fixed_ || started;
    if (!gps_fixed_)  // zeros until the node has started on them, whenever it connects
    {
      odom.pose.pose.position.x = odom.pose.pose.position.y = 0.0;
      odom.twist.twist.linear.x = 0.0;
    }
    else
    {
      odom.pose.pose.position.x += kGpsOffsetX;
      odom.pose.pose.position.y += kGpsOffsetY;
    }
    gps_odom_pub_.publish(odom);
  }

  void command(const std::string& node, double rudder, double elevator)
  {
    tow_sim::FinCommand cmd;
    cmd.rudder = rudder;
    cmd.elevator = elevator;
    fin_pubs_[node].publish(cmd);
  }

  ros::NodeHandle nh_;
  Recorder rec_;
  // Listening from the start: the lock-step clock runs far faster than real time, so a listener made
  // later could miss every transform before its subscription is connected.
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_{ tf_buffer_ };
  double time_ = 100.0;
  ros::Publisher robust_odom_pub_, gps_odom_pub_;
  bool gps_fixed_ = false;  // the gps node has started on the zeros: its real track follows

private:
  void waitForEveryNode(const std::map<std::string, int>& before, double wait)
  {
    const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(wait);
    while (ros::WallTime::now() < give_up)
    {
      {
        std::lock_guard<std::mutex> lock(rec_.mutex);
        bool all = true;
        for (const char* name : kNodes)
        {
          const auto was = before.find(name);
          all = all && rec_.state_count[name] > (was == before.end() ? 0 : was->second);
        }
        if (all)
          return;
      }
      ros::WallDuration(0.0005).sleep();
    }
    ++late_steps_;
    std::printf("late step at %.2f s: not every node published within %.1f s of wall time\n", time_, wait);
  }

  void publishClock()
  {
    rosgraph_msgs::Clock c;
    c.clock = ros::Time(time_);
    clock_pub_.publish(c);
  }

  long tick_ = 0;
  int late_steps_ = 0;
  ros::AsyncSpinner spinner_{ 2 };
  ros::Publisher clock_pub_, odom_pub_;
  std::map<std::string, ros::Publisher> fin_pubs_;
  std::vector<ros::Subscriber> subs_;
};

std::unique_ptr<World> world;

bool allFinite(const tow_sim::CableState& s)
{
  for (const auto& p : s.joints)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return false;
  for (double t : s.tension)
    if (!std::isfinite(t))
      return false;
  return std::isfinite(s.tension_ship) && std::isfinite(s.vehicle_depth) && std::isfinite(s.diversion) &&
         std::isfinite(s.layback);
}

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
  // a node under load may skip some of it (roscpp keeps one /clock message), so the two nodes' latest
  // stamps need not be the same: compare them at the latest stamp both published, which must be recent.
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const auto& dopri5_kept = world->rec_.state_by_stamp["dopri5"];
  const auto& implicit_kept = world->rec_.state_by_stamp["base"];
  ASSERT_FALSE(dopri5_kept.empty());
  ASSERT_FALSE(implicit_kept.empty());
  auto common = implicit_kept.rbegin();
  while (common != implicit_kept.rend() && dopri5_kept.count(common->first) == 0)
    ++common;
  ASSERT_NE(common, implicit_kept.rend()) << "no stamp published by both nodes among their last 100 states";
  EXPECT_LT((implicit_kept.rbegin()->first - common->first).toSec(), 1.0) << "the common stamp is old";
  const auto& dopri5 = dopri5_kept.at(common->first);
  const auto& implicit = common->second;
  std::printf("implicit vs dopri5 node at %.3f s (latest %.3f s): depth %.4f vs %.4f m, tension %.2f vs %.2f N\n",
              common->first.toSec(), implicit_kept.rbegin()->first.toSec(), implicit.vehicle_depth,
              dopri5.vehicle_depth, implicit.tension_ship, dopri5.tension_ship);
  EXPECT_NEAR(implicit.vehicle_depth, dopri5.vehicle_depth, 1e-3 * dopri5.vehicle_depth);
  EXPECT_NEAR(implicit.tension_ship, dopri5.tension_ship, 5e-3 * dopri5.tension_ship);
  EXPECT_NEAR(implicit.layback, dopri5.layback, 1e-3 * dopri5.layback);
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

TEST(TowSimNode, PauseAndResetServicesWork)
{
  ros::ServiceClient pause = world->nh_.serviceClient<std_srvs::SetBool>("/base/tow_sim/set_paused");
  ros::ServiceClient reset = world->nh_.serviceClient<std_srvs::Trigger>("/base/tow_sim/reset");
  ASSERT_TRUE(pause.waitForExistence(ros::Duration(5.0)));
  std_srvs::SetBool p;
  p.request.data = true;
  ASSERT_TRUE(pause.call(p));
  EXPECT_TRUE(p.response.success);
  world->advance(1.0);
  ros::Time paused_stamp;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    paused_stamp = world->rec_.state["base"].header.stamp;
  }
  world->advance(2.0);
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    EXPECT_EQ(world->rec_.state["base"].header.stamp, paused_stamp);  // frozen
  }
  p.request.data = false;
  ASSERT_TRUE(pause.call(p));
  world->advance(2.0);
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    EXPECT_GT(world->rec_.state["base"].header.stamp, paused_stamp);  // running again
  }
  double depth_before;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    depth_before = world->rec_.state["base"].vehicle_depth;
  }
  std_srvs::Trigger r;
  ASSERT_TRUE(reset.call(r));
  EXPECT_TRUE(r.response.success) << r.response.message;
  world->advance(0.5);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const auto& s = world->rec_.state["base"];
  EXPECT_TRUE(allFinite(s));
  // Laid out again as a straight line at 0.5 rad: 100 m of cable and the bail at sin(0.5) of that depth.
  std::printf("reset: depth %.2f m before, %.2f m after\n", depth_before, s.vehicle_depth);
  EXPECT_NEAR(s.vehicle_depth, 100.0 * std::sin(0.5), 3.0);
}

TEST(TowSimNode, SaveAndLoadStateServicesRestoreTheShape)
{
  ros::ServiceClient save = world->nh_.serviceClient<tow_sim::StateFile>("/base/tow_sim/save_state");
  ros::ServiceClient load = world->nh_.serviceClient<tow_sim::StateFile>("/base/tow_sim/load_state");
  ros::ServiceClient reset = world->nh_.serviceClient<std_srvs::Trigger>("/base/tow_sim/reset");
  ASSERT_TRUE(load.waitForExistence(ros::Duration(5.0)));
  world->advance(20.0);  // away from the last reset's straight line
  const std::string path = "/tmp/tow_sim_test_base_state.txt", damaged_path = "/tmp/tow_sim_test_damaged_state.txt";
  tow_sim::StateFile f;
  f.request.path = path;
  ASSERT_TRUE(save.call(f));
  ASSERT_TRUE(f.response.success) << f.response.message;
  double depth_saved;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    depth_saved = world->rec_.state["base"].vehicle_depth;
  }
  std_srvs::Trigger r;
  ASSERT_TRUE(reset.call(r));
  world->advance(1.0);
  double depth_reset;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    depth_reset = world->rec_.state["base"].vehicle_depth;
  }
  ASSERT_TRUE(load.call(f));
  ASSERT_TRUE(f.response.success) << f.response.message;
  world->advance(0.5);
  double depth_loaded;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    depth_loaded = world->rec_.state["base"].vehicle_depth;
    EXPECT_TRUE(allFinite(world->rec_.state["base"]));
  }
  std::printf("save/load: depth %.3f m saved, %.3f m after a reset, %.3f m after the load\n", depth_saved, depth_reset,
              depth_loaded);
  EXPECT_GT(std::abs(depth_reset - depth_saved), 1.0);  // the reset moved it: the load has to bring it back
  EXPECT_NEAR(depth_loaded, depth_saved, 0.2);          // a steady tow on the same track, 1.5 s later

  // Refused, naming why, with the run going on: no such file, no such folder, a damaged file.
  f.request.path = "/tmp/no_such_dir/state.txt";
  ASSERT_TRUE(load.call(f));
  EXPECT_FALSE(f.response.success);
  EXPECT_NE(f.response.message.find("/tmp/no_such_dir/state.txt"), std::string::npos) << f.response.message;
  ASSERT_TRUE(save.call(f));
  EXPECT_FALSE(f.response.success);
  EXPECT_NE(f.response.message.find("cannot write"), std::string::npos) << f.response.message;
  {
    std::ifstream in(path);
    std::ofstream out(damaged_path);
    std::string line;
    while (std::getline(in, line))
      out << (line.rfind("thrust ", 0) == 0 ? "thrust abc" : line) << "\n";
  }
  f.request.path = damaged_path;
  ASSERT_TRUE(load.call(f));
  EXPECT_FALSE(f.response.success);
  EXPECT_NE(f.response.message.find(damaged_path + ": line"), std::string::npos) << f.response.message;
  EXPECT_NE(f.response.message.find("'abc' is not a number"), std::string::npos) << f.response.message;
  ros::Time stamp;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    stamp = world->rec_.state["base"].header.stamp;
  }
  world->advance(0.5);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  EXPECT_GT(world->rec_.state["base"].header.stamp, stamp);
  EXPECT_NEAR(world->rec_.state["base"].vehicle_depth, depth_saved, 0.3);  // the loaded run, untouched
  std::remove(path.c_str());
  std::remove(damaged_path.c_str());
}

TEST(TowSimNode, DivergenceRestartsThenHoldsAndNothingNonFiniteIsPublished)
{
  // The unstable node has been diverging since the start: it restarts a few times, then holds its last good
  // state and says so (an error, not a loop); it never publishes a non-finite state.
  auto unstable = [](const std::string& key)
  {
    for (const auto& kv : world->rec_.diagnostics)
      if (kv.first.find("unstable") != std::string::npos && kv.first.find(key) != std::string::npos)
        return kv.second;
    return std::string();
  };
  std::string summary;
  for (int i = 0; i < 30 && summary.find("diverging repeatedly") == std::string::npos; ++i)
  {
    world->advance(1.0);
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    summary = unstable("/summary");
  }
  ros::Time held_stamp;
  int restarts = -1;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    restarts = std::atoi(unstable("restarts after divergence").c_str());
    held_stamp = world->rec_.state["unstable"].header.stamp;
    std::printf("unstable node: %d restarts after divergence, %d cable/state messages, diagnostics say '%s'\n",
                restarts, world->rec_.state_count["unstable"], summary.c_str());
  }
  EXPECT_NE(summary.find("diverging repeatedly"), std::string::npos) << summary;
  EXPECT_GE(restarts, 5);  // five restarts within 10 s make it hold
  world->advance(5.0);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  // Holding: still publishing, the same (last good) simulation time, no more restarts.
  EXPECT_EQ(world->rec_.state["unstable"].header.stamp, held_stamp);
  EXPECT_EQ(std::atoi(unstable("restarts after divergence").c_str()), restarts);
  EXPECT_NE(unstable("/summary").find("diverging repeatedly"), std::string::npos);
  for (const char* name : kNodes)
    EXPECT_EQ(world->rec_.non_finite_states[name], 0) << name;
  EXPECT_GT(world->rec_.state_count["unstable"], 0);
}

int rejectedMessages(const std::string& node)
{
  int count = -1;
  for (const auto& kv : world->rec_.diagnostics)
    if (kv.first.find(node) != std::string::npos && kv.first.find("rejected messages") != std::string::npos)
      count = std::atoi(kv.second.c_str());
  return count;
}

// A GPS driver's (0, 0, 0) before its fix, then the real track 1.1 km away: the node refuses the real
// messages as jumps until reacquire_after (5) of them in a row agree, then lays the cable out on the
// real track: at least 4 refused (the exact count, 4, is OdometryCheck's; here messages queued while
// the node connects may add to it), the tow point on the track.
TEST(TowSimNode, ReacquiresTheShipAfterAWrongFirstFix)
{
  world->advance(1.0);
  int rejected = -1;
  for (int i = 0; i < 30 && rejected < 4; ++i)  // diagnostics come at 1 Hz of wall time
  {
    {
      std::lock_guard<std::mutex> lock(world->rec_.mutex);
      rejected = rejectedMessages("gps");
    }
    if (rejected < 4)
      ros::WallDuration(0.1).sleep();
  }
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const tow_sim::CableState& s = world->rec_.state["gps"];
  const double t = s.header.stamp.toSec();
  const Eigen::Vector3d tow(s.joints[0].x, s.joints[0].y, s.joints[0].z);
  const Eigen::Vector3d expected(2.0 * (t - 100.0) + kGpsOffsetX - 20.0, kGpsOffsetY, 0.0);
  std::printf("gps node: %d messages refused, tow point %.3f m from the real track at t = %.1f s\n", rejected,
              (tow - expected).norm(), t);
  EXPECT_GE(rejected, 4);
  EXPECT_LT((tow - expected).norm(), 0.1);
  EXPECT_TRUE(allFinite(s));
}

TEST(TowSimNode, WinchPaysOutOverTheSeabedAndTheStateSaysSo)
{
  ros::Publisher winch = world->nh_.advertise<std_msgs::Float64>("/winch/winch/command", 5, true);
  ros::Publisher profile = world->nh_.advertise<tow_sim::CurrentProfile>("/winch/current_profile", 5);
  ros::Publisher base_winch = world->nh_.advertise<std_msgs::Float64>("/base/winch/command", 5);
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(10.0);
  while ((winch.getNumSubscribers() < 1 || profile.getNumSubscribers() < 1 || base_winch.getNumSubscribers() < 1) &&
         ros::WallTime::now() < give_up)
    ros::WallDuration(0.05).sleep();
  world->advance(1.0);
  int rejected_before, base_rejected_before;
  size_t joints_before;
  double length_before;
  {
    std::lock_guard<std::mutex> lock(world->rec_.mutex);
    rejected_before = rejectedMessages("winch");
    base_rejected_before = rejectedMessages("base");
    joints_before = world->rec_.state["winch"].joints.size();
    length_before = world->rec_.state["winch"].cable_length;
  }
  std_msgs::Float64 rate;
  rate.data = std::numeric_limits<double>::quiet_NaN();  // refused
  winch.publish(rate);
  base_winch.publish(rate);  // refused too: base has no winch
  tow_sim::CurrentProfile bad;
  bad.depth = { 50.0, 20.0 };  // not increasing: refused
  bad.velocity.resize(2);
  profile.publish(bad);
  world->advance(0.5);
  rate.data = 1.0;
  winch.publish(rate);
  world->advance(20.0);
  // The vehicle odometry of the same output as the last state (it may arrive just after the state).
  const ros::WallTime wait_for_odom = ros::WallTime::now() + ros::WallDuration(5.0);
  for (;;)
  {
    {
      std::lock_guard<std::mutex> lock(world->rec_.mutex);
      if (world->rec_.odom_by_stamp["winch"].count(world->rec_.state["winch"].header.stamp) ||
          ros::WallTime::now() > wait_for_odom)
        break;
    }
    ros::WallDuration(0.01).sleep();
  }
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const tow_sim::CableState& s = world->rec_.state["winch"];
  std::printf(
      "winch: %.2f m -> %.2f m of cable at %.3f m/s, %zu -> %zu joints; depth %.2f m, altitude %.2f m over "
      "the 60 m seabed\n",
      length_before, s.cable_length, s.payout_rate, joints_before, s.joints.size(), s.vehicle_depth,
      s.vehicle_altitude);
  EXPECT_NEAR(length_before, 100.0, 1e-6);
  EXPECT_GT(s.cable_length, 115.0);  // about 18 m in 20 s, after the rate ramp
  EXPECT_LT(s.cable_length, 121.0);
  EXPECT_NEAR(s.payout_rate, 1.0, 1e-3);
  EXPECT_GE(s.joints.size(), joints_before + 3);  // 5 m segments split off at the ship
  EXPECT_EQ(s.tension.size(), s.joints.size() - 1);
  EXPECT_EQ(s.seabed_contact.size(), s.joints.size());
  EXPECT_TRUE(s.seabed_present);
  EXPECT_TRUE(allFinite(s));
  // The vehicle's altitude is the seabed's depth less its own (flat bottom).
  const auto same_output = world->rec_.odom_by_stamp["winch"].find(s.header.stamp);
  ASSERT_NE(same_output, world->rec_.odom_by_stamp["winch"].end()) << "no vehicle odometry stamped as the state";
  const double cg_z = same_output->second.pose.pose.position.z;
  EXPECT_NEAR(s.vehicle_altitude, cg_z + 60.0, 1e-6);
  EXPECT_FALSE(world->rec_.state["base"].seabed_present);
  EXPECT_NEAR(world->rec_.state["base"].cable_length, 100.0, 1e-9);
  EXPECT_GE(rejectedMessages("winch"), rejected_before + 2);  // NaN rate and the bad profile
  EXPECT_GE(rejectedMessages("base"), base_rejected_before + 1);
}

// ~plan_cable_out: the base node answers what the towing chart's planner says for its configuration (the
// library is checked against the settled dynamics in test_towing_chart); a depth out of reach and execute
// without a winch are refused; the winch node pays out or hauls in to the plan and stops there.
TEST(TowSimNode, PlanCableOutAnswersAndTheWinchExecutesIt)
{
  ros::ServiceClient base = world->nh_.serviceClient<tow_sim::PlanCableOut>("/base/tow_sim/plan_cable_out");
  ros::ServiceClient winch = world->nh_.serviceClient<tow_sim::PlanCableOut>("/winch/tow_sim/plan_cable_out");
  ASSERT_TRUE(base.waitForExistence(ros::Duration(5.0)));
  ASSERT_TRUE(winch.waitForExistence(ros::Duration(5.0)));
  const tow_sim::SimulationConfig config =
      tow_sim::loadConfigFile(std::string(TOW_SIM_SOURCE_DIR) + "/test/ros/test_config.yaml");
  const tow_sim::CableOutPlan expected = tow_sim::planCableOut(config, 50.0, 2.0, Eigen::Vector3d::Zero(),
                                                               config.winch.min_length, config.winch.max_length);
  ASSERT_TRUE(expected.reachable) << expected.reason;
  tow_sim::PlanCableOut plan;
  plan.request.depth = 50.0;
  plan.request.speed = 2.0;
  ASSERT_TRUE(base.call(plan));
  EXPECT_TRUE(plan.response.reachable) << plan.response.message;
  EXPECT_NEAR(plan.response.cable_out, expected.cable_out, 1e-6);
  EXPECT_NEAR(plan.response.depth, 50.0, 0.1);
  EXPECT_FALSE(plan.response.executing);
  plan.request.depth = 5000.0;
  ASSERT_TRUE(base.call(plan));
  EXPECT_FALSE(plan.response.reachable);
  EXPECT_NE(plan.response.message.find("out of reach"), std::string::npos) << plan.response.message;
  // The speed window on 120 m out for 40..60 m, as the library's (tow_sim_chart --depth-band); a window alone
  // with depth 0; a bad band refused naming it.
  const tow_sim::SpeedWindow window = tow_sim::speedWindow(config, 120.0, 40.0, 60.0, Eigen::Vector3d::Zero());
  ASSERT_TRUE(window.found) << window.reason;
  plan.request.depth = 0.0;
  plan.request.depth_min = 40.0;
  plan.request.depth_max = 60.0;
  plan.request.window_cable_out = 120.0;
  ASSERT_TRUE(base.call(plan));
  EXPECT_TRUE(plan.response.window_found) << plan.response.message;
  EXPECT_NEAR(plan.response.slowest, window.slowest, 1e-9);
  EXPECT_NEAR(plan.response.fastest, window.fastest, 1e-9);
  EXPECT_FALSE(plan.response.reachable);  // no cable-out plan asked for
  std::printf("plan_cable_out window: %.4f .. %.4f m/s (library %.4f .. %.4f m/s)\n", plan.response.slowest,
              plan.response.fastest, window.slowest, window.fastest);
  plan.request.depth_max = 30.0;
  ASSERT_TRUE(base.call(plan));
  EXPECT_NE(plan.response.message.find("depth_max = 30"), std::string::npos) << plan.response.message;
  plan.request.depth_min = plan.request.depth_max = plan.request.window_cable_out = 0.0;

  plan.request.depth = 50.0;
  plan.request.execute = true;
  ASSERT_TRUE(base.call(plan));
  EXPECT_NE(plan.response.message.find("needs the winch"), std::string::npos) << plan.response.message;

  // The winch node (min 80 m, max 140 m): to the cable out for 50 m there.
  ASSERT_TRUE(winch.call(plan));
  ASSERT_TRUE(plan.response.reachable) << plan.response.message;
  EXPECT_TRUE(plan.response.executing) << plan.response.message;
  world->advance(60.0);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const tow_sim::CableState& s = world->rec_.state["winch"];
  std::printf("plan_cable_out: %.2f m out for 50 m at 2 m/s (library %.2f m); the winch node at %.2f m, %.4f m/s\n",
              plan.response.cable_out, expected.cable_out, s.cable_length, s.payout_rate);
  EXPECT_NEAR(s.cable_length, plan.response.cable_out, 0.1);
  EXPECT_NEAR(s.payout_rate, 0.0, 0.02);
}

TEST(TowSimNode, BadConfigurationExitsNamingTheParameter)
{
  world->nh_.setParam("/bad/tow_sim/cable/length", -1.0);
  FILE* pipe = popen(TOW_SIM_NODE_BINARY " __ns:=/bad __name:=tow_sim 2>&1", "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe))
    output += buffer;
  const int status = pclose(pipe);
  EXPECT_NE(status, 0);
  EXPECT_NE(output.find("/bad/tow_sim/cable/length = -1"), std::string::npos) << output;
  EXPECT_NE(output.find("(0, 100000] [m]"), std::string::npos) << output;
}

// Last, since it moves every node's clock: a clock that jumps back (rosbag play -l, a simulator reset)
// makes the node lay the cable out again on the new clock instead of refusing every later message.
TEST(TowSimNode, ClockJumpingBackLaysTheCableOutAgain)
{
  const double before = world->time_;
  world->time_ -= 30.0;
  // The nodes forget the ship and start again at the next odometry; their timers restart on the new clock:
  // the first steps need not find every node publishing (at most 0.5 s of wall time for each).
  world->advance(5.0, 0.5);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  const auto& base = world->rec_.state["base"];
  std::printf("clock back from %.1f s to %.1f s: base node state stamped %.1f s\n", before, before - 30.0,
              base.header.stamp.toSec());
  EXPECT_LT(base.header.stamp.toSec(), before - 20.0);
  EXPECT_GT(base.header.stamp.toSec(), before - 30.0);
  EXPECT_TRUE(allFinite(base));
}

}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_tow_sim_node");
  world = std::make_unique<World>();
  const int result = RUN_ALL_TESTS();
  world.reset();
  return result;
}
