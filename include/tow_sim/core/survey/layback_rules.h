// The rules survey software places a towfish by (docs/survey.md, "Baselines"), from the tow point's track, the
// cable out and the fish's depth, with no cable model:
//
//   Pythagoras       layback l = sqrt(L^2 - D^2), the fish l behind the tow point along the ship's heading
//   follow-the-dog   the same l, but measured back along the tow point's own track (the fish follows the ship)
//   catenary factor  l = k sqrt(L^2 - D^2) along the heading (k < 1 for the cable's sag; k = 1 is Pythagoras)
//
// L the cable out, D the fish's depth below the tow point (its depth plus the tow point's height).
#pragma once

#include <Eigen/Core>
#include <deque>

namespace tow_sim
{
struct LaybackFixes
{
  double layback = 0.0;                                  // [m] sqrt(L^2 - D^2) (0 when D >= L)
  Eigen::Vector2d pythagoras = Eigen::Vector2d::Zero();  // [m] world ENU
  Eigen::Vector2d track = Eigen::Vector2d::Zero();
  Eigen::Vector2d catenary = Eigen::Vector2d::Zero();
};

class LaybackRules
{
public:
  // tow_point_S: the tow point in the ship frame (FLU) [m]; catenary_factor in (0, 1] (std::invalid_argument
  // otherwise); the track is kept for `memory` metres behind the tow point (> 0; at least the longest cable out).
  LaybackRules(const Eigen::Vector3d& tow_point_S, double catenary_factor, double memory = 20000.0);

  // The ship's reference point [m] and heading [rad] (ENU) at a time; the tow point's track grows by it (a point
  // within 1 m of the one before the newest replaces the newest, so that a fix's noise does not lengthen it).
  void addShip(double x, double y, double heading);
  bool hasShip() const { return !track_.empty(); }
  // The three fixes for a cable out L [m] and the fish's depth [m] (std::logic_error before addShip).
  LaybackFixes at(double cable_out, double depth) const;
  // The point `distance` [m] back along the tow point's track from its newest point; past the oldest point,
  // on along the track's oldest piece (or against the heading when the track has no piece).
  Eigen::Vector2d backAlongTrack(double distance) const;

private:
  Eigen::Vector3d tow_point_S_;
  double catenary_factor_, memory_;
  std::deque<Eigen::Vector2d> track_;  // the tow point, newest first
  double heading_ = 0.0;
  double track_length_ = 0.0;
};

}  // namespace tow_sim
