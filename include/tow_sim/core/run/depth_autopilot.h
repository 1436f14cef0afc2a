// Depth autopilot for the towed vehicle, without ROS: a PID on depth for the elevator and track keeping
// behind the ship for the rudder. The caller hands it time and measurements (the core reads no clock);
// depth_autopilot_node wraps it for ROS.
//
// Signs (msg/FinCommand.msg): a positive elevator pushes the fins up, so the vehicle rises; a positive
// rudder pushes the fins to port. Depth is positive down (depth = -z, world ENU).
#pragma once

#include <Eigen/Core>

#include <deque>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "tow_sim/core/param_table.h"

namespace tow_sim
{
struct DepthAutopilotParams
{
  // Elevator: elevator = -(kp e + ki int(e) dt + kd de/dt) with e = setpoint - depth (positive: too shallow,
  // so the elevator goes negative and the vehicle dives). de/dt = v_up, the measured vertical velocity
  // (world, up), so a setpoint step gives no derivative kick. Anti-windup: the integral stops growing
  // while the output saturates in the direction it would grow, and its term is bounded by max_elevator.
  double kp = 0.1;              // [rad/m] elevator per metre of depth error, [0, 10]
  double ki = 0.0025;           // [rad/(m s)] integral gain, [0, 10]
  double kd = 0.2;              // [rad/(m/s)] elevator per m/s of vertical velocity (world, up), [0, 100]
  double max_elevator = 0.436;  // [rad] output limit, (0, pi/2]; the default vehicle's max_deflection
  // Rudder: rudder = clamp(-rudder_kp offset - rudder_kd offset_rate, +-max_rudder), the offset measured
  // from the ship's past track, positive to port.
  bool track_keeping = true;     // false: the rudder stays at 0
  double rudder_kp = 0.02;       // [rad/m] rudder per metre of lateral offset, [0, 10]
  double rudder_kd = 0.2;        // [rad/(m/s)] rudder per m/s of lateral offset rate, [0, 100]
  double max_rudder = 0.436;     // [rad] output limit, (0, pi/2]
  double track_spacing = 1.0;    // [m] a ship position is stored each time it has moved this far, [0.01, 1000]
  double track_length = 5000.0;  // [m] of past track kept (older points dropped), [10, 1e6], >= 2 spacings
  double thrust = 0.0;           // [N] constant thrust command, [-1e6, 1e6]
  double odom_timeout = 1.0;     // [s] older vehicle odometry is stale: fins centred, (0, 3600]
  double max_depth = 10000.0;    // [m] setpoints are accepted in [0, max_depth], (0, 1e5]
  // What holds the depth: the elevator (the PID above), the winch, or both. The winch: the cable out it
  // aims at is L* = L_ff + winch_kp e + winch_ki int(e) dt (e as above, positive: too shallow, so more
  // cable), L_ff the planner's steady cable out for the setpoint (setCableOutFeedForward; without one the
  // cable out at the first measurement); the payout rate closes the gap, (L* - L)/winch_time_constant,
  // within +-max_payout_rate. The integral stops growing while the rate saturates in its direction.
  enum class Actuator
  {
    kElevator,
    kWinch,  // the elevator stays centred
    kBoth
  };
  Actuator actuator = Actuator::kElevator;
  double winch_kp = 1.0;              // [m/m] cable out per metre of depth error, [0, 1000]
  double winch_ki = 0.05;             // [m/(m s)] integral gain, [0, 100]
  double winch_time_constant = 30.0;  // [s] of the payout toward L*, (0, 1000]
  double max_payout_rate = 0.5;       // [m/s] payout command limit, (0, 100]
  // Roll hold (a vehicle with vehicle.roll: free, physics.md §5b): the elevator's differential
  // clamp(roll_kp phi + roll_kd p, +-max_differential) from the measured roll phi and spin p (a positive
  // differential rolls the vehicle to port, phi < 0). Off: the differential stays 0.
  bool roll_hold = false;
  double roll_kp = 1.0;           // [rad/rad] differential per radian of roll, [0, 100]
  double roll_kd = 0.2;           // [rad/(rad/s)] differential per rad/s of spin, [0, 100]
  double max_differential = 0.2;  // [rad] output limit, (0, pi/2]

