#include "tow_sim/core/run/ship_track.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
}  // namespace

ShipTrack::ShipTrack(double max_extrapolation, size_t capacity, double max_speed)
    : max_extrapolation_(max_extrapolation), capacity_(std::max<size_t>(capacity, 3)), max_speed_(max_speed)
{
  if (!(max_extrapolation >= 0.0 && max_extrapolation <= 60.0))
    throw std::invalid_argument("max_extrapolation must be in [0, 60] [s]");
  if (!(max_speed > 0.0))
    throw std::invalid_argument("max_speed must be > 0 [m/s]");
}

double ShipTrack::newestTime() const
{
  return samples_.empty() ? 0.0 : samples_.back().t;
}
double ShipTrack::oldestTime() const
{
  return samples_.empty() ? 0.0 : samples_.front().t;
}

Eigen::Vector3d ShipTrack::differenceVelocity(size_t i) const
{
  const size_t lo = i > 0 ? i - 1 : i, hi = i + 1 < samples_.size() ? i + 1 : i;
  return (samples_[hi].p - samples_[lo].p) / (samples_[hi].t - samples_[lo].t);
}

void ShipTrack::updateVelocity(size_t i)
{
  // Trust the reported velocity only where the positions agree with it: publishers that send a zero
  // or stale twist, or a burst of stale positions, would otherwise make the interpolant swing back
  // and forth between samples with violent accelerations.
  Sample& s = samples_[i];
  Eigen::Vector3d from_positions = differenceVelocity(i);
  const double tolerance = kVelocityTolerance + kVelocityRelativeTolerance * from_positions.norm();
  if ((s.v_reported - from_positions).norm() <= tolerance)
  {
    s.v = s.v_reported;
    return;
  }
  const double speed = from_positions.norm();
  if (speed > max_speed_)
    from_positions *= max_speed_ / speed;  // jitter between close samples: no faster than a ship goes
  s.v = from_positions;
}

void ShipTrack::updateAcceleration(size_t i)
{
  Sample& s = samples_[i];
  if (samples_.size() < 2)
    s.a.setZero();
  else if (i == 0)
    s.a = (samples_[1].v - s.v) / (samples_[1].t - s.t);
  else if (i + 1 == samples_.size())
    s.a = (s.v - samples_[i - 1].v) / (s.t - samples_[i - 1].t);
  else
    s.a = (samples_[i + 1].v - samples_[i - 1].v) / (samples_[i + 1].t - samples_[i - 1].t);
}

bool ShipTrack::add(double t, const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W)
{
  if (!std::isfinite(t) || !p_W.allFinite() || !v_W.allFinite())
    return false;
  if (!samples_.empty() && !(t > samples_.back().t))
    return false;
  samples_.push_back(Sample{ t, p_W, v_W, v_W, Eigen::Vector3d::Zero() });
  if (samples_.size() > capacity_)
    samples_.pop_front();
  const size_t n = samples_.size();
  if (n < 2)
    return true;
  // The new sample changes the velocity check of itself and its predecessor, and the accelerations
  // of the three newest samples.
  updateVelocity(n - 1);
  updateVelocity(n - 2);
  for (size_t k = n >= 3 ? n - 3 : 0; k < n; ++k)
    updateAcceleration(k);
  return true;
}

void ShipTrack::dropBefore(double t)
{
  while (samples_.size() > 2 && samples_[1].t <= t)
    samples_.pop_front();
}

