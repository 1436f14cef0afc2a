// rostest of depth_autopilot_node in the loop with tow_sim_node (vehicle with a lifting wing,
// config/autopilot_vehicle.yaml). The test plays the ship (2 m/s, then a 180 degree turn to port of radius
// 400 m) and the clock. It steps the clock by 0.1 s and then waits until both nodes have published for
// that step (vehicle/odom and fins/command), so the closed loop sees the same timing on a fast or a slow,
// loaded machine.
#include <gtest/gtest.h>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Float64.h>
#include <std_srvs/SetBool.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>
#include <visualization_msgs/InteractiveMarkerUpdate.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <limits>
#include <memory>
#include <mutex>
#include <string>

#include "tow_sim/CableState.h"
#include "tow_sim/FinCommand.h"
#include "tow_sim/PlanCableOut.h"
#include "tow_sim/core/constants.h"

namespace
{
constexpr double kSpeed = 2.0;          // [m/s] ship
constexpr double kTurnRadius = 400.0;   // [m]
constexpr double kSettlingTime = 60.0;  // [s] documented in docs/nodes.md: within 1 m of a 20 m step
constexpr double kTolerance = 1.0;      // [m]

class Loop
{
public:
  Loop()
  {
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    ship_pub_ = nh_.advertise<nav_msgs::Odometry>("/ship/odom", 50);
    setpoint_pub_ = nh_.advertise<std_msgs::Float64>("/autopilot/depth_setpoint", 5, true);
    vehicle_sub_ = nh_.subscribe<nav_msgs::Odometry>("/vehicle/odom", 20,
                                                     [this](const nav_msgs::Odometry::ConstPtr& m)
                                                     {
                                                       std::lock_guard<std::mutex> lock(mutex_);
                                                       vehicle_ = *m;
                                                       ++vehicle_count_;
                                                     });
    fin_sub_ = nh_.subscribe<tow_sim::FinCommand>("/fins/command", 20,
                                                  [this](const tow_sim::FinCommand::ConstPtr& m)
                                                  {
                                                    std::lock_guard<std::mutex> lock(mutex_);
                                                    fins_ = *m;
                                                    ++fin_count_;
                                                  });
    spinner_.start();
    publishClock();
    const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(60.0);
    // /clock: tow_sim, the autopilot and this node (use_sim_time).
    while ((ship_pub_.getNumSubscribers() < 2 || clock_pub_.getNumSubscribers() < 3 ||
            setpoint_pub_.getNumSubscribers() < 1 || vehicle_sub_.getNumPublishers() < 1 ||
            fin_sub_.getNumPublishers() < 1) &&
           ros::WallTime::now() < give_up)
      ros::WallDuration(0.05).sleep();
    // tow_sim_node starts at the first ship odometry: tick until its vehicle odometry comes back.
    while (ros::WallTime::now() < give_up)
    {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (vehicle_count_ > 0)
          break;
      }
      tick();
      ros::WallDuration(0.02).sleep();
    }
  }

  // 0.1 s of simulated time: two clock ticks with ship odometry (20 Hz), then wait until tow_sim_node and
  // the autopilot have both published for this step.
  void step()
  {
    long vehicle0, fins0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      vehicle0 = vehicle_count_;
      fins0 = fin_count_;
    }
    tick();
    tick();
    const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(5.0);
    while (ros::WallTime::now() < give_up)
    {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        // Both 10 Hz timers fire once per 0.1 s of clock (in either order, so the vehicle's stamp, which
        // trails the clock by odom_delay, may repeat; the count does not).
        if (vehicle_count_ > vehicle0 && fin_count_ > fins0 && fins_.header.stamp.toSec() > time_ - 0.1 - 1e-6)
          return;
      }
      ros::WallDuration(0.0005).sleep();
    }
    ++late_steps_;
    std::lock_guard<std::mutex> lock(mutex_);
    std::printf("late step at %.2f s: vehicle/odom %ld -> %ld (stamp %.2f), fins/command %ld -> %ld (stamp %.2f)\n",
                time_, vehicle0, vehicle_count_, vehicle_.header.stamp.toSec(), fins0, fin_count_,
                fins_.header.stamp.toSec());
  }

  // 0.05 s of clock and ship odometry, without waiting.
  void tick()
  {
    moveShip(0.05);
    publishClock();
    ship_pub_.publish(shipOdometry());
  }

  void run(
      double seconds, const std::function<void()>& each = [] {})
  {
    const int steps = static_cast<int>(std::round(seconds / 0.1));
    for (int i = 0; i < steps; ++i)
    {
      step();
      each();
    }
  }

  double depth()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return -vehicle_.pose.pose.position.z;
  }
  double vehicleY()  // [m] world
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return vehicle_.pose.pose.position.y;
  }
  tow_sim::FinCommand fins()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return fins_;
  }
  void setpoint(double depth)
  {
    std_msgs::Float64 m;
    m.data = depth;
    setpoint_pub_.publish(m);
  }

  ros::NodeHandle nh_;
  // [s] the clock, kept in whole nanoseconds: 0.05 s added to a double 21,121 times from 100 s falls 1 ns short
  // of 1156.05 s, and the nodes' 10 Hz timers due then waited for the next tick (issue 26, item 8).
  int64_t clock_ns_ = 100'000'000'000;
  double time_ = 100.0;
  double heading_ = 0.0, yaw_rate_ = 0.0, yaw_rate_target_ = 0.0;  // [rad], [rad/s]
  int late_steps_ = 0;

