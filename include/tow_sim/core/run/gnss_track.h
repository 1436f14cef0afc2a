// A survey vessel's GNSS as ship odometry: antenna fixes (already in the local ENU world frame) and the
// heading, one pair at a time, become the ship frame's pose and velocity (docs/own_ship.md). The antenna's
// lever arm is taken out with the heading, then an alpha-beta tracker (Benedict-Bordner gains from a
// smoothing time) smooths the position and gives the velocity, and another the heading and its rate:
// tow_sim_node needs a velocity, and a GNSS receiver gives positions a few centimetres to metres apart
// from the truth at 1-10 Hz.
//
//   predicted   x' = x + v dt            residual r = z - x'
//   updated     x = x' + alpha r         v = v + (beta / dt) r
//   alpha = 1 - exp(-dt / smoothing_time),   beta = alpha^2 / (2 - alpha)
//
// A constant velocity is followed without lag; a constant acceleration a with the steady lag
// a dt^2 (1 - alpha) / beta (docs/own_ship.md). No ROS here: the node (gnss_ship_node) converts latitude,
// longitude and altitude to the ENU frame about the geodetic origin.
#pragma once

#include <Eigen/Core>

#include <string>

namespace tow_sim
{
struct GnssTrackParams
{
  Eigen::Vector3d antenna_S = Eigen::Vector3d::Zero();  // [m] the antenna in the ship frame (FLU)
  double smoothing_time = 2.0;                          // [s] the trackers' time constant; 0: no smoothing
  bool use_altitude = false;  // the ship's z from the fixes' altitude; else the ship is on z = 0
};
// Throws std::invalid_argument naming PREFIX.antenna / PREFIX.smoothing_time and the range.
void validate(const GnssTrackParams& params, const std::string& prefix);

struct GnssFix
{
  double t = 0.0;                                       // [s] the fix's stamp
  Eigen::Vector3d antenna_W = Eigen::Vector3d::Zero();  // [m] the antenna, ENU about the origin
  double yaw = 0.0;  // [rad] the ship's heading from +x (east) toward +y (north), REP-103
};

struct ShipEstimate
{
  double t = 0.0;                                 // [s]
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // [m] the ship frame's origin, world
  double yaw = 0.0;                               // [rad] unwrapped (continuous through +-pi)
  Eigen::Vector3d v_S = Eigen::Vector3d::Zero();  // [m/s] the ship frame's velocity in ship axes (REP-105)
  double yaw_rate = 0.0;                          // [rad/s]
};

class GnssTrack
{
public:
  explicit GnssTrack(const GnssTrackParams& params);

  // The estimate after this fix. The first fix starts the track at rest; a fix not later than the
  // previous one throws std::invalid_argument (the track is unchanged).
  ShipEstimate update(const GnssFix& fix);
  bool started() const { return started_; }
  void reset() { started_ = false; }

  // The tracker's gains for a fix dt after the previous one.
  static void gains(double dt, double smoothing_time, double& alpha, double& beta);

private:
  GnssTrackParams params_;
  bool started_ = false;
  double t_ = 0.0;
  Eigen::Vector3d p_W_ = Eigen::Vector3d::Zero(), v_W_ = Eigen::Vector3d::Zero();
  double yaw_ = 0.0, yaw_rate_ = 0.0;
};

}  // namespace tow_sim
