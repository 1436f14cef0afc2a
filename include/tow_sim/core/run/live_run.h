// A tow run driven live by a clock and a ship's odometry (tow_sim_node's logic, without ROS): the run and
// the ship's history it owns, the time axis (nanoseconds of the clock, relative to an origin fixed at the
// first odometry), the pacing of the physics ticks, the restart policy after a divergence, the ship's
// re-acquisition, the whole-step interpolation at the clock, the winch driven to a planned cable out, and
// the counters the diagnostics show. The node converts messages into calls and snapshots into messages;
// what it should say comes back as notices. Tested with a fake clock (test_live_run.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tow_sim/core/run/odometry_check.h"
#include "tow_sim/core/run/tow_run.h"

namespace tow_sim
{
struct LiveSettings
{
  OdometryLimits odometry;         // frame, tow point, speed and age limits of ship odometry
  double odom_delay = 0.2;         // [s] the simulation runs this far behind the clock
  double max_extrapolation = 1.0;  // [s] past the newest odometry, then hold
  double max_tick_wall = 0.05;     // [s] wall time a tick aims to stay within (at least one step)
  double max_tick_sim = 0.5;       // [s] simulated time a tick integrates at most
  double tick_period = 0.02;       // [s] of the physics ticks (the winch's plan loop is at least two)
  int reacquire_after = 5;         // [messages] consistent ones away from the track re-acquire the ship
  size_t track_capacity = 100000;  // ship odometry samples kept at most (pruned by time as they are used)
  size_t restart_burst = 5;        // restarts after divergence ...
  double restart_window = 10.0;    // [s] of wall time within which they mean the numerics cannot work
  double winch_arrived = 0.05;     // [m] the winch is at a planned cable out within this
  InitialShape initial_shape;
};

// Something the front end should tell its user (tow_sim_node logs it, throttled per kind).
struct LiveNotice
{
  enum class Level
  {
    kInfo,
    kWarn,
    kError
  };
  enum class Kind
  {
    kFirstOdometry,     // info: the cable is laid out
    kOdometryRejected,  // warn: why (names the field)
    kShipReacquired,    // warn: the track is dropped; the next odometry lays the cable out again
    kClockJumpedBack,   // warn: likewise
    kTrackOutrun,       // warn: the run is older than the odometry kept: laid out again at the newest
    kHolding,           // warn: the odometry is late, the simulation holds
    kStartFallback,     // warn: no equilibrium, a straight line
    kRestarted,         // error: a divergence, restarted from the initial shape
    kDiverging,         // error: restart_burst restarts within restart_window: holding until reset()
    kWinchArrived,      // info: at the planned cable out
    kWinchPlanDropped,  // warn: the cable parted under way
    kCount
  };
  Level level = Level::kInfo;
  Kind kind = Kind::kFirstOdometry;
  std::string text;
};

// The run's state for the diagnostics, worst first.
enum class LiveStatus
{
  kDiverging,  // holding the last good state until reset()
  kRestarted,  // after a divergence, within restart_window
  kWaiting,    // for ship odometry
  kPaused,
  kHolding,  // the odometry is late
  kLagging,  // more than a second behind the clock
  kRunning
};
const char* describe(LiveStatus status);

struct LiveCounters
{
  uint64_t rejected_steps = 0;      // by the adaptive steppers, since the start
  uint64_t rejected_messages = 0;   // odometry, commands and settings refused, since the start
  uint64_t restarts = 0;            // after a divergence, since the start
  double realtime_factor = 0.0;     // [-] simulated over wall seconds, smoothed over ticks
  double tick_cost = 0.0;           // [s/s] wall seconds per simulated second of the last tick
  double lag = 0.0;                 // [s] the clock's target minus the run's time, at the last tick
  double last_odometry_wall = 0.0;  // [s] wall time of the last accepted odometry (0: none)
  double max_length_error = 0.0;    // [-] over the outputs since takeLoad()
};

// The integration's share of one core and its steps per wall second, over the interval since the last
// takeLoad() (zero at the first).
struct LiveLoad
{
  double physics_load = 0.0;      // [-]
  double steps_per_second = 0.0;  // [1/s]
  double max_length_error = 0.0;  // [-] over the outputs of the interval
};

class LiveRun
{
public:
  using WallClock = std::function<double()>;  // [s] a steady wall clock
  using Notify = std::function<void(const LiveNotice&)>;