private:
  // The test's own ship: its yaw rate follows its target with a 5 s lag (a gentler entry into the turn than
  // ship_motion_node's 2 s; the documented figures are for this ship).
  void moveShip(double dt)
  {
    clock_ns_ += std::llround(dt * 1e9);
    time_ = static_cast<double>(clock_ns_) * 1e-9;
    yaw_rate_ += (yaw_rate_target_ - yaw_rate_) * dt / 5.0;
    heading_ += yaw_rate_ * dt;
    x_ += kSpeed * std::cos(heading_) * dt;
    y_ += kSpeed * std::sin(heading_) * dt;
  }

  nav_msgs::Odometry shipOdometry() const
  {
    nav_msgs::Odometry odom;
    odom.header.stamp.fromNSec(clock_ns_);
    odom.header.frame_id = "odom";
    odom.child_frame_id = "ship";
    odom.pose.pose.position.x = x_;
    odom.pose.pose.position.y = y_;
    odom.pose.pose.orientation.z = std::sin(0.5 * heading_);
    odom.pose.pose.orientation.w = std::cos(0.5 * heading_);
    odom.twist.twist.linear.x = kSpeed;
    odom.twist.twist.angular.z = yaw_rate_;
    return odom;
  }

  void publishClock()
  {
    rosgraph_msgs::Clock c;
    c.clock.fromNSec(clock_ns_);
    clock_pub_.publish(c);
  }

  double x_ = 0.0, y_ = 0.0;
  std::mutex mutex_;
  nav_msgs::Odometry vehicle_;
  tow_sim::FinCommand fins_;
  long vehicle_count_ = 0, fin_count_ = 0;
  ros::AsyncSpinner spinner_{ 2 };
  ros::Publisher clock_pub_, ship_pub_, setpoint_pub_;
  ros::Subscriber vehicle_sub_, fin_sub_;
};

std::unique_ptr<Loop> loop;

TEST(DepthAutopilotNode, ReachesAStepSetpointAndHoldsItThroughA180DegreeTurn)
{
  const ros::WallTime wall_start = ros::WallTime::now();
  // Steady tow: without a setpoint the autopilot holds the first depth it sees.
  loop->run(5.0);
  const double first = loop->depth();
  double drift = 0.0;
  loop->run(15.0, [&] { drift = std::max(drift, std::abs(loop->depth() - first)); });
  std::printf("steady tow at %.2f m; held within %.3f m for 15 s without a setpoint\n", first, drift);
  EXPECT_GT(first, 100.0);
  EXPECT_LT(drift, 0.5);

  // 20 m shallower: settle within the documented time, then hold until the turn.
  const double target = first - 20.0;
  loop->setpoint(target);
  const double t_step = loop->time_;
  double last_outside = t_step, max_elevator = 0.0;
  loop->run(kSettlingTime + 40.0,
            [&]
            {
              if (std::abs(loop->depth() - target) > kTolerance)
                last_outside = loop->time_;
              max_elevator = std::max(max_elevator, std::abs(loop->fins().elevator));
            });
  const double settling = last_outside - t_step;
  std::printf("setpoint %.2f m (20 m up): within %.1f m after %.1f s (documented %.0f s); max |elevator| %.3f rad\n",
              target, kTolerance, settling, kSettlingTime, max_elevator);
  EXPECT_LE(settling, kSettlingTime);
  EXPECT_GT(max_elevator, 0.05);  // the elevator did the work

  // 180 degree turn to port at 2 m/s, radius 400 m, then straight on while the vehicle comes round.
  const double turn_start = loop->time_;
  double max_error = 0.0, max_rudder = 0.0, max_turn_elevator = 0.0;
  auto watch = [&]
  {
    max_error = std::max(max_error, std::abs(loop->depth() - target));
    max_rudder = std::max(max_rudder, std::abs(loop->fins().rudder));
    max_turn_elevator = std::max(max_turn_elevator, std::abs(loop->fins().elevator));
  };
  loop->yaw_rate_target_ = kSpeed / kTurnRadius;
  while (loop->heading_ < tow_sim::kPi - 5.0 * loop->yaw_rate_ && loop->time_ < turn_start + 1000.0)
    loop->run(0.1, watch);
  loop->yaw_rate_target_ = 0.0;
  const double turn_time = loop->time_ - turn_start;
  loop->run(250.0, watch);
  std::printf(
      "turn: %.0f s to %.1f deg; then 250 s straight. Max depth error %.3f m (limit %.1f m); "
      "max |elevator| %.3f rad, max |rudder| %.3f rad\n",
      turn_time, loop->heading_ * 180.0 / tow_sim::kPi, max_error, kTolerance, max_turn_elevator, max_rudder);
  EXPECT_GT(loop->heading_, tow_sim::kPi - 0.05);
  EXPECT_LT(max_error, kTolerance);
  EXPECT_GT(max_rudder, 0.01);  // track keeping was steering
  std::printf("%.0f s simulated in %.0f s of wall time; %d of the 0.1 s steps waited more than 5 s for a node\n",
              loop->time_ - 100.0, (ros::WallTime::now() - wall_start).toSec(), loop->late_steps_);
  // A late step means a node stopped answering for 5 s of wall time: the loop then ran on timing other than
  // the documented one, and the figures above do not hold.
  EXPECT_EQ(loop->late_steps_, 0);
}

