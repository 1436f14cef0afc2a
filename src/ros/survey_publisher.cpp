#include "tow_sim/ros/survey_publisher.h"

#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/Range.h>
#include <GeographicLib/LocalCartesian.hpp>

#include <Eigen/Geometry>
#include <cmath>

#include "tow_sim/SensorValue.h"
#include "tow_sim/core/attitude.h"
#include "tow_sim/ros/conversions.h"

namespace tow_sim
{
namespace
{
constexpr double kAtmosphere = 101325.0;  // [Pa] at the surface

tow_sim::SensorValue value(const std_msgs::Header& header, double v, double sigma)
{
  tow_sim::SensorValue m;
  m.header = header;
  m.value = v;
  m.variance = sigma * sigma;
  return m;
}

// The ship's GNSS fix as latitude, longitude and altitude about the origin, its noise as a known diagonal.
sensor_msgs::NavSatFix toFix(const std_msgs::Header& header, const SurveyMeasurement& m, double noise,
                             const GeographicLib::LocalCartesian& origin)
{
  sensor_msgs::NavSatFix fix;
  fix.header = header;
  fix.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
  fix.status.service = sensor_msgs::NavSatStatus::SERVICE_GPS;
  origin.Reverse(m.ship_x, m.ship_y, 0.0, fix.latitude, fix.longitude, fix.altitude);
  const double variance = noise * noise;
  fix.position_covariance = { variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance };
  fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
  return fix;
}

// The fish's AHRS: REP-103 orientation, yaw about z, then pitch about the body's y (positive nose down), then
// roll about its x (positive starboard down); no rates or accelerations (their covariances' first element -1).
sensor_msgs::Imu toImu(const std_msgs::Header& header, const SurveyMeasurement& m, const SurveySensorParams& params)
{
  sensor_msgs::Imu imu;
  imu.header = header;
  const double roll = std::isfinite(m.fish_roll) ? m.fish_roll : 0.0;
  imu.orientation = ros_conv::toQuaternion(Eigen::Quaterniond(rotationFromEuler(roll, m.fish_pitch, m.fish_heading)));
  const double roll_var = std::pow(params.ahrs_roll_noise, 2), pitch = std::pow(params.ahrs_pitch_noise, 2),
               yaw = std::pow(params.ahrs.noise, 2);
  imu.orientation_covariance = { roll_var, 0.0, 0.0, 0.0, pitch, 0.0, 0.0, 0.0, yaw };
  imu.angular_velocity_covariance[0] = -1.0;
  imu.linear_acceleration_covariance[0] = -1.0;
  return imu;
}

sensor_msgs::Range toRange(const std_msgs::Header& header, double altitude)
{
  sensor_msgs::Range r;
  r.header = header;
  r.radiation_type = sensor_msgs::Range::ULTRASOUND;
  r.field_of_view = 0.1f;
  r.min_range = 0.0f;
  r.max_range = 1000.0f;
  r.range = static_cast<float>(altitude);
  return r;
}

}  // namespace

SurveyPublisher::SurveyPublisher(ros::NodeHandle nh, const SurveySensorParams& params, const std::string& world_frame,
                                 const std::string& vehicle_frame, double water_density, double gravity,
                                 const std::string& prefix)
    : params_(params), world_frame_(world_frame), vehicle_frame_(vehicle_frame), rho_g_(water_density * gravity)
{
  validate(params_, prefix + "sensors");
  reset();
  origin_ = std::make_unique<GeographicLib::LocalCartesian>(params_.origin_latitude, params_.origin_longitude,
                                                            params_.origin_altitude);
  fix_ = nh.advertise<sensor_msgs::NavSatFix>("survey/ship/fix", 10);
  heading_ = nh.advertise<geometry_msgs::QuaternionStamped>("survey/ship/heading", 20);
  cable_out_ = nh.advertise<tow_sim::SensorValue>("survey/cable_out", 10);
  tension_ = nh.advertise<tow_sim::SensorValue>("survey/tension", 20);
  pressure_ = nh.advertise<sensor_msgs::FluidPressure>("survey/fish/pressure", 10);
  depth_ = nh.advertise<tow_sim::SensorValue>("survey/fish/depth", 10);
  imu_ = nh.advertise<sensor_msgs::Imu>("survey/fish/imu", 20);
  altitude_ = nh.advertise<sensor_msgs::Range>("survey/fish/altitude", 10);
  usbl_ = nh.advertise<geometry_msgs::PointStamped>("survey/usbl", 10);
}

SurveyPublisher::~SurveyPublisher() = default;

void SurveyPublisher::reset()
{
  sensors_ = std::make_unique<SurveySensors>(params_, SurveySensors::Output::kSamples);
}

void SurveyPublisher::publish(const TowSnapshot& s, const std::function<ros::Time(double)>& stamp)
{
  sensors_->observe(s);
  for (const SensorSample& sample : sensors_->takeSamples(s.t))
    send(sample, stamp(sample.measured));
}

void SurveyPublisher::send(const SensorSample& sample, const ros::Time& measured)
{
  const SurveyMeasurement& m = sample.values;
  std_msgs::Header header;
  header.stamp = measured;
  header.frame_id = vehicle_frame_;
  std_msgs::Header in_ship = header;
  in_ship.frame_id = params_.ship_frame;
  switch (sample.kind)
  {
    case SensorKind::kGnss:
      fix_.publish(toFix(in_ship, m, params_.gnss.noise, *origin_));
      break;
    case SensorKind::kHeading:
    {
      geometry_msgs::QuaternionStamped q;
      q.header = header;
      q.header.frame_id = world_frame_;
      q.quaternion =
          ros_conv::toQuaternion(Eigen::Quaterniond(Eigen::AngleAxisd(m.ship_heading, Eigen::Vector3d::UnitZ())));
      heading_.publish(q);
      break;
    }
    case SensorKind::kCableCounter:
      cable_out_.publish(value(header, m.cable_out, params_.cable_counter.noise));
      break;
    case SensorKind::kLoadCell:
      tension_.publish(value(header, m.tension, params_.load_cell.noise));
      break;
    case SensorKind::kDepth:
    {
      depth_.publish(value(header, m.fish_depth, params_.depth.noise));
      sensor_msgs::FluidPressure p;
      p.header = header;
      p.fluid_pressure = kAtmosphere + rho_g_ * m.fish_depth;
      p.variance = std::pow(rho_g_ * params_.depth.noise, 2);
      pressure_.publish(p);
      break;
    }
    case SensorKind::kAhrs:
      imu_.publish(toImu(header, m, params_));
      break;
    case SensorKind::kAltimeter:
      altitude_.publish(toRange(header, m.fish_altitude));
      break;
    case SensorKind::kUsbl:
    {
      geometry_msgs::PointStamped p;
      p.header = in_ship;
      p.point.x = sample.usbl_S.x();
      p.point.y = sample.usbl_S.y();
      p.point.z = sample.usbl_S.z();
      usbl_.publish(p);
      break;
    }
  }
}

}  // namespace tow_sim
