// Mathematical constants and the attitude formulas shared by the core, the adapters and the tools: one
// definition of each.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace tow_sim
{
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kHalfPi = 0.5 * kPi;
inline constexpr double kTwoPi = 2.0 * kPi;
inline constexpr double kDegree = kPi / 180.0;  // [rad] one degree

// REP-103 attitude of a body from its axes in the world (ENU): pitch nose down positive from the x (forward)
// axis, yaw from the y (port) axis, so that both stay defined when the body points straight up or down.
inline double pitchOf(const Eigen::Vector3d& x_axis_W)
{
  return -std::asin(std::clamp(x_axis_W.z(), -1.0, 1.0));
}
inline double yawOf(const Eigen::Vector3d& y_axis_W)
{
  return std::atan2(-y_axis_W.x(), y_axis_W.y());
}

}  // namespace tow_sim
