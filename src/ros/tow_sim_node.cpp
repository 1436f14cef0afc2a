#include "tow_sim/ros/tow_sim_node.h"

#include <geometry_msgs/TransformStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tow_sim/CableState.h"
#include "tow_sim/FinLoads.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/odometry_check.h"
#include "tow_sim/ros/conversions.h"
#include "tow_sim/ros/markers.h"

namespace tow_sim
{
namespace
{
constexpr size_t kRestartBurst = 5;        // restarts after divergence ...
constexpr double kRestartWindow = 10.0;    // [s] of wall time within which they mean the numerics cannot work
constexpr size_t kTrackCapacity = 100000;  // ship odometry samples at most (pruned by time as it is used)

// Runs f; an exception is reported (throttled) instead of leaving a ROS callback, which would end the node.
// Returns false if f threw.
template <class F>
bool guarded(const char* what, F&& f)
{
  try
  {
    f();
    return true;
  }
  catch (const std::exception& e)
  {
    ROS_ERROR_THROTTLE(2.0, "tow_sim: %s: %s (the node runs on)", what, e.what());
    return false;
  }
}

// The configuration; the adaptive implicit stepper's steps are capped at max_command_lag, since a command
// from another node acts from the end of the step under way (implicit_fixed keeps its fixed_step).
SimulationConfig readConfig(const ros::NodeHandle& pnh, const NodeParams& params)
{
  try
  {
    SimulationConfig config = loadConfig(ros_conv::privateParameters(pnh), pnh.getNamespace() + "/");
    if (isImplicit(config.numerics.stepper))
      config.numerics.max_step = std::min(config.numerics.max_step, params.max_command_lag);
    return config;
  }
  catch (const std::invalid_argument& e)
  {
    throw ros_conv::withSlashes(e);
  }
}

// The node's initial_shape and initial_angle as the run's policy (a line straight astern, initial_angle
// below the horizontal, is also the fallback when no equilibrium is found).
InitialShape initialShape(const NodeParams& p)
{
  InitialShape shape;
  shape.type = p.initial_shape == "line"      ? InitialShape::Type::kLine
               : p.initial_shape == "hanging" ? InitialShape::Type::kHanging
                                              : InitialShape::Type::kEquilibrium;
  shape.line_direction_S = Eigen::Vector3d(-std::cos(p.initial_angle), 0.0, -std::sin(p.initial_angle));
  return shape;
}
}  // namespace

TowSimNode::TowSimNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh),
      pnh_(pnh),
      params_(ros_conv::readPrivateParams<NodeParams>(pnh, nodeParams(), validate)),
      config_(readConfig(pnh, params_)),
      ship_(std::make_shared<ShipHistory>(params_.max_extrapolation, kTrackCapacity, params_.max_ship_speed)),
      run_(config_, ship_, initialShape(params_)),
      whole_steps_(isImplicit(config_.numerics.stepper)),
      reacquisition_(params_.reacquire_after)
{
  if (params_.trail_duration > 0.0)
  {
    ship_trail_ = std::make_unique<TrackTrail>(params_.trail_duration);
    vehicle_trail_ = std::make_unique<TrackTrail>(params_.trail_duration);
  }
  odometry_limits_.world_frame = params_.world_frame;
  odometry_limits_.tow_point_S = params_.tow_point_S;
  odometry_limits_.max_ship_speed = params_.max_ship_speed;
  odometry_limits_.max_age = params_.max_odom_age;
  diagnostics_.setHardwareID("tow_sim");
  diagnostics_.add("simulation", this, &TowSimNode::diagnose);

  odom_sub_ = subscribe<nav_msgs::Odometry>("ship/odom", 50, &TowSimNode::onOdometry);
  fin_sub_ = subscribe<tow_sim::FinCommand>("fins/command", 10, &TowSimNode::onFinCommand);
  current_sub_ = subscribe<geometry_msgs::Vector3Stamped>("current", 10, &TowSimNode::onCurrent);
  current_profile_sub_ = subscribe<tow_sim::CurrentProfile>("current_profile", 2, &TowSimNode::onCurrentProfile);
  winch_sub_ = subscribe<std_msgs::Float64>("winch/command", 10, &TowSimNode::onWinchCommand);
  state_pub_ = nh_.advertise<tow_sim::CableState>("cable/state", 10);
  marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("cable/markers", 2);
  vehicle_odom_pub_ = nh_.advertise<nav_msgs::Odometry>("vehicle/odom", 10);
  fin_loads_pub_ = nh_.advertise<tow_sim::FinLoads>("vehicle/fin_loads", 10);
  ship_force_pub_ = nh_.advertise<geometry_msgs::WrenchStamped>("ship/tow_force", 10);
  vehicle_force_pub_ = nh_.advertise<geometry_msgs::WrenchStamped>("vehicle/tow_force", 10);
  joint_state_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
  parting_pub_ = nh_.advertise<tow_sim::CableParting>("cable/parting", 1, true);
  reset_srv_ = pnh_.advertiseService("reset", &TowSimNode::onReset, this);
  pause_srv_ = pnh_.advertiseService("set_paused", &TowSimNode::onSetPaused, this);
  plan_srv_ = pnh_.advertiseService("plan_cable_out", &TowSimNode::onPlanCableOut, this);
  save_srv_ = pnh_.advertiseService("save_state", &TowSimNode::onSaveState, this);
  load_srv_ = pnh_.advertiseService("load_state", &TowSimNode::onLoadState, this);
  setUpReconfigure();
  physics_timer_ = nh_.createTimer(ros::Duration(1.0 / params_.physics_rate), [this](const ros::TimerEvent& e)
                                   { guarded("physics tick", [&] { physicsTick(e); }); });
  publish_timer_ = nh_.createTimer(ros::Duration(1.0 / params_.publish_rate), [this](const ros::TimerEvent& e)
                                   { guarded("publishing", [&] { publishTick(e); }); });
  if (params_.print_status)
    status_timer_ = nh_.createTimer(
        ros::Duration(1.0), [this](const ros::TimerEvent&) { guarded("status line", [this] { printStatus(); }); });
  ROS_INFO("tow_sim: %.0f m cable in %d segments, %.0f kg vehicle; waiting for %s in frame '%s'", config_.cable.length,
           config_.cable.segments, config_.vehicle.mass, odom_sub_.getTopic().c_str(), params_.world_frame.c_str());
}

