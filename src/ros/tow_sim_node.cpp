#include "tow_sim/ros/tow_sim_node.h"

#include <geometry_msgs/TransformStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tow_sim/CableState.h"
#include "tow_sim/FinLoads.h"
#include "tow_sim/core/equilibrium.h"
#include "tow_sim/core/odometry_check.h"
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

// The core names keys "section.key"; on the parameter server they are "section/key".
std::invalid_argument withSlashes(const std::invalid_argument& e)
{
  std::string message = e.what();
  const size_t end = message.find_first_of(" :");
  for (size_t i = 0; i < end && i < message.size(); ++i)
    if (message[i] == '.')
      message[i] = '/';
  return std::invalid_argument(message);
}

double readDouble(const ros::NodeHandle& pnh, const std::string& key, double fallback, double lo, double hi,
                  const char* unit, bool lo_open = false)
{
  double value = fallback;
  if (pnh.hasParam(key) && !pnh.getParam(key, value))
    throw std::invalid_argument(pnh.resolveName(key) + ": must be a number " + unit);
  requireInRange(pnh.resolveName(key), value, lo, hi, unit, lo_open);
  return value;
}

std::string readString(const ros::NodeHandle& pnh, const std::string& key, const std::string& fallback)
{
  std::string value = fallback;
  if (pnh.hasParam(key) && !pnh.getParam(key, value))
    throw std::invalid_argument(pnh.resolveName(key) + ": must be a string");
  return value;
}

NodeParams readNodeParams(const ros::NodeHandle& pnh)
{
  NodeParams p;
  p.world_frame = readString(pnh, "world_frame", p.world_frame);
  p.vehicle_frame = readString(pnh, "vehicle_frame", p.vehicle_frame);
  if (p.world_frame.empty() || p.vehicle_frame.empty() || p.world_frame == p.vehicle_frame)
    throw std::invalid_argument(pnh.resolveName("vehicle_frame") +
                                ": world_frame and vehicle_frame must be "
                                "non-empty and different");
  std::vector<double> tow;
  if (pnh.hasParam("tow_point"))
  {
    if (!pnh.getParam("tow_point", tow) || tow.size() != 3)
      throw std::invalid_argument(pnh.resolveName("tow_point") +
                                  ": must be a list of 3 numbers [x, y, z] [m] in "
                                  "the ship frame");
    for (int i = 0; i < 3; ++i)
      requireInRange(pnh.resolveName("tow_point") + "[" + std::to_string(i) + "]", tow[i], -1000.0, 1000.0, "[m]");
    p.tow_point_S = Eigen::Vector3d(tow[0], tow[1], tow[2]);
  }
  p.physics_rate = readDouble(pnh, "physics_rate", p.physics_rate, 1.0, 1000.0, "[Hz]");
  p.publish_rate = readDouble(pnh, "publish_rate", p.publish_rate, 0.1, 100.0, "[Hz]");
  p.odom_delay = readDouble(pnh, "odom_delay", p.odom_delay, 0.0, 10.0, "[s]");
  p.max_extrapolation = readDouble(pnh, "max_extrapolation", p.max_extrapolation, 0.0, 60.0, "[s]");
  p.max_ship_speed = readDouble(pnh, "max_ship_speed", p.max_ship_speed, 0.0, 1000.0, "[m/s]", true);
  p.max_odom_age = readDouble(pnh, "max_odom_age", p.max_odom_age, 0.0, 1e6, "[s]", true);
  p.initial_shape = readString(pnh, "initial_shape", p.initial_shape);
  if (p.initial_shape != "equilibrium" && p.initial_shape != "line" && p.initial_shape != "hanging")
    throw std::invalid_argument(pnh.resolveName("initial_shape") + " = '" + p.initial_shape +
                                "' must be 'equilibrium', 'line' or 'hanging'");
  p.initial_angle = readDouble(pnh, "initial_angle", p.initial_angle, 0.0, M_PI / 2, "[rad]");
  p.tension_color_max = readDouble(pnh, "tension_color_max", p.tension_color_max, 0.0, 1e9, "[N]", true);
  p.force_arrow_scale = readDouble(pnh, "force_arrow_scale", p.force_arrow_scale, 0.0, 10.0, "[m/N]", true);
  p.cable_marker_width = readDouble(pnh, "cable_marker_width", p.cable_marker_width, 0.0, 100.0, "[m]", true);
  p.vehicle_diameter = readDouble(pnh, "vehicle_diameter", p.vehicle_diameter, 0.0, 100.0, "[m]", true);
  if (pnh.hasParam("print_status") && !pnh.getParam("print_status", p.print_status))
    throw std::invalid_argument(pnh.resolveName("print_status") + ": must be true or false");
  return p;
}

