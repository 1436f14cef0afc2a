// REP-103 attitude as Z-Y-X Euler angles: yaw about the world's z, then pitch about the body's y (nose down
// positive), then roll about its x (starboard side down positive). One definition of the rotation and of the
// way back, for the ship's motion, the survey AHRS and every adapter that reads or writes an orientation.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace tow_sim
{
struct EulerAngles
{
  double roll = 0.0;   // [rad] about x_b, starboard down positive
  double pitch = 0.0;  // [rad] about y_b, nose down positive
  double yaw = 0.0;    // [rad] about z (up), from east, counter-clockwise
};

// R_WB = Rz(yaw) Ry(pitch) Rx(roll). As matrices, not quaternions: with roll = pitch = 0 this is exactly the
// heading's rotation.
inline Eigen::Matrix3d rotationFromEuler(double roll, double pitch, double yaw)
{
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix() *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

// The angles of R_WB = Rz(yaw) Ry(pitch) Rx(roll): yaw = atan2(R10, R00), pitch = asin(-R20),
// roll = atan2(R21, R22); pitch in [-pi/2, pi/2].
inline EulerAngles eulerOf(const Eigen::Matrix3d& R_WB)
{
  EulerAngles e;
  e.yaw = std::atan2(R_WB(1, 0), R_WB(0, 0));
  e.pitch = std::asin(std::clamp(-R_WB(2, 0), -1.0, 1.0));
  e.roll = std::atan2(R_WB(2, 1), R_WB(2, 2));
  return e;
}

}  // namespace tow_sim
