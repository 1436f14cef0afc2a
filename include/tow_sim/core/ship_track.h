// Tow-point motion rebuilt from timestamped samples (e.g. ship odometry), with continuous position,
// velocity and acceleration (physics.md §7): quintic Hermite pieces between samples, the knot
// accelerations taken from the velocities on either side. A reported velocity that the positions
// around it contradict (by more than 0.5 m/s + 20 %) is replaced by the one the positions give, so a
// zero or stale twist cannot make the track swing. Past the newest sample it extrapolates with
// constant acceleration for at most `max_extrapolation`, then holds that state.
#pragma once

#include <Eigen/Core>
#include <deque>

#include "tow_sim/core/chain_model.h"

namespace tow_sim
{
class ShipTrack
{
public:
  explicit ShipTrack(double max_extrapolation = 1.0, size_t capacity = 400);

  // Adds a sample of the tow point at time t [s]: position [m] and velocity [m/s], world. Returns false
  // and keeps the track unchanged unless t is later than the newest sample and all values are finite.
  bool add(double t, const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W);

  ShipEndState operator()(double t) const;
  bool empty() const { return samples_.empty(); }
  double newestTime() const;
  double oldestTime() const;
  double maxExtrapolation() const { return max_extrapolation_; }
  void clear() { samples_.clear(); }
  // Forgets the samples no longer needed to evaluate the track at t or later (the one at or before t
  // stays), so a caller that moves forward in time keeps a short history, whatever the sample rate.
  void dropBefore(double t);

private:
  struct Sample
  {
    double t;
    Eigen::Vector3d p, v_reported, v, a;  // v: the velocity used (reported, or from the positions)
  };
  static constexpr double kVelocityTolerance = 0.5;          // [m/s]
  static constexpr double kVelocityRelativeTolerance = 0.2;  // [-]
  Eigen::Vector3d differenceVelocity(size_t i) const;
  void updateVelocity(size_t i);
  void updateAcceleration(size_t i);

  double max_extrapolation_;
  size_t capacity_;
  std::deque<Sample> samples_;
};

}  // namespace tow_sim
