#include "tow_sim/ros/tow_nav_node.h"

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <sensor_msgs/NavSatFix.h>
#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>

#include <ctime>

#include "tow_sim/config/config.h"
#include "tow_sim/config/nav_params.h"
#include "tow_sim/core/attitude.h"
#include "tow_sim/ros/conversions.h"

namespace tow_sim
{
namespace
{
constexpr double kUnknownVariance = 1e6;  // [rad^2] an angle the node does not know (no AHRS yet)
constexpr double kFreshAttitude = 5.0;    // [s] an AHRS attitude this old is still the pose's

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

// The estimate in WGS84: latitude and longitude of its point on the origin's tangent plane; the altitude is the
// origin's (the sea surface's ellipsoidal height when it is configured so) plus the estimate's z. ENU covariance.
sensor_msgs::NavSatFix fishFix(const std_msgs::Header& header, const std::string& frame,
                               const GeographicLib::LocalCartesian& origin, const TowNavEstimate& e)
{
  sensor_msgs::NavSatFix fix;
  fix.header = header;
  fix.header.frame_id = frame;
  fix.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
  double h = 0.0;
  origin.Reverse(e.p_W.x(), e.p_W.y(), 0.0, fix.latitude, fix.longitude, h);
  fix.altitude = origin.HeightOrigin() + e.p_W.z();
  for (int i = 0; i < 9; ++i)
    fix.position_covariance[i] = e.covariance(i / 3, i % 3);
  fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_KNOWN;
  return fix;
}

tow_sim::SensorValue sensorValue(const std_msgs::Header& header, double value, double variance)
{
  tow_sim::SensorValue m;
  m.header = header;
  m.value = value;
  m.variance = variance;
  return m;
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
      config_(config),
      rows_(std::make_unique<SurveyRows>(surveyRowSettings(params_, nav_params_, config))),
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
                            const std::string why = ((*rows_).*take)(*msg);
                            if (!why.empty())
                              warnRefused(topic, why);
                          });
}

// At most one warning every 2 s per topic (a stream of bad messages on one hides none on another).
void TowNavNode::warnRefused(const std::string& topic, const std::string& why)
{
  const ros::WallTime now = ros::WallTime::now();
  auto last = warned_.find(topic);
  if (last != warned_.end() && (now - last->second).toSec() < 2.0)
    return;
  warned_[topic] = now;
  ROS_WARN("tow_nav: refused a message on %s: %s (the estimate carries on)", nh_.resolveName(topic).c_str(),
           why.c_str());
}

// The clock went back (a simulation reset, a bag played again): the measurements start again, and so does the
// estimate.
void TowNavNode::restart(const ros::Time& now)
{
  ROS_WARN("tow_nav: the clock went back from %.3f to %.3f s: the estimate starts again", last_now_.toSec(),
           now.toSec());
  rows_ = std::make_unique<SurveyRows>(surveyRowSettings(params_, nav_params_, config_));
  nav_ = std::make_unique<TowNav>(config_, nav_params_);
  last_ = TowNavEstimate();
  fish_yaw_ = fish_pitch_ = fish_roll_ = fish_t_ = NAN;
  ++restarts_;
}

void TowNavNode::tick(const ros::TimerEvent&)
{
  const double cpu = threadCpu();
  const ros::Time now = ros::Time::now();
  if (!last_now_.isZero() && now + ros::Duration(1.0) < last_now_)
    restart(now);
  last_now_ = now;
  bool moved = false;
  for (const SurveyMeasurement& row : rows_->release(now))
  {
    if (std::isfinite(row.fish_heading))
      fish_yaw_ = row.fish_heading, fish_pitch_ = row.fish_pitch, fish_roll_ = row.fish_roll, fish_t_ = row.t;
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
  header.stamp = rows_->stampOf(e.t);
  header.frame_id = params_.world_frame;
  // The AHRS's attitude while fresh: yaw, pitch and roll with its variances (unknown where it gives none; a row
  // without a roll: roll 0, unknown).
  const bool attitude = std::isfinite(fish_t_) && e.t - fish_t_ <= kFreshAttitude;
  const bool rolled = attitude && std::isfinite(fish_roll_);
  const Eigen::Vector3d variance = rows_->attitudeVariance();
  const double roll_var = rolled && std::isfinite(variance[0]) ? variance[0] : kUnknownVariance;
  const double pitch_var = attitude && std::isfinite(variance[1]) ? variance[1] : kUnknownVariance;
  const double yaw_var = attitude && std::isfinite(variance[2]) ? variance[2] : kUnknownVariance;
  geometry_msgs::PoseWithCovarianceStamped pose;
  pose.header = header;
  pose.pose.pose.position = ros_conv::toPoint(e.p_W);
  pose.pose.pose.orientation = ros_conv::toQuaternion(
      attitude ? Eigen::Quaterniond(rotationFromEuler(rolled ? fish_roll_ : 0.0, fish_pitch_, fish_yaw_))
               : Eigen::Quaterniond::Identity());
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      pose.pose.covariance[6 * r + c] = e.covariance(r, c);
  pose.pose.covariance[21] = roll_var;
  pose.pose.covariance[28] = pitch_var;
  pose.pose.covariance[35] = yaw_var;
  pose_pub_.publish(pose);
  if (rows_->origin())
    fix_pub_.publish(fishFix(header, params_.fish_frame, *rows_->origin(), e));
  const Eigen::Vector2d forward(std::cos(e.heading), std::sin(e.heading)), port(-forward.y(), forward.x());
  const Eigen::Matrix2d P = e.covariance.topLeftCorner<2, 2>();
  layback_pub_.publish(sensorValue(header, e.layback, forward.dot(P * forward)));
  cross_track_pub_.publish(sensorValue(header, e.cross_track, port.dot(P * port)));
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
  const double ahead = rows_->ahead(ros::Time::now());
  if (ahead > 10.0)
    status.mergeSummaryf(DiagnosticStatus::WARN,
                         "the measurements' stamps are %.0f s ahead of the clock: nothing is taken until the clock "
                         "reaches them (playing a bag: use_sim_time and rosbag play --clock)",
                         ahead);
  const TowNavEstimate& e = last_;
  const double wall = ros::WallTime::now().toSec();
  status.add("estimate time [s after the epoch]", e.t);
  status.add("horizontal sigma [m]", std::sqrt(0.5 * (e.covariance(0, 0) + e.covariance(1, 1))));
  status.add("current east [m/s]", e.current.x());
  status.add("current north [m/s]", e.current.y());
  status.add("drag scale [-]", e.drag_scale);
  status.add("rows taken", rows_taken_);
  status.add("messages refused (bad field)", rows_->refused());
  status.add("USBL fixes without a ship pose around them", rows_->unplaced());
  status.add("messages late (after their row)", rows_->late());
  status.add("measurements waiting", static_cast<long>(rows_->held()));
  status.add("newest stamp ahead of the clock [s]", ahead);
  status.add("restarts (the clock went back)", restarts_);
  status.add("rows rejected (time)", e.rows_rejected);
  status.add("ship fixes rejected", e.fixes_rejected);
  status.add("USBL fixes rejected (gate)", e.usbl_rejected);
  status.add("depths rejected (below the seabed)", e.depths_rejected);
  status.add("load [share of one core]", wall > cpu_since_ ? cpu_ / (wall - cpu_since_) : 0.0);
  cpu_ = 0.0;
  cpu_since_ = wall;
}

}  // namespace tow_sim