template <class M>
ros::Subscriber TowSimNode::subscribe(const std::string& topic, uint32_t queue,
                                      void (TowSimNode::*callback)(const typename M::ConstPtr&))
{
  const boost::function<void(const typename M::ConstPtr&)> guarded_callback =
      [this, callback, topic](const typename M::ConstPtr& msg)
  {
    if (!guarded(topic.c_str(), [&] { (this->*callback)(msg); }))
      ++rejected_messages_;  // the message is dropped
  };
  return nh_.subscribe<M>(topic, queue, guarded_callback);
}

ros::Time TowSimNode::absolute(double t) const
{
  const double ns = static_cast<double>(time_origin_ns_) + t * 1e9;
  ros::Time out;
  out.fromNSec(static_cast<uint64_t>(std::clamp(ns, 0.0, static_cast<double>(ros::TIME_MAX.sec) * 1e9)));
  return out;
}

void TowSimNode::printStatus()
{
  if (!started_)
  {
    ROS_INFO("waiting for ship odometry on %s", odom_sub_.getTopic().c_str());
    return;
  }
  if (!have_last_)
  {
    ROS_INFO("t %7.1f s | no output of this run published yet (or the last was not finite)", run_.time());
    return;
  }
  ROS_INFO(
      "t %7.1f s | ship %4.2f m/s | vehicle depth %6.1f m, diversion %6.2f m | tension ship %7.0f N, "
      "vehicle %6.0f N | physics %4.1f %% of a core, %.0f steps/s",
      last_.t, last_.tow_point.v_W.norm(), last_.depth, last_.diversion.offset, last_.tension_ship,
      last_.tension_vehicle, 100.0 * physics_load_, steps_per_second_);
}

