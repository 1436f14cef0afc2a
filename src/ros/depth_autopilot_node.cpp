#include "tow_sim/ros/depth_autopilot_node.h"

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "tow_sim/FinCommand.h"
#include "tow_sim/core/attitude.h"
#include "tow_sim/ros/conversions.h"

namespace tow_sim
{
namespace
{
// Stamp in seconds; a zero stamp is taken as now.
double stampOf(const std_msgs::Header& header)
{
  return (header.stamp.isZero() ? ros::Time::now() : header.stamp).toSec();
}
}  // namespace

DepthAutopilotNode::DepthAutopilotNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh),
      pnh_(pnh),
      node_params_(ros_conv::readOwnPrivateParams<AutopilotNodeParams>(pnh, autopilotNodeParams(), validate)),
      autopilot_(node_params_.controller)
{
  vehicle_sub_ = nh_.subscribe("vehicle/odom", 10, &DepthAutopilotNode::onVehicleOdometry, this);
  ship_sub_ = nh_.subscribe("ship/odom", 50, &DepthAutopilotNode::onShipOdometry, this);
  setpoint_sub_ = nh_.subscribe("autopilot/depth_setpoint", 10, &DepthAutopilotNode::onSetpoint, this);
  altitude_setpoint_sub_ =
      nh_.subscribe("autopilot/altitude_setpoint", 10, &DepthAutopilotNode::onAltitudeSetpoint, this);
  state_sub_ = nh_.subscribe("cable/state", 10, &DepthAutopilotNode::onCableState, this);
  fin_pub_ = nh_.advertise<tow_sim::FinCommand>("fins/command", 10);
  drives_winch_ = node_params_.controller.actuator != DepthAutopilotParams::Actuator::kElevator;
  if (drives_winch_)
  {
    winch_pub_ = nh_.advertise<std_msgs::Float64>("winch/command", 10);
    const std::string plan = node_params_.plan_service.empty()
                                 ? std::string("none: the cable out at the first cable/state stands in")
                                 : "from " + nh_.resolveName(node_params_.plan_service) + " at each depth setpoint";
    ROS_INFO("depth_autopilot: the winch holds the depth%s (winch/command, at most %.2f m/s; feed-forward %s)",
             node_params_.controller.actuator == DepthAutopilotParams::Actuator::kBoth ? " with the elevator" : "",
             node_params_.controller.max_payout_rate, plan.c_str());
  }
  timer_ = nh_.createTimer(ros::Duration(1.0 / node_params_.rate), &DepthAutopilotNode::tick, this);
  if (node_params_.setpoint_marker)
    setUpMarker();
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<tow_sim::DepthAutopilotConfig>>(reconfigure_mutex_, pnh_);
  reconfigure_->updateConfig(liveConfig());  // the start-up values, not the generator's defaults
  reconfigure_->setCallback([this](tow_sim::DepthAutopilotConfig& c, uint32_t) { onReconfigure(c); });
  ROS_INFO(
      "depth_autopilot: kp %.3g rad/m, ki %.3g rad/(m s), kd %.3g rad/(m/s), elevator within +-%.3f rad; "
      "track keeping %s; fins/command at %.1f Hz",
      node_params_.controller.kp, node_params_.controller.ki, node_params_.controller.kd,
      node_params_.controller.max_elevator, node_params_.controller.track_keeping ? "on" : "off", node_params_.rate);
}

tow_sim::DepthAutopilotConfig DepthAutopilotNode::liveConfig() const
{
  const DepthAutopilotParams& p = autopilot_.params();
  tow_sim::DepthAutopilotConfig c;
  c.kp = p.kp;
  c.ki = p.ki;
  c.kd = p.kd;
  c.max_elevator = p.max_elevator;
  c.track_keeping = p.track_keeping;
  c.rudder_kp = p.rudder_kp;
  c.rudder_kd = p.rudder_kd;
  c.max_rudder = p.max_rudder;
  c.winch_kp = p.winch_kp;
  c.winch_ki = p.winch_ki;
  c.winch_time_constant = p.winch_time_constant;
  c.max_payout_rate = p.max_payout_rate;
  c.roll_hold = p.roll_hold;
  c.roll_kp = p.roll_kp;
  c.roll_kd = p.roll_kd;
  c.max_differential = p.max_differential;
  return c;
}

