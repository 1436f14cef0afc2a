#include "tow_sim/core/run/live_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/attitude.h"
#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
double steadyWall()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

const char* shapeName(InitialShape::Type type)
{
  switch (type)
  {
    case InitialShape::Type::kLine:
      return "line";
    case InitialShape::Type::kHanging:
      return "hanging";
    case InitialShape::Type::kPoints:
      return "points";
    case InitialShape::Type::kFile:
      return "file";
    case InitialShape::Type::kEquilibrium:
      break;
  }
  return "equilibrium";
}
}  // namespace

const char* describe(LiveStatus status)
{
  switch (status)
  {
    case LiveStatus::kDiverging:
      return "diverging repeatedly: holding the last good state until ~reset";
    case LiveStatus::kRestarted:
      return "restarted after divergence";
    case LiveStatus::kWaiting:
      return "waiting for ship odometry";
    case LiveStatus::kPaused:
      return "paused";
    case LiveStatus::kHolding:
      return "ship odometry is late: holding";
    case LiveStatus::kLagging:
      return "cannot keep up with the clock";
    case LiveStatus::kRunning:
      break;
  }
  return "running";
}

LiveRun::LiveRun(const SimulationConfig& config, const LiveSettings& settings, WallClock wall)
    : settings_(settings),
      wall_(wall ? std::move(wall) : WallClock(steadyWall)),
      ship_(std::make_shared<ShipHistory>(settings.max_extrapolation, settings.track_capacity,
                                          settings.odometry.max_ship_speed)),
      run_(config, ship_, settings.initial_shape),
      whole_steps_(isImplicit(config.numerics.stepper)),
      reacquisition_(settings.reacquire_after)
{
}

void LiveRun::say(LiveNotice::Level level, LiveNotice::Kind kind, const std::string& text) const
{
  if (notify_)
    notify_(LiveNotice{ level, kind, text });
}

int64_t LiveRun::absolute(double t) const
{
  // To the nearest nanosecond: a time from the clock's (relative(), then back) comes back to the same stamp.
  const double ns = static_cast<double>(origin_ns_) + t * 1e9;
  constexpr double kLargest = 9.2e18;  // below 2^63 ns, as a double
  return std::llround(std::clamp(ns, 0.0, kLargest));
}

ShipPose LiveRun::newestShipPose() const
{
  return ship_->empty() ? ShipPose() : ship_->pose(ship_->newestTime());
}

// The ship's pose of an accepted odometry: position, heading of its x axis in the horizontal plane (kept
// when the axis is vertical), speed over ground (a heaving ship's vertical speed left out), REP-103 roll
// and pitch (R = Rz Ry Rx).
ShipPose LiveRun::poseOf(const OdometryInput& in, const OdometryResult& r) const
{
  const Eigen::Matrix3d R = r.q_WS.toRotationMatrix();
  ShipPose pose;
  pose.x = in.p_W.x();
  pose.y = in.p_W.y();
  pose.z = in.p_W.z();
  const Eigen::Vector3d x_axis = r.q_WS * Eigen::Vector3d::UnitX();
  pose.heading = x_axis.head<2>().norm() > 1e-6 ? std::atan2(x_axis.y(), x_axis.x()) : newestShipPose().heading;
  pose.speed = (r.q_WS * in.v_S).head<2>().norm();
  pose.pitch = pitchOf(R.col(0));
  pose.roll = eulerOf(R).roll;
  return pose;
}