  // Throws std::invalid_argument naming `prefix + key`, the value and its range.
  void validate(const std::string& prefix = "") const;
};
// The parameter table of the depth autopilot (param_table.h): every key with its unit, range, default and meaning.
const ParamTable<DepthAutopilotParams>& autopilotParams();

// The ship's past track: positions stored every `spacing` metres travelled, at most `length` metres of
// them (a bounded deque). The vehicle's lateral offset is measured from the nearest segment; the oldest
// and newest segments extend as straight lines beyond their ends, so a vehicle astern of the oldest
// stored point (the ship has not yet gone far) still gets an offset.
class PastTrack
{
public:
  PastTrack(double spacing, double length);
  void add(const Eigen::Vector2d& p_W);  // [m] ship position, world; ignored unless finite
  void clear() { points_.clear(); }
  size_t size() const { return points_.size(); }
  bool usable() const { return points_.size() >= 2; }

  struct Offset
  {
    double offset = 0.0;  // [m] horizontal, positive to port of the track's direction of travel
    double rate = 0.0;    // [m/s] of the offset: the velocity along the segment's port normal
    size_t segment = 0;   // index of the nearest segment, oldest first
  };
  // Needs usable(); p_W [m] and v_W [m/s] of the vehicle, world, horizontal components.
  Offset offset(const Eigen::Vector2d& p_W, const Eigen::Vector2d& v_W) const;

  // The stored points [m], oldest first (a saved state), and those points back (at most the most recent
  // ones that fit; non-finite ones are skipped).
  std::vector<Eigen::Vector2d> points() const { return { points_.begin(), points_.end() }; }
  void restore(const std::vector<Eigen::Vector2d>& points);

private:
  double spacing_;
  size_t max_points_;
  std::deque<Eigen::Vector2d> points_;
};

// Vehicle CG measurement from odometry.
struct VehicleMeasurement
{
  double t = 0.0;                                               // [s] stamp
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();                // [m] CG position, world ENU (z up, depth = -z)
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();                // [m/s] CG velocity, world ENU
  double altitude = std::numeric_limits<double>::quiet_NaN();   // [m] CG above the seabed; NaN: unknown
  double cable_out = std::numeric_limits<double>::quiet_NaN();  // [m] the winch's; NaN: unknown (no winch command)
  // [rad] roll (REP-103, positive starboard down) and [rad/s] the spin about x_b; NaN: unknown (no roll hold)
  double roll = std::numeric_limits<double>::quiet_NaN(), roll_rate = std::numeric_limits<double>::quiet_NaN();
  // [s] when it arrived, on update()'s clock; NaN: at its stamp. Staleness counts from here.
  double received = std::numeric_limits<double>::quiet_NaN();
};

struct AutopilotCommand
{
  enum class Status
  {
    kWaiting,  // no vehicle odometry yet: fins centred
    kStale,    // the newest vehicle odometry arrived more than odom_timeout ago: fins centred
    kActive
  };
  Status status = Status::kWaiting;
  double rudder = 0.0;        // [rad]
  double elevator = 0.0;      // [rad]
  double thrust = 0.0;        // [N]
  double differential = 0.0;  // [rad] the elevator's differential (roll_hold), starboard fin +
  double depth_error = 0.0;   // [m] setpoint - depth (positive: too shallow)
  double integral = 0.0;      // [rad] the integral term's contribution to the elevator
  bool elevator_saturated = false;
  bool tracking = false;           // the rudder is steering on the ship's track
  double track_offset = 0.0;       // [m] positive to port
  double track_offset_rate = 0.0;  // [m/s]
  // The winch (actuator winch or both), with the cable out known: the payout rate it commands [m/s]
  // (positive pays out), the cable out it aims at [m] and the integral's part of it [m].
  bool winch = false;
  double payout_rate = 0.0;
  double cable_out_target = 0.0;
  double winch_integral = 0.0;
};

// What the autopilot holds between updates (a saved state): its setpoint, newest measurement, integrals,
// feed-forward and the ship's past track; its parameters are not part of it.
struct DepthAutopilotState
{
  bool has_setpoint = false;
  double setpoint = 0.0;  // [m]
  bool altitude_mode = false;
  double altitude_setpoint = 0.0;  // [m]
  bool has_vehicle = false;
  VehicleMeasurement vehicle;
  double integrated_until = 0.0;  // [s]
  bool integrated = false;
  double integral = 0.0;                                             // [rad]
  double cable_out_base = std::numeric_limits<double>::quiet_NaN();  // [m]
  bool feed_forward = false;
  double winch_integral = 0.0;         // [m]
  std::vector<Eigen::Vector2d> track;  // [m] oldest first
};

class DepthAutopilot
{
public:
  explicit DepthAutopilot(const DepthAutopilotParams& params);  // validates