void DepthAutopilotNode::onReconfigure(tow_sim::DepthAutopilotConfig& c)
{
  DepthAutopilotParams p = autopilot_.params();
  p.kp = c.kp;
  p.ki = c.ki;
  p.kd = c.kd;
  p.max_elevator = c.max_elevator;
  p.track_keeping = c.track_keeping;
  p.rudder_kp = c.rudder_kp;
  p.rudder_kd = c.rudder_kd;
  p.max_rudder = c.max_rudder;
  p.winch_kp = c.winch_kp;
  p.winch_ki = c.winch_ki;
  p.winch_time_constant = c.winch_time_constant;
  p.max_payout_rate = c.max_payout_rate;
  p.roll_hold = c.roll_hold;
  p.roll_kp = c.roll_kp;
  p.roll_kd = c.roll_kd;
  p.max_differential = c.max_differential;
  try
  {
    autopilot_.setTuning(p, pnh_.getNamespace() + "/");
    node_params_.controller = autopilot_.params();
    ROS_INFO(
        "depth_autopilot: reconfigured: kp %g, ki %g, kd %g, max_elevator %g; track keeping %s; winch kp %g, "
        "ki %g, time constant %g s, max payout rate %g m/s",
        p.kp, p.ki, p.kd, p.max_elevator, p.track_keeping ? "on" : "off", p.winch_kp, p.winch_ki, p.winch_time_constant,
        p.max_payout_rate);
  }
  catch (const std::invalid_argument& e)
  {
    ROS_ERROR("depth_autopilot: reconfigure refused: %s; every setting keeps its previous value", e.what());
    c = liveConfig();
  }
}

bool DepthAutopilotNode::frameOk(const nav_msgs::Odometry& msg, const char* topic)
{
  if (msg.header.frame_id == node_params_.world_frame)
    return true;
  ROS_WARN_THROTTLE(2.0, "depth_autopilot: rejected %s: header.frame_id = '%s', expected ~world_frame = '%s'", topic,
                    msg.header.frame_id.c_str(), node_params_.world_frame.c_str());
  return false;
}

void DepthAutopilotNode::onVehicleOdometry(const nav_msgs::Odometry::ConstPtr& msg)
{
  try
  {
    if (!frameOk(*msg, "vehicle/odom"))
      return;
    const auto& p = msg->pose.pose.position;
    const auto& o = msg->pose.pose.orientation;
    const auto& v = msg->twist.twist.linear;
    Eigen::Quaterniond q(o.w, o.x, o.y, o.z);
    if (!std::isfinite(q.norm()) || std::abs(q.norm() - 1.0) > 0.01)
    {
      ROS_WARN_THROTTLE(2.0, "depth_autopilot: rejected vehicle/odom: pose.orientation must be a unit quaternion");
      return;
    }
    VehicleMeasurement m;
    m.t = stampOf(msg->header);
    m.received = ros::Time::now().toSec();  // stale by arrival: tow_sim_node stamps trail the clock by odom_delay
    m.p_W = Eigen::Vector3d(p.x, p.y, p.z);
    m.v_W = q.normalized() * Eigen::Vector3d(v.x, v.y, v.z);  // the twist is in the vehicle frame
    const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
    m.roll = eulerOf(R).roll;  // REP-103: yaw, pitch, then roll about x_b
    m.roll_rate = msg->twist.twist.angular.x;
    // Altitude from the newest cable/state of the same moment (within 0.5 s), moved by the depth change
    // since (a flat bottom over that short time).
    if (have_cable_out_ && std::abs(m.t - cable_out_stamp_) <= 0.5)
      m.cable_out = cable_out_;
    if (have_altitude_ && std::abs(m.t - altitude_stamp_) <= 0.5)
      m.altitude = altitude_ - (-p.z - altitude_depth_);
    else if (autopilot_.altitudeMode())
      ROS_WARN_THROTTLE(5.0,
                        "depth_autopilot: altitude mode but no recent cable/state with a seabed: holding the "
                        "last depth setpoint, %.2f m",
                        autopilot_.setpoint());
    const bool had_setpoint = autopilot_.hasSetpoint();
    // tow_sim_node repeats a stamp while its simulation holds: ignored quietly; older ones are warned of.
    if (autopilot_.hasVehicle() && m.t < autopilot_.vehicleStamp())
      ROS_WARN_THROTTLE(2.0, "depth_autopilot: ignored vehicle/odom: its stamp is older than the previous one");
    if (!autopilot_.addVehicle(m))
      return;
    if (!had_setpoint && !announced_hold_)
    {
      announced_hold_ = true;
      ROS_INFO("depth_autopilot: no setpoint on %s yet: holding the first vehicle depth, %.2f m",
               setpoint_sub_.getTopic().c_str(), autopilot_.setpoint());
    }
  }
  catch (const std::exception& e)
  {
    ROS_WARN_THROTTLE(2.0, "depth_autopilot: rejected vehicle/odom: %s", e.what());
  }
}