SimulationConfig readConfig(const ros::NodeHandle& pnh)
{
  XmlRpc::XmlRpcValue tree;
  YAML::Node root;
  if (pnh.getParam(pnh.getNamespace(), tree))
    root = ros_conv::toYaml(tree);
  try
  {
    return loadConfig(root, pnh.getNamespace() + "/");
  }
  catch (const std::invalid_argument& e)
  {
    throw withSlashes(e);
  }
}

}  // namespace

TowSimNode::TowSimNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh),
      pnh_(pnh),
      params_(readNodeParams(pnh)),
      config_(readConfig(pnh)),
      track_(params_.max_extrapolation, kTrackCapacity)
{
  odometry_limits_.world_frame = params_.world_frame;
  odometry_limits_.tow_point_S = params_.tow_point_S;
  odometry_limits_.max_ship_speed = params_.max_ship_speed;
  odometry_limits_.max_age = params_.max_odom_age;
  vehicle_ = std::make_shared<Vehicle>(config_.vehicle, config_.numerics);
  if (config_.seabed.type != SeabedParams::Type::kNone)
    seabed_ = std::make_shared<Seabed>(config_.seabed);
  model_ = std::make_shared<ChainModel>(config_.cable, vehicle_, config_.environment, config_.numerics, seabed_);
  sim_ = std::make_unique<Simulator>(
      model_, [this](double time) { return track_(time); }, config_.winch);
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
  reset_srv_ = pnh_.advertiseService("reset", &TowSimNode::onReset, this);
  pause_srv_ = pnh_.advertiseService("set_paused", &TowSimNode::onSetPaused, this);
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
  const VehicleOutputs o = vehicle_->outputs(sim_->time(), sim_->elementKinematics(sim_->geometry().segments),
                                             sim_->data().environment, sim_->data().actuators);
  const Diversion d = lateralDiversion(o.p_cg_W, o.v_cg_W, sim_->shipEnd(), track_direction_);
  ROS_INFO(
      "t %7.1f s | ship %4.2f m/s | vehicle depth %6.1f m, diversion %6.2f m | tension ship %7.0f N, "
      "vehicle %6.0f N",
      sim_->time(), sim_->shipEnd().v_W.norm(), o.depth, d.offset, sim_->tensions().col(0).norm(),
      sim_->tensions().col(sim_->geometry().segments).norm());
}

void TowSimNode::start(double t)
{
  const ShipEndState ship = track_(t);
  const Eigen::Vector3d heading(track_direction_.x(), track_direction_.y(), 0.0);
  Eigen::Vector3d direction = -Eigen::Vector3d::UnitZ();
  if (params_.initial_shape != "hanging")
    direction = -std::cos(params_.initial_angle) * heading - std::sin(params_.initial_angle) * Eigen::Vector3d::UnitZ();
  sim_->resetActuators(t);
  // The initial shapes know nothing of the seabed: joints below it are raised onto it.
  auto lift = [this](ChainState state)
  {
    if (seabed_)
      liftAboveSeabed(*seabed_, state);
    return state;
  };
  if (params_.initial_shape == "equilibrium")
  {
    try
    {
      sim_->reset(t, lift(steadyTowEquilibrium(*model_, sim_->data(), t, ship.p_W, ship.v_W).state));
      started_ = true;
      attitude_.reset();
      return;
    }
    catch (const std::runtime_error& e)
    {
      ROS_WARN_THROTTLE(5.0, "tow_sim: %s; starting from a straight line instead", e.what());
    }
  }
  sim_->reset(t, lift(straightChain(sim_->geometry(), ship.p_W, direction, ship.v_W)));
  attitude_.reset();
  started_ = true;
}