bool LiveRun::addOdometry(OdometryInput in, int64_t stamp_ns, int64_t now_ns)
{
  if (stamp_ns == 0)
    stamp_ns = now_ns;
  if (!started_ && ship_->empty())  // a fresh axis: the first sample a second and the delay after its origin
    origin_ns_ = stamp_ns - static_cast<int64_t>((settings_.odom_delay + 1.0) * 1e9);
  in.t = relative(stamp_ns);
  OdometryResult r = checkOdometry(in, settings_.odometry, ship_->track(), relative(now_ns));
  if (r.accepted || !r.jumped)
    reacquisition_.reset();
  else if (reacquisition_.jumped(in.t, r.tow_p_W, settings_.odometry))
  {
    forgetShip("ship odometry stayed " + std::to_string(settings_.reacquire_after) +
                   " messages in a row away from the track (a wrong first fix, a ship moved by a reset?)",
               LiveNotice::Kind::kShipReacquired);
    r = checkOdometry(in, settings_.odometry, ship_->track(), relative(now_ns));
  }
  if (!r.accepted)
  {
    ++counters_.rejected_messages;
    say(LiveNotice::Level::kWarn, LiveNotice::Kind::kOdometryRejected, "rejected ship odometry: " + r.reason);
    return false;
  }
  ship_->add(in.t, r.tow_p_W, r.tow_v_W, poseOf(in, r));
  counters_.last_odometry_wall = wall_();
  if (!started_)
  {
    start(in.t);
    say(LiveNotice::Level::kInfo, LiveNotice::Kind::kFirstOdometry,
        std::string("first ship odometry received; cable laid out (") + shapeName(settings_.initial_shape.type) +
            ") from the tow point");
  }
  return true;
}

void LiveRun::start(double t)
{
  const std::string warning = run_.start(t);
  if (!warning.empty())
    say(LiveNotice::Level::kWarn, LiveNotice::Kind::kStartFallback, warning);
  afterStart();
}

void LiveRun::afterStart()
{
  // The sea runs on the clock (ship_motion_node's ship heaves in the same waves): run time t is clock time
  // origin + t.
  run_.setWaveTime(static_cast<double>(origin_ns_) * 1e-9);
  started_ = true;
  have_after_ = have_steps_ = false;
  ++run_number_;
}

void LiveRun::forgetShip(const std::string& why, LiveNotice::Kind kind)
{
  say(LiveNotice::Level::kWarn, kind, why + ": laying the cable out again at the next ship odometry");
  winch_target_.reset();
  ship_->clear();
  started_ = false;
  holding_ = false;
}

