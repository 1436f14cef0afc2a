#include "tow_sim/core/run/odometry_check.h"

#include <cmath>
#include <sstream>

namespace tow_sim
{
namespace
{
// [s] a stamp closer than this to the previous one is a duplicate: the track's quintic pieces need spans that
// their fifth powers do not underflow (found by fuzzing: stamps 1e-318 s apart made the track infinite).
constexpr double kMinStampSpacing = 1e-6;
// [s] and a stamp this far from the time origin (31 years) would overflow them (fuzzing: -4e307 s).
constexpr double kMaxStamp = 1e9;

// The message on its own: frame, finite fields, position, quaternion, stamp against the clock and the track.
// Returns why it is refused, or "".
std::string messageProblem(const OdometryInput& in, const OdometryLimits& limits, const ShipTrack& track, double now)
{
  std::ostringstream os;
  if (in.frame_id != limits.world_frame)
    os << "header.frame_id = '" << in.frame_id << "', expected the world frame '" << limits.world_frame << "'";
  else if (!std::isfinite(in.t) || !in.p_W.allFinite() || !in.q_wxyz.allFinite() || !in.v_S.allFinite() ||
           !in.w_S.allFinite())
    os << "a stamp, pose or twist field is not finite";
  else if (!(std::abs(in.t) <= kMaxStamp))
    os << "header.stamp is " << in.t << " s from the time origin (beyond +-1e9 s)";
  else if (!(in.p_W.cwiseAbs().maxCoeff() <= limits.max_position))
    os << "pose.pose.position has a component beyond +-" << limits.max_position << " m";
  else if (std::abs(in.q_wxyz.norm() - 1.0) > 0.01)
    os << "pose.pose.orientation has norm " << in.q_wxyz.norm() << ", must be within 0.01 of 1";
  else if (in.t > now + limits.max_future)
    os << "header.stamp is " << in.t - now << " s in the future";
  else if (in.t < now - limits.max_age)
    os << "header.stamp is " << now - in.t << " s in the past (more than max_odom_age = " << limits.max_age
       << " s): is the publisher on another clock (use_sim_time, rosbag play --clock)?";
  else if (!track.empty() && !(in.t >= track.newestTime() + kMinStampSpacing))
    os << "header.stamp is not after the previous message's by 1 us or more (duplicated or reordered)";
  return os.str();
}
}  // namespace

OdometryResult checkOdometry(const OdometryInput& in, const OdometryLimits& limits, const ShipTrack& track, double now)
{
  OdometryResult r;
  r.reason = messageProblem(in, limits, track, now);
  if (!r.reason.empty())
    return r;
  // The tow point it implies: its speed, and how far it is from where the track puts it.
  r.q_WS = Eigen::Quaterniond(in.q_wxyz[0], in.q_wxyz[1], in.q_wxyz[2], in.q_wxyz[3]).normalized();
  const Eigen::Matrix3d R = r.q_WS.toRotationMatrix();
  const Eigen::Vector3d arm = R * limits.tow_point_S;
  r.tow_p_W = in.p_W + arm;
  r.tow_v_W = R * in.v_S + (R * in.w_S).cross(arm);
  std::ostringstream os;
  if (!(r.tow_v_W.norm() <= limits.max_ship_speed))
    os << "tow-point speed " << r.tow_v_W.norm() << " m/s exceeds max_ship_speed = " << limits.max_ship_speed << " m/s";
  else if (!track.empty())
  {
    const double dt = in.t - track.newestTime();
    const double jump = (r.tow_p_W - track(in.t).p_W).norm();
    if (!(jump <= limits.max_ship_speed * dt + limits.max_jump_slack))
    {
      os << "the tow point jumped " << jump << " m from where the previous message put it";
      r.jumped = true;
    }
  }
  r.reason = os.str();
  r.accepted = r.reason.empty();
  return r;
}

bool TrackReacquisition::jumped(double t, const Eigen::Vector3d& tow_p_W, const OdometryLimits& limits)
{
  const bool consistent = count_ > 0 && t > last_t_ &&
                          (tow_p_W - last_p_).norm() <= limits.max_ship_speed * (t - last_t_) + limits.max_jump_slack;
  count_ = consistent ? count_ + 1 : 1;
  last_t_ = t;
  last_p_ = tow_p_W;
  if (count_ < needed_)
    return false;
  count_ = 0;
  return true;
}

}  // namespace tow_sim
