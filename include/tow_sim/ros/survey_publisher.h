// tow_sim_node's simulated survey sensors (docs/survey.md, "In tow_sim_node"): the run's published outputs sampled
// by SurveySensors (core/survey/survey_sensors.h) and each sample sent as the message a survey vessel's sensor
// sends, stamped with the instant it measures and sent when it arrives (a sensor's latency later):
//
//   survey/ship/fix        sensor_msgs/NavSatFix           the ship's reference point, WGS84 about the origin
//   survey/ship/heading    geometry_msgs/QuaternionStamped the ship's heading (yaw from east, REP-103), world frame
//   survey/cable_out       tow_sim/SensorValue             [m] the winch's counter
//   survey/tension         tow_sim/SensorValue             [N] the tow point's load cell
//   survey/fish/pressure   sensor_msgs/FluidPressure       [Pa] absolute: 101325 + rho g depth
//   survey/fish/depth      tow_sim/SensorValue             [m] positive down
//   survey/fish/imu        sensor_msgs/Imu                 orientation only (yaw and pitch; roll 0), vehicle frame
//   survey/fish/altitude   sensor_msgs/Range               [m] above the seabed (with a seabed)
//   survey/usbl            geometry_msgs/PointStamped      [m] the fish in the ship frame (FLU) at its instant
#pragma once

#include <ros/ros.h>

#include <functional>
#include <memory>
#include <string>

#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/core/survey/survey_sensors.h"

namespace GeographicLib
{
class LocalCartesian;
}

namespace tow_sim
{
class SurveyPublisher
{
public:
  // Validates params (std::invalid_argument naming "<prefix>sensors.<key>").
  SurveyPublisher(ros::NodeHandle nh, const SurveySensorParams& params, const std::string& world_frame,
                  const std::string& vehicle_frame, double water_density, double gravity, const std::string& prefix);
  ~SurveyPublisher();

  // A published snapshot of the run (in time order): every sample due since the previous one, sent once it has
  // arrived by the snapshot's time. `stamp` turns the run's time [s] into a ROS time.
  void publish(const TowSnapshot& s, const std::function<ros::Time(double)>& stamp);
  // A new run or time axis: the sensors start again (their seeds too).
  void reset();

private:
  void send(const SensorSample& sample, const ros::Time& measured);

  SurveySensorParams params_;
  std::string world_frame_, vehicle_frame_;
  double rho_g_;  // [Pa/m] water density times gravity
  std::unique_ptr<SurveySensors> sensors_;
  std::unique_ptr<GeographicLib::LocalCartesian> origin_;
  ros::Publisher fix_, heading_, cable_out_, tension_, pressure_, depth_, imu_, altitude_, usbl_;
};

}  // namespace tow_sim