ShipEndState ShipTrack::operator()(double t) const
{
  ShipEndState out;
  if (samples_.empty())
    return out;
  const Sample& last = samples_.back();
  if (t >= last.t)
  {
    const double tau = std::min(t - last.t, max_extrapolation_);
    out.p_W = last.p + last.v * tau + 0.5 * last.a * tau * tau;
    out.v_W = last.v + last.a * tau;
    out.a_W = t - last.t <= max_extrapolation_ ? last.a : Eigen::Vector3d::Zero();
    return out;
  }
  if (t <= samples_.front().t)
  {
    const Sample& first = samples_.front();
    out.p_W = first.p + first.v * (t - first.t);
    out.v_W = first.v;
    return out;
  }
  const auto upper =
      std::upper_bound(samples_.begin(), samples_.end(), t, [](double value, const Sample& s) { return value < s.t; });
  const Sample& s1 = *upper;
  const Sample& s0 = *(upper - 1);
  // Quintic Hermite on [0, 1] matching p, v, a at both ends (C2 across samples).
  const double h = s1.t - s0.t;
  const double x = (t - s0.t) / h, x2 = x * x, x3 = x2 * x, x4 = x3 * x, x5 = x4 * x;
  const double h00 = 1 - 10 * x3 + 15 * x4 - 6 * x5, h10 = x - 6 * x3 + 8 * x4 - 3 * x5,
               h20 = 0.5 * x2 - 1.5 * x3 + 1.5 * x4 - 0.5 * x5, h01 = 10 * x3 - 15 * x4 + 6 * x5,
               h11 = -4 * x3 + 7 * x4 - 3 * x5, h21 = 0.5 * x3 - x4 + 0.5 * x5;
  const double d00 = -30 * x2 + 60 * x3 - 30 * x4, d10 = 1 - 18 * x2 + 32 * x3 - 15 * x4,
               d20 = x - 4.5 * x2 + 6 * x3 - 2.5 * x4, d01 = 30 * x2 - 60 * x3 + 30 * x4,
               d11 = -12 * x2 + 28 * x3 - 15 * x4, d21 = 1.5 * x2 - 4 * x3 + 2.5 * x4;
  const double s00 = -60 * x + 180 * x2 - 120 * x3, s10 = -36 * x + 96 * x2 - 60 * x3,
               s20 = 1 - 9 * x + 18 * x2 - 10 * x3, s01 = 60 * x - 180 * x2 + 120 * x3,
               s11 = -24 * x + 84 * x2 - 60 * x3, s21 = 3 * x - 12 * x2 + 10 * x3;
  const Eigen::Vector3d P0 = s0.p, V0 = s0.v * h, A0 = s0.a * h * h, P1 = s1.p, V1 = s1.v * h, A1 = s1.a * h * h;
  out.p_W = h00 * P0 + h10 * V0 + h20 * A0 + h01 * P1 + h11 * V1 + h21 * A1;
  out.v_W = (d00 * P0 + d10 * V0 + d20 * A0 + d01 * P1 + d11 * V1 + d21 * A1) / h;
  out.a_W = (s00 * P0 + s10 * V0 + s20 * A0 + s01 * P1 + s11 * V1 + s21 * A1) / (h * h);
  return out;
}

ShipHistory::ShipHistory(double max_extrapolation, size_t capacity, double max_speed)
    : track_(max_extrapolation, capacity, max_speed)
{
}

bool ShipHistory::add(double t, const Eigen::Vector3d& tow_p_W, const Eigen::Vector3d& tow_v_W, const ShipPose& pose)
{
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.heading) || !std::isfinite(pose.speed))
    return false;
  if (!track_.add(t, tow_p_W, tow_v_W))
    return false;
  ShipPose p = pose;
  // Unwrap: within half a turn of the previous heading (a continuous heading is kept as it is).
  if (!poses_.empty() && std::abs(p.heading - poses_.back().heading) > kPi)
    p.heading = poses_.back().heading + std::remainder(p.heading - poses_.back().heading, 2.0 * kPi);
  // The track may have dropped its oldest sample to stay within its capacity: keep the poses alongside.
  while (!times_.empty() && times_.front() < track_.oldestTime())
  {
    times_.pop_front();
    poses_.pop_front();
  }
  times_.push_back(t);
  poses_.push_back(p);
  return true;
}

ShipPose ShipHistory::pose(double t) const
{
  if (times_.empty())
    return ShipPose();
  const auto upper = std::upper_bound(times_.begin(), times_.end(), t);
  if (upper == times_.begin())
    return poses_.front();
  // Between samples i - 1 and i, or past the newest: on from the last two at their rates, for at most
  // max_extrapolation (as the tow point's track).
  const bool beyond = upper == times_.end();
  if (beyond && times_.size() < 2)
    return poses_.back();
  const size_t i = beyond ? times_.size() - 1 : static_cast<size_t>(upper - times_.begin());
  const double span = times_[i] - times_[i - 1];
  const double w =
      beyond ? 1.0 + std::min(t - times_[i], track_.maxExtrapolation()) / span : (t - times_[i - 1]) / span;
  const ShipPose &a = poses_[i - 1], &b = poses_[i];
  ShipPose out;
  out.x = (1.0 - w) * a.x + w * b.x;
  out.y = (1.0 - w) * a.y + w * b.y;
  // The shorter way round (headings wrap at +-pi in odometry).
  out.heading = a.heading + w * std::remainder(b.heading - a.heading, 2.0 * kPi);
  out.speed = b.speed;
  out.z = (1.0 - w) * a.z + w * b.z;
  out.roll = a.roll + w * std::remainder(b.roll - a.roll, 2.0 * kPi);
  out.pitch = (1.0 - w) * a.pitch + w * b.pitch;
  return out;
}

void ShipHistory::clear()
{
  track_.clear();
  times_.clear();
  poses_.clear();
}

void ShipHistory::dropBefore(double t)
{
  track_.dropBefore(t);
  while (times_.size() > 2 && times_[1] <= t)
  {
    times_.pop_front();
    poses_.pop_front();
  }
}

}  // namespace tow_sim
