// The depth autopilot without ROS: signs, saturation, anti-windup on a plant where windup matters, the
// past track's offset sign on straight and turned tracks, validation, stale odometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/depth_autopilot.h"

namespace
{
using tow_sim::AutopilotCommand;
using tow_sim::DepthAutopilot;
using tow_sim::DepthAutopilotParams;
using tow_sim::PastTrack;
using tow_sim::VehicleMeasurement;

VehicleMeasurement at(double t, double depth, double v_up = 0.0)
{
  VehicleMeasurement m;
  m.t = t;
  m.p_W = Eigen::Vector3d(0.0, 0.0, -depth);
  m.v_W = Eigen::Vector3d(2.0, 0.0, v_up);
  return m;
}

DepthAutopilotParams noTrack()
{
  DepthAutopilotParams p;
  p.track_keeping = false;
  return p;
}

TEST(DepthAutopilot, TooShallowDivesTooDeepRisesRisingIsDamped)
{
  DepthAutopilot ap(noTrack());
  ap.setSetpoint(100.0);
  ap.addVehicle(at(0.0, 98.0));  // 2 m too shallow
  const AutopilotCommand shallow = ap.update(0.0);
  EXPECT_EQ(shallow.status, AutopilotCommand::Status::kActive);
  EXPECT_NEAR(shallow.depth_error, 2.0, 1e-12);
  EXPECT_NEAR(shallow.elevator, -0.1 * 2.0, 1e-12);  // negative elevator pushes the fins down: dive

  DepthAutopilot deep(noTrack());
  deep.setSetpoint(100.0);
  deep.addVehicle(at(0.0, 103.0));
  EXPECT_NEAR(deep.update(0.0).elevator, 0.1 * 3.0, 1e-12);

  DepthAutopilot rising(noTrack());
  rising.setSetpoint(100.0);
  rising.addVehicle(at(0.0, 100.0, 0.5));  // on depth, rising at 0.5 m/s: the derivative pushes down
  EXPECT_NEAR(rising.update(0.0).elevator, -0.2 * 0.5, 1e-12);
}

TEST(DepthAutopilot, RollHoldCommandsTheDifferentialAgainstTheRoll)
{
  DepthAutopilotParams p = noTrack();
  DepthAutopilot off(p);
  p.roll_hold = true;
  p.roll_kp = 2.0;
  p.roll_kd = 0.5;
  p.max_differential = 0.1;
  DepthAutopilot on(p);
  VehicleMeasurement m = at(0.0, 50.0);
  EXPECT_EQ((on.addVehicle(m), on.update(0.0)).differential, 0.0);  // roll unknown: nothing to hold
  m.t = 0.1;
  m.roll = 0.02;  // starboard down: a positive differential rolls it back to port
  m.roll_rate = -0.01;
  EXPECT_DOUBLE_EQ((on.addVehicle(m), on.update(0.1)).differential, 2.0 * 0.02 - 0.5 * 0.01);
  EXPECT_EQ((off.addVehicle(m), off.update(0.1)).differential, 0.0);  // roll_hold off
  m.t = 0.2;
  m.roll = -0.3;
  EXPECT_EQ((on.addVehicle(m), on.update(0.2)).differential, -0.1);  // saturated
  m.t = 0.3;
  m.roll = INFINITY;
  EXPECT_THROW(on.addVehicle(m), std::invalid_argument);
  p.max_differential = 0.0;
  EXPECT_THROW(DepthAutopilot{ p }, std::invalid_argument);
}

TEST(DepthAutopilot, OutputSaturatesAtMaxElevator)
{
  DepthAutopilotParams p = noTrack();
  p.max_elevator = 0.3;
  DepthAutopilot ap(p);
  ap.setSetpoint(50.0);
  ap.addVehicle(at(0.0, 10.0));  // 40 m too shallow: -4 rad unsaturated
  AutopilotCommand c = ap.update(0.0);
  EXPECT_DOUBLE_EQ(c.elevator, -0.3);
  EXPECT_TRUE(c.elevator_saturated);
  ap.addVehicle(at(1.0, 90.0));  // 40 m too deep
  c = ap.update(1.0);
  EXPECT_DOUBLE_EQ(c.elevator, 0.3);
  EXPECT_TRUE(c.elevator_saturated);
  ap.addVehicle(at(2.0, 50.5));
  c = ap.update(2.0);
  EXPECT_FALSE(c.elevator_saturated);
  EXPECT_LT(std::abs(c.elevator), 0.3);
}

// A first-order depth plant like the towed vehicle's: 170 m per rad of elevator, 40 s time constant,
// 217 m deep at zero elevator. 60 m up (to 157 m) needs 0.353 rad in the end, and the step asks for far
// more at first, so the output saturates for a while.
constexpr double kStart = 217.0, kTarget = 157.0, kDt = 0.1;

struct PlantRun
{
  double overshoot = 0.0;               // [m] past the setpoint, after first reaching it
  double max_integral_saturated = 0.0;  // [rad] largest |integral term| while saturated
  double saturated_time = 0.0;          // [s]
};

// controller(t, depth, v_up, &integral, &saturated) -> elevator [rad]
template <typename Controller>
PlantRun runPlant(Controller controller)
{
  PlantRun run;
  double depth = kStart, v_up = 0.0;
  bool reached = false;
  for (int i = 0; i < 6000; ++i)
  {
    double integral = 0.0;
    bool saturated = false;
    const double elevator = controller(i * kDt, depth, v_up, &integral, &saturated);
    const double depth_rate = (kStart - 170.0 * elevator - depth) / 40.0;
    depth += depth_rate * kDt;
    v_up = -depth_rate;
    if (saturated)
    {
      run.saturated_time += kDt;
      run.max_integral_saturated = std::max(run.max_integral_saturated, std::abs(integral));
    }
    reached = reached || depth <= kTarget;
    if (reached)
      run.overshoot = std::max(run.overshoot, kTarget - depth);
  }
  return run;
}

TEST(DepthAutopilot, AntiWindupBoundsTheIntegralWhileSaturatedAndAvoidsOvershoot)
{
  // 60 m up needs 0.35 rad of elevator at the end but the step asks for far more at first: saturated.
  DepthAutopilot ap(noTrack());
  ap.setSetpoint(kTarget);
  const PlantRun ours = runPlant(
      [&](double t, double depth, double v_up, double* integral, bool* saturated)
      {
        ap.addVehicle(at(t, depth, v_up));
        const AutopilotCommand c = ap.update(t);
        *integral = c.integral;
        *saturated = c.elevator_saturated;
        return c.elevator;
      });

  // The same PID with a plain integrator (no anti-windup) on the same plant, to show that the case matters.
  const DepthAutopilotParams p;
  double plain_integral = 0.0;
  const PlantRun plain = runPlant(
      [&](double, double depth, double v_up, double* integral, bool* saturated)
      {
        const double e = kTarget - depth;
        plain_integral += -p.ki * e * kDt;
        const double u = -p.kp * e - p.kd * v_up + plain_integral;
        *integral = plain_integral;
        *saturated = std::abs(u) > p.max_elevator;
        return std::clamp(u, -p.max_elevator, p.max_elevator);
      });
  std::printf(
      "saturated %.1f s; |integral| while saturated: %.3f rad (plain PID %.3f rad); overshoot %.2f m "
      "(plain PID %.2f m)\n",
      ours.saturated_time, ours.max_integral_saturated, plain.max_integral_saturated, ours.overshoot, plain.overshoot);
  ASSERT_GT(ours.saturated_time, 5.0);  // the case does saturate
  EXPECT_GT(plain.overshoot, 3.0);      // and windup would matter in it
  // Conditional integration: the integral (0 at the step) does not wind up while saturated at all; merely
  // clamping it to +-max_elevator would let it reach 0.436 rad here and overshoot 0.66 m.
  EXPECT_LT(ours.max_integral_saturated, 0.05);
  EXPECT_LT(ours.overshoot, 0.3);
}

// Live tuning (dynamic_reconfigure's path): new gains act on the next command by the law written out here,
// the integral is kept (within a smaller max_elevator), a bad value changes nothing and is named.
TEST(DepthAutopilot, TuningWhileRunningKeepsTheStateAndRefusesBadValues)
{
  DepthAutopilot ap(noTrack());
  ap.setSetpoint(100.0);
  double integral = 0.0;
  for (int i = 0; i <= 100; ++i)  // 100 s at 0.5 m too shallow: the integral collects -ki e t (unsaturated)
  {
    ap.addVehicle(at(i, 99.5));
    integral = ap.update(i).integral;
  }
  EXPECT_NEAR(integral, -0.0025 * 0.5 * 100.0, 1e-12);
  DepthAutopilotParams tuned = noTrack();
  tuned.kp = 0.05;
  tuned.kd = 0.4;
  tuned.max_elevator = 0.3;
  tuned.actuator = DepthAutopilotParams::Actuator::kWinch;  // structural: kept as constructed
  ap.setTuning(tuned);
  EXPECT_EQ(ap.params().actuator, DepthAutopilotParams::Actuator::kElevator);
  ap.addVehicle(at(101.0, 99.5, -0.25));  // sinking at 0.25 m/s
  const AutopilotCommand c = ap.update(101.0);
  const double expected_integral = integral - 0.0025 * 0.5;
  EXPECT_NEAR(c.integral, expected_integral, 1e-12);
  EXPECT_NEAR(c.elevator, -0.05 * 0.5 - 0.4 * -0.25 + expected_integral, 1e-12);
  EXPECT_FALSE(c.elevator_saturated);

  tuned.max_elevator = 0.1;  // below the integral's 0.126 rad: clamped
  ap.setTuning(tuned);
  ap.addVehicle(at(102.0, 100.0));
  EXPECT_NEAR(ap.update(102.0).integral, -0.1, 1e-12);

  DepthAutopilotParams bad = tuned;
  bad.kp = -1.0;
  try
  {
    ap.setTuning(bad, "/depth_autopilot/");
    FAIL() << "kp = -1 accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("/depth_autopilot/kp = -1 is out of range"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ap.params().kp, 0.05);
  EXPECT_EQ(ap.params().max_elevator, 0.1);
}

TEST(DepthAutopilot, IntegratesOncePerMeasurementNotPerCall)
{
  DepthAutopilot a(noTrack()), b(noTrack());
  a.setSetpoint(100.0);
  b.setSetpoint(100.0);
  for (int i = 0; i < 50; ++i)
  {
    a.addVehicle(at(i * 0.1, 101.0));
    b.addVehicle(at(i * 0.1, 101.0));
    a.update(i * 0.1);
    for (int k = 0; k < 5; ++k)
      b.update(i * 0.1 + 0.01 * k);
  }
  EXPECT_NEAR(a.update(4.9).integral, b.update(4.9).integral, 1e-15);
  EXPECT_NEAR(a.update(4.9).integral, 0.0025 * 1.0 * 4.9, 1e-12);  // positive: too deep, rise
}

TEST(DepthAutopilot, HoldsTheFirstDepthWithoutASetpoint)
{
  DepthAutopilot ap(noTrack());
  EXPECT_EQ(ap.update(0.0).status, AutopilotCommand::Status::kWaiting);
  EXPECT_FALSE(ap.hasSetpoint());
  ap.addVehicle(at(1.0, 87.5));
  EXPECT_TRUE(ap.hasSetpoint());
  EXPECT_DOUBLE_EQ(ap.setpoint(), 87.5);
  EXPECT_NEAR(ap.update(1.0).elevator, 0.0, 1e-15);
}

TEST(DepthAutopilot, AltitudeModeTurnsTheAltitudeIntoADepthSetpoint)
{
  DepthAutopilot ap(noTrack());
  ap.setAltitudeSetpoint(10.0);
  VehicleMeasurement m = at(0.0, 100.0);
  m.altitude = 30.0;  // 20 m higher than wanted: go to 120 m, i.e. too shallow, dive
  ap.addVehicle(m);
  EXPECT_TRUE(ap.altitudeMode());
  EXPECT_DOUBLE_EQ(ap.setpoint(), 120.0);
  const AutopilotCommand c = ap.update(0.0);
  EXPECT_NEAR(c.depth_error, 20.0, 1e-12);
  EXPECT_LT(c.elevator, 0.0);
  // The bottom rises under the vehicle: at the same depth 4 m of altitude is 6 m too low: climb.
  m = at(1.0, 100.0);
  m.altitude = 4.0;
  ap.addVehicle(m);
  EXPECT_DOUBLE_EQ(ap.setpoint(), 94.0);
  EXPECT_GT(ap.update(1.0).elevator, 0.0);
  // No altitude (no seabed in sight): the last depth setpoint is held.
  ap.addVehicle(at(2.0, 97.0));
  EXPECT_DOUBLE_EQ(ap.setpoint(), 94.0);
  // A depth setpoint leaves altitude mode; a bad altitude setpoint is refused.
  ap.setSetpoint(50.0);
  EXPECT_FALSE(ap.altitudeMode());
  EXPECT_THROW(ap.setAltitudeSetpoint(-1.0), std::invalid_argument);
  EXPECT_THROW(ap.setAltitudeSetpoint(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST(DepthAutopilot, StaleOdometryCentresTheFins)
{
  DepthAutopilotParams p;
  p.thrust = 50.0;
  DepthAutopilot ap(p);
  ap.setSetpoint(10.0);
  ap.addVehicle(at(5.0, 30.0));
  EXPECT_EQ(ap.update(5.5).status, AutopilotCommand::Status::kActive);
  const AutopilotCommand stale = ap.update(6.01);  // > odom_timeout = 1 s after the stamp
  EXPECT_EQ(stale.status, AutopilotCommand::Status::kStale);
  EXPECT_EQ(stale.elevator, 0.0);
  EXPECT_EQ(stale.rudder, 0.0);
  EXPECT_EQ(stale.thrust, 0.0);
  EXPECT_FALSE(ap.addVehicle(at(5.0, 30.0)));  // not after the previous stamp
  EXPECT_TRUE(ap.addVehicle(at(7.0, 10.5)));   // 0.5 m deep of the setpoint: the output is not saturated
  const AutopilotCommand back = ap.update(7.0);
  EXPECT_EQ(back.status, AutopilotCommand::Status::kActive);
  EXPECT_EQ(back.thrust, 50.0);
  EXPECT_FALSE(back.elevator_saturated);
  EXPECT_EQ(back.integral, 0.0);  // nothing integrated across the 2 s gap
  ap.addVehicle(at(7.5, 10.5));
  EXPECT_NEAR(ap.update(7.5).integral, -p.ki * (10.0 - 10.5) * 0.5, 1e-15);  // and on again after it
}

TEST(DepthAutopilot, StalenessCountsFromArrivalWhenTheArrivalIsKnown)
{
  // tow_sim_node stamps vehicle/odom with its simulation time, odom_delay (and any lag) behind the
  // clock: odometry that keeps arriving is fresh however far its stamps trail.
  DepthAutopilot ap(noTrack());
  ap.setSetpoint(10.0);
  VehicleMeasurement m = at(5.0, 30.0);
  m.received = 8.0;  // 3 s behind, more than odom_timeout
  ap.addVehicle(m);
  EXPECT_EQ(ap.update(8.5).status, AutopilotCommand::Status::kActive);
  EXPECT_EQ(ap.update(9.01).status, AutopilotCommand::Status::kStale);  // nothing new for over 1 s
  m = at(5.0, 30.0);
  m.received = 9.5;  // the same stamp again (the simulation holding): not news
  EXPECT_FALSE(ap.addVehicle(m));
  EXPECT_EQ(ap.update(9.5).status, AutopilotCommand::Status::kStale);
}

TEST(DepthAutopilot, RejectsBadSetpointsMeasurementsAndParameters)
{
  DepthAutopilot ap(noTrack());
  ap.setSetpoint(20.0);
  EXPECT_THROW(ap.setSetpoint(-1.0), std::invalid_argument);
  EXPECT_THROW(ap.setSetpoint(10000.5), std::invalid_argument);
  EXPECT_THROW(ap.setSetpoint(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_DOUBLE_EQ(ap.setpoint(), 20.0);
  VehicleMeasurement bad = at(0.0, 10.0);
  bad.v_W.z() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ap.addVehicle(bad), std::invalid_argument);
  EXPECT_THROW(ap.addShip(Eigen::Vector2d(std::nan(""), 0.0)), std::invalid_argument);

  DepthAutopilotParams p;
  p.kp = -1.0;
  try
  {
    DepthAutopilot broken(p);
    ADD_FAILURE() << "kp = -1 accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_EQ(std::string(e.what()), "kp = -1 is out of range: must be a finite number in [0, 10] [rad/m]");
  }
  p = DepthAutopilotParams();
  p.max_elevator = 2.0;
  EXPECT_THROW(p.validate("/ap/"), std::invalid_argument);
  p = DepthAutopilotParams();
  p.track_length = 1.5;  // less than two spacings
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(PastTrack, OffsetIsPositiveToPortOfAStraightTrack)
{
  PastTrack east(1.0, 1000.0);
  for (int i = 0; i <= 100; ++i)
    east.add(Eigen::Vector2d(i * 2.0, 0.0));  // travelling +x: port is +y
  EXPECT_NEAR(east.offset(Eigen::Vector2d(50.0, 10.0), Eigen::Vector2d(2.0, 0.3)).offset, 10.0, 1e-12);
  EXPECT_NEAR(east.offset(Eigen::Vector2d(50.0, 10.0), Eigen::Vector2d(2.0, 0.3)).rate, 0.3, 1e-12);
  EXPECT_NEAR(east.offset(Eigen::Vector2d(50.0, -4.0), Eigen::Vector2d::Zero()).offset, -4.0, 1e-12);
  // Astern of the oldest point (the ship has not gone far yet) the track extends as a line.
  EXPECT_NEAR(east.offset(Eigen::Vector2d(-300.0, 7.0), Eigen::Vector2d::Zero()).offset, 7.0, 1e-12);

  PastTrack west(1.0, 1000.0);
  for (int i = 0; i <= 100; ++i)
    west.add(Eigen::Vector2d(-i * 2.0, 0.0));  // travelling -x: port is -y
  EXPECT_NEAR(west.offset(Eigen::Vector2d(-50.0, 10.0), Eigen::Vector2d::Zero()).offset, -10.0, 1e-12);
}

TEST(PastTrack, OffsetFollowsATurnedTrack)
{
  // East 500 m, a 180 degree turn to port of radius 100 m about (500, 100), then west along y = 200.
  PastTrack track(1.0, 5000.0);
  for (double x = 0.0; x <= 500.0; x += 0.5)
    track.add(Eigen::Vector2d(x, 0.0));
  for (double a = 0.0; a <= tow_sim::kPi; a += 0.002)
    track.add(Eigen::Vector2d(500.0 + 100.0 * std::sin(a), 100.0 - 100.0 * std::cos(a)));
  for (double x = 500.0; x >= 0.0; x -= 0.5)
    track.add(Eigen::Vector2d(x, 200.0));
  const Eigen::Vector2d still = Eigen::Vector2d::Zero();
  // Outbound leg: port is +y.
  EXPECT_NEAR(track.offset(Eigen::Vector2d(300.0, 10.0), still).offset, 10.0, 1e-9);
  // Return leg (heading west): port is -y, toward the outbound leg; the nearest segment is on this leg.
  EXPECT_NEAR(track.offset(Eigen::Vector2d(300.0, 190.0), still).offset, 10.0, 1e-9);
  EXPECT_NEAR(track.offset(Eigen::Vector2d(300.0, 215.0), still).offset, -15.0, 1e-9);
  // Inside the arc (a port turn) is to port, outside to starboard; the chords are 0.2 m, so within 1 mm.
  EXPECT_NEAR(track.offset(Eigen::Vector2d(590.0, 100.0), still).offset, 10.0, 1e-3);
  EXPECT_NEAR(track.offset(Eigen::Vector2d(620.0, 100.0), Eigen::Vector2d(0.0, 1.0)).offset, -20.0, 1e-3);
  EXPECT_NEAR(track.offset(Eigen::Vector2d(620.0, 100.0), Eigen::Vector2d(-1.0, 0.0)).rate, 1.0, 1e-3);
}

TEST(PastTrack, KeepsABoundedLengthAndSpacing)
{
  PastTrack track(2.0, 100.0);
  for (int i = 0; i < 100000; ++i)
    track.add(Eigen::Vector2d(i * 0.1, 0.0));
  EXPECT_EQ(track.size(), 51u);  // 100 m in 2 m steps
  track.add(Eigen::Vector2d(std::nan(""), 0.0));
  EXPECT_EQ(track.size(), 51u);
}

TEST(DepthAutopilot, RudderSteersBackToTheTrackAndSaturates)
{
  DepthAutopilotParams p;
  DepthAutopilot ap(p);
  for (int i = 0; i <= 200; ++i)
    ap.addShip(Eigen::Vector2d(i * 2.0, 0.0));
  VehicleMeasurement m = at(0.0, 50.0);
  m.p_W.y() = 5.0;  // 5 m to port: steer to starboard (negative rudder)
  ap.addVehicle(m);
  AutopilotCommand c = ap.update(0.0);
  EXPECT_TRUE(c.tracking);
  EXPECT_NEAR(c.track_offset, 5.0, 1e-12);
  EXPECT_NEAR(c.rudder, -p.rudder_kp * 5.0, 1e-12);
  m.t = 1.0;
  m.p_W.y() = -500.0;  // far to starboard: saturated to port
  ap.addVehicle(m);
  EXPECT_DOUBLE_EQ(ap.update(1.0).rudder, p.max_rudder);

  p.track_keeping = false;
  DepthAutopilot off(p);
  for (int i = 0; i <= 200; ++i)
    off.addShip(Eigen::Vector2d(i * 2.0, 0.0));
  off.addVehicle(m);
  EXPECT_EQ(off.update(1.0).rudder, 0.0);
}

}  // namespace
