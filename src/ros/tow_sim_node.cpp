#include "tow_sim/ros/tow_sim_node.h"

#include <geometry_msgs/TransformStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>

#include "tow_sim/CableState.h"
#include "tow_sim/FinLoads.h"
#include "tow_sim/config/nav_params.h"
#include "tow_sim/ros/conversions.h"
#include "tow_sim/ros/markers.h"

namespace tow_sim
{
namespace
{
double wallNow()
{
  return ros::WallTime::now().toSec();
}

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
// from another node acts from the end of the step under way (implicit_fixed keeps its fixed_step). `as_loaded`
// gets its keys before that (what a saved state records, so that the batch can load the node's states).
SimulationConfig readConfig(const ros::NodeHandle& pnh, const NodeParams& params,
                            std::map<std::string, std::string>& as_loaded)
{
  try
  {
    const YAML::Node parameters = ros_conv::privateParameters(pnh);
    SimulationConfig config = loadConfig(parameters, pnh.getNamespace() + "/");
    std::vector<std::string> known = configurationFileKeys();
    for (const char* live : { "current_x", "current_y", "current_z", "safe_working_load", "breaking_load" })
      known.push_back(live);  // dynamic_reconfigure's own (cfg/TowSim.cfg): its server writes them here
    requireKnownKeys(parameters, pnh.getNamespace() + "/", known);
    as_loaded = configurationKeys(config);
    if (isImplicit(config.numerics.stepper))
      config.numerics.max_step = std::min(config.numerics.max_step, params.max_command_lag);
    return config;
  }
  catch (const std::invalid_argument& e)
  {
    throw ros_conv::withSlashes(e);
  }
}

// The survey sensors (a sensors: section), or none.
std::unique_ptr<SurveyPublisher> surveyPublisher(ros::NodeHandle nh, const ros::NodeHandle& pnh,
                                                 const NodeParams& params, const SimulationConfig& config)
{
  try
  {
    const SurveySensorParams sensors = loadSensorParams(ros_conv::privateParameters(pnh), pnh.getNamespace() + "/");
    if (!sensors.enabled)
      return nullptr;
    return std::make_unique<SurveyPublisher>(nh, sensors, params.world_frame, params.vehicle_frame,
                                             config.environment.water_density, config.environment.gravity,
                                             pnh.getNamespace() + "/");
  }
  catch (const std::invalid_argument& e)
  {
    throw ros_conv::withSlashes(e);
  }
}

// The node's parameters as the live run's: the odometry's limits, the pacing, the initial shape (a line
// straight astern, initial_angle below the horizontal, is also the fallback when no equilibrium is found).
LiveSettings liveSettings(const NodeParams& p)
{
  LiveSettings s;
  s.odometry.world_frame = p.world_frame;
  s.odometry.tow_point_S = p.tow_point_S;
  s.odometry.max_ship_speed = p.max_ship_speed;
  s.odometry.max_age = p.max_odom_age;
  s.odom_delay = p.odom_delay;
  s.max_extrapolation = p.max_extrapolation;
  s.max_tick_wall = p.max_tick_wall;
  s.tick_period = 1.0 / p.physics_rate;
  s.reacquire_after = p.reacquire_after;
  s.initial_shape.type = p.initial_shape == "line"      ? InitialShape::Type::kLine
                         : p.initial_shape == "hanging" ? InitialShape::Type::kHanging
                                                        : InitialShape::Type::kEquilibrium;
  s.initial_shape.line_direction_S = Eigen::Vector3d(-std::cos(p.initial_angle), 0.0, -std::sin(p.initial_angle));
  return s;
}

// [s] how often a notice of each kind is logged at most (0: each time)
double throttle(LiveNotice::Kind kind)
{
  switch (kind)
  {
    case LiveNotice::Kind::kOdometryRejected:
      return 2.0;
    case LiveNotice::Kind::kHolding:
    case LiveNotice::Kind::kStartFallback:
    case LiveNotice::Kind::kRestarted:
      return 5.0;
    default:
      return 0.0;
  }
}
}  // namespace

TowSimNode::TowSimNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh),
      pnh_(pnh),
      params_(ros_conv::readPrivateParams<NodeParams>(pnh, nodeParams(), validate)),
      config_(readConfig(pnh, params_, config_keys_)),
      live_(config_, liveSettings(params_), wallNow)
{
  live_.setNotify([this](const LiveNotice& notice) { say(notice); });
  if (params_.trail_duration > 0.0)
  {
    ship_trail_ = std::make_unique<TrackTrail>(params_.trail_duration);
    vehicle_trail_ = std::make_unique<TrackTrail>(params_.trail_duration);
  }
  survey_ = surveyPublisher(nh_, pnh_, params_, config_);
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
  physics_timer_ = nh_.createTimer(ros::Duration(1.0 / params_.physics_rate), [this](const ros::TimerEvent&)
                                   { guarded("physics tick", [this] { physicsTick(); }); });
  publish_timer_ = nh_.createTimer(ros::Duration(1.0 / params_.publish_rate), [this](const ros::TimerEvent&)
                                   { guarded("publishing", [this] { publishTick(); }); });
  if (params_.print_status)
    status_timer_ = nh_.createTimer(
        ros::Duration(1.0), [this](const ros::TimerEvent&) { guarded("status line", [this] { printStatus(); }); });
  ROS_INFO(
      "tow_sim: %.0f m cable in %d segments (%zu sections, %zu point bodies), %.0f kg vehicle; waiting for %s in "
      "frame '%s'",
      config_.cable.length, config_.cable.segments, std::max<size_t>(1, config_.sections.size()), config_.bodies.size(),
      config_.vehicle.mass, odom_sub_.getTopic().c_str(), params_.world_frame.c_str());
}