void TowSimNode::start(double t)
{
  const std::string warning = run_.start(t);
  if (!warning.empty())
    ROS_WARN_THROTTLE(5.0, "tow_sim: %s", warning.c_str());
  afterStart();
}

void TowSimNode::afterStart()
{
  // The sea runs on ROS time (ship_motion_node's ship heaves in the same waves): run time t is ROS time
  // time_origin + t.
  run_.setWaveTime(static_cast<double>(time_origin_ns_) * 1e-9);
  started_ = true;
  have_last_ = false;  // the status line waits for this run's first output
  if (ship_trail_)
  {
    ship_trail_->clear();
    vehicle_trail_->clear();
  }
  have_after_ = have_steps_ = false;
}

void TowSimNode::onOdometry(const nav_msgs::Odometry::ConstPtr& msg)
{
  const ros::Time now = ros::Time::now();
  const ros::Time stamp = msg->header.stamp.isZero() ? now : msg->header.stamp;
  if (!started_ && ship_->empty())
    time_origin_ns_ = static_cast<int64_t>(stamp.toNSec()) - static_cast<int64_t>((params_.odom_delay + 1.0) * 1e9);
  const auto& pose = msg->pose.pose;
  const auto& twist = msg->twist.twist;
  OdometryInput in;
  in.t = relative(stamp);
  in.frame_id = msg->header.frame_id;
  in.p_W = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  in.q_wxyz = Eigen::Vector4d(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z);
  in.v_S = Eigen::Vector3d(twist.linear.x, twist.linear.y, twist.linear.z);
  in.w_S = Eigen::Vector3d(twist.angular.x, twist.angular.y, twist.angular.z);
  OdometryResult r = checkOdometry(in, odometry_limits_, ship_->track(), relative(now));
  if (r.accepted || !r.jumped)
    reacquisition_.reset();
  else if (reacquisition_.jumped(in.t, r.tow_p_W, odometry_limits_))
  {
    forgetShip("ship odometry stayed " + std::to_string(params_.reacquire_after) +
               " messages in a row away from the track (a wrong first fix, a ship moved by a reset?)");
    r = checkOdometry(in, odometry_limits_, ship_->track(), relative(now));
  }
  if (!r.accepted)
  {
    ++rejected_messages_;
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected ship odometry: %s", r.reason.c_str());
    return;
  }
  // The ship's heading: of its x axis in the horizontal plane (kept when the axis is vertical).
  const Eigen::Vector3d x_axis = r.q_WS * Eigen::Vector3d::UnitX();
  ShipPose ship_pose;
  ship_pose.x = in.p_W.x();
  ship_pose.y = in.p_W.y();
  ship_pose.heading = x_axis.head<2>().norm() > 1e-6 ? std::atan2(x_axis.y(), x_axis.x())
                      : ship_->empty()               ? 0.0
                                                     : ship_->pose(ship_->newestTime()).heading;
  const Eigen::Vector3d v_W = r.q_WS * in.v_S;
  ship_pose.speed = v_W.head<2>().norm();               // over ground (a heaving ship's vertical speed left out)
  const Eigen::Matrix3d R = r.q_WS.toRotationMatrix();  // REP-103 roll and pitch: R = Rz Ry Rx
  ship_pose.z = in.p_W.z();
  ship_pose.pitch = pitchOf(R.col(0));
  ship_pose.roll = std::atan2(R(2, 1), R(2, 2));
  ship_->add(in.t, r.tow_p_W, r.tow_v_W, ship_pose);
  last_odom_wall_ = ros::WallTime::now().toSec();
  if (!started_)
  {
    start(in.t);
    ROS_INFO("tow_sim: first ship odometry received; cable laid out (%s) from the tow point",
             params_.initial_shape.c_str());
  }
}

