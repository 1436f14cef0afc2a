#include "tow_sim/core/odometry_check.h"

#include <cmath>
#include <sstream>

namespace tow_sim
{
OdometryResult checkOdometry(const OdometryInput& in, const OdometryLimits& limits, const ShipTrack& track, double now)
{
  OdometryResult r;
  auto refuse = [&r](const std::string& why)
  {
    r.reason = why;
    return r;
  };
  if (in.frame_id != limits.world_frame)
    return refuse("header.frame_id = '" + in.frame_id + "', expected the world frame '" + limits.world_frame + "'");
  if (!std::isfinite(in.t) || !in.p_W.allFinite() || !in.q_wxyz.allFinite() || !in.v_S.allFinite() ||
      !in.w_S.allFinite())
    return refuse("a stamp, pose or twist field is not finite");
  if (!(in.p_W.cwiseAbs().maxCoeff() <= limits.max_position))
  {
    std::ostringstream os;
    os << "pose.pose.position has a component beyond +-" << limits.max_position << " m";
    return refuse(os.str());
  }
  const double norm = in.q_wxyz.norm();
  if (std::abs(norm - 1.0) > 0.01)
  {
    std::ostringstream os;
    os << "pose.pose.orientation has norm " << norm << ", must be within 0.01 of 1";
    return refuse(os.str());
  }
  if (in.t > now + limits.max_future)
  {
    std::ostringstream os;
    os << "header.stamp is " << in.t - now << " s in the future";
    return refuse(os.str());
  }
  if (in.t < now - limits.max_age)
  {
    std::ostringstream os;
    os << "header.stamp is " << now - in.t << " s in the past (more than max_odom_age = " << limits.max_age
       << " s): is the publisher on another clock (use_sim_time, rosbag play --clock)?";
    return refuse(os.str());
  }
  if (!track.empty() && !(in.t > track.newestTime()))
    return refuse("header.stamp is not after the previous message's (duplicated or reordered)");
  r.q_WS = Eigen::Quaterniond(in.q_wxyz[0], in.q_wxyz[1], in.q_wxyz[2], in.q_wxyz[3]).normalized();
  const Eigen::Matrix3d R = r.q_WS.toRotationMatrix();
  const Eigen::Vector3d arm = R * limits.tow_point_S;
  r.tow_p_W = in.p_W + arm;
  r.tow_v_W = R * in.v_S + (R * in.w_S).cross(arm);
  if (!(r.tow_v_W.norm() <= limits.max_ship_speed))
  {
    std::ostringstream os;
    os << "tow-point speed " << r.tow_v_W.norm() << " m/s exceeds max_ship_speed = " << limits.max_ship_speed << " m/s";
    return refuse(os.str());
  }
  if (!track.empty())
  {
    const double dt = in.t - track.newestTime();
    const double jump = (r.tow_p_W - track(in.t).p_W).norm();
    if (!(jump <= limits.max_ship_speed * dt + limits.max_jump_slack))
    {
      std::ostringstream os;
      os << "the tow point jumped " << jump << " m from where the previous message put it";
      return refuse(os.str());
    }
  }
  r.accepted = true;
  return r;
}

}  // namespace tow_sim