template <class M>
ros::Subscriber TowSimNode::subscribe(const std::string& topic, uint32_t queue,
                                      void (TowSimNode::*callback)(const typename M::ConstPtr&))
{
  const boost::function<void(const typename M::ConstPtr&)> guarded_callback =
      [this, callback, topic](const typename M::ConstPtr& msg)
  {
    if (!guarded(topic.c_str(), [&] { (this->*callback)(msg); }))
      live_.countRejected();  // the message is dropped
  };
  return nh_.subscribe<M>(topic, queue, guarded_callback);
}

ros::Time TowSimNode::stamp(double t) const
{
  ros::Time out;
  out.fromNSec(static_cast<uint64_t>(
      std::min<int64_t>(live_.absolute(t), static_cast<int64_t>(ros::TIME_MAX.sec) * 1'000'000'000)));
  return out;
}

void TowSimNode::say(const LiveNotice& notice)
{
  const double period = throttle(notice.kind);
  const double wall = wallNow();
  double& said = said_wall_[static_cast<size_t>(notice.kind)];
  if (period > 0.0 && said > 0.0 && wall - said < period)
    return;
  said = wall;
  const char* text = notice.text.c_str();
  if (notice.level == LiveNotice::Level::kError)
    ROS_ERROR("tow_sim: %s", text);
  else if (notice.level == LiveNotice::Level::kWarn)
    ROS_WARN("tow_sim: %s", text);
  else
    ROS_INFO("tow_sim: %s", text);
}

void TowSimNode::printStatus()
{
  if (!live_.started())
  {
    ROS_INFO("waiting for ship odometry on %s", odom_sub_.getTopic().c_str());
    return;
  }
  if (!have_last_)
  {
    ROS_INFO("t %7.1f s | no output of this run published yet (or the last was not finite)", live_.run().time());
    return;
  }
  ROS_INFO(
      "t %7.1f s | ship %4.2f m/s | vehicle depth %6.1f m, diversion %6.2f m | tension ship %7.0f N, "
      "vehicle %6.0f N | physics %4.1f %% of a core, %.0f steps/s",
      last_.t, last_.tow_point.v_W.norm(), last_.depth, last_.diversion.offset, last_.tension_ship,
      last_.tension_vehicle, 100.0 * load_.physics_load, load_.steps_per_second);
}

void TowSimNode::onOdometry(const nav_msgs::Odometry::ConstPtr& msg)
{
  live_.addOdometry(ros_conv::toOdometryInput(*msg), static_cast<int64_t>(msg->header.stamp.toNSec()), nowNs());
}

void TowSimNode::onFinCommand(const tow_sim::FinCommand::ConstPtr& msg)
{
  bool saturated = false;
  if (live_.finCommand(msg->rudder, msg->elevator, msg->thrust, &saturated, msg->differential))
  {
    if (saturated)
      ROS_WARN_THROTTLE(2.0,
                        "tow_sim: fins/command saturated: |rudder| <= %.3f rad, |elevator| and |differential| <= "
                        "%.3f rad, |thrust| <= %.0f N",
                        config_.vehicle.rudder.max_deflection, config_.vehicle.elevator.max_deflection,
                        config_.vehicle.max_thrust);
  }
  else if (live_.started())
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected fins/command: rudder, elevator, thrust and differential must be finite");
  else  // the first odometry lays the cable out with the fins centred
    ROS_WARN_THROTTLE(2.0, "tow_sim: fins/command ignored: no ship odometry yet");
}

void TowSimNode::onCurrent(const geometry_msgs::Vector3Stamped::ConstPtr& msg)
{
  std::string why;
  if (!msg->header.frame_id.empty() && msg->header.frame_id != params_.world_frame)
  {
    live_.countRejected();
    why = "header.frame_id = '" + msg->header.frame_id + "', expected '" + params_.world_frame + "'";
  }
  else if (live_.setCurrent(ros_conv::toEigen(msg->vector), &why))
    return;
  ROS_WARN_THROTTLE(2.0, "tow_sim: rejected current: %s", why.c_str());
}

void TowSimNode::onCurrentProfile(const tow_sim::CurrentProfile::ConstPtr& msg)
{
  std::string why;
  if (!msg->header.frame_id.empty() && msg->header.frame_id != params_.world_frame)
    why = "header.frame_id = '" + msg->header.frame_id + "', expected '" + params_.world_frame + "'";
  else if (msg->depth.size() != msg->velocity.size())
    why = "depth has " + std::to_string(msg->depth.size()) + " entries, velocity " +
          std::to_string(msg->velocity.size()) + ": they must match";
  else
  {
    std::vector<CurrentSample> profile;
    for (std::size_t i = 0; i < msg->depth.size(); ++i)
      profile.push_back(CurrentSample{ msg->depth[i], ros_conv::toEigen(msg->velocity[i]) });
    if (live_.setCurrentProfile(profile, &why))
      return;
    ROS_WARN_THROTTLE(2.0, "tow_sim: rejected current_profile: %s", why.c_str());
    return;
  }
  live_.countRejected();
  ROS_WARN_THROTTLE(2.0, "tow_sim: rejected current_profile: %s", why.c_str());
}

void TowSimNode::onWinchCommand(const std_msgs::Float64::ConstPtr& msg)
{
  double applied = 0.0;
  std::string why;
  if (!live_.winchCommand(msg->data, &applied, &why))
  {
    if (live_.started())
      ROS_WARN_THROTTLE(2.0, "tow_sim: rejected winch/command (data [m/s]): %s", why.c_str());
    else
      ROS_WARN_THROTTLE(2.0, "tow_sim: winch/command ignored: %s", why.c_str());
  }
  else if (applied != msg->data)
    ROS_WARN_THROTTLE(2.0, "tow_sim: winch/command %.3f m/s saturated at %.3f m/s (winch.max_rate)", msg->data,
                      applied);
}

bool TowSimNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  res.message = live_.reset();
  res.success = res.message.empty();
  if (res.success)
    res.message = "restarted from the initial shape (" + params_.initial_shape + ") at the current ship pose";
  return true;
}

bool TowSimNode::onSetPaused(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res)
{
  live_.setPaused(req.data);
  res.success = true;
  res.message = req.data ? "paused" : "running";
  return true;
}

void TowSimNode::physicsTick()
{
  live_.tick(nowNs());
}

void TowSimNode::publishTick()
{
  diagnostics_.update();
  if (live_.runNumber() != run_number_)  // a new run: its own outputs and trails
  {
    run_number_ = live_.runNumber();
    have_last_ = false;  // the status line waits for this run's first output
    if (ship_trail_)
    {
      ship_trail_->clear();
      vehicle_trail_->clear();
    }
    if (survey_)
      survey_->reset();
  }
  if (live_.absolute(0.0) != tf_origin_ns_)  // a new time axis (the ship was forgotten)
  {
    tf_origin_ns_ = live_.absolute(0.0);
    last_tf_stamp_ = ros::Time();
    if (survey_)
      survey_->reset();
  }
  std::optional<TowSnapshot> output;
  try
  {
    output = live_.output(nowNs());
  }
  catch (const std::runtime_error& e)
  {
    ROS_ERROR_THROTTLE(2.0, "tow_sim: %s; not published", e.what());
    have_last_ = false;
    return;
  }
  if (!output)
    return;
  const TowSnapshot& snapshot = *output;
  last_ = snapshot;
  have_last_ = true;
  noteTensionLimits(snapshot);
  noteParting(snapshot);
  std_msgs::Header header;
  header.stamp = stamp(snapshot.t);
  header.frame_id = params_.world_frame;
  state_pub_.publish(ros_conv::toCableState(snapshot, header));
  vehicle_odom_pub_.publish(ros_conv::toVehicleOdometry(snapshot, header, params_.vehicle_frame));
  // tf listeners warn about repeated stamps: while the simulation holds (paused, late odometry, a slow
  // physics rate) the transform is sent once per new simulation time only.
  if (header.stamp > last_tf_stamp_)
  {
    tf_broadcaster_.sendTransform(ros_conv::toVehicleTransform(snapshot, header, params_.vehicle_frame));
    if (!params_.view_frame.empty())
      tf_broadcaster_.sendTransform(ros_conv::toViewTransform(snapshot, header, params_.view_frame));
    last_tf_stamp_ = header.stamp;
  }
  fin_loads_pub_.publish(ros_conv::toFinLoads(snapshot, header, params_.vehicle_frame));
  ship_force_pub_.publish(ros_conv::toShipTowForce(snapshot, header));
  vehicle_force_pub_.publish(ros_conv::toVehicleTowForce(snapshot, header, params_.vehicle_frame));
  joint_state_pub_.publish(ros_conv::toJointState(snapshot, header, params_.vehicle_frame));
  if (survey_)
    survey_->publish(snapshot, [this](double t) { return stamp(t); });
  if (ship_trail_)
  {
    ship_trail_->add(snapshot.t, Eigen::Vector3d(snapshot.ship.x, snapshot.ship.y, 0.0));
    vehicle_trail_->add(snapshot.t, snapshot.vehicle.p_cg_W);
  }
  if (marker_pub_.getNumSubscribers() > 0)
    marker_pub_.publish(makeMarkers(snapshot, config_.vehicle, live_.run().seabed(), params_, header,
                                    MarkerTrails{ ship_trail_.get(), vehicle_trail_.get() },
                                    cableLook(config_, params_.cable_marker_width)));
}

void TowSimNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  using diagnostic_msgs::DiagnosticStatus;
  reportCurrent();
  const LiveStatus now = live_.status();
  const auto level = now == LiveStatus::kDiverging || now == LiveStatus::kRestarted ? DiagnosticStatus::ERROR
                     : now == LiveStatus::kRunning || now == LiveStatus::kPaused    ? DiagnosticStatus::OK
                                                                                    : DiagnosticStatus::WARN;
  status.summary(level, describe(now));
  const LiveCounters& counters = live_.counters();
  // The share of one core the integration took, its steps and the largest length error since the previous
  // report (the diagnostics run at 1 Hz, the outputs faster).
  load_ = live_.takeLoad();
  status.add("real-time factor", counters.realtime_factor);
  status.add("physics load [share of one core]", load_.physics_load);
  status.add("steps per wall second", load_.steps_per_second);
  status.add("lag behind the clock [s]", counters.lag);
  status.add("odometry age [s]", counters.last_odometry_wall > 0.0 ? wallNow() - counters.last_odometry_wall : -1.0);
  status.add("rejected steps", counters.rejected_steps);
  status.add("rejected messages", counters.rejected_messages);
  status.add("restarts after divergence", counters.restarts);
  status.add("max relative length error", load_.max_length_error);
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