void TowSimNode::onFinCommand(const tow_sim::FinCommand::ConstPtr& msg)
{
  if (!std::isfinite(msg->rudder) || !std::isfinite(msg->elevator) || !std::isfinite(msg->thrust))
  {
    ++rejected_messages_;
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected fins/command: rudder, elevator and thrust must be finite");
    return;
  }
  if (!started_)  // the first odometry lays the cable out with the fins centred
  {
    ROS_WARN_THROTTLE(2.0, "tow_sim: fins/command ignored: no ship odometry yet");
    return;
  }
  if (run_.command(msg->rudder, msg->elevator, msg->thrust))
    ROS_WARN_THROTTLE(2.0,
                      "tow_sim: fins/command saturated: |rudder| <= %.3f rad, |elevator| <= %.3f rad, |thrust| "
                      "<= %.0f N",
                      config_.vehicle.rudder.max_deflection, config_.vehicle.elevator.max_deflection,
                      config_.vehicle.max_thrust);
}

void TowSimNode::onCurrent(const geometry_msgs::Vector3Stamped::ConstPtr& msg)
{
  if (!msg->header.frame_id.empty() && msg->header.frame_id != params_.world_frame)
  {
    ++rejected_messages_;
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected current: header.frame_id = '%s', expected '%s'",
                      msg->header.frame_id.c_str(), params_.world_frame.c_str());
    return;
  }
  try
  {
    run_.setCurrent(Eigen::Vector3d(msg->vector.x, msg->vector.y, msg->vector.z));
  }
  catch (const std::invalid_argument& e)
  {
    ++rejected_messages_;
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected current: %s", e.what());
  }
}

void TowSimNode::onCurrentProfile(const tow_sim::CurrentProfile::ConstPtr& msg)
{
  auto reject = [this](const std::string& why)
  {
    ++rejected_messages_;
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected current_profile: %s", why.c_str());
  };
  if (!msg->header.frame_id.empty() && msg->header.frame_id != params_.world_frame)
    return reject("header.frame_id = '" + msg->header.frame_id + "', expected '" + params_.world_frame + "'");
  if (msg->depth.size() != msg->velocity.size())
    return reject("depth has " + std::to_string(msg->depth.size()) + " entries, velocity " +
                  std::to_string(msg->velocity.size()) + ": they must match");
  std::vector<CurrentSample> profile;
  for (std::size_t i = 0; i < msg->depth.size(); ++i)
    profile.push_back(
        CurrentSample{ msg->depth[i], Eigen::Vector3d(msg->velocity[i].x, msg->velocity[i].y, msg->velocity[i].z) });
  try
  {
    run_.setCurrentProfile(profile);
  }
  catch (const std::invalid_argument& e)
  {
    reject(e.what());
  }
}

void TowSimNode::onWinchCommand(const std_msgs::Float64::ConstPtr& msg)
{
  if (!started_)
  {
    ROS_WARN_THROTTLE(2.0, "tow_sim: winch/command ignored: no ship odometry yet");
    return;
  }
  winch_target_.reset();  // a command from outside takes over from a plan being executed
  try
  {
    const double applied = run_.setWinchCommand(msg->data);
    if (applied != msg->data)
      ROS_WARN_THROTTLE(2.0, "tow_sim: winch/command %.3f m/s saturated at %.3f m/s (winch.max_rate)", msg->data,
                        applied);
  }
  catch (const std::invalid_argument& e)
  {
    ++rejected_messages_;
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected winch/command (data [m/s]): %s", e.what());
  }
}

