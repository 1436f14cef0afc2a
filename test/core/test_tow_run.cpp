// TowRun, the one run loop, driven directly: a start at any time (a restart is a start) replays the
// schedule as it stands then, the autopilot starts afresh from that time, and bad arguments are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "core/chain_fixtures.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"

namespace tow_sim
{
namespace
{
// A ship at 2 m/s along +x, sampled every second for 200 s.
std::shared_ptr<ShipHistory> straightShip()
{
  return test::steamingShip(Eigen::Vector2d::Zero(), 0.0, 200);
}

SimulationConfig smallConfig()
{
  SimulationConfig c;
  c.cable.segments = 10;
  return c;
}

CommandEvent thrustAndElevator(double t, double elevator, double thrust)
{
  CommandEvent c;
  c.t = t;
  c.elevator = elevator;
  c.thrust = thrust;
  return c;
}

TEST(TowRun, AStartAtAnyTimeAppliesTheLastCommandDueThenFromThatTime)
{
  TowRun run(smallConfig(), straightShip());
  run.schedule({ thrustAndElevator(0.0, 0.1, 50.0), thrustAndElevator(10.0, -0.1, 200.0) });
  run.start(5.0);
  const Actuators& a = run.simulator().data().actuators;
  EXPECT_EQ(a.thrust, 50.0);
  EXPECT_EQ(a.elevator.target(), 0.1);
  // The servo leaves the centre at the start time, not at the previous run's time (0 here).
  EXPECT_EQ(a.elevator.angleAt(5.0), 0.0);
  EXPECT_GT(a.elevator.angleAt(5.1), 0.0);
  run.advanceTo(12.0);
  EXPECT_EQ(run.simulator().data().actuators.thrust, 200.0);  // the later command still comes
}

TEST(TowRun, ARestartReplaysTheScheduleInsteadOfForgettingIt)
{
  TowRun run(smallConfig(), straightShip());
  run.schedule({ thrustAndElevator(10.0, -0.1, 200.0) });
  run.start(0.0);
  run.advanceTo(30.0);
  run.start(30.0);  // as after a divergence
  const Actuators& a = run.simulator().data().actuators;
  EXPECT_EQ(a.thrust, 200.0);
  EXPECT_EQ(a.elevator.target(), -0.1);
  EXPECT_EQ(run.time(), 30.0);
}

TEST(TowRun, TheAutopilotStartsFromTheStartTime)
{
  AutopilotLoop loop;
  loop.enabled = true;
  loop.rate = 10.0;
  AutopilotSetpoint sp;
  sp.t = 0.0;
  sp.value = 150.0;
  loop.setpoints = { sp };
  TowRun run(smallConfig(), straightShip());
  run.setAutopilot(loop);
  run.start(5.0);
  EXPECT_NO_THROW(run.advanceTo(6.0));  // its first tick is at 5 s, not 0
  const TowSnapshot s = run.snapshot();
  ASSERT_TRUE(s.depth_setpoint.has_value());  // the setpoint due at 0 s was given at the start
  EXPECT_EQ(*s.depth_setpoint, 150.0);
  // Set after the start, it ticks from the run's time on.
  TowRun later(smallConfig(), straightShip());
  later.start(5.0);
  later.setAutopilot(loop);
  EXPECT_NO_THROW(later.advanceTo(6.0));
  EXPECT_EQ(*later.snapshot().depth_setpoint, 150.0);  // a setpoint scheduled in the past acts at once
}

TEST(TowRun, RefusesATargetThatIsNotFiniteOrInThePastAndOutputsBeforeTheStart)
{
  TowRun run(smallConfig(), straightShip());
  EXPECT_THROW(run.snapshot(), std::logic_error);
  EXPECT_THROW(run.advanceTo(1.0), std::logic_error);
  EXPECT_THROW(run.start(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  run.schedule({ thrustAndElevator(1.0, 0.0, 10.0) });
  run.start(0.0);
  run.advanceTo(2.0);
  for (double bad : { std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1.0 })
    EXPECT_THROW(run.advanceTo(bad), std::invalid_argument) << bad;
  EXPECT_EQ(run.time(), 2.0);  // nothing moved
  EXPECT_NO_THROW(run.snapshot());
}

// The node publishes between whole steps of the implicit stepper by interpolating two snapshots.
// The node's physics tick (tickTarget) by hand: 0.5 s of simulated time at most, about max_wall of wall
// time at the measured cost, at least one step, never past what the odometry allows.
TEST(TowRun, ATickIsBoundedInSimulatedAndWallTime)
{
  using tow_sim::tickTarget;
  EXPECT_DOUBLE_EQ(tickTarget(10.0, 12.0, 20.0, 0.0, 0.0, 0.5, 0.05), 10.5);    // cost unknown: 0.5 s
  EXPECT_DOUBLE_EQ(tickTarget(10.0, 10.2, 20.0, 0.0, 0.0, 0.5, 0.05), 10.2);    // the clock first
  EXPECT_DOUBLE_EQ(tickTarget(10.0, 12.0, 10.3, 0.0, 0.0, 0.5, 0.05), 10.3);    // the odometry's end
  EXPECT_DOUBLE_EQ(tickTarget(10.0, 12.0, 20.0, 0.0, 0.5, 0.5, 0.05), 10.1);    // 0.5 wall s per s: 0.1 s
  EXPECT_DOUBLE_EQ(tickTarget(10.0, 12.0, 20.0, 0.0, 1e3, 0.5, 0.05), 10.001);  // hopeless: 1 ms
  EXPECT_DOUBLE_EQ(tickTarget(10.0, 12.0, 20.0, 0.2, 1e3, 0.5, 0.05), 10.2);    // whole steps: one
  EXPECT_DOUBLE_EQ(tickTarget(10.0, 10.05, 20.0, 0.2, 0.0, 0.5, 0.05), 10.2);   // one step past the clock
  EXPECT_DOUBLE_EQ(tickTarget(10.0, 12.0, 20.0, 0.0, 1e-3, 0.5, 0.05), 10.5);   // cheap: 0.5 s still
}

TEST(TowRun, SnapshotsInterpolateBetweenTwoTimes)
{
  SimulationConfig c = smallConfig();
  c.numerics.stepper = StepperType::kImplicit;
  TowRun run(c, straightShip()), twin(c, straightShip());
  run.schedule({ thrustAndElevator(1.0, 0.2, 100.0) });  // a moving vehicle
  twin.schedule({ thrustAndElevator(1.0, 0.2, 100.0) });
  run.start(0.0);
  twin.start(0.0);
  run.advanceTo(10.0);
  const TowSnapshot a = run.snapshot();
  run.advanceTo(10.5);
  const TowSnapshot b = run.snapshot();
  twin.advanceTo(10.25);
  const TowSnapshot mid = twin.snapshot();
  const TowSnapshot i = interpolate(a, b, 10.25);
  EXPECT_EQ(i.t, 10.25);
  // Linear in time between outputs that move by decimetres: the midpoint within millimetres.
  EXPECT_LT((i.joints - mid.joints).cwiseAbs().maxCoeff(), 5e-3);
  EXPECT_NEAR(i.depth, mid.depth, 1e-3);
  EXPECT_NEAR(i.tension_ship, mid.tension_ship, 1e-3 * mid.tension_ship);
  EXPECT_NEAR(i.vehicle.elevator, mid.vehicle.elevator, 1e-3);
  EXPECT_LT(i.attitude.angularDistance(mid.attitude), 1e-3);
  // The ends are the snapshots themselves; outside them the nearer end.
  EXPECT_EQ(interpolate(a, b, 10.0).joints, a.joints);
  EXPECT_EQ(interpolate(a, b, 10.5).joints, b.joints);
  EXPECT_EQ(interpolate(a, b, 11.0).t, b.t);
  // Yaw the short way round across +-pi.
  TowSnapshot left = a, right = b;
  left.yaw = kPi - 0.1;
  right.yaw = -kPi + 0.1;
  EXPECT_NEAR(std::abs(interpolate(left, right, 10.25).yaw), kPi, 1e-12);
  // A change of layout (the winch re-meshing): the nearer snapshot whole.
  right.joints.conservativeResize(3, right.joints.cols() + 1);
  EXPECT_EQ(interpolate(left, right, 10.1).joints, left.joints);
  // Across a parting with the same joints (a cable left on the ship on one side only): the nearer whole.
  TowSnapshot parted = b;
  parted.parted = true;
  parted.ship_side = Eigen::Matrix3Xd::Ones(3, 4);
  parted.ship_side_tensions = Eigen::Matrix3Xd::Ones(3, 3);
  EXPECT_EQ(interpolate(a, parted, 10.4).ship_side_tensions.cols(), 3);
  EXPECT_EQ(interpolate(a, parted, 10.1).ship_side_tensions.cols(), 0);
  TowSnapshot stale = parted, none = parted;  // both without joints on the ship, one with stale tensions
  stale.ship_side.resize(3, 0);
  stale.t = a.t;
  none.ship_side.resize(3, 0);
  none.ship_side_tensions.resize(3, 0);
  EXPECT_EQ(interpolate(stale, none, 10.1).ship_side_tensions.cols(), 3);
  EXPECT_EQ(interpolate(stale, none, 10.4).ship_side_tensions.cols(), 0);
}

}  // namespace
}  // namespace tow_sim