void TowSimNode::onOdometry(const nav_msgs::Odometry::ConstPtr& msg)
{
  const ros::Time now = ros::Time::now();
  const ros::Time stamp = msg->header.stamp.isZero() ? now : msg->header.stamp;
  if (!started_ && track_.empty())
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
  const OdometryResult r = checkOdometry(in, odometry_limits_, track_, relative(now));
  if (!r.accepted)
  {
    ++rejected_messages_;
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected ship odometry: %s", r.reason.c_str());
    return;
  }
  track_.add(in.t, r.tow_p_W, r.tow_v_W);
  ship_attitude_ = r.q_WS;
  const Eigen::Vector3d heading = r.q_WS * Eigen::Vector3d::UnitX();
  if (heading.head<2>().norm() > 1e-6)
    track_direction_ = Eigen::Vector3d(heading.x(), heading.y(), 0.0).normalized();
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
  if (sim_->command(msg->rudder, msg->elevator, msg->thrust))
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
    sim_->setCurrent(Eigen::Vector3d(msg->vector.x, msg->vector.y, msg->vector.z));
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
    sim_->setCurrentProfile(profile);
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
  try
  {
    const double applied = sim_->setWinchCommand(msg->data);
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
  if (track_.empty())
  {
    res.success = false;
    res.message = "no ship odometry yet";
    return true;
  }
  diverging_ = false;
  restart_walls_.clear();
  start(started_ ? sim_->time() : track_.newestTime());
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
  if (sim_->time() < track_.oldestTime())
  {
    // Only after more than kTrackCapacity odometry messages without a physics tick (a very long pause).
    ROS_WARN(
        "tow_sim: the simulation (t = %.1f s) is older than the ship odometry kept (from %.1f s): laying the "
        "cable out again at the newest odometry",
        sim_->time(), track_.oldestTime());
    start(track_.newestTime());
    return;
  }
  const double wanted = relative(now) - params_.odom_delay;
  const double available = track_.newestTime() + params_.max_extrapolation;
  holding_ = wanted > available;
  if (holding_)
    ROS_WARN_THROTTLE(5.0, "tow_sim: ship odometry is %.1f s old: holding the simulation until it resumes",
                      wanted - track_.newestTime());
  // Bounded work per tick, so callbacks are never starved; the lag shows in diagnostics.
  const double target = std::min({ wanted, available, sim_->time() + 0.5 });
  lag_ = wanted - sim_->time();
  if (target <= sim_->time())
    return;
  const ros::WallTime wall_start = ros::WallTime::now();
  const double t0 = sim_->time();
  try
  {
    const StepReport report = sim_->advanceTo(target);
    rejected_steps_ += report.rejected;
    max_length_error_ = report.max_length_error;
  }
  catch (const std::runtime_error& e)
  {
    restartAfterDivergence(e.what());
  }
  track_.dropBefore(sim_->time());  // the simulation never looks back: the history stays short
  const double wall = (ros::WallTime::now() - wall_start).toSec();
  if (wall > 0.0)
    realtime_factor_ = 0.9 * realtime_factor_ + 0.1 * ((sim_->time() - t0) / wall);
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
  start(sim_->time());
}

void TowSimNode::forgetShip(const std::string& why)
{
  ROS_WARN("tow_sim: %s: laying the cable out again at the next ship odometry", why.c_str());
  track_.clear();
  started_ = false;
  holding_ = false;
  last_tf_stamp_ = ros::Time();
}

void TowSimNode::publishTick(const ros::TimerEvent&)
{
  diagnostics_.update();
  if (!started_)
    return;
  const int nu = sim_->geometry().segments;
  const ElementKinematics k = sim_->elementKinematics(nu);
  const VehicleOutputs o = vehicle_->outputs(sim_->time(), k, sim_->data().environment, sim_->data().actuators);
  const Eigen::Matrix3Xd joints = sim_->jointPositions();
  const Eigen::Matrix3Xd& tensions = sim_->tensions();
  if (!joints.allFinite() || !tensions.allFinite() || !o.p_cg_W.allFinite() || !o.v_cg_W.allFinite())
  {
    ROS_ERROR_THROTTLE(2.0, "tow_sim: non-finite state; not published");
    return;
  }
  std_msgs::Header header;
  header.stamp = absolute(sim_->time());
  header.frame_id = params_.world_frame;
  const ShipEndState ship = sim_->shipEnd();
  const Diversion d = lateralDiversion(o.p_cg_W, o.v_cg_W, ship, track_direction_);

  tow_sim::CableState state;
  state.header = header;
  for (int j = 0; j < joints.cols(); ++j)
    state.joints.push_back(ros_conv::toPoint(joints.col(j)));
  for (int j = 0; j <= nu; ++j)
  {
    state.tension.push_back(tensions.col(j).norm());
    state.tension_vector.push_back(ros_conv::toVector3(tensions.col(j)));
  }
  for (bool slack : slackFlags(joints, tensions))
    state.slack.push_back(slack);
  state.tension_ship = tensions.col(0).norm();
  state.tension_vehicle = tensions.col(nu).norm();
  state.vehicle_depth = o.depth;
  state.layback = (ship.p_W - o.p_cg_W).dot(track_direction_);
  state.diversion = d.offset;
  state.diversion_rate = d.rate;
  state.cable_length = sim_->cableLength();
  state.payout_rate = sim_->payoutRate();
  state.seabed_present = seabed_ != nullptr;
  state.seabed_contact.assign(joints.cols(), false);
  if (seabed_)
  {
    state.vehicle_altitude = seabed_->altitude(o.p_cg_W);
    for (int j = 1; j < joints.cols(); ++j)
      state.seabed_contact[j] = seabed_->altitude(joints.col(j)) < 0.0;
    for (double eta : vehicle_->contactFractions())
      state.vehicle_on_seabed = state.vehicle_on_seabed || seabed_->altitude(k.pointAt(eta)) < 0.0;
  }
  state.max_length_error = max_length_error_;
  state_pub_.publish(state);

  const Eigen::Quaterniond q = attitude_.update(o.q_WB * Eigen::Vector3d::UnitX());
  const Eigen::Matrix3d R = q.toRotationMatrix();
  nav_msgs::Odometry odom;
  odom.header = header;
  odom.child_frame_id = params_.vehicle_frame;
  odom.pose.pose.position = ros_conv::toPoint(o.p_cg_W);
  odom.pose.pose.orientation = ros_conv::toQuaternion(q);
  odom.twist.twist.linear = ros_conv::toVector3(R.transpose() * o.v_cg_W);
  odom.twist.twist.angular = ros_conv::toVector3(R.transpose() * o.omega_W);
  vehicle_odom_pub_.publish(odom);

  // tf listeners warn about repeated stamps: while the simulation holds (paused, late odometry, a slow
  // physics rate) the transform is sent once per new simulation time only.
  if (header.stamp > last_tf_stamp_)
  {
    geometry_msgs::TransformStamped tf;
    tf.header = header;
    tf.child_frame_id = params_.vehicle_frame;
    tf.transform.translation = ros_conv::toVector3(o.p_cg_W);
    tf.transform.rotation = odom.pose.pose.orientation;
    tf_broadcaster_.sendTransform(tf);
    last_tf_stamp_ = header.stamp;
  }

  tow_sim::FinLoads loads;
  loads.header = header;
  loads.header.frame_id = params_.vehicle_frame;
  loads.rudder_angle = o.rudder;
  loads.elevator_angle = o.elevator;
  loads.thrust = o.thrust;
  loads.rudder_angle_of_attack = o.rudder_loads.angle_of_attack;
  loads.elevator_angle_of_attack = o.elevator_loads.angle_of_attack;
  loads.rudder_lift = ros_conv::toVector3(o.rudder_loads.lift_B);
  loads.rudder_drag = ros_conv::toVector3(o.rudder_loads.drag_B);
  loads.rudder_moment = ros_conv::toVector3(o.rudder_loads.moment_cg_B);
  loads.rudder_hinge_moment = o.rudder_loads.hinge_moment;
  loads.elevator_lift = ros_conv::toVector3(o.elevator_loads.lift_B);
  loads.elevator_drag = ros_conv::toVector3(o.elevator_loads.drag_B);
  loads.elevator_moment = ros_conv::toVector3(o.elevator_loads.moment_cg_B);
  loads.elevator_hinge_moment = o.elevator_loads.hinge_moment;
  fin_loads_pub_.publish(loads);

  if (marker_pub_.getNumSubscribers() > 0)
    marker_pub_.publish(makeMarkers(*sim_, *vehicle_, o, q, params_, header));
}

void TowSimNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  using diagnostic_msgs::DiagnosticStatus;
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
  status.add("lag behind the clock [s]", lag_);
  status.add("odometry age [s]", last_odom_wall_ > 0.0 ? ros::WallTime::now().toSec() - last_odom_wall_ : -1.0);
  status.add("rejected steps", rejected_steps_);
  status.add("rejected messages", rejected_messages_);
  status.add("restarts after divergence", restarts_);
  status.add("max relative length error", max_length_error_);
}

}  // namespace tow_sim
