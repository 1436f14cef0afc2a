#include "tow_sim/ros/tow_nav_node.h"

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <sensor_msgs/NavSatFix.h>
#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>

#include <ctime>

#include "tow_sim/config/config.h"
#include "tow_sim/config/nav_params.h"
#include "tow_sim/ros/conversions.h"

namespace tow_sim
{
namespace
{
constexpr double kUnknownVariance = 1e6;  // [rad^2] an orientation the node does not know (no AHRS yet)

TowNavNodeParams readParams(const ros::NodeHandle& pnh)
{
  ros_conv::requireConfigurationOrOwnKeys(pnh, towNavNodeParams());
  return ros_conv::readPrivateParams(pnh, towNavNodeParams(), validate);
}

SimulationConfig readConfig(const ros::NodeHandle& pnh)
{
  try
  {
    return loadConfig(ros_conv::privateParameters(pnh), pnh.getNamespace() + "/");
  }
  catch (const std::invalid_argument& e)
  {
    throw ros_conv::withSlashes(e);
  }
}

TowNavParams readNavParams(const ros::NodeHandle& pnh)
{
  try
  {
    return loadNavParams(ros_conv::privateParameters(pnh), pnh.getNamespace() + "/");
  }
  catch (const std::invalid_argument& e)
  {
    throw ros_conv::withSlashes(e);
  }
}

double threadCpu()  // [s]
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
}  // namespace

TowNavNode::TowNavNode(ros::NodeHandle nh, ros::NodeHandle pnh) : TowNavNode(nh, pnh, readConfig(pnh)) {}

TowNavNode::TowNavNode(ros::NodeHandle nh, ros::NodeHandle pnh, const SimulationConfig& config)
    : nh_(nh),
      params_(readParams(pnh)),
      nav_params_(readNavParams(pnh)),
      rows_(surveyRowSettings(params_, nav_params_, config)),
      nav_(std::make_unique<TowNav>(config, nav_params_))
{
  pose_pub_ = nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("nav/fish/pose", 10);
  fix_pub_ = nh_.advertise<sensor_msgs::NavSatFix>("nav/fish/fix", 10);
  layback_pub_ = nh_.advertise<tow_sim::SensorValue>("nav/layback", 10);
  cross_track_pub_ = nh_.advertise<tow_sim::SensorValue>("nav/cross_track", 10);
  subs_.push_back(subscribe("survey/ship/fix", &SurveyRows::fix));
  subs_.push_back(subscribe("survey/ship/heading", &SurveyRows::heading));
  subs_.push_back(subscribe("survey/cable_out", &SurveyRows::cableOut));
  subs_.push_back(subscribe("survey/tension", &SurveyRows::tension));
  subs_.push_back(subscribe("survey/fish/depth", &SurveyRows::depth));
  subs_.push_back(subscribe("survey/fish/pressure", &SurveyRows::pressure));
  subs_.push_back(subscribe("survey/fish/imu", &SurveyRows::imu));
  subs_.push_back(subscribe("survey/usbl", &SurveyRows::usbl));
  diagnostics_.setHardwareID("tow_nav");
  diagnostics_.add("estimate", this, &TowNavNode::diagnose);
  cpu_since_ = ros::WallTime::now().toSec();
  timer_ = nh_.createTimer(ros::Duration(1.0 / params_.rate), &TowNavNode::tick, this);
  ROS_INFO(
      "tow_nav: %d tow runs of %d segments; the estimate on nav/fish/pose in '%s' about %s, %g s behind "
      "the clock",
      nav_params_.members, config.cable.segments, params_.world_frame.c_str(),
      params_.origin_from_first_fix ? "the first good fix" : "the configured origin", params_.hold);
}

TowNavNode::~TowNavNode() = default;

template <class M>
ros::Subscriber TowNavNode::subscribe(const std::string& topic, std::string (SurveyRows::*take)(const M&))
{
  return nh_.subscribe<M>(topic, 50,
                          [this, topic, take](const typename M::ConstPtr& msg)
                          {
                            const std::string why = (rows_.*take)(*msg);
                            if (!why.empty())
                              ROS_WARN_THROTTLE(2.0, "tow_nav: refused a message on %s: %s (the estimate carries on)",
                                                nh_.resolveName(topic).c_str(), why.c_str());
                          });
}

void TowNavNode::tick(const ros::TimerEvent&)
{
  const double cpu = threadCpu();
  bool moved = false;
  for (const SurveyMeasurement& row : rows_.release(ros::Time::now()))
  {
    if (std::isfinite(row.fish_heading))
      fish_yaw_ = row.fish_heading, fish_pitch_ = row.fish_pitch;
    last_ = nav_->update(row);
    ++rows_taken_;
    moved = true;
  }
  if (moved && last_.valid)
    publish(last_);
  cpu_ += threadCpu() - cpu;
  diagnostics_.update();
}

void TowNavNode::publish(const TowNavEstimate& e)
{
  std_msgs::Header header;
  header.stamp = rows_.stampOf(e.t);
  header.frame_id = params_.world_frame;
  geometry_msgs::PoseWithCovarianceStamped pose;
  pose.header = header;
  pose.pose.pose.position = ros_conv::toPoint(e.p_W);
  const bool attitude = std::isfinite(fish_yaw_) && std::isfinite(fish_pitch_);
  pose.pose.pose.orientation =
      ros_conv::toQuaternion(attitude ? Eigen::Quaterniond(Eigen::AngleAxisd(fish_yaw_, Eigen::Vector3d::UnitZ()) *
                                                           Eigen::AngleAxisd(fish_pitch_, Eigen::Vector3d::UnitY()))
                                      : Eigen::Quaterniond::Identity());
  const double angle_variance = attitude ? nav_params_.heading_sigma * nav_params_.heading_sigma : kUnknownVariance;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
      pose.pose.covariance[6 * r + c] = e.covariance(r, c);
    pose.pose.covariance[6 * (r + 3) + r + 3] = angle_variance;
  }
  pose_pub_.publish(pose);

