// Small geometry helpers shared by the core.
#pragma once

#include <Eigen/Core>

namespace tow_sim
{
// [r x], the matrix with [r x] v = r x v.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& r)
{
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

}  // namespace tow_sim