  // Depth setpoint [m], positive down, in [0, max_depth]; throws std::invalid_argument otherwise.
  void setSetpoint(double depth);
  // Altitude setpoint [m] above the seabed, in [0, max_depth]; throws std::invalid_argument otherwise.
  // In altitude mode each measurement that carries an altitude turns it into the depth setpoint
  // depth + altitude - altitude setpoint; without one the last such depth is held.
  void setAltitudeSetpoint(double altitude);
  bool altitudeMode() const { return altitude_mode_; }
  double altitudeSetpoint() const { return altitude_setpoint_; }
  bool hasSetpoint() const { return has_setpoint_; }
  double setpoint() const { return setpoint_; }

  // New gains and limits while running (dynamic_reconfigure): validated as at construction (throws
  // std::invalid_argument naming `prefix + key`; nothing changes then); the integrals, measurements, setpoint
  // and track are kept (the elevator's integral within the new max_elevator). The actuator and the track's
  // spacing and length stay as constructed.
  void setTuning(const DepthAutopilotParams& params, const std::string& prefix = "");

  // The planner's steady cable out [m] for the present setpoint, the winch's feed-forward (> 0, finite;
  // else std::invalid_argument). NaN clears it: the cable out at the next measurement stands in.
  void setCableOutFeedForward(double cable_out);
  // Vehicle odometry; throws std::invalid_argument for a non-finite field. A measurement whose stamp is
  // not after the previous one is ignored (returns false). Without a setpoint, the first measurement's
  // depth becomes the setpoint.
  bool addVehicle(const VehicleMeasurement& m);
  // Ship position [m], world; throws std::invalid_argument if not finite.
  void addShip(const Eigen::Vector2d& p_W);

  // The command at time `now` [s] from the newest measurement. The integral advances by the time between
  // measurements, so calling this more often than odometry arrives does not integrate twice.
  AutopilotCommand update(double now);

  void reset();  // forgets the integral, the measurements, the setpoint and the track
  bool hasVehicle() const { return has_vehicle_; }
  double vehicleStamp() const { return vehicle_.t; }                       // [s] of the newest accepted measurement
  const Eigen::Vector3d& vehiclePosition() const { return vehicle_.p_W; }  // [m] of it, world
  const DepthAutopilotParams& params() const { return p_; }
  const PastTrack& track() const { return track_; }

  // Everything but the parameters, and back (a saved state; the caller validates it).
  DepthAutopilotState state() const;
  void restore(const DepthAutopilotState& s);

private:
  double elevator(double error, double v_up, double dt, AutopilotCommand& out);
  void winch(double error, double dt, AutopilotCommand& out);

  DepthAutopilotParams p_;
  PastTrack track_;
  bool has_setpoint_ = false;
  double setpoint_ = 0.0;  // [m] depth
  bool altitude_mode_ = false;
  double altitude_setpoint_ = 0.0;  // [m]
  bool has_vehicle_ = false;
  VehicleMeasurement vehicle_;
  double integrated_until_ = 0.0;  // [s] stamp of the measurement last integrated
  bool integrated_ = false;
  double integral_ = 0.0;  // [rad] -ki int(e) dt: the integral term's part of the elevator
  double cable_out_base_ = std::numeric_limits<double>::quiet_NaN();  // [m] L_ff, or the first cable out
  bool feed_forward_ = false;                                         // cable_out_base_ is the planner's
  double winch_integral_ = 0.0;                                       // [m] winch_ki int(e) dt
};

// The autopilot in a tow run's loop (tow_sim_batch): its gains, its rate and a setpoint schedule.
struct AutopilotSetpoint
{
  double t = 0.0;         // [s] from this time on
  bool altitude = false;  // false: `value` is a depth [m, positive down]; true: an altitude above the seabed [m]
  double value = 0.0;     // [m]
};
struct AutopilotLoop
{
  bool enabled = false;
  DepthAutopilotParams params;
  double rate = 10.0;                        // [Hz] fin commands, [0.1, 1000]
  std::vector<AutopilotSetpoint> setpoints;  // sorted by time; none: hold the first depth
  // The winch's feed-forward (actuator winch or both): the steady cable out [m] for a depth setpoint [m]
  // at a ship speed [m/s], NaN when none reaches it (the batch plans it with tow_sim_chart's planner).
  std::function<double(double depth, double speed)> cable_out_plan;
};

}  // namespace tow_sim
