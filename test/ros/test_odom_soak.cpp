// Soak of tow_sim_node against a misbehaving odometry publisher, in wall time: normal 20 Hz stretches,
// dropouts of 0.5 to 5 s (longer than max_extrapolation: the node must hold, not stop publishing),
// bursts of 50 delayed messages at once (most of them older than what already arrived), stretches
// with a zero twist, a publisher restart, and junk messages (NaN, zero quaternion, stamps from the
// past). Every 10 s window must hold cable/state messages at the 10 Hz publish rate, all finite, and the
// simulation must never diverge. The only allowance is for CPU starvation, measured: the time the node's
// and this test's threads spent waiting for a processor (the kernel's run-queue wait, /proc/PID/task/*/
// schedstat), at 10 messages a second, plus 3 messages for the window edges.
#include <gtest/gtest.h>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include <dirent.h>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <mutex>
#include <random>
#include <string>

#include <diagnostic_msgs/DiagnosticArray.h>

#include "tow_sim/CableState.h"

namespace
{
std::mutex mutex;
int window_count = 0;
bool all_finite = true;
int restarts = -1;

// Seconds the threads of process `pid` have waited on a run queue (ready but not running), summed.
double runQueueWait(const std::string& pid)
{
  double total = 0.0;
  const std::string tasks = "/proc/" + pid + "/task";
  DIR* dir = opendir(tasks.c_str());
  if (!dir)
    return 0.0;
  while (const dirent* entry = readdir(dir))
  {
    std::ifstream stat(tasks + "/" + entry->d_name + "/schedstat");
    double on_cpu = 0.0, waiting = 0.0;
    if (stat >> on_cpu >> waiting)
      total += waiting * 1e-9;
  }
  closedir(dir);
  return total;
}

// The process id of the tow_sim_node beside this test (the only one: rostests run one at a time), or "".
std::string nodePid()
{
  DIR* dir = opendir("/proc");
  std::string found;
  while (const dirent* entry = dir ? readdir(dir) : nullptr)
  {
    std::ifstream comm(std::string("/proc/") + entry->d_name + "/comm");
    std::string name;
    if (std::getline(comm, name) && name == "tow_sim_node")
      found = entry->d_name;
  }
  if (dir)
    closedir(dir);
  return found;
}

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& m)
{
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& status : m->status)
    for (const auto& kv : status.values)
      if (kv.key == "restarts after divergence")
        restarts = std::atoi(kv.value.c_str());
}

void onState(const tow_sim::CableState::ConstPtr& s)
{
  bool finite = std::isfinite(s->tension_ship) && std::isfinite(s->vehicle_depth);
  for (const auto& p : s->joints)
    finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  std::lock_guard<std::mutex> lock(mutex);
  ++window_count;
  all_finite = all_finite && finite;
}

// The ship's odometry publisher, misbehaving by chance: dropouts, bursts of delayed messages, stretches of
// zero twist, junk (NaN, a zero quaternion, a stale stamp) and restarts, between messages at 20 Hz.
class MisbehavingShip
{
public:
  explicit MisbehavingShip(ros::NodeHandle& nh) : nh_(nh), odom_(nh.advertise<nav_msgs::Odometry>("ship/odom", 100)) {}

  // One pick of what to do next, then 50 ms of wall time.
  void next()
  {
    const ros::Time now = ros::Time::now();
    x_ += 2.0 * (now - previous_).toSec();  // the ship keeps moving even when its messages do not
    previous_ = now;
    const double pick = u_(rng_);
    if (pick < 0.01)  // dropout
      ros::WallDuration(0.5 + 4.5 * u_(rng_)).sleep();
    else if (pick < 0.02)  // burst: 50 messages at once, as if delayed and delivered together
      burst(now);
    else if (pick < 0.022)  // a stretch of messages with a zero twist, as some drivers send
      zeroTwist();
    else if (pick < 0.025)  // junk
    {
      nav_msgs::Odometry m = message(now);
      m.pose.pose.position.y = std::numeric_limits<double>::quiet_NaN();
      odom_.publish(m);
      m = message(now);
      m.pose.pose.orientation.w = 0.0;
      odom_.publish(m);
      odom_.publish(message(now - ros::Duration(30.0)));
    }
    else if (pick < 0.027)  // restart: the publisher goes away and comes back
    {
      odom_.shutdown();
      ros::WallDuration(2.0).sleep();
      odom_ = nh_.advertise<nav_msgs::Odometry>("ship/odom", 100);
      ros::WallDuration(0.5).sleep();
    }
    else
      odom_.publish(message(now));
    ros::WallDuration(0.05).sleep();
  }

private:
  nav_msgs::Odometry message(const ros::Time& stamp) const
  {
    nav_msgs::Odometry m;
    m.header.stamp = stamp;
    m.header.frame_id = "odom";
    m.pose.pose.position.x = x_;
    m.pose.pose.orientation.w = 1.0;
    m.twist.twist.linear.x = 2.0;
    return m;
  }

