// ship_motion_node: a scripted ship for demos and tests. Publishes nav_msgs/Odometry on ship/odom and the
// tf world -> ship; follows geometry_msgs/Twist on cmd_vel (surge speed, yaw rate) while it keeps coming.
// The ship moves by the scenarios' manoeuvre law (ScriptedShip, tow_sim_scenario); ~manoeuvre picks a
// preset: straight, turn (after ~turn_start, radius ~turn_radius, to port if ~turn_radius > 0), zigzag
// (+-~speed/~turn_radius * ~zigzag_period/4 about the course, from ~turn_start), speed_change (to ~speed_2 at
// ~change_time over ~change_duration), waypoints (~waypoints, each within ~waypoint_radius).
// In waves (~environment/waves, the towing configuration's section loaded here too) the ship heaves, rolls and
// pitches by its RAOs (~rao_file, or the generic vessel's; ~wave_response false keeps it level), the sea
// running on ROS time like tow_sim_node's.
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "tow_sim/config/config.h"
#include "tow_sim/core/environment/ship_response.h"
#include "tow_sim/ros/conversions.h"
#include "tow_sim/scenario/scripted_ship.h"

namespace
{
using tow_sim::Manoeuvre;

struct Presets
{
  std::string manoeuvre = "straight";
  double speed = 2.0, speed_2 = 1.0, change_time = 120.0, change_duration = 30.0;
  double turn_radius = 200.0, turn_start = 120.0, zigzag_period = 240.0, waypoint_radius = 30.0;
  std::vector<Eigen::Vector2d> waypoints;
};

// A private parameter of type T if set: a value of another type is an error naming the parameter (not a
// silent fall back to the default, as ros::NodeHandle::param does).
template <class T>
void readTyped(const ros::NodeHandle& pnh, const std::string& key, T& value, const char* type)
{
  if (pnh.hasParam(key) && !pnh.getParam(key, value))
    throw std::invalid_argument(pnh.resolveName(key) + " must be " + type);
}

Presets readPresets(const ros::NodeHandle& pnh)
{
  Presets p;
  readTyped(pnh, "manoeuvre", p.manoeuvre, "a string");
  for (auto [key, value] : { std::pair<const char*, double*>{ "speed", &p.speed },
                             { "speed_2", &p.speed_2 },
                             { "change_time", &p.change_time },
                             { "change_duration", &p.change_duration },
                             { "turn_radius", &p.turn_radius },
                             { "turn_start", &p.turn_start },
                             { "zigzag_period", &p.zigzag_period },
                             { "waypoint_radius", &p.waypoint_radius } })
    readTyped(pnh, key, *value, "a number");
  std::vector<double> points;
  readTyped(pnh, "waypoints", points, "a list of numbers [x1, y1, x2, y2, ...]");
  if (points.size() % 2 != 0)
    throw std::invalid_argument(pnh.resolveName("waypoints") + " must hold x, y pairs [m]: an even count of numbers");
  for (size_t i = 0; i + 1 < points.size(); i += 2)
    p.waypoints.emplace_back(points[i], points[i + 1]);
  const std::string known[] = { "straight", "turn", "zigzag", "speed_change", "waypoints" };
  if (std::find(std::begin(known), std::end(known), p.manoeuvre) == std::end(known))
    throw std::invalid_argument(pnh.resolveName("manoeuvre") + " = '" + p.manoeuvre +
                                "' must be straight, turn, zigzag, speed_change or waypoints");
  if (p.manoeuvre == "waypoints" && p.waypoints.empty())
    throw std::invalid_argument(pnh.resolveName("waypoints") +
                                " is empty: the waypoints manoeuvre needs at least one [x, y] pair");
  if (!(std::abs(p.speed) <= 15.0 && std::abs(p.speed_2) <= 15.0))
    throw std::invalid_argument(pnh.resolveName("speed") + " and speed_2 must be in [-15, 15] [m/s]");
  if (!(std::abs(p.turn_radius) >= 10.0 && std::abs(p.turn_radius) <= 1e5))
    throw std::invalid_argument(pnh.resolveName("turn_radius") + " must have a magnitude in [10, 1e5] [m]");
  if (!(p.zigzag_period > 0.0) || !(p.change_duration > 0.0) || !(p.turn_start >= 0.0) || !(p.change_time >= 0.0))
    throw std::invalid_argument(pnh.resolveName("zigzag_period") +
                                " and change_duration must be > 0 [s], turn_start "
                                "and change_time >= 0 [s]");
  return p;
}

// A preset as a list of manoeuvres, straight on for ever (1e6 s) after it.
std::vector<Manoeuvre> manoeuvres(const Presets& p)
{
  auto make = [&](Manoeuvre::Type type, double duration)
  {
    Manoeuvre m;
    m.type = type;
    m.speed = p.speed;
    m.duration = duration;
    m.radius = std::abs(p.turn_radius);
    m.direction = p.turn_radius > 0.0 ? 1 : -1;
    return m;
  };
  std::vector<Manoeuvre> list;
  const bool delayed = p.manoeuvre == "turn" || p.manoeuvre == "zigzag";
  if (delayed && p.turn_start > 0.0)
    list.push_back(make(Manoeuvre::Type::kStraight, p.turn_start));
  if (p.manoeuvre == "turn")
  {
    list.push_back(make(Manoeuvre::Type::kTurn, 0.0));
    list.back().angle = 1e9;  // [rad] turning for good (1.6e8 turns)
  }
  else if (p.manoeuvre == "zigzag")
  {
    list.push_back(make(Manoeuvre::Type::kZigzag, 0.0));
    list.back().angle = std::abs(p.speed) / std::abs(p.turn_radius) * p.zigzag_period / 4.0;
    list.back().legs = 1000;
  }
  else if (p.manoeuvre == "speed_change")
  {
    list.push_back(make(Manoeuvre::Type::kStraight, std::max(p.change_time, 1e-3)));
    list.push_back(make(Manoeuvre::Type::kSpeedChange, p.change_duration));
    list.back().to_speed = p.speed_2;
  }
  else if (p.manoeuvre == "waypoints")
  {
    list.push_back(make(Manoeuvre::Type::kWaypoints, 0.0));
    list.back().acceptance = p.waypoint_radius;
    list.back().points = p.waypoints;
  }
  list.push_back(make(Manoeuvre::Type::kStraight, 1e6));
  if (p.manoeuvre == "speed_change")
    list.back().speed = p.speed_2;
  return list;
}

class ShipMotionNode
{
public:
  ShipMotionNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) : presets_(readPresets(pnh))
  {
    double heading = 0.0;
    pnh.param("heading", heading, heading);
    pnh.param("rate", rate_, 20.0);
    pnh.param<std::string>("world_frame", world_frame_, "odom");
    pnh.param<std::string>("ship_frame", ship_frame_, "ship");
    if (!(rate_ >= 1.0 && rate_ <= 1000.0))
      throw std::invalid_argument(pnh.resolveName("rate") + " must be in [1, 1000] [Hz]");
    ship_ = std::make_unique<tow_sim::ScriptedShip>(manoeuvres(presets_), 0.0, 0.0, heading);
    readWaves(pnh);
    odom_pub_ = nh.advertise<nav_msgs::Odometry>("ship/odom", 20);
    cmd_sub_ = nh.subscribe("cmd_vel", 5, &ShipMotionNode::onCmdVel, this);
    timer_ = nh.createTimer(ros::Duration(1.0 / rate_), &ShipMotionNode::tick, this);
  }

private:
  void readWaves(const ros::NodeHandle& pnh)
  {
    bool respond = true;
    std::string rao_file;
    readTyped(pnh, "wave_response", respond, "true or false");
    readTyped(pnh, "rao_file", rao_file, "a string (a CSV file)");
    const tow_sim::SimulationConfig config =
        tow_sim::loadConfig(tow_sim::ros_conv::privateParameters(pnh), pnh.getNamespace() + "/");
    const tow_sim::Environment& env = config.environment;
    if (!respond || env.waves.type == tow_sim::WaveParams::Type::kNone)
      return;
    waves_ = std::make_unique<tow_sim::WaveField>(env.waves, env.gravity);
    try
    {
      rao_ = std::make_unique<tow_sim::RaoTable>(rao_file.empty() ? tow_sim::RaoTable::genericVessel(env.gravity)
                                                                  : tow_sim::RaoTable::fromCsvFile(rao_file));
    }
    catch (const std::invalid_argument& e)
    {
      throw std::invalid_argument(pnh.resolveName("rao_file") + ": " + e.what());
    }
    ROS_INFO("ship_motion: heaving, rolling and pitching in %s waves (%s)",
             env.waves.type == tow_sim::WaveParams::Type::kRegular ? "regular" : "JONSWAP",
             rao_file.empty() ? "the generic vessel's RAOs" : rao_file.c_str());
  }