void DepthAutopilotNode::onShipOdometry(const nav_msgs::Odometry::ConstPtr& msg)
{
  try
  {
    if (!frameOk(*msg, "ship/odom"))
      return;
    autopilot_.addShip(Eigen::Vector2d(msg->pose.pose.position.x, msg->pose.pose.position.y));
  }
  catch (const std::exception& e)
  {
    ROS_WARN_THROTTLE(2.0, "depth_autopilot: rejected ship/odom: %s", e.what());
  }
}

void DepthAutopilotNode::onSetpoint(const std_msgs::Float64::ConstPtr& msg)
{
  applyDepthSetpoint(msg->data, setpoint_sub_.getTopic() + ": data");
}

void DepthAutopilotNode::applyDepthSetpoint(double depth, const std::string& source)
{
  try
  {
    autopilot_.setSetpoint(depth);
    announced_hold_ = true;
    ROS_INFO("depth_autopilot: depth setpoint %.2f m (%s)", depth, source.c_str());
    if (drives_winch_ && !node_params_.plan_service.empty() && depth > 0.0)
    {
      plan_depth_ = depth;  // asked at the next tick
      plan_retry_at_ = 0.0;
    }
  }
  catch (const std::invalid_argument&)
  {
    ROS_WARN_THROTTLE(2.0,
                      "depth_autopilot: rejected %s = %g is out of range: must be a finite number in [0, %g] [m] "
                      "(depth, positive down); keeping %.2f m",
                      source.c_str(), depth, node_params_.controller.max_depth, autopilot_.setpoint());
  }
  moveMarker();  // to the setpoint in force (back, if refused)
}

void DepthAutopilotNode::onAltitudeSetpoint(const std_msgs::Float64::ConstPtr& msg)
{
  try
  {
    autopilot_.setAltitudeSetpoint(msg->data);
    announced_hold_ = true;
    // No feed-forward in altitude mode (its depth changes with the bottom): the feedback alone.
    plan_depth_ = std::numeric_limits<double>::quiet_NaN();
    if (drives_winch_)
      autopilot_.setCableOutFeedForward(std::numeric_limits<double>::quiet_NaN());
    ROS_INFO("depth_autopilot: altitude setpoint %.2f m above the seabed", msg->data);
  }
  catch (const std::invalid_argument&)
  {
    ROS_WARN_THROTTLE(2.0,
                      "depth_autopilot: rejected %s: data = %g is out of range: must be a finite number in "
                      "[0, %g] [m] (above the seabed)",
                      altitude_setpoint_sub_.getTopic().c_str(), msg->data, node_params_.controller.max_depth);
  }
}