// depth_autopilot_winch.test: ~actuator winch, tow_sim_node with the winch free (300 m out, 200-600 m), the
// default vehicle at 2 m/s. A setpoint 20 m deeper: the autopilot asks tow_sim_node's ~plan_cable_out for
// the steady cable out there (its feed-forward) and pays out (winch/command) with the elevator centred.
// The test asks the same service itself: the vehicle must settle within 1 m of the setpoint in
// kWinchSettlingTime (without the feed-forward the integral alone needs far longer: see docs/nodes.md) and
// stay there over the last 100 s of the 500 s, with the cable out then within 1 % of the plan.
constexpr double kWinchSettlingTime = 150.0;  // [s] documented in docs/nodes.md
TEST(DepthAutopilotNode, TheWinchReachesADeeperSetpointWithTheElevatorCentred)
{
  double payout = 0.0, cable_out = 0.0;
  std::mutex mutex;
  ros::Subscriber winch_sub = loop->nh_.subscribe<std_msgs::Float64>(
      "/winch/command", 20, [&](const std_msgs::Float64::ConstPtr& m) { payout = std::max(payout, m->data); });
  ros::Subscriber state_sub = loop->nh_.subscribe<tow_sim::CableState>("/cable/state", 20,
                                                                       [&](const tow_sim::CableState::ConstPtr& m)
                                                                       {
                                                                         std::lock_guard<std::mutex> lock(mutex);
                                                                         cable_out = m->cable_length;
                                                                       });
  loop->run(5.0);
  const double first = loop->depth();
  const double target = first + 20.0;
  tow_sim::PlanCableOut plan;
  plan.request.depth = target;
  ASSERT_TRUE(ros::service::call("/tow_sim/plan_cable_out", plan));
  ASSERT_TRUE(plan.response.reachable) << plan.response.message;
  loop->setpoint(target);
  const double t_step = loop->time_;
  double max_elevator = 0.0, worst_late = 0.0, deepest = 0.0, last_outside = t_step;
  loop->run(500.0,
            [&]
            {
              max_elevator = std::max(max_elevator, std::abs(loop->fins().elevator));
              deepest = std::max(deepest, loop->depth());
              if (std::abs(loop->depth() - target) >= kTolerance)
                last_outside = loop->time_;
              if (loop->time_ - t_step >= 400.0)
                worst_late = std::max(worst_late, std::abs(loop->depth() - target));
            });
  std::lock_guard<std::mutex> lock(mutex);
  std::printf(
      "winch: from %.2f m to a setpoint of %.2f m: within 1 m from %.1f s on, overshoot %.2f m, within %.2f m over "
      "the last 100 s; cable out %.2f m, planned %.2f m; largest payout command %.2f m/s, max |elevator| %.3f rad; "
      "%d late steps\n",
      first, target, last_outside - t_step, deepest - target, worst_late, cable_out, plan.response.cable_out, payout,
      max_elevator, loop->late_steps_);
  EXPECT_GT(payout, 0.1);
  EXPECT_EQ(max_elevator, 0.0);
  EXPECT_LT(last_outside - t_step, kWinchSettlingTime);
  EXPECT_LT(worst_late, kTolerance);
  EXPECT_NEAR(cable_out, plan.response.cable_out, 0.01 * plan.response.cable_out);
  EXPECT_EQ(loop->late_steps_, 0);
}

