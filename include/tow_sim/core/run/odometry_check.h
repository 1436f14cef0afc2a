// Validation of ship odometry before it reaches the ShipTrack (ROS-free, so it can be tested and
// fuzzed without roscore). The node converts nav_msgs/Odometry into OdometryInput.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "tow_sim/core/run/ship_track.h"

namespace tow_sim
{
struct OdometryInput
{
  double t = 0.0;                                        // [s] stamp, on the ShipTrack's time axis
  std::string frame_id;                                  // header.frame_id
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();         // [m] ship position, world
  Eigen::Vector4d q_wxyz = Eigen::Vector4d(1, 0, 0, 0);  // orientation as sent (not necessarily unit)
  Eigen::Vector3d v_S = Eigen::Vector3d::Zero();         // [m/s] linear velocity, ship frame (REP-105)
  Eigen::Vector3d w_S = Eigen::Vector3d::Zero();         // [rad/s] angular velocity, ship frame
};

struct OdometryLimits
{
  std::string world_frame = "odom";
  Eigen::Vector3d tow_point_S = Eigen::Vector3d(-20.0, 0.0, 0.0);  // [m]
  double max_ship_speed = 25.0;                                    // [m/s] of the tow point, and for jumps
  double max_future = 1.0;                                         // [s] stamps later than now + this are refused
  double max_age = 10.0;         // [s] stamps earlier than now - this are refused (a publisher on another clock)
  double max_jump_slack = 10.0;  // [m] a sample may land this far from the extrapolated track, plus speed x dt
  double max_position = 1e7;     // [m] each position component within +-this (joints 1e-9 m apart in double)
};

struct OdometryResult
{
  bool accepted = false;
  bool jumped = false;  // refused only because it is too far from the track (see TrackReacquisition)
  std::string reason;   // why not, naming the field
  Eigen::Vector3d tow_p_W = Eigen::Vector3d::Zero(), tow_v_W = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_WS = Eigen::Quaterniond::Identity();  // normalised
};

// Checks frame, finiteness, position within max_position, unit quaternion (norm within 0.01 of 1; normalised), order of
// stamps against the track (no duplicates or reordering), stamps from the future or the far past, speed and jumps;
// gives the tow point's position and velocity for an accepted sample. Never throws.
OdometryResult checkOdometry(const OdometryInput& in, const OdometryLimits& limits, const ShipTrack& track, double now);

// When the track itself is wrong (a GPS driver's (0, 0, 0) before its fix, a ship teleported by a
// simulator reset), every later message is refused as a jump. This counts such refusals: when `needed`
// of them in a row are consistent with each other (each within max_ship_speed x dt + max_jump_slack of
// the one before), the ship is elsewhere for good and the track should be dropped and started again
// from the last of them. Any accepted message, or one refused for another reason, starts the count anew.
class TrackReacquisition
{
public:
  explicit TrackReacquisition(int needed) : needed_(needed) {}

  // A message refused as a jump, its stamp t and tow point: true when it completes `needed` in a row (the
  // count then starts anew).
  bool jumped(double t, const Eigen::Vector3d& tow_p_W, const OdometryLimits& limits);
  void reset() { count_ = 0; }
  int count() const { return count_; }

private:
  int needed_;
  int count_ = 0;
  double last_t_ = 0.0;
  Eigen::Vector3d last_p_ = Eigen::Vector3d::Zero();
};

}  // namespace tow_sim