  // Validates the configuration (std::invalid_argument naming the key). `wall` times the integration and
  // the restart policy (default: std::chrono::steady_clock).
  LiveRun(const SimulationConfig& config, const LiveSettings& settings, WallClock wall = WallClock());
  void setNotify(Notify notify) { notify_ = std::move(notify); }

  // Ship odometry stamped stamp_ns (0: received now) at clock now_ns [ns]; in.t is set here. The first
  // fixes the time origin and lays the cable out. Returns false (counted, noticed) when refused.
  bool addOdometry(OdometryInput in, int64_t stamp_ns, int64_t now_ns);
  // One physics tick at clock now_ns: integrates toward now - odom_delay within the tick's budget.
  void tick(int64_t now_ns);
  // The outputs at clock now_ns (between the last two whole steps of an implicit stepper, else the run's
  // state); nullopt before the first odometry. Throws std::runtime_error when the state is not finite.
  std::optional<TowSnapshot> output(int64_t now_ns);

  // Commands from outside. Each is refused (false, counted) when not finite or, fins and winch, before the
  // first odometry; `saturated` reports a command limited to the actuator's range.
  bool finCommand(double rudder, double elevator, double thrust, bool* saturated, double differential = 0.0);
  bool winchCommand(double payout_rate, double* applied, std::string* why);  // ends a plan under way
  bool setCurrent(const Eigen::Vector3d& current_W, std::string* why);
  bool setCurrentProfile(const std::vector<CurrentSample>& profile, std::string* why);
  void countRejected() { ++counters_.rejected_messages; }  // a message the front end refused itself

  // The winch to `cable_out` [m] (a planner's answer), driven at each tick until there; "" when it goes,
  // else why not.
  std::string driveWinchTo(double cable_out);
  void setPaused(bool paused) { paused_ = paused; }
  // Lays the cable out again at the ship's pose now and ends a hold after divergence; "" or why not.
  std::string reset();
  // A saved state carried to the ship's pose now (relocate) and continued; std::invalid_argument when it
  // does not fit (nothing changes), std::logic_error before the first odometry.
  void load(const RunState& saved);

  LiveStatus status() const;
  const LiveCounters& counters() const { return counters_; }
  LiveLoad takeLoad();
  bool started() const { return started_; }
  // Counts the starts (the first odometry, restarts, reset(), load()): a front end clears what it drew of
  // an earlier run when it changes.
  uint64_t runNumber() const { return run_number_; }
  bool paused() const { return paused_; }
  bool shipKnown() const { return !ship_->empty(); }
  // [s] seconds since the origin of the clock time t_ns, and back to the nearest ns (within [0, 2^63) ns)
  double relative(int64_t t_ns) const { return static_cast<double>(t_ns - origin_ns_) * 1e-9; }
  int64_t absolute(double t) const;
  const TowRun& run() const { return run_; }
  const ShipHistory& ship() const { return *ship_; }
  // The ship's pose at its newest odometry (a zero pose without any).
  ShipPose newestShipPose() const;

private:
  void say(LiveNotice::Level level, LiveNotice::Kind kind, const std::string& text) const;
  void start(double t);
  void afterStart();
  void forgetShip(const std::string& why, LiveNotice::Kind kind);
  void integrateTo(double target);
  void recordStep();
  void restartAfterDivergence(const std::string& why);
  void driveWinch();
  ShipPose poseOf(const OdometryInput& in, const OdometryResult& r) const;

  LiveSettings settings_;
  WallClock wall_;
  Notify notify_;
  std::shared_ptr<ShipHistory> ship_;
  TowRun run_;
  bool whole_steps_ = false;  // an implicit stepper: outputs between the last two step ends
  TrackReacquisition reacquisition_;
  int64_t origin_ns_ = 0;
  std::optional<int64_t> last_clock_ns_;  // at the previous tick, to see the clock jump back
  bool started_ = false;                  // false until the first odometry, and again after forgetShip
  bool paused_ = false;
  bool holding_ = false;
  bool diverging_ = false;
  std::deque<double> restart_walls_;  // [s] of the recent restarts (at most restart_burst)
  TowSnapshot before_, after_;
  bool have_after_ = false;  // after_ is of the current run
  bool have_steps_ = false;  // and so is before_
  std::optional<double> winch_target_;
  uint64_t run_number_ = 0;
  LiveCounters counters_;
  double physics_wall_ = 0.0;   // [s] integrating, since takeLoad()
  uint64_t physics_steps_ = 0;  // accepted, since takeLoad()
  double last_load_wall_ = 0.0;
};

}  // namespace tow_sim
