// The live run (tow_sim_node's logic) driven by a fake clock without roscore: the time axis, the pacing
// against the clock and the odometry, holding, re-acquisition, the clock jumping back, the restart policy,
// the whole-step interpolation at the clock, the planned winch and the counters. Expected values come
// from the settings (the clock's arithmetic), not from the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "tow_sim/core/run/live_run.h"

namespace tow_sim
{
namespace
{
constexpr int64_t kSecond = 1'000'000'000;
constexpr int64_t kClock0 = 1000 * kSecond;  // the clock at the first odometry
constexpr double kSpeed = 2.0;               // [m/s] the ship's, along +x

// A wall clock the test sets, advancing `per_call` [s] at each reading (the time integration takes).
struct FakeWall
{
  double now = 50.0;
  double per_call = 0.0;
};

// Ten segments; dopri5 reaches each tick's target exactly (the implicit stepper, the default, steps past it).
SimulationConfig smallConfig(StepperType stepper = StepperType::kDopri5)
{
  SimulationConfig c;
  c.cable.segments = 10;
  c.numerics.stepper = stepper;
  return c;
}

class Live
{
public:
  explicit Live(SimulationConfig config = smallConfig(), LiveSettings settings = LiveSettings())
      : wall_(std::make_shared<FakeWall>()),
        live_(config, settings,
              [w = wall_]
              {
                w->now += w->per_call;
                return w->now;
              })
  {
    live_.setNotify([this](const LiveNotice& n) { notices.push_back(n); });
  }

  // The ship on its straight track at clock time t_ns, stamped then.
  static OdometryInput shipAt(int64_t t_ns, double offset_y = 0.0)
  {
    OdometryInput in;
    in.frame_id = "odom";
    in.p_W = Eigen::Vector3d(kSpeed * static_cast<double>(t_ns - kClock0) * 1e-9, offset_y, 0.0);
    in.v_S = Eigen::Vector3d(kSpeed, 0.0, 0.0);
    return in;
  }

  // Odometry every 0.1 s and a tick every 0.02 s of the clock, from `from` to `to` [ns]; the last
  // odometry at `odometry_until` (default: to).
  void drive(int64_t from, int64_t to, int64_t odometry_until = -1)
  {
    if (odometry_until < 0)
      odometry_until = to;
    for (int64_t t = from; t <= to; t += kSecond / 50)
    {
      if ((t - kClock0) % (kSecond / 10) == 0 && t <= odometry_until)
        live_.addOdometry(shipAt(t), t, t);
      live_.tick(t);
    }
  }

  bool said(LiveNotice::Kind kind) const
  {
    for (const LiveNotice& n : notices)
      if (n.kind == kind)
        return true;
    return false;
  }

