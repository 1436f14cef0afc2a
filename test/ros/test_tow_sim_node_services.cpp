// rostest of tow_sim_node (the world: tow_sim_node_world.h): its services (pause, reset, save and load a
// state, plan the cable out), restarts after divergence, re-acquiring the ship, the winch over the seabed, a
// bad configuration, and the clock jumping back.
#include "tow_sim/core/io/saved_state.h"
#include "tow_sim_node_world.h"

namespace tow_sim_test
{
namespace
{
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

// A state saved under another configuration (here: its numerics.max_step changed) is refused naming the key
// with both values, and loaded when asked for with any_configuration.
TEST(TowSimNode, AStateSavedUnderAnotherConfigurationIsRefusedUnlessAskedFor)
{
  ros::ServiceClient save = world->nh_.serviceClient<tow_sim::StateFile>("/base/tow_sim/save_state");
  ros::ServiceClient load = world->nh_.serviceClient<tow_sim::StateFile>("/base/tow_sim/load_state");
  ASSERT_TRUE(load.waitForExistence(ros::Duration(5.0)));
  world->advance(1.0);
  const std::string path = "/tmp/tow_sim_test_configuration_state.txt";
  tow_sim::StateFile f;
  f.request.path = path;
  ASSERT_TRUE(save.call(f));
  ASSERT_TRUE(f.response.success) << f.response.message;
  tow_sim::RunState other = tow_sim::readRunState(path);
  ASSERT_EQ(other.configuration.count("numerics.max_step"), 1u);
  other.configuration.at("numerics.max_step") = "0.125";
  tow_sim::writeRunState(path, other);
  ASSERT_TRUE(load.call(f));
  EXPECT_FALSE(f.response.success);
  EXPECT_NE(f.response.message.find("1 key differs: numerics.max_step (saved 0.125, now "), std::string::npos)
      << f.response.message;
  f.request.any_configuration = true;
  ASSERT_TRUE(load.call(f));
  EXPECT_TRUE(f.response.success) << f.response.message;
  world->advance(0.5);
  std::lock_guard<std::mutex> lock(world->rec_.mutex);
  EXPECT_TRUE(allFinite(world->rec_.state["base"]));
  std::remove(path.c_str());
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
  world->setClockBack(30);
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
}  // namespace tow_sim_test