bool TowSimNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  if (ship_->empty())
  {
    res.success = false;
    res.message = "no ship odometry yet";
    return true;
  }
  diverging_ = false;
  restart_walls_.clear();
  winch_target_.reset();
  start(started_ ? run_.time() : ship_->newestTime());
  res.success = true;
  res.message = "restarted from the initial shape (" + params_.initial_shape + ") at the current ship pose";
  return true;
}

bool TowSimNode::onSetPaused(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res)
{
  paused_ = req.data;
  res.success = true;
  res.message = paused_ ? "paused" : "running";
  return true;
}

void TowSimNode::physicsTick(const ros::TimerEvent&)
{
  const ros::Time now = ros::Time::now();
  if (!last_clock_.isZero() && now.toSec() < last_clock_.toSec() - 1.0)
  {
    std::ostringstream os;
    os << "the clock jumped back " << last_clock_.toSec() - now.toSec() << " s (rosbag play -l, a simulator reset?)";
    forgetShip(os.str());
  }
  last_clock_ = now;
  holding_ = false;
  if (!started_ || paused_ || diverging_)
    return;
  if (run_.time() < ship_->oldestTime())
  {
    // Only after more than kTrackCapacity odometry messages without a physics tick (a very long pause).
    ROS_WARN(
        "tow_sim: the simulation (t = %.1f s) is older than the ship odometry kept (from %.1f s): laying the "
        "cable out again at the newest odometry",
        run_.time(), ship_->oldestTime());
    start(ship_->newestTime());
    return;
  }
  const double wanted = relative(now) - params_.odom_delay;
  const double available = ship_->newestTime() + params_.max_extrapolation;
  holding_ = wanted > available;
  if (holding_)
    ROS_WARN_THROTTLE(5.0, "tow_sim: ship odometry is %.1f s old: holding the simulation until it resumes",
                      wanted - ship_->newestTime());
  // Bounded work per tick (0.5 s simulated, about max_tick_wall of wall time), so callbacks are never starved;
  // the lag shows in diagnostics. An implicit stepper goes on in its own steps, up to one past the clock
  // (its outputs are interpolated).
  lag_ = wanted - run_.time();
  if (wanted <= run_.time())
    return;
  const double step = whole_steps_ ? run_.nextStep() : 0.0;
  const double target = tickTarget(run_.time(), wanted, available, step, tick_cost_, 0.5, params_.max_tick_wall);
  if (target <= run_.time())
    return;
  driveWinch();
  integrateTo(target);
}

void TowSimNode::integrateTo(double target)
{
  if (whole_steps_ && !have_after_)
    recordStep();  // the step's start
  const ros::WallTime wall_start = ros::WallTime::now();
  const double t0 = run_.time();
  try
  {
    const StepReport report = run_.advanceTo(target);
    rejected_steps_ += report.rejected;
    physics_steps_ += report.steps;
  }
  catch (const std::runtime_error& e)
  {
    restartAfterDivergence(e.what());
  }
  if (whole_steps_)
    recordStep();
  ship_->dropBefore(run_.time());  // the simulation never looks back: the history stays short
  const double wall = (ros::WallTime::now() - wall_start).toSec();
  physics_wall_ += wall;
  if (wall > 0.0)
    realtime_factor_ = 0.9 * realtime_factor_ + 0.1 * ((run_.time() - t0) / wall);
  if (run_.time() > t0)
    tick_cost_ = wall / (run_.time() - t0);  // the next tick's measure
}

void TowSimNode::recordStep()
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
    have_after_ = have_steps_ = false;  // publishTick reports it
  }
}

