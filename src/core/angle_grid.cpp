#include "tow_sim/core/angle_grid.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/constants.h"

namespace tow_sim
{
AngleGrid::AngleGrid(std::vector<double> angles, const std::string& name) : angles_(std::move(angles))
{
  std::ostringstream problem;
  if (!angles_.empty() && std::abs(angles_.back() - kHalfPi) <= 1e-4)
    angles_.back() = kHalfPi;  // before the order is checked
  if (angles_.size() < 2)
    problem << "angles needs at least 2 points, from 0 to pi/2 [rad]; got " << angles_.size();
  for (size_t i = 0; problem.str().empty() && i < angles_.size(); ++i)
  {
    if (!std::isfinite(angles_[i]))
      problem << "angles[" << i << "] = " << angles_[i] << " must be finite";
    else if (i > 0 && !(angles_[i] > angles_[i - 1]))
      problem << "angles must increase strictly; angles[" << i << "] = " << angles_[i] << " [rad] follows "
              << angles_[i - 1];
  }
  if (problem.str().empty() && (angles_.front() != 0.0 || angles_.back() != kHalfPi))
    problem << "angles must run from 0 to pi/2 = 1.5707963 [rad] (within 1e-4); got " << angles_.front() << " .. "
            << angles_.back();
  if (!problem.str().empty())
    throw std::invalid_argument(name + ": " + problem.str());
}

AngleGrid::Place AngleGrid::locate(double phi) const
{
  phi = std::clamp(phi, 0.0, kHalfPi);
  const size_t upper = static_cast<size_t>(std::upper_bound(angles_.begin(), angles_.end(), phi) - angles_.begin());
  Place p;
  p.i = std::clamp<size_t>(upper, 1, angles_.size() - 1);
  p.width = angles_[p.i] - angles_[p.i - 1];
  p.w = (phi - angles_[p.i - 1]) / p.width;
  return p;
}

}  // namespace tow_sim