TEST(DepthAutopilotNode, BadSetpointsAreIgnoredAndStaleOdometryCentresTheFins)
{
  const double held = loop->depth();
  loop->setpoint(-5.0);
  loop->run(1.0);
  loop->setpoint(std::numeric_limits<double>::quiet_NaN());
  loop->run(1.0);
  loop->setpoint(20000.0);
  double max_error = 0.0;
  loop->run(20.0, [&] { max_error = std::max(max_error, std::abs(loop->depth() - held)); });
  std::printf("after setpoints -5, NaN and 20000 m: depth within %.3f m of %.2f m\n", max_error, held);
  EXPECT_LT(max_error, kTolerance);
  EXPECT_EQ(loop->late_steps_, 0);

  // Pause the simulation: vehicle/odom keeps its stamp, so after odom_timeout the fins are centred.
  ros::ServiceClient pause = loop->nh_.serviceClient<std_srvs::SetBool>("/tow_sim/set_paused");
  std_srvs::SetBool srv;
  srv.request.data = true;
  ASSERT_TRUE(pause.call(srv));
  tow_sim::FinCommand fins;
  const double paused_at = loop->time_;
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::WallTime::now() < give_up)
  {
    loop->tick();  // the ship and the clock go on; the autopilot keeps publishing
    ros::WallDuration(0.01).sleep();
    fins = loop->fins();
    if (fins.header.stamp.toSec() > paused_at + 1.0 && fins.elevator == 0.0 && fins.rudder == 0.0)
      break;
  }
  std::printf("paused at %.1f s: fins centred at %.2f s (odom_timeout 1 s)\n", paused_at, fins.header.stamp.toSec());
  EXPECT_EQ(fins.elevator, 0.0);
  EXPECT_EQ(fins.rudder, 0.0);
  EXPECT_EQ(fins.thrust, 0.0);
  srv.request.data = false;
  EXPECT_TRUE(pause.call(srv));
}

TEST(DepthAutopilotNode, BadParameterExitsNamingIt)
{
  loop->nh_.setParam("/bad/depth_autopilot/kp", -1.0);
  FILE* pipe = popen(DEPTH_AUTOPILOT_NODE_BINARY " __ns:=/bad __name:=depth_autopilot 2>&1", "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe))
    output += buffer;
  EXPECT_NE(pclose(pipe), 0);
  EXPECT_NE(output.find("/bad/depth_autopilot/kp = -1 is out of range"), std::string::npos) << output;
  EXPECT_NE(output.find("[0, 10] [rad/m]"), std::string::npos) << output;
}

}  // namespace

// `rosrun dynamic_reconfigure dynparam ARGS` (as docs/nodes.md documents it), its output; the clock goes on
// meanwhile (dynparam waits on it with use_sim_time).
std::string dynparam(const std::string& args)
{
  auto call = std::async(std::launch::async,
                         [args]
                         {
                           std::string out;
                           FILE* pipe = popen(("rosrun dynamic_reconfigure dynparam " + args + " 2>&1").c_str(), "r");
                           char buffer[512];
                           while (pipe && fgets(buffer, sizeof(buffer), pipe))
                             out += buffer;
                           if (pipe)
                             pclose(pipe);
                           return out;
                         });
  while (call.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready)
    loop->step();
  return call.get();
}

