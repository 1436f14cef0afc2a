// A survey vessel's sensor messages as the rows tow_nav takes (docs/survey.md, "tow_nav_node"): the messages
// tow_sim_node's survey/ topics carry, from a live system or a bag. Each message becomes a sample at its
// header.stamp (the instant it measures) in a SurveyRowQueue; a USBL fix (the fish in the ship frame) waits
// until its row is due, is put into the world frame with the ship's fixes and headings on both sides of its
// stamp, and its row is placed usbl_latency after the stamp, where tow_nav looks for it (tow_nav.h). Times in
// the rows are seconds after an epoch: the first message's stamp, whole seconds.
#pragma once

#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <ros/time.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>

#include <Eigen/Core>
#include <deque>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "tow_sim/SensorValue.h"
#include "tow_sim/config/config.h"
#include "tow_sim/config/node_params.h"
#include "tow_sim/core/survey/survey_row_queue.h"
#include "tow_sim/core/survey/tow_nav.h"

namespace GeographicLib
{
class LocalCartesian;
}

namespace tow_sim
{
struct SurveyRowSettings
{
  bool origin_from_first_fix = true;                                            // else the three below
  double origin_latitude = 0.0, origin_longitude = 0.0, origin_altitude = 0.0;  // [deg], [deg], [m] WGS84
  std::string heading_convention = "enu";  // enu: yaw from east toward north; compass: from north, clockwise
  std::string ship_frame = "ship";         // the USBL fixes' frame_id
  std::string depth_source = "depth";      // depth: survey/fish/depth; pressure: from survey/fish/pressure
  double atmospheric_pressure = 101325.0;  // [Pa] subtracted from the fish's absolute pressure
  double rho_g = 1025.0 * 9.81;            // [Pa/m]
  double hold = 1.5;                       // [s] a row waits this long for the samples of its instant
  double usbl_latency = 1.0;               // [s] tow_nav's: a USBL row is placed this long after its stamp
  double max_ship_gap = 2.0;  // [s] a USBL fix needs ship fixes and headings on both sides, 2x this apart at most
};

// tow_nav_node's settings: its keys, the estimator's usbl_latency, the water's density and gravity.
SurveyRowSettings surveyRowSettings(const TowNavNodeParams& node, const TowNavParams& nav,
                                    const SimulationConfig& config);

class SurveyRows
{
public:
  explicit SurveyRows(const SurveyRowSettings& settings);
  ~SurveyRows();

  // Each takes one message and returns "" or why it was refused, naming the message's field and the allowed
  // range (the refusal is counted in refused()).
  std::string fix(const sensor_msgs::NavSatFix& msg);
  std::string heading(const geometry_msgs::QuaternionStamped& msg);
  std::string cableOut(const tow_sim::SensorValue& msg);
  std::string tension(const tow_sim::SensorValue& msg);
  std::string depth(const tow_sim::SensorValue& msg);
  std::string pressure(const sensor_msgs::FluidPressure& msg);
  std::string imu(const sensor_msgs::Imu& msg);
  std::string usbl(const geometry_msgs::PointStamped& msg);

  // The rows held for `hold` by now, in time order; every row held (the end of a bag).
  std::vector<SurveyMeasurement> release(const ros::Time& now);
  std::vector<SurveyMeasurement> releaseAll();

  // Rows' times and ROS stamps (false/zero before the first message).
  bool hasEpoch() const { return has_epoch_; }
  ros::Time stampOf(double t) const { return epoch_ + ros::Duration(t); }
  // The world's geodetic origin (null until the first good fix or the configured one).
  const GeographicLib::LocalCartesian* origin() const { return origin_.get(); }
  long refused() const { return refused_; }    // unplaced USBL fixes included
  long unplaced() const { return unplaced_; }  // USBL fixes without ship fixes and headings around their stamps
  long late() const { return queue_.late(); }
  // [rad^2] the latest AHRS message's roll, pitch and yaw variances (NaN where it gave none).
  const Eigen::Vector3d& attitudeVariance() const { return attitude_variance_; }
  size_t held() const { return queue_.held() + usbl_.size(); }
  // [s] how far the newest stamp is ahead of `now` (large: the stamps and the clock are not the same clock).
  double ahead(const ros::Time& now) const;

private:
  double timeOf(const ros::Time& stamp);
  std::string sample(const ros::Time& stamp, double value, const char* field, double low, double high, const char* unit,
                     double SurveyMeasurement::*member);
  static void remember(std::deque<Eigen::Vector3d>& history, const Eigen::Vector3d& entry);
  void placeUsbl(double cutoff);
  struct PendingUsbl
  {
    double t;             // [s] its stamp, after the epoch
    Eigen::Vector3d p_S;  // [m] the fish in the ship frame
  };
  std::string refuse(const std::string& why);
  bool shipAt(double t, Eigen::Vector2d& p, double& yaw) const;

  SurveyRowSettings settings_;
  SurveyRowQueue queue_;
  std::unique_ptr<GeographicLib::LocalCartesian> origin_;
  ros::Time epoch_;
  bool has_epoch_ = false;
  double newest_ = -std::numeric_limits<double>::infinity();  // the newest stamp's t
  std::vector<PendingUsbl> usbl_;                             // USBL fixes whose rows are not yet due
  std::deque<Eigen::Vector3d> fixes_, headings_;  // (t, x, y) and (t, yaw, 0) of the last minute, for the USBL
  long refused_ = 0, unplaced_ = 0;
  Eigen::Vector3d attitude_variance_ = Eigen::Vector3d::Constant(NAN);
};

}  // namespace tow_sim
