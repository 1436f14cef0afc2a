#include "tow_sim/core/run/track_trail.h"

#include <stdexcept>

namespace tow_sim
{
TrackTrail::TrackTrail(double duration, double spacing, std::size_t max_points)
    : duration_(duration), spacing_(spacing), max_points_(max_points)
{
  if (!(duration > 0.0) || !(spacing > 0.0) || max_points < 2)
    throw std::invalid_argument("TrackTrail: duration and spacing must be > 0, max_points >= 2");
}

void TrackTrail::add(double t, const Eigen::Vector3d& p)
{
  if (t < last_t_)
    samples_.clear();
  last_t_ = t;
  if (samples_.empty() || (p - samples_.back().p).norm() >= spacing_)
    samples_.push_back({ t, p });
  while (!samples_.empty() && (samples_.front().t < t - duration_ || samples_.size() > max_points_))
    samples_.pop_front();
}

}  // namespace tow_sim