// dynamic_reconfigure: a cross current set on tow_sim_node moves the vehicle to the side, a smaller kp on
// depth_autopilot_node gives a proportionally smaller elevator for the same depth error, and out-of-range
// values are refused with the old ones kept (the configuration read back).
TEST(DepthAutopilotNode, DynparamChangesTheCurrentAndTheGainsAndRefusesBadValues)
{
  loop->run(5.0);
  const double before = loop->vehicleY();
  std::printf("%s", dynparam("set /tow_sim current_y 0.5").c_str());
  loop->run(60.0);
  const double moved = loop->vehicleY() - before;
  std::string config = dynparam("get /tow_sim");
  EXPECT_NE(config.find("'current_y': 0.5"), std::string::npos) << config;
  std::printf("%s", dynparam("set /tow_sim current_y 25").c_str());  // out of range: [-20, 20]
  config = dynparam("get /tow_sim");
  EXPECT_NE(config.find("'current_y': 0.5"), std::string::npos) << config;
  std::printf("%s", dynparam("set /tow_sim current_y 0").c_str());
  std::printf("a 0.5 m/s current to +y moved the vehicle %.2f m to +y in 60 s (the ship heading -x)\n", moved);
  EXPECT_GT(moved, 5.0);

  // kp 0.1 -> 0.02 rad/m: a setpoint 5 m deeper changes the elevator by about -0.02 * 5 = -0.1 rad at once
  // (with the default kp: -0.5, saturated at -0.436 rad).
  loop->run(60.0);
  std::printf("%s", dynparam("set /depth_autopilot kp 0.02").c_str());
  std::printf("%s", dynparam("set /depth_autopilot kp -1").c_str());  // out of range: [0, 10]
  config = dynparam("get /depth_autopilot");
  EXPECT_NE(config.find("'kp': 0.02"), std::string::npos) << config;
  const double elevator0 = loop->fins().elevator;
  const double depth0 = loop->depth();
  loop->setpoint(depth0 + 5.0);
  loop->run(0.3);
  const double change = loop->fins().elevator - elevator0;
  std::printf("kp 0.02: the elevator changed by %.4f rad for a 5 m step (kp e = 0.1 rad)\n", change);
  EXPECT_NEAR(change, -0.1, 0.03);
  std::printf("%s", dynparam("set /depth_autopilot kp 0.1").c_str());
  loop->setpoint(depth0);
  loop->run(30.0);
  // Every 0.1 s step answered by both nodes, dynparam's calls and all (it was late once at 1156.05 s while
  // the test's clock summed doubles: issue 26, item 8).
  EXPECT_EQ(loop->late_steps_, 0);
}

// ~setpoint_marker: a drag in rviz ends with a MOUSE_UP feedback at the new pose; its depth becomes the
// setpoint (the vehicle gets there), the marker stays there; a pose above the surface is refused and the
// marker goes back to the setpoint in force.
TEST(DepthAutopilotNode, TheSetpointMarkerSetsTheDepthWhereItIsLetGo)
{
  std::mutex mutex;
  double marker_z = std::numeric_limits<double>::quiet_NaN();
  ros::Subscriber updates = loop->nh_.subscribe<visualization_msgs::InteractiveMarkerUpdate>(
      "/depth_autopilot/setpoint_marker/update", 20,
      [&](const visualization_msgs::InteractiveMarkerUpdate::ConstPtr& m)
      {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& marker : m->markers)
          if (marker.name == "depth_setpoint")
            marker_z = marker.pose.position.z;
        for (const auto& pose : m->poses)
          if (pose.name == "depth_setpoint")
            marker_z = pose.pose.position.z;
      });
  ros::Publisher feedback = loop->nh_.advertise<visualization_msgs::InteractiveMarkerFeedback>(
      "/depth_autopilot/setpoint_marker/feedback", 5);
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(10.0);
  while ((updates.getNumPublishers() < 1 || feedback.getNumSubscribers() < 1) && ros::WallTime::now() < give_up)
    loop->run(0.1);
  auto letGo = [&](double z)
  {
    visualization_msgs::InteractiveMarkerFeedback f;
    f.header.frame_id = "odom";
    f.client_id = "test";
    f.marker_name = "depth_setpoint";
    f.control_name = "move_z";
    f.event_type = visualization_msgs::InteractiveMarkerFeedback::MOUSE_UP;
    f.pose.position.z = z;
    f.pose.orientation.w = 1.0;
    feedback.publish(f);
  };
  const double target = loop->depth() + 10.0;
  letGo(-target);
  loop->run(90.0);
  const double final_error = std::abs(loop->depth() - target);
  double z_after_drag;
  {
    std::lock_guard<std::mutex> lock(mutex);
    z_after_drag = marker_z;
  }
  letGo(5.0);  // above the water: refused
  loop->run(2.0);
  std::lock_guard<std::mutex> lock(mutex);
  std::printf("marker let go at %.2f m: the vehicle at %.2f m after 90 s; marker z %.2f, after a refused drag %.2f\n",
              target, loop->depth(), z_after_drag, marker_z);
  EXPECT_LT(final_error, kTolerance);
  EXPECT_NEAR(z_after_drag, -target, 1e-9);
  EXPECT_NEAR(marker_z, -target, 1e-9);  // back where the setpoint is
  EXPECT_EQ(loop->late_steps_, 0);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_depth_autopilot");
  loop = std::make_unique<Loop>();
  const int result = RUN_ALL_TESTS();
  loop.reset();
  return result;
}