void DepthAutopilotNode::onCableState(const tow_sim::CableState::ConstPtr& msg)
{
  if (std::isfinite(msg->cable_length) && msg->cable_length > 0.0)
  {
    have_cable_out_ = true;
    cable_out_ = msg->cable_length;
    cable_out_stamp_ = stampOf(msg->header);
  }
  if (!msg->seabed_present || !std::isfinite(msg->vehicle_altitude) || !std::isfinite(msg->vehicle_depth))
    return;
  have_altitude_ = true;
  altitude_ = msg->vehicle_altitude;
  altitude_depth_ = msg->vehicle_depth;
  altitude_stamp_ = stampOf(msg->header);
}

void DepthAutopilotNode::askForPlan(double now)
{
  if (plan_call_.valid() || std::isnan(plan_depth_) || now < plan_retry_at_)
    return;
  plan_depth_asked_ = plan_depth_;
  tow_sim::PlanCableOut srv;
  srv.request.depth = plan_depth_;  // at the ship's present speed, no speed window, not executed
  const std::string name = nh_.resolveName(node_params_.plan_service);
  plan_call_ = std::async(std::launch::async,
                          [name, srv]() mutable
                          {
                            const bool answered = ros::service::call(name, srv);
                            return std::make_pair(answered, srv.response);
                          });
}

void DepthAutopilotNode::takePlan(double now)
{
  if (!plan_call_.valid() || plan_call_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return;
  const auto [answered, plan] = plan_call_.get();
  const std::string name = nh_.resolveName(node_params_.plan_service);
  if (!answered)
  {
    ROS_WARN_THROTTLE(10.0,
                      "depth_autopilot: no answer from %s (is tow_sim_node running?): asking again in 2 s; "
                      "meanwhile the winch works without feed-forward",
                      name.c_str());
    plan_retry_at_ = now + 2.0;
    return;
  }
  if (plan_depth_asked_ != plan_depth_ || autopilot_.altitudeMode())
    return;  // a newer setpoint is asked for next, or altitude mode took over
  plan_depth_ = std::numeric_limits<double>::quiet_NaN();
  if (plan.reachable && std::isfinite(plan.cable_out) && plan.cable_out > 0.0)
  {
    autopilot_.setCableOutFeedForward(plan.cable_out);
    ROS_INFO("depth_autopilot: feed-forward %.2f m of cable out for %.2f m (%s: steady tension %.0f N at the ship)",
             plan.cable_out, plan_depth_asked_, name.c_str(), plan.tension_ship);
    return;
  }
  autopilot_.setCableOutFeedForward(std::numeric_limits<double>::quiet_NaN());
  ROS_WARN("depth_autopilot: no feed-forward for %.2f m (%s: %s): the feedback alone", plan_depth_asked_, name.c_str(),
           plan.message.c_str());
}

void DepthAutopilotNode::tick(const ros::TimerEvent&)
{
  try
  {
    const double now = ros::Time::now().toSec();
    if (drives_winch_)
    {
      takePlan(now);
      askForPlan(now);
    }
    const AutopilotCommand c = autopilot_.update(now);
    followWithMarker();
    if (c.status == AutopilotCommand::Status::kWaiting)
      ROS_INFO_THROTTLE(10.0, "depth_autopilot: waiting for %s; fins centred", vehicle_sub_.getTopic().c_str());
    else if (c.status == AutopilotCommand::Status::kStale)
      ROS_WARN_THROTTLE(2.0, "depth_autopilot: nothing new on %s for ~odom_timeout = %.2f s: fins centred, no thrust",
                        vehicle_sub_.getTopic().c_str(), node_params_.controller.odom_timeout);
    tow_sim::FinCommand cmd;
    cmd.header.stamp = ros::Time::now();
    cmd.rudder = c.rudder;
    cmd.elevator = c.elevator;
    cmd.thrust = c.thrust;
    cmd.differential = c.differential;
    fin_pub_.publish(cmd);
    if (drives_winch_)
    {
      // Stopped while waiting, stale or without a recent cable out.
      std_msgs::Float64 rate;
      rate.data = c.winch ? c.payout_rate : 0.0;
      winch_pub_.publish(rate);
    }
  }
  catch (const std::exception& e)
  {
    ROS_ERROR_THROTTLE(2.0, "depth_autopilot: %s", e.what());
  }
}

}  // namespace tow_sim
