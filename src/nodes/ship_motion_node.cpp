// ship_motion_node: a scripted ship for demos and tests. Publishes nav_msgs/Odometry on ship/odom and the
// tf world -> ship; follows geometry_msgs/Twist on cmd_vel (surge speed, yaw rate) while it keeps coming.
// Manoeuvres (~manoeuvre): straight, turn (after ~turn_start, radius ~turn_radius, to port if
// ~turn_radius > 0), zigzag (yaw rate +-speed/radius switching every ~zigzag_period / 2), speed_change (to
// ~speed_2 at ~change_time over ~change_duration). Yaw rate follows its target with a 5 s lag and speed
// ramps, so the ship's acceleration is continuous.
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace
{
class ShipMotion
{
public:
  explicit ShipMotion(ros::NodeHandle& nh, ros::NodeHandle& pnh)
  {
    pnh.param<std::string>("manoeuvre", manoeuvre_, "straight");
    pnh.param("speed", speed_, 2.0);
    pnh.param("speed_2", speed_2_, 1.0);
    pnh.param("change_time", change_time_, 120.0);
    pnh.param("change_duration", change_duration_, 30.0);
    pnh.param("turn_radius", turn_radius_, 200.0);
    pnh.param("turn_start", turn_start_, 120.0);
    pnh.param("zigzag_period", zigzag_period_, 240.0);
    pnh.param("rate", rate_, 20.0);
    pnh.param<std::string>("world_frame", world_frame_, "odom");
    pnh.param<std::string>("ship_frame", ship_frame_, "ship");
    pnh.param("heading", heading_, 0.0);
    pnh.param("waypoint_radius", waypoint_radius_, 30.0);
    std::vector<double> waypoints;
    pnh.param("waypoints", waypoints, waypoints);
    if (waypoints.size() % 2 != 0)
      throw std::invalid_argument(pnh.resolveName("waypoints") + " must hold x, y pairs [m]: an even count of numbers");
    for (size_t i = 0; i + 1 < waypoints.size(); i += 2)
      waypoints_.emplace_back(waypoints[i], waypoints[i + 1]);
    const std::string known[] = { "straight", "turn", "zigzag", "speed_change", "waypoints" };
    if (std::find(std::begin(known), std::end(known), manoeuvre_) == std::end(known))
      throw std::invalid_argument(pnh.resolveName("manoeuvre") + " = '" + manoeuvre_ +
                                  "' must be straight, turn, zigzag, speed_change or waypoints");
    if (manoeuvre_ == "waypoints" && waypoints_.empty())
      throw std::invalid_argument(pnh.resolveName("waypoints") +
                                  " is empty: the waypoints manoeuvre needs at least "
                                  "one [x, y] pair");
    if (!(std::abs(speed_) <= 15.0 && std::abs(speed_2_) <= 15.0))
      throw std::invalid_argument(pnh.resolveName("speed") + " and speed_2 must be in [-15, 15] [m/s]");
    if (!(std::abs(turn_radius_) >= 10.0 && std::abs(turn_radius_) <= 1e5))
      throw std::invalid_argument(pnh.resolveName("turn_radius") + " must have a magnitude in [10, 1e5] [m]");
    if (!(rate_ >= 1.0 && rate_ <= 1000.0) || !(zigzag_period_ > 0.0) || !(change_duration_ > 0.0))
      throw std::invalid_argument(pnh.resolveName("rate") +
                                  " must be in [1, 1000] [Hz]; zigzag_period and "
                                  "change_duration > 0 [s]");
    u_ = speed_;
    odom_pub_ = nh.advertise<nav_msgs::Odometry>("ship/odom", 20);
    cmd_sub_ = nh.subscribe("cmd_vel", 5, &ShipMotion::onCmdVel, this);
    timer_ = nh.createTimer(ros::Duration(1.0 / rate_), &ShipMotion::tick, this);
  }

private:
  void onCmdVel(const geometry_msgs::Twist::ConstPtr& msg)
  {
    if (!std::isfinite(msg->linear.x) || !std::isfinite(msg->angular.z))
    {
      ROS_WARN_THROTTLE(2.0, "ship_motion: rejected cmd_vel: linear.x and angular.z must be finite");
      return;
    }
    cmd_u_ = std::clamp(msg->linear.x, -15.0, 15.0);
    cmd_r_ = std::clamp(msg->angular.z, -0.5, 0.5);
    last_cmd_ = ros::Time::now();
  }

  void tick(const ros::TimerEvent&)
  {
    const ros::Time now = ros::Time::now();
    if (start_.isZero())
    {
      start_ = now;
      last_ = now;
    }
    const double dt = (now - last_).toSec();
    last_ = now;
    const double t = (now - start_).toSec();
    double u_target = speed_, r_target = 0.0;
    const bool teleop = !last_cmd_.isZero() && (now - last_cmd_).toSec() < 1.0;
    if (teleop)
    {
      u_target = cmd_u_;
      r_target = cmd_r_;
    }
    else if (manoeuvre_ == "turn" && t > turn_start_)
      r_target = speed_ / turn_radius_;
    else if (manoeuvre_ == "zigzag" && t > turn_start_)
      r_target = (std::fmod(t - turn_start_, zigzag_period_) < 0.5 * zigzag_period_ ? 1.0 : -1.0) * speed_ /
                 std::abs(turn_radius_);
    else if (manoeuvre_ == "waypoints" && next_waypoint_ < waypoints_.size())
    {
      const auto& w = waypoints_[next_waypoint_];
      if (std::hypot(w.first - x_, w.second - y_) < waypoint_radius_)
      {
        ROS_INFO("ship_motion: waypoint %zu reached", next_waypoint_ + 1);
        ++next_waypoint_;
      }
      const double wanted = std::atan2(w.second - y_, w.first - x_);
      const double error = std::atan2(std::sin(wanted - heading_), std::cos(wanted - heading_));
      const double r_max = std::abs(speed_ / turn_radius_);
      r_target = std::clamp(error / 20.0, -r_max, r_max);
    }
    else if (manoeuvre_ == "speed_change" && t > change_time_)
      u_target = speed_ + (speed_2_ - speed_) * std::min(1.0, (t - change_time_) / change_duration_);
    // Smooth: speed slews at most 0.1 m/s^2, yaw rate follows with a 5 s lag.
    const double du = std::clamp(u_target - u_, -0.1 * dt, 0.1 * dt);
    u_ += du;
    r_ += (r_target - r_) * std::min(1.0, dt / 5.0);
    heading_ += r_ * dt;
    x_ += u_ * std::cos(heading_) * dt;
    y_ += u_ * std::sin(heading_) * dt;

    nav_msgs::Odometry odom;
    odom.header.stamp = now;
    odom.header.frame_id = world_frame_;
    odom.child_frame_id = ship_frame_;
    odom.pose.pose.position.x = x_;
    odom.pose.pose.position.y = y_;
    odom.pose.pose.orientation.z = std::sin(0.5 * heading_);
    odom.pose.pose.orientation.w = std::cos(0.5 * heading_);
    odom.twist.twist.linear.x = u_;  // REP-105: twist in the ship frame
    odom.twist.twist.angular.z = r_;
    odom_pub_.publish(odom);

    geometry_msgs::TransformStamped tf;
    tf.header = odom.header;
    tf.child_frame_id = ship_frame_;
    tf.transform.translation.x = x_;
    tf.transform.translation.y = y_;
    tf.transform.rotation = odom.pose.pose.orientation;
    broadcaster_.sendTransform(tf);
  }

  std::string manoeuvre_, world_frame_, ship_frame_;
  double speed_, speed_2_, change_time_, change_duration_, turn_radius_, turn_start_, zigzag_period_, rate_;
  std::vector<std::pair<double, double>> waypoints_;
  size_t next_waypoint_ = 0;
  double waypoint_radius_ = 30.0;
  double x_ = 0.0, y_ = 0.0, heading_ = 0.0, u_ = 0.0, r_ = 0.0, cmd_u_ = 0.0, cmd_r_ = 0.0;
  ros::Time start_, last_, last_cmd_;
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
    ShipMotion ship(nh, pnh);
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("ship_motion: %s", e.what());
    return 1;
  }
  return 0;
}
