// The world of tow_sim_node's rostest (test_tow_sim_node*.cpp): the test plays the ship and the clock
// (use_sim_time) for eight nodes that get the same odometry, so the only differences between them are the
// commands and parameters. The clock moves in steps of 0.1 s, and the next step waits until every node has
// published its cable/state for this one (lock-step), so what the nodes see and the message counts do not
// depend on how fast or loaded the machine is. One World for the whole process (main in
// tow_sim_node_world.cpp); the tests run in the order of their files on the command line.
#pragma once

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

namespace tow_sim_test
{
const char* const kNodes[] = { "base", "elevator", "rudder", "robust", "unstable", "winch", "dopri5", "gps" };
// The gps node's ship: the same track 1 km east and 500 m north, after a first fix at (0, 0, 0).
const double kGpsOffsetX = 1000.0, kGpsOffsetY = 500.0;

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

// Every joint, tension and scalar of the state finite.
bool allFinite(const tow_sim::CableState& s);

class World
{
public:
  // Subscribes to every node and waits (up to a minute) until each has started on the first odometry.
  World();

  // Advances the clock by `seconds` in steps of 0.1 s (ten clock ticks of 10 ms, the ship towing at 2 m/s
  // along +x with its odometry at 20 Hz); after each step it waits until every node has published a
  // cable/state (publish_rate 10 Hz: once per step), at most `wait` of wall time, else the step counts as late.
  void advance(double seconds, double wait = 10.0);
  int lateSteps() const { return late_steps_; }
  nav_msgs::Odometry shipOdometry() const;
  // The gps node's odometry: (0, 0, 0) first (a driver before its fix), then the ship's track offset.
  void publishGps();
  void command(const std::string& node, double rudder, double elevator);

  ros::NodeHandle nh_;
  Recorder rec_;
  // Listening from the start: the lock-step clock runs far faster than real time, so a listener made
  // later could miss every transform before its subscription is connected.
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_{ tf_buffer_ };
  double time_ = 100.0;            // [s] the clock, a whole number of nanoseconds (tickClock)
  void setClockBack(int seconds);  // the next tick is that much earlier (rosbag play -l)
  ros::Publisher robust_odom_pub_, gps_odom_pub_;
  bool gps_fixed_ = false;  // the gps node has started on the zeros: its real track follows

private:
  void subscribeNode(const std::string& n);
  void subscribeDiagnostics();
  void waitForTheNodes();
  // 10 ms on the clock, counted in nanoseconds: a double summed 0.01 s at a time drifts off the exact
  // multiples, and a ROS timer due at one waits a tick more (issue 26, item 8).
  void tickClock();
  int64_t clock_ns_ = 100'000'000'000;
  void waitForEveryNode(const std::map<std::string, int>& before, double wait);
  void publishClock();

  long tick_ = 0;
  int late_steps_ = 0;
  ros::AsyncSpinner spinner_{ 2 };
  ros::Publisher clock_pub_, odom_pub_;
  std::map<std::string, ros::Publisher> fin_pubs_;
  std::vector<ros::Subscriber> subs_;
};

extern std::unique_ptr<World> world;

// The count of odometry messages the node has rejected (its diagnostics; -1: not reported yet).
int rejectedMessages(const std::string& node);

}  // namespace tow_sim_test