void LiveRun::tick(int64_t now_ns)
{
  if (last_clock_ns_ && now_ns < *last_clock_ns_ - 1'000'000'000)
  {
    std::ostringstream os;
    os << "the clock jumped back " << static_cast<double>(*last_clock_ns_ - now_ns) * 1e-9
       << " s (rosbag play -l, a simulator reset?)";
    forgetShip(os.str(), LiveNotice::Kind::kClockJumpedBack);
  }
  last_clock_ns_ = now_ns;
  holding_ = false;
  if (!started_ || paused_ || diverging_)
    return;
  if (run_.time() < ship_->oldestTime())
  {
    // Only after more than track_capacity odometry messages without a tick (a very long pause).
    std::ostringstream os;
    os << "the simulation (t = " << run_.time() << " s) is older than the ship odometry kept (from "
       << ship_->oldestTime() << " s): laying the cable out again at the newest odometry";
    say(LiveNotice::Level::kWarn, LiveNotice::Kind::kTrackOutrun, os.str());
    start(ship_->newestTime());
    return;
  }
  const double wanted = relative(now_ns) - settings_.odom_delay;
  const double available = ship_->newestTime() + settings_.max_extrapolation;
  holding_ = wanted > available;
  if (holding_)
  {
    std::ostringstream os;
    os.precision(2);
    os << "ship odometry is " << std::fixed << wanted - ship_->newestTime()
       << " s old: holding the simulation until it resumes";
    say(LiveNotice::Level::kWarn, LiveNotice::Kind::kHolding, os.str());
  }
  // Bounded work per tick (max_tick_sim simulated, about max_tick_wall of wall time), so the front end's
  // callbacks are never starved; the lag shows in the counters. An implicit stepper goes on in its own
  // steps, up to one past the clock (its outputs are interpolated).
  counters_.lag = wanted - run_.time();
  if (wanted <= run_.time())
    return;
  const double step = whole_steps_ ? run_.nextStep() : 0.0;
  const double target = tickTarget(run_.time(), wanted, available, step, counters_.tick_cost, settings_.max_tick_sim,
                                   settings_.max_tick_wall);
  if (target <= run_.time())
    return;
  driveWinch();
  integrateTo(target);
}

void LiveRun::integrateTo(double target)
{
  if (whole_steps_ && !have_after_)
    recordStep();  // the step's start
  const double wall_start = wall_();
  const double t0 = run_.time();
  try
  {
    const StepReport report = run_.advanceTo(target);
    counters_.rejected_steps += report.rejected;
    physics_steps_ += report.steps;
  }
  catch (const std::runtime_error& e)
  {
    restartAfterDivergence(e.what());
  }
  if (whole_steps_)
    recordStep();
  ship_->dropBefore(run_.time());  // the simulation never looks back: the history stays short
  const double wall = wall_() - wall_start;
  physics_wall_ += wall;
  if (wall > 0.0)
    counters_.realtime_factor = 0.9 * counters_.realtime_factor + 0.1 * ((run_.time() - t0) / wall);
  if (run_.time() > t0)
    counters_.tick_cost = wall / (run_.time() - t0);  // the next tick's measure
}

void LiveRun::recordStep()
{
  try
  {
    TowSnapshot now = run_.snapshot();
    have_steps_ = have_after_;
    if (have_after_)
      before_ = std::move(after_);
    after_ = std::move(now);
    have_after_ = true;
  }
  catch (const std::runtime_error&)
  {
    have_after_ = have_steps_ = false;  // output() reports it
  }
}

void LiveRun::restartAfterDivergence(const std::string& why)
{
  ++counters_.restarts;
  const double wall = wall_();
  restart_walls_.push_back(wall);
  while (restart_walls_.size() > settings_.restart_burst)
    restart_walls_.pop_front();
  if (restart_walls_.size() == settings_.restart_burst && wall - restart_walls_.front() < settings_.restart_window)
  {
    // Restarting again would only diverge again: hold the last good state, say so, wait for reset().
    diverging_ = true;
    std::ostringstream os;
    os << why << "; " << settings_.restart_burst << " restarts within " << settings_.restart_window
       << " s: holding the last good state until ~reset (the numerics cannot follow this configuration: "
          "check numerics.stepper, fixed_step, max_step, cable.segments)";
    say(LiveNotice::Level::kError, LiveNotice::Kind::kDiverging, os.str());
    return;
  }
  say(LiveNotice::Level::kError, LiveNotice::Kind::kRestarted,
      why + "; restarting from the initial shape at the current ship pose (" + std::to_string(counters_.restarts) +
          " restarts)");
  start(run_.time());
}

std::optional<TowSnapshot> LiveRun::output(int64_t now_ns)
{
  if (!started_)
    return std::nullopt;
  TowSnapshot snapshot = whole_steps_ && have_steps_
                             ? interpolate(before_, after_, relative(now_ns) - settings_.odom_delay)
                             : run_.snapshot();
  counters_.max_length_error = std::max(counters_.max_length_error, snapshot.max_length_error);
  return snapshot;
}

LiveLoad LiveRun::takeLoad()
{
  LiveLoad load;
  const double wall = wall_();
  if (last_load_wall_ > 0.0 && wall > last_load_wall_)
  {
    load.physics_load = physics_wall_ / (wall - last_load_wall_);
    load.steps_per_second = static_cast<double>(physics_steps_) / (wall - last_load_wall_);
  }
  load.max_length_error = counters_.max_length_error;
  last_load_wall_ = wall;
  physics_wall_ = 0.0;
  physics_steps_ = 0;
  counters_.max_length_error = 0.0;
  return load;
}

LiveStatus LiveRun::status() const
{
  if (diverging_)
    return LiveStatus::kDiverging;
  if (!restart_walls_.empty() && wall_() - restart_walls_.back() < settings_.restart_window)
    return LiveStatus::kRestarted;
  if (!started_)
    return LiveStatus::kWaiting;
  if (paused_)
    return LiveStatus::kPaused;
  if (holding_)
    return LiveStatus::kHolding;
  return counters_.lag > 1.0 ? LiveStatus::kLagging : LiveStatus::kRunning;
}

bool LiveRun::finCommand(double rudder, double elevator, double thrust, bool* saturated, double differential)
{
  *saturated = false;
  if (!std::isfinite(rudder) || !std::isfinite(elevator) || !std::isfinite(thrust) || !std::isfinite(differential))
  {
    ++counters_.rejected_messages;
    return false;
  }
  if (!started_)  // the first odometry lays the cable out with the fins centred
    return false;
  *saturated = run_.command(rudder, elevator, thrust, differential);
  return true;
}

bool LiveRun::winchCommand(double payout_rate, double* applied, std::string* why)
{
  if (!started_)
  {
    *why = "no ship odometry yet";
    return false;
  }
  winch_target_.reset();  // a command from outside takes over from a plan being executed
  try
  {
    *applied = run_.setWinchCommand(payout_rate);
    return true;
  }
  catch (const std::invalid_argument& e)
  {
    ++counters_.rejected_messages;
    *why = e.what();
    return false;
  }
}

bool LiveRun::setCurrent(const Eigen::Vector3d& current_W, std::string* why)
{
  try
  {
    run_.setCurrent(current_W);
    return true;
  }
  catch (const std::invalid_argument& e)
  {
    ++counters_.rejected_messages;
    *why = e.what();
    return false;
  }
}

bool LiveRun::setCurrentProfile(const std::vector<CurrentSample>& profile, std::string* why)
{
  try
  {
    run_.setCurrentProfile(profile);
    return true;
  }
  catch (const std::invalid_argument& e)
  {
    ++counters_.rejected_messages;
    *why = e.what();
    return false;
  }
}

std::string LiveRun::driveWinchTo(double cable_out)
{
  if (!run_.config().winch.enabled)
    return "the winch is not enabled (winch.enabled)";
  if (!started_)
    return "no ship odometry yet";
  if (run_.simulator().parted())
    return "the cable has parted (~reset joins it again)";
  winch_target_ = cable_out;
  return "";
}

void LiveRun::driveWinch()
{
  if (!winch_target_)
    return;
  if (run_.simulator().parted())  // the winch stopped with the parting: nothing to drive
  {
    winch_target_.reset();
    say(LiveNotice::Level::kWarn, LiveNotice::Kind::kWinchPlanDropped,
        "the planned cable out is given up: the cable has parted");
    return;
  }
  const double remaining = *winch_target_ - run_.simulator().cableLength();
  if (std::abs(remaining) <= settings_.winch_arrived)
  {
    winch_target_.reset();
    run_.setWinchCommand(0.0);
    say(LiveNotice::Level::kInfo, LiveNotice::Kind::kWinchArrived, "the winch has reached the planned cable out");
    return;
  }
  // Payout rate = remaining length / (4 x the winch's response time), within max_rate: with the winch's own
  // first-order lag the approach is critically damped. The command holds for a tick, so the time constant
  // is at least two ticks (else the loop would hunt).
  const WinchParams& winch = run_.config().winch;
  const double time_constant = std::max(4.0 * winch.response_time, 2.0 * settings_.tick_period);
  run_.setWinchCommand(std::clamp(remaining / time_constant, -winch.max_rate, winch.max_rate));
}

std::string LiveRun::reset()
{
  if (ship_->empty())
    return "no ship odometry yet";
  diverging_ = false;
  restart_walls_.clear();
  winch_target_.reset();
  start(started_ ? run_.time() : ship_->newestTime());
  return "";
}

void LiveRun::load(const RunState& saved)
{
  if (ship_->empty())
    throw std::logic_error("no ship odometry yet: a state is placed at the ship");
  // The saved shape relative to the tow point, turned with the ship's heading, at the run's time now.
  const double t = started_ ? run_.time() : ship_->newestTime();
  run_.restore(relocate(saved, t, ship_->towPoint(t), ship_->pose(t).heading));  // refused: nothing changed
  diverging_ = false;
  restart_walls_.clear();
  winch_target_.reset();
  afterStart();
}

}  // namespace tow_sim
