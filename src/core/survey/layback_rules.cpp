#include "tow_sim/core/survey/layback_rules.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tow_sim
{
LaybackRules::LaybackRules(const Eigen::Vector3d& tow_point_S, double catenary_factor, double memory)
    : tow_point_S_(tow_point_S), catenary_factor_(catenary_factor), memory_(memory)
{
  if (!(catenary_factor > 0.0 && catenary_factor <= 1.0))
    throw std::invalid_argument("catenary_factor: " + std::to_string(catenary_factor) + " must be in (0, 1]");
  if (!(memory > 0.0))
    throw std::invalid_argument("track memory: " + std::to_string(memory) + " m must be > 0");
}

void LaybackRules::addShip(double x, double y, double heading)
{
  const double c = std::cos(heading), s = std::sin(heading);
  const Eigen::Vector2d tow(x + c * tow_point_S_.x() - s * tow_point_S_.y(),
                            y + s * tow_point_S_.x() + c * tow_point_S_.y());
  heading_ = heading;
  // Points closer than 1 m to the one before the newest replace the newest: the track's length is not made of the
  // fixes' noise, and a ship at rest keeps the older point, which holds the direction of travel.
  if (track_.size() >= 2 && (tow - track_[1]).norm() < 1.0)
  {
    track_length_ += (tow - track_[1]).norm() - (track_[0] - track_[1]).norm();
    track_.front() = tow;
    return;
  }
  if (!track_.empty())
    track_length_ += (tow - track_.front()).norm();
  track_.push_front(tow);
  while (track_.size() > 2 && track_length_ - (track_[track_.size() - 2] - track_.back()).norm() > memory_)
  {
    track_length_ -= (track_[track_.size() - 2] - track_.back()).norm();
    track_.pop_back();
  }
}

Eigen::Vector2d LaybackRules::backAlongTrack(double distance) const
{
  if (track_.empty())
    throw std::logic_error("LaybackRules: no ship position yet");
  double left = distance;
  for (size_t i = 0; i + 1 < track_.size(); ++i)
  {
    const Eigen::Vector2d piece = track_[i + 1] - track_[i];
    const double length = piece.norm();
    if (length < 1e-9)  // the newest point back on the one before it
      continue;
    if (left <= length || i + 2 == track_.size())
      return track_[i] + piece * (left / length);
    left -= length;
  }
  return track_.back() - left * Eigen::Vector2d(std::cos(heading_), std::sin(heading_));
}

LaybackFixes LaybackRules::at(double cable_out, double depth) const
{
  if (track_.empty())
    throw std::logic_error("LaybackRules: no ship position yet");
  const double below = depth + tow_point_S_.z();  // the fish below the tow point (a ship on z = 0)
  LaybackFixes f;
  f.layback = std::sqrt(std::max(0.0, cable_out * cable_out - below * below));
  const Eigen::Vector2d ahead(std::cos(heading_), std::sin(heading_));
  f.pythagoras = track_.front() - f.layback * ahead;
  f.catenary = track_.front() - catenary_factor_ * f.layback * ahead;
  f.track = backAlongTrack(f.layback);
  return f;
}

}  // namespace tow_sim
