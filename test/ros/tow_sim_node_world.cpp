#include "tow_sim_node_world.h"

namespace tow_sim_test
{
std::unique_ptr<World> world;

World::World()
{
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/ship/odom", 50);
  robust_odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/robust/ship/odom", 50);
  gps_odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/gps/ship/odom", 50);
  for (const char* name : kNodes)
    subscribeNode(name);
  subscribeDiagnostics();
  spinner_.start();
  publishClock();
  waitForTheNodes();
}

void World::subscribeNode(const std::string& n)
{
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

void World::subscribeDiagnostics()
{
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
}

void World::waitForTheNodes()
{
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
    tickClock();
    if (++tick_ % 5 == 0)
    {
      odom_pub_.publish(shipOdometry());
      robust_odom_pub_.publish(shipOdometry());
      publishGps();
    }
    ros::WallDuration(0.01).sleep();
  }
}

void World::advance(double seconds, double wait)
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
      tickClock();
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

nav_msgs::Odometry World::shipOdometry() const
{
  nav_msgs::Odometry odom;
  odom.header.stamp.fromNSec(clock_ns_);
  odom.header.frame_id = "odom";
  odom.child_frame_id = "ship";
  odom.pose.pose.position.x = 2.0 * (time_ - 100.0);
  odom.pose.pose.orientation.w = 1.0;
  odom.twist.twist.linear.x = 2.0;
  return odom;
}

void World::publishGps()
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

void World::command(const std::string& node, double rudder, double elevator)
{
  tow_sim::FinCommand cmd;
  cmd.rudder = rudder;
  cmd.elevator = elevator;
  fin_pubs_[node].publish(cmd);
}

void World::waitForEveryNode(const std::map<std::string, int>& before, double wait)
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

void World::tickClock()
{
  clock_ns_ += 10'000'000;
  time_ = static_cast<double>(clock_ns_) * 1e-9;
  publishClock();
}

void World::setClockBack(int seconds)
{
  clock_ns_ -= seconds * int64_t{ 1'000'000'000 };
  time_ = static_cast<double>(clock_ns_) * 1e-9;
}

void World::publishClock()
{
  rosgraph_msgs::Clock c;
  c.clock.fromNSec(clock_ns_);
  clock_pub_.publish(c);
}

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

int rejectedMessages(const std::string& node)
{
  int count = -1;
  for (const auto& kv : world->rec_.diagnostics)
    if (kv.first.find(node) != std::string::npos && kv.first.find("rejected messages") != std::string::npos)
      count = std::atoi(kv.second.c_str());
  return count;
}

}  // namespace tow_sim_test

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_tow_sim_node");
  tow_sim_test::world = std::make_unique<tow_sim_test::World>();
  const int result = RUN_ALL_TESTS();
  tow_sim_test::world.reset();
  return result;
}