  void onCmdVel(const geometry_msgs::Twist::ConstPtr& msg)
  {
    if (!std::isfinite(msg->linear.x) || !std::isfinite(msg->angular.z))
    {
      ROS_WARN_THROTTLE(2.0, "ship_motion: rejected cmd_vel: linear.x and angular.z must be finite");
      return;
    }
    teleop_.speed = std::clamp(msg->linear.x, -15.0, 15.0);
    teleop_.yaw_rate = std::clamp(msg->angular.z, -0.5, 0.5);
    last_cmd_ = ros::Time::now();
  }

  void tick(const ros::TimerEvent&)
  {
    const ros::Time now = ros::Time::now();
    if (last_.isZero() || now < last_)
      last_ = now;  // the first tick, or the clock jumped back
    const double dt = (now - last_).toSec();
    last_ = now;
    const bool teleop = !last_cmd_.isZero() && (now - last_cmd_).toSec() < 1.0;
    if (dt > 0.0)
      ship_->step(dt, teleop ? &teleop_ : nullptr);
    publish(now);
  }

  void publish(const ros::Time& now)
  {
    const tow_sim::ShipRigidMotion m =
        tow_sim::scriptedShipMotion(now.toSec(), ship_->x(), ship_->y(), ship_->heading(), ship_->speed(),
                                    ship_->yawRate(), waves_.get(), rao_.get());
    const Eigen::Matrix3d R = tow_sim::shipRotation(m.roll, m.pitch, m.yaw);
    const Eigen::Quaterniond q(R);
    const Eigen::Vector3d v_S = R.transpose() * m.v_W, w_S = R.transpose() * tow_sim::shipAngularVelocity(m);
    nav_msgs::Odometry odom;
    odom.header.stamp = now;
    odom.header.frame_id = world_frame_;
    odom.child_frame_id = ship_frame_;
    odom.pose.pose.position.x = m.p_W.x();
    odom.pose.pose.position.y = m.p_W.y();
    odom.pose.pose.position.z = m.p_W.z();
    odom.pose.pose.orientation.x = q.x();
    odom.pose.pose.orientation.y = q.y();
    odom.pose.pose.orientation.z = q.z();
    odom.pose.pose.orientation.w = q.w();
    odom.twist.twist.linear.x = v_S.x();  // REP-105: twist in the ship frame
    odom.twist.twist.linear.y = v_S.y();
    odom.twist.twist.linear.z = v_S.z();
    odom.twist.twist.angular.x = w_S.x();
    odom.twist.twist.angular.y = w_S.y();
    odom.twist.twist.angular.z = w_S.z();
    odom_pub_.publish(odom);

    geometry_msgs::TransformStamped tf;
    tf.header = odom.header;
    tf.child_frame_id = ship_frame_;
    tf.transform.translation.x = m.p_W.x();
    tf.transform.translation.y = m.p_W.y();
    tf.transform.translation.z = m.p_W.z();
    tf.transform.rotation = odom.pose.pose.orientation;
    broadcaster_.sendTransform(tf);
  }

  Presets presets_;
  double rate_ = 20.0;
  std::string world_frame_, ship_frame_;
  std::unique_ptr<tow_sim::ScriptedShip> ship_;
  std::unique_ptr<tow_sim::WaveField> waves_;  // none: a level ship
  std::unique_ptr<tow_sim::RaoTable> rao_;
  tow_sim::ScriptedShip::Teleop teleop_;
  ros::Time last_, last_cmd_;
  ros::Publisher odom_pub_;
  ros::Subscriber cmd_sub_;
  ros::Timer timer_;
  tf2_ros::TransformBroadcaster broadcaster_;
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "ship_motion");
  ros::NodeHandle nh, pnh("~");
  try
  {
    ShipMotionNode ship(nh, pnh);
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("ship_motion: %s", e.what());
    return 1;
  }
  return 0;
}
