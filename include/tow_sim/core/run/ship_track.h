// Tow-point motion rebuilt from timestamped samples (e.g. ship odometry), with continuous position,
// velocity and acceleration (physics.md §7): quintic Hermite pieces between samples, the knot
// accelerations taken from the velocities on either side. A reported velocity that the positions
// around it contradict (by more than 0.5 m/s + 20 %) is replaced by the one the positions give, so a
// zero or stale twist cannot make the track swing; such a velocity from jittery positions is clamped to
// `max_speed` (the node's max_ship_speed). Past the newest sample it extrapolates with
// constant acceleration for at most `max_extrapolation`, then holds that state.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <limits>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
class ShipTrack
{
public:
  // max_speed [m/s] bounds a velocity taken from the positions (> 0; infinity: none).
  explicit ShipTrack(double max_extrapolation = 1.0, size_t capacity = 400,
                     double max_speed = std::numeric_limits<double>::infinity());

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
  double max_speed_;
  std::deque<Sample> samples_;
};

// The ship's own pose and its speed at one time (its reference point, not the tow point).
struct ShipPose
{
  double x = 0.0, y = 0.0;  // [m] world
  double heading = 0.0;     // [rad] ENU, counter-clockwise from +x
  double speed = 0.0;       // [m/s] over ground
  double z = 0.0;           // [m] heave (world z of the reference point)
  double roll = 0.0;        // [rad] REP-103, about x (positive: port side up)
  double pitch = 0.0;       // [rad] about y (positive: bow down)
};

// What a tow run knows of the ship: the tow point's motion (a ShipTrack) and the ship's pose, from
// timestamped samples: ship odometry as it arrives, or a scripted path sampled in advance.
class ShipHistory
{
public:
  explicit ShipHistory(double max_extrapolation = 1.0, size_t capacity = 400,
                       double max_speed = std::numeric_limits<double>::infinity());

  // Adds a sample at time t [s]: the tow point's position [m] and velocity [m/s] (world) and the ship's
  // pose. Returns false and changes nothing unless the ShipTrack takes it (later than the newest, finite).
  bool add(double t, const Eigen::Vector3d& tow_p_W, const Eigen::Vector3d& tow_v_W, const ShipPose& pose);

  ShipEndState towPoint(double t) const { return track_(t); }
  // The pose at time t: position and heading linear between samples (the heading unwrapped, so it turns
  // the short way), the speed of the first sample after t; the first or the newest pose beyond them.
  ShipPose pose(double t) const;
  const ShipTrack& track() const { return track_; }

  bool empty() const { return track_.empty(); }
  double newestTime() const { return track_.newestTime(); }
  double oldestTime() const { return track_.oldestTime(); }
  void clear();
  void dropBefore(double t);  // as ShipTrack::dropBefore

private:
  ShipTrack track_;
  std::deque<double> times_;
  std::deque<ShipPose> poses_;
};

}  // namespace tow_sim
