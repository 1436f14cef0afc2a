// The recent track of a point (the ship, the vehicle) for drawing: samples at least `spacing` apart over
// the last `duration` seconds, at most `max_points` of them (the oldest dropped first).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <deque>
#include <limits>

namespace tow_sim
{
class TrackTrail
{
public:
  struct Sample
  {
    double t;
    Eigen::Vector3d p;
  };

  // duration [s] > 0, spacing [m] > 0, max_points >= 2.
  TrackTrail(double duration, double spacing = 1.0, std::size_t max_points = 5000);

  // A new position at time t: kept if it is at least `spacing` from the last kept one; samples older
  // than t - duration are dropped; a time going back (a restart, a clock jump) starts the trail afresh.
  void add(double t, const Eigen::Vector3d& p);
  void clear()
  {
    samples_.clear();
    last_t_ = -std::numeric_limits<double>::infinity();
  }
  const std::deque<Sample>& samples() const { return samples_; }

private:
  double duration_, spacing_;
  std::size_t max_points_;
  std::deque<Sample> samples_;
  double last_t_ = -std::numeric_limits<double>::infinity();  // of the last add()
};

}  // namespace tow_sim