  void burst(const ros::Time& now)
  {
    const double x_now = x_;
    for (int i = 0; i < 50; ++i)
    {
      const double age = 0.5 - 0.01 * i;
      x_ = x_now - 2.0 * age;
      odom_.publish(message(now - ros::Duration(age)));
    }
    x_ = x_now;
  }

  void zeroTwist()
  {
    for (int i = 0; i < 20; ++i)
    {
      const ros::Time t = ros::Time::now();
      x_ += 2.0 * (t - previous_).toSec();
      previous_ = t;
      nav_msgs::Odometry m = message(t);
      m.twist.twist.linear.x = 0.0;
      odom_.publish(m);
      ros::WallDuration(0.05).sleep();
    }
  }

  ros::NodeHandle& nh_;
  ros::Publisher odom_;
  std::mt19937 rng_{ 7 };
  std::uniform_real_distribution<double> u_{ 0.0, 1.0 };
  double x_ = 0.0;
  ros::Time previous_ = ros::Time::now();
};

// The cable/state messages counted in windows of 10 s of wall time against the 10 Hz owed, less the time
// the node or this test waited for a processor (the first 10 s are start-up and not counted).
class RateWindows
{
public:
  explicit RateWindows(const std::string& node_pid) : node_pid_(node_pid) {}

  void check()
  {
    if (ros::WallTime::now() >= window_start_ + ros::WallDuration(10.0))
    {
      const ros::WallTime end = ros::WallTime::now();
      const double starved = starvation() - starvation_at_start_;
      std::lock_guard<std::mutex> lock(mutex);
      if (windows_ > 0 || window_count > 0)
      {
        // At 10 Hz but for the time the node or this test waited for a processor, and 3 for the edges.
        const double owed = 10.0 * ((end - window_start_).toSec() - starved) - 3.0;
        worst_ = std::min(worst_, window_count);
        worst_margin_ = std::min(worst_margin_, window_count - owed);
        largest_starvation_ = std::max(largest_starvation_, starved);
        if (window_count < owed)
          std::printf("window %d: %d cable/state in %.2f s with %.2f s of run-queue wait (owed %.1f)\n", windows_,
                      window_count, (end - window_start_).toSec(), starved, owed);
      }
      ++windows_;
      window_count = 0;
      window_start_ = end;
      starvation_at_start_ = starvation();
    }
    else if (windows_ == 0 && ros::WallTime::now() < window_start_)
    {
      std::lock_guard<std::mutex> lock(mutex);
      window_count = 0;  // still in the start-up period
      starvation_at_start_ = starvation();
    }
  }

  int windows() const { return windows_; }
  int worst() const { return worst_; }
  double worstMargin() const { return worst_margin_; }
  double largestStarvation() const { return largest_starvation_; }

private:
  double starvation() const { return runQueueWait(node_pid_) + runQueueWait("self"); }

  std::string node_pid_;
  int windows_ = 0, worst_ = 1000000;
  double worst_margin_ = 1e9, largest_starvation_ = 0.0, starvation_at_start_ = 0.0;
  ros::WallTime window_start_ = ros::WallTime::now() + ros::WallDuration(10.0);  // first 10 s: start-up
};

TEST(OdomSoak, KeepsPublishingThroughDropoutsBurstsAndRestarts)
{
  ros::NodeHandle nh, pnh("~");
  double duration = 120.0;
  pnh.param("duration", duration, duration);
  MisbehavingShip ship(nh);
  ros::Subscriber sub = nh.subscribe("cable/state", 100, onState);
  ros::Subscriber diag = nh.subscribe("/diagnostics", 10, onDiagnostics);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const ros::WallTime start = ros::WallTime::now();
  std::string node_pid = nodePid();
  for (int i = 0; i < 100 && node_pid.empty(); ++i)
  {
    ros::WallDuration(0.1).sleep();
    node_pid = nodePid();
  }
  ASSERT_FALSE(node_pid.empty()) << "no tow_sim_node process";
  RateWindows windows(node_pid);
  while ((ros::WallTime::now() - start).toSec() < duration && ros::ok())
  {
    ship.next();
    windows.check();
  }
  std::printf(
      "odometry soak: %.0f s, %d windows of 10 s, fewest cable/state messages in a window: %d (rate 10 Hz); "
      "smallest margin over the rate less starvation %.1f messages; largest run-queue wait in a window %.2f s\n",
      duration, windows.windows(), windows.worst(), windows.worstMargin(), windows.largestStarvation());
  // A window closes at the first check after 10 s; dropouts and restarts can stretch it to 15 s.
  EXPECT_GE(windows.windows(), static_cast<int>(duration / 15.0) - 1);
  EXPECT_GE(windows.worstMargin(), 0.0);
  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_TRUE(all_finite);
  std::printf("odometry soak: restarts after divergence %d\n", restarts);
  EXPECT_EQ(restarts, 0);
}

}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_odom_soak");
  return RUN_ALL_TESTS();
}