  LiveRun& operator*() { return live_; }
  LiveRun* operator->() { return &live_; }
  FakeWall& wall() { return *wall_; }
  std::vector<LiveNotice> notices;

private:
  std::shared_ptr<FakeWall> wall_;
  LiveRun live_;
};

TEST(LiveRun, WaitsForTheFirstOdometryAndRefusesCommandsUntilThen)
{
  Live live;
  live->tick(kClock0);
  EXPECT_FALSE(live->started());
  EXPECT_EQ(live->status(), LiveStatus::kWaiting);
  EXPECT_FALSE(live->output(kClock0).has_value());
  bool saturated = true;
  EXPECT_FALSE(live->finCommand(0.1, 0.0, 0.0, &saturated));
  double applied = 0.0;
  std::string why;
  EXPECT_FALSE(live->winchCommand(0.5, &applied, &why));
  EXPECT_EQ(why, "no ship odometry yet");
  EXPECT_EQ(live->reset(), "no ship odometry yet");
  EXPECT_THROW(live->load(RunState()), std::logic_error);
  EXPECT_EQ(live->counters().rejected_messages, 0u);  // none of these was a bad message
}

// The first odometry fixes the origin one second and the odometry delay before its stamp, and the run
// starts there; ticks then follow the clock, odom_delay behind it.
TEST(LiveRun, TheRunFollowsTheClockOdomDelayBehind)
{
  LiveSettings settings;
  settings.odom_delay = 0.3;
  Live live(smallConfig(), settings);
  ASSERT_TRUE(live->addOdometry(Live::shipAt(kClock0), kClock0, kClock0));
  EXPECT_TRUE(live.said(LiveNotice::Kind::kFirstOdometry));
  EXPECT_DOUBLE_EQ(live->run().time(), 1.3);
  EXPECT_EQ(live->absolute(1.3), kClock0);
  EXPECT_DOUBLE_EQ(live->relative(kClock0 + 2 * kSecond), 3.3);
  // Outputs at the clock minus the delay carry the clock's stamp minus the delay, to the nanosecond.
  for (int64_t t = kClock0; t < kClock0 + 100 * kSecond; t += 10'000'001)
    ASSERT_EQ(live->absolute(live->relative(t) - 0.3), t - 300'000'000) << t;
  live.drive(kClock0, kClock0 + 5 * kSecond);
  EXPECT_NEAR(live->run().time(), 1.3 + 5.0 - 0.3, 1e-9);
  EXPECT_EQ(live->status(), LiveStatus::kRunning);
  const std::optional<TowSnapshot> out = live->output(kClock0 + 5 * kSecond);
  ASSERT_TRUE(out.has_value());
  EXPECT_NEAR(out->t, 6.0, 1e-9);
  EXPECT_NEAR(out->tow_point.p_W.x(), kSpeed * 4.7 - 20.0, 1e-6);  // the tow point 20 m astern, 0.3 s back
  // A stamp of zero is taken as received now.
  EXPECT_TRUE(live->addOdometry(Live::shipAt(kClock0 + 5100 * kSecond / 1000), 0, kClock0 + 5100 * kSecond / 1000));
  EXPECT_DOUBLE_EQ(live->ship().newestTime(), 6.4);
}

// The implicit stepper goes on in whole steps, up to one past the clock; the outputs are interpolated at
// the clock between the last two step ends.
TEST(LiveRun, WholeStepsGoPastTheClockAndTheOutputsAreAtTheClock)
{
  const SimulationConfig config = smallConfig(StepperType::kImplicit);
  Live live(config);
  int64_t from = kClock0;
  for (int64_t end : { 3 * kSecond, 3 * kSecond + kSecond / 50, 7 * kSecond + 3 * kSecond / 50 })
  {
    live.drive(from, kClock0 + end);
    from = kClock0 + end + kSecond / 50;
    const double wanted = 1.2 + static_cast<double>(end) * 1e-9 - 0.2;
    EXPECT_GE(live->run().time(), wanted - 1e-12);
    EXPECT_LT(live->run().time(), wanted + config.numerics.max_step + 1e-12);  // at most one step past it
    const std::optional<TowSnapshot> out = live->output(kClock0 + end);
    ASSERT_TRUE(out.has_value());
    EXPECT_NEAR(out->t, wanted, 1e-9);
    EXPECT_NEAR(out->tow_point.p_W.x(), kSpeed * (wanted - 1.2) - 20.0, 1e-6);
  }
  // Stamped with the clock's time less the delay to the nanosecond, as a dopri5 run's outputs are (the node
  // test compares the two nodes' outputs of one stamp).
  for (int i = 1; i <= 200; ++i)
  {
    const int64_t now = from + i * kSecond / 50;
    live->addOdometry(Live::shipAt(now), now, now);
    live->tick(now);
    ASSERT_EQ(live->absolute(live->output(now)->t), now - 200'000'000) << i;
  }
}

// Past the newest odometry the run goes on max_extrapolation, then holds; odometry again and it goes on.
TEST(LiveRun, HoldsMaxExtrapolationPastTheNewestOdometryAndResumes)
{
  LiveSettings settings;
  settings.max_extrapolation = 0.5;
  Live live(smallConfig(), settings);
  live.drive(kClock0, kClock0 + 10 * kSecond, kClock0 + 2 * kSecond);
  const double newest = live->ship().newestTime();
  EXPECT_DOUBLE_EQ(newest, 1.2 + 2.0);
  EXPECT_NEAR(live->run().time(), newest + 0.5, 1e-9);
  EXPECT_EQ(live->status(), LiveStatus::kHolding);
  EXPECT_TRUE(live.said(LiveNotice::Kind::kHolding));
  EXPECT_NEAR(live->counters().lag, 1.2 + 10.0 - 0.2 - live->run().time(), 1e-9);
  // Odometry again: the ship's history has no gap the run has not covered, and the run catches up.
  live.drive(kClock0 + 10 * kSecond + kSecond / 50, kClock0 + 12 * kSecond);
  EXPECT_NEAR(live->run().time(), 1.2 + 12.0 - 0.2, 1e-9);
  EXPECT_EQ(live->status(), LiveStatus::kRunning);
}

TEST(LiveRun, RefusedOdometryIsCountedWithItsReason)
{
  Live live;
  live.drive(kClock0, kClock0 + kSecond);
  OdometryInput wrong = Live::shipAt(kClock0 + 2 * kSecond);
  wrong.frame_id = "map";
  EXPECT_FALSE(live->addOdometry(wrong, kClock0 + 2 * kSecond, kClock0 + 2 * kSecond));
  EXPECT_EQ(live->counters().rejected_messages, 1u);
  ASSERT_FALSE(live.notices.empty());
  EXPECT_EQ(live.notices.back().kind, LiveNotice::Kind::kOdometryRejected);
  EXPECT_NE(live.notices.back().text.find("map"), std::string::npos) << live.notices.back().text;
  bool saturated = false;
  EXPECT_FALSE(live->finCommand(std::nan(""), 0.0, 0.0, &saturated));
  std::string why;
  EXPECT_FALSE(live->setCurrent(Eigen::Vector3d(std::nan(""), 0.0, 0.0), &why));
  EXPECT_FALSE(why.empty());
  EXPECT_EQ(live->counters().rejected_messages, 3u);
  EXPECT_TRUE(live->started());  // the run goes on
}

// A ship that is elsewhere for good (reacquire_after consistent messages away from the track): the track is
// dropped, and the last of them lays the cable out again at its time.
TEST(LiveRun, AShipMovedForGoodIsReacquired)
{
  LiveSettings settings;
  settings.reacquire_after = 3;
  Live live(smallConfig(), settings);
  live.drive(kClock0, kClock0 + 2 * kSecond);
  const uint64_t run = live->runNumber();
  for (int i = 1; i <= 3; ++i)
  {
    const int64_t t = kClock0 + 2 * kSecond + i * kSecond / 10;
    const bool accepted = live->addOdometry(Live::shipAt(t, 5000.0), t, t);
    EXPECT_EQ(accepted, i == 3) << i;
  }
  EXPECT_TRUE(live.said(LiveNotice::Kind::kShipReacquired));
  EXPECT_EQ(live->counters().rejected_messages, 2u);
  EXPECT_TRUE(live->started());
  EXPECT_EQ(live->runNumber(), run + 1);
  EXPECT_EQ(live->absolute(live->run().time()), kClock0 + 2300 * kSecond / 1000);
  EXPECT_NEAR(live->ship().towPoint(live->run().time()).p_W.y(), 5000.0, 1e-9);
}

TEST(LiveRun, TheClockJumpingBackForgetsTheShip)
{
  Live live;
  live.drive(kClock0, kClock0 + 3 * kSecond);
  live->tick(kClock0 + 2500 * kSecond / 1000);  // half a second back: jitter, nothing happens
  EXPECT_TRUE(live->started());
  live->tick(kClock0);  // three seconds back: rosbag play -l
  EXPECT_FALSE(live->started());
  EXPECT_FALSE(live->shipKnown());
  EXPECT_TRUE(live.said(LiveNotice::Kind::kClockJumpedBack));
  live.drive(kClock0, kClock0 + kSecond);  // the bag again from its start
  EXPECT_TRUE(live->started());
}

TEST(LiveRun, APausedRunHoldsItsTime)
{
  Live live;
  live.drive(kClock0, kClock0 + kSecond);
  const double t = live->run().time();
  live->setPaused(true);
  live.drive(kClock0 + kSecond + kSecond / 50, kClock0 + 3 * kSecond);
  EXPECT_EQ(live->run().time(), t);
  EXPECT_EQ(live->status(), LiveStatus::kPaused);
  live->setPaused(false);
  live.drive(kClock0 + 3 * kSecond + kSecond / 50, kClock0 + 4 * kSecond);
  EXPECT_EQ(live->counters().rejected_messages, 0u);
  EXPECT_NEAR(live->run().time(), 1.2 + 4.0 - 0.2, 1e-9);
}

// rk4 with 20 ms steps on a stiff elastic cable (axial frequency sqrt(EA / m) / d about 1e3 rad/s, far
// beyond rk4's stability limit of 2.8 / 0.02 s): every run diverges within its first tick.
SimulationConfig divergingConfig()
{
  SimulationConfig c = smallConfig(StepperType::kRk4);
  c.cable.axial_stiffness = 1e10;
  c.numerics.fixed_step = 0.02;
  return c;
}

// A divergence restarts the run from the initial shape at the run's time; restart_burst of them within
// restart_window of wall time hold the last good state until reset(); restarts spread out in wall time do not.
TEST(LiveRun, RestartsAfterADivergenceAndHoldsWhenTheyComeInABurst)
{
  LiveSettings settings;
  settings.restart_burst = 3;
  settings.restart_window = 10.0;
  Live live(divergingConfig(), settings);
  live->addOdometry(Live::shipAt(kClock0), kClock0, kClock0);
  live->tick(kClock0 + kSecond / 2);
  ASSERT_EQ(live->counters().restarts, 1u) << "the configuration was meant to diverge";
  EXPECT_TRUE(live.said(LiveNotice::Kind::kRestarted));
  EXPECT_EQ(live->status(), LiveStatus::kRestarted);
  EXPECT_LT(live->run().time(), 1.5);  // started again at the last good state, short of the target
  live->tick(kClock0 + 6 * kSecond / 10);
  EXPECT_EQ(live->status(), LiveStatus::kRestarted);
  live->tick(kClock0 + 7 * kSecond / 10);  // the third within the window (the wall clock stands still)
  EXPECT_EQ(live->counters().restarts, 3u);
  EXPECT_TRUE(live.said(LiveNotice::Kind::kDiverging));
  EXPECT_EQ(live->status(), LiveStatus::kDiverging);
  live->tick(kClock0 + 8 * kSecond / 10);
  EXPECT_EQ(live->counters().restarts, 3u);  // no more attempts
  EXPECT_EQ(live->reset(), "");
  EXPECT_NE(live->status(), LiveStatus::kDiverging);
  live->tick(kClock0 + 9 * kSecond / 10);
  EXPECT_EQ(live->counters().restarts, 4u);  // it tries again
}

TEST(LiveRun, RestartsSpreadOutInWallTimeGoOn)
{
  LiveSettings settings;
  settings.restart_burst = 3;
  settings.restart_window = 10.0;
  Live live(divergingConfig(), settings);
  live->addOdometry(Live::shipAt(kClock0), kClock0, kClock0);
  for (int i = 1; i <= 6; ++i)
  {
    live->tick(kClock0 + (4 + i) * kSecond / 10);
    live.wall().now += 6.0;  // three restarts span 12 s of wall time
  }
  EXPECT_EQ(live->counters().restarts, 6u);
  EXPECT_FALSE(live.said(LiveNotice::Kind::kDiverging));
  EXPECT_EQ(live->status(), LiveStatus::kRestarted);  // the last one 6 s ago
  live.wall().now += 5.0;
  EXPECT_EQ(live->status(), LiveStatus::kRunning);
}

// The counters' wall-time figures from a wall clock that advances 10 ms at each reading: a tick reads it
// twice around its integration, so each tick costs 10 ms of wall time.
TEST(LiveRun, CountsWallTimeAndStepsAndTakesTheLoadPerInterval)
{
  Live live;
  live.drive(kClock0, kClock0 + kSecond);
  live->takeLoad();  // the interval starts here
  live.wall().per_call = 0.01;
  const double t0 = live->run().time();
  const double wall0 = live.wall().now;
  for (int i = 1; i <= 10; ++i)
    live->tick(kClock0 + kSecond + i * kSecond / 50);
  const double advanced = live->run().time() - t0;
  EXPECT_NEAR(advanced, 0.2, 1e-9);
  EXPECT_NEAR(live->counters().tick_cost, 0.01 / 0.02, 1e-9);  // 10 ms for 20 ms of simulated time
  const LiveLoad load = live->takeLoad();
  const double interval = live.wall().now - wall0;
  EXPECT_NEAR(load.physics_load, 10 * 0.01 / interval, 1e-9);
  EXPECT_GT(load.steps_per_second, 0.0);
  EXPECT_EQ(live->takeLoad().physics_load, 0.0);  // nothing since
}

// ~plan_cable_out's execution: the winch driven to a cable out, stopped there, and said.
TEST(LiveRun, TheWinchGoesToAPlannedCableOutAndStops)
{
  SimulationConfig config = smallConfig();
  EXPECT_NE(Live(config)->driveWinchTo(150.0), "");  // winch.enabled is false
  config.winch.enabled = true;
  config.cable.length = 100.0;
  Live live(config);
  EXPECT_EQ(live->driveWinchTo(150.0), "no ship odometry yet");
  live.drive(kClock0, kClock0 + kSecond);
  EXPECT_EQ(live->driveWinchTo(120.0), "");
  live.drive(kClock0 + kSecond + kSecond / 50, kClock0 + 60 * kSecond);
  EXPECT_TRUE(live.said(LiveNotice::Kind::kWinchArrived));
  EXPECT_NEAR(live->run().simulator().cableLength(), 120.0, 0.05 + 0.02);  // stopped within reach of the mark
  // A command from outside ends a plan under way.
  EXPECT_EQ(live->driveWinchTo(140.0), "");
  double applied = 0.0;
  std::string why;
  EXPECT_TRUE(live->winchCommand(0.0, &applied, &why));
  live.drive(kClock0 + 60 * kSecond + kSecond / 50, kClock0 + 70 * kSecond);
  EXPECT_LT(live->run().simulator().cableLength(), 125.0);
}

// A saved state goes on at the run's time now, placed at the ship: a new run for the front end.
TEST(LiveRun, ALoadedStateGoesOnFromTheRunsTimeAtTheShip)
{
  Live live;
  live.drive(kClock0, kClock0 + 2 * kSecond);
  const TowSnapshot before = *live->output(kClock0 + 2 * kSecond);
  const RunState saved = live->run().saveState();
  live.drive(kClock0 + 2 * kSecond + kSecond / 50, kClock0 + 5 * kSecond);
  const uint64_t run = live->runNumber();
  const double t = live->run().time();
  live->load(saved);
  EXPECT_EQ(live->runNumber(), run + 1);
  EXPECT_EQ(live->run().time(), t);
  // The saved shape, relative to the tow point, at the ship 3 s (6 m) further along.
  const TowSnapshot after = *live->output(kClock0 + 5 * kSecond);
  ASSERT_EQ(after.joints.cols(), before.joints.cols());
  EXPECT_NEAR(after.joints(0, 0) - before.joints(0, 0), 3.0 * kSpeed, 1e-9);
  for (Eigen::Index j = 1; j < after.joints.cols(); ++j)
    EXPECT_NEAR(((after.joints.col(j) - after.joints.col(0)) - (before.joints.col(j) - before.joints.col(0))).norm(),
                0.0, 1e-9)
        << j;
  EXPECT_EQ(live->status(), LiveStatus::kRunning);
}

}  // namespace
}  // namespace tow_sim