  if (const GeographicLib::LocalCartesian* origin = rows_.origin())
  {
    sensor_msgs::NavSatFix fix;
    fix.header = header;
    fix.header.frame_id = params_.fish_frame;
    fix.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
    origin->Reverse(e.p_W.x(), e.p_W.y(), e.p_W.z(), fix.latitude, fix.longitude, fix.altitude);
    for (int i = 0; i < 9; ++i)
      fix.position_covariance[i] = e.covariance(i / 3, i % 3);  // ENU, as NavSatFix has it
    fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_KNOWN;
    fix_pub_.publish(fix);
  }

  tow_sim::SensorValue layback, cross_track;
  layback.header = cross_track.header = header;
  layback.value = e.layback;
  cross_track.value = e.cross_track;
  layback.variance = cross_track.variance = 0.5 * (e.covariance(0, 0) + e.covariance(1, 1));
  layback_pub_.publish(layback);
  cross_track_pub_.publish(cross_track);

  if (!params_.publish_tf)
    return;
  geometry_msgs::TransformStamped tf;
  tf.header = header;
  tf.child_frame_id = params_.fish_frame;
  tf.transform.translation = ros_conv::toVector3(e.p_W);
  tf.transform.rotation = pose.pose.pose.orientation;
  broadcaster_.sendTransform(tf);
}

void TowNavNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  using diagnostic_msgs::DiagnosticStatus;
  if (!nav_->started())
    status.summaryf(DiagnosticStatus::WARN,
                    "waiting: the model starts after nav.start_after = %g s of ship fixes and headings on "
                    "survey/ship/fix and survey/ship/heading",
                    nav_params_.start_after);
  else
    status.summary(DiagnosticStatus::OK, "estimating the towfish's position");
  const TowNavEstimate& e = last_;
  const double wall = ros::WallTime::now().toSec();
  status.add("estimate time [s after the epoch]", e.t);
  status.add("horizontal sigma [m]", std::sqrt(0.5 * (e.covariance(0, 0) + e.covariance(1, 1))));
  status.add("current east [m/s]", e.current.x());
  status.add("current north [m/s]", e.current.y());
  status.add("drag scale [-]", e.drag_scale);
  status.add("rows taken", rows_taken_);
  status.add("messages refused (bad field)", rows_.refused());
  status.add("messages late (after their row)", rows_.late());
  status.add("rows rejected (time)", e.rows_rejected);
  status.add("ship fixes rejected", e.fixes_rejected);
  status.add("USBL fixes rejected (gate)", e.usbl_rejected);
  status.add("depths rejected (below the seabed)", e.depths_rejected);
  status.add("load [share of one core]", wall > cpu_since_ ? cpu_ / (wall - cpu_since_) : 0.0);
  cpu_ = 0.0;
  cpu_since_ = wall;
}

}  // namespace tow_sim