void TowSimNode::restartAfterDivergence(const std::string& why)
{
  ++restarts_;
  const double wall = ros::WallTime::now().toSec();
  restart_walls_.push_back(wall);
  while (restart_walls_.size() > kRestartBurst)
    restart_walls_.pop_front();
  if (restart_walls_.size() == kRestartBurst && wall - restart_walls_.front() < kRestartWindow)
  {
    // Restarting again would only diverge again: hold the last good state, say so, wait for ~reset.
    diverging_ = true;
    ROS_ERROR(
        "tow_sim: %s; %zu restarts within %.0f s: holding the last good state until ~reset (the numerics "
        "cannot follow this configuration: check numerics.stepper, fixed_step, max_step, cable.segments)",
        why.c_str(), kRestartBurst, kRestartWindow);
    return;
  }
  ROS_ERROR_THROTTLE(5.0, "tow_sim: %s; restarting from the initial shape at the current ship pose (%llu restarts)",
                     why.c_str(), static_cast<unsigned long long>(restarts_));
  start(run_.time());
}

void TowSimNode::forgetShip(const std::string& why)
{
  ROS_WARN("tow_sim: %s: laying the cable out again at the next ship odometry", why.c_str());
  winch_target_.reset();
  ship_->clear();
  started_ = false;
  holding_ = false;
  last_tf_stamp_ = ros::Time();
}

void TowSimNode::publishTick(const ros::TimerEvent&)
{
  diagnostics_.update();
  if (!started_)
    return;
  TowSnapshot snapshot;
  try
  {
    if (whole_steps_ && have_steps_)
      snapshot = interpolate(before_, after_, relative(ros::Time::now()) - params_.odom_delay);
    else
      snapshot = run_.snapshot();
  }
  catch (const std::runtime_error& e)
  {
    ROS_ERROR_THROTTLE(2.0, "tow_sim: %s; not published", e.what());
    have_last_ = false;
    return;
  }
  last_ = snapshot;
  have_last_ = true;
  max_length_error_ = std::max(max_length_error_, snapshot.max_length_error);
  noteTensionLimits(snapshot);
  noteParting(snapshot);
  std_msgs::Header header;
  header.stamp = absolute(snapshot.t);
  header.frame_id = params_.world_frame;
  state_pub_.publish(ros_conv::toCableState(snapshot, header));
  vehicle_odom_pub_.publish(ros_conv::toVehicleOdometry(snapshot, header, params_.vehicle_frame));
  // tf listeners warn about repeated stamps: while the simulation holds (paused, late odometry, a slow
  // physics rate) the transform is sent once per new simulation time only.
  if (header.stamp > last_tf_stamp_)
  {
    tf_broadcaster_.sendTransform(ros_conv::toVehicleTransform(snapshot, header, params_.vehicle_frame));
    last_tf_stamp_ = header.stamp;
  }
  fin_loads_pub_.publish(ros_conv::toFinLoads(snapshot, header, params_.vehicle_frame));
  ship_force_pub_.publish(ros_conv::toShipTowForce(snapshot, header));
  vehicle_force_pub_.publish(ros_conv::toVehicleTowForce(snapshot, header, params_.vehicle_frame));
  joint_state_pub_.publish(ros_conv::toJointState(snapshot, header, params_.vehicle_frame));
  if (ship_trail_)
  {
    ship_trail_->add(snapshot.t, Eigen::Vector3d(snapshot.ship.x, snapshot.ship.y, 0.0));
    vehicle_trail_->add(snapshot.t, snapshot.vehicle.p_cg_W);
  }
  if (marker_pub_.getNumSubscribers() > 0)
    marker_pub_.publish(makeMarkers(snapshot, config_.vehicle, run_.seabed(), params_, header,
                                    MarkerTrails{ ship_trail_.get(), vehicle_trail_.get() }));
}

void TowSimNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  using diagnostic_msgs::DiagnosticStatus;
  reportCurrent();
  const bool recent_restart =
      !restart_walls_.empty() && ros::WallTime::now().toSec() - restart_walls_.back() < kRestartWindow;
  if (diverging_)
    status.summary(DiagnosticStatus::ERROR, "diverging repeatedly: holding the last good state until ~reset");
  else if (recent_restart)
    status.summary(DiagnosticStatus::ERROR, "restarted after divergence");
  else if (!started_)
    status.summary(DiagnosticStatus::WARN, "waiting for ship odometry");
  else if (paused_)
    status.summary(DiagnosticStatus::OK, "paused");
  else if (holding_)
    status.summary(DiagnosticStatus::WARN, "ship odometry is late: holding");
  else if (lag_ > 1.0)
    status.summary(DiagnosticStatus::WARN, "cannot keep up with the clock");
  else
    status.summary(DiagnosticStatus::OK, "running");
  status.add("real-time factor", realtime_factor_);
  // The share of one core the integration took, and its steps, since the previous report.
  const double wall_now = ros::WallTime::now().toSec();
  if (last_diagnose_wall_ > 0.0 && wall_now > last_diagnose_wall_)
  {
    physics_load_ = physics_wall_ / (wall_now - last_diagnose_wall_);
    steps_per_second_ = static_cast<double>(physics_steps_) / (wall_now - last_diagnose_wall_);
  }
  last_diagnose_wall_ = wall_now;
  physics_wall_ = 0.0;
  physics_steps_ = 0;
  status.add("physics load [share of one core]", physics_load_);
  status.add("steps per wall second", steps_per_second_);
  status.add("lag behind the clock [s]", lag_);
  status.add("odometry age [s]", last_odom_wall_ > 0.0 ? ros::WallTime::now().toSec() - last_odom_wall_ : -1.0);
  status.add("rejected steps", rejected_steps_);
  status.add("rejected messages", rejected_messages_);
  status.add("restarts after divergence", restarts_);
  // Over every output since the last report (the diagnostics run at 1 Hz, the outputs faster).
  status.add("max relative length error", max_length_error_);
  max_length_error_ = 0.0;
  diagnoseTensionLimits(status);
  diagnoseParting(status);
}

void TowSimNode::noteTensionLimits(const TowSnapshot& snapshot)
{
  const TensionLimitCheck now = checkTensionLimits(config_.cable, snapshot.tensions);
  tension_limit_ = TensionLimitCheck::worse(tension_limit_, now);
  if (now.level == TensionLimitCheck::Level::kAboveBreakingLoad)
    ROS_ERROR_THROTTLE(5.0, "tow_sim: cable tension %.0f N at joint %d exceeds the breaking load %.0f N (t = %.1f s)",
                       now.largest, now.joint + 1, *config_.cable.breaking_load, snapshot.t);
  else if (now.level == TensionLimitCheck::Level::kAboveWorkingLoad)
    ROS_WARN_THROTTLE(5.0,
                      "tow_sim: cable tension %.0f N at joint %d exceeds the safe working load %.0f N (t = %.1f s)",
                      now.largest, now.joint + 1, *config_.cable.safe_working_load, snapshot.t);
}

void TowSimNode::diagnoseTensionLimits(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  using diagnostic_msgs::DiagnosticStatus;
  const TensionLimitCheck& worst = tension_limit_;
  if (worst.level == TensionLimitCheck::Level::kAboveBreakingLoad)
    status.mergeSummaryf(DiagnosticStatus::ERROR, "cable tension %.0f N above the breaking load", worst.largest);
  else if (worst.level == TensionLimitCheck::Level::kAboveWorkingLoad)
    status.mergeSummaryf(DiagnosticStatus::WARN, "cable tension %.0f N above the safe working load", worst.largest);
  status.add("largest tension [N]", worst.largest);
  status.add("largest tension at joint", worst.joint + 1);
  status.add("safe working load [N]", config_.cable.safe_working_load ? *config_.cable.safe_working_load : 0.0);
  status.add("breaking load [N]", config_.cable.breaking_load ? *config_.cable.breaking_load : 0.0);
  tension_limit_ = TensionLimitCheck();
}

}  // namespace tow_sim
