#include "tow_sim/core/run/gnss_track.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/constants.h"

namespace tow_sim
{
void validate(const GnssTrackParams& p, const std::string& prefix)
{
  if (!(p.antenna_S.allFinite() && p.antenna_S.cwiseAbs().maxCoeff() <= 1000.0))
    throw std::invalid_argument(prefix + "antenna: each of x, y, z must be finite, within [-1000, 1000] [m]");
  if (!(p.smoothing_time >= 0.0 && p.smoothing_time <= 600.0))
  {
    std::ostringstream why;
    why << prefix << "smoothing_time = " << p.smoothing_time << " must be in [0, 600] [s]";
    throw std::invalid_argument(why.str());
  }
}

GnssTrack::GnssTrack(const GnssTrackParams& params) : params_(params)
{
  validate(params, "");
}

void GnssTrack::gains(double dt, double smoothing_time, double& alpha, double& beta)
{
  alpha = smoothing_time > 0.0 ? 1.0 - std::exp(-dt / smoothing_time) : 1.0;
  beta = alpha * alpha / (2.0 - alpha);  // Benedict-Bordner: alpha = 1 gives beta = 1, a two-point difference
}

ShipEstimate GnssTrack::update(const GnssFix& fix)
{
  if (!(std::isfinite(fix.t) && fix.antenna_W.allFinite() && std::isfinite(fix.yaw)))
    throw std::invalid_argument("GNSS fix: stamp, position and heading must be finite");
  if (started_ && !(fix.t > t_))
  {
    std::ostringstream why;
    why.precision(12);
    why << "GNSS fix: stamp " << fix.t << " s is not after the previous fix's " << t_ << " s";
    throw std::invalid_argument(why.str());
  }
  const double c = std::cos(fix.yaw), s = std::sin(fix.yaw);
  const Eigen::Vector3d& a = params_.antenna_S;
  // The ship frame's origin: the antenna less its lever arm, turned by the heading (roll and pitch unknown).
  Eigen::Vector3d z_W = fix.antenna_W - Eigen::Vector3d(c * a.x() - s * a.y(), s * a.x() + c * a.y(), a.z());
  if (!params_.use_altitude)
    z_W.z() = 0.0;
  if (!started_)
  {
    started_ = true;
    p_W_ = z_W;
    v_W_.setZero();
    yaw_ = fix.yaw;
    yaw_rate_ = 0.0;
  }
  else
  {
    const double dt = fix.t - t_;
    double alpha = 0.0, beta = 0.0;
    gains(dt, params_.smoothing_time, alpha, beta);
    const Eigen::Vector3d r = z_W - (p_W_ + v_W_ * dt);
    p_W_ += v_W_ * dt + alpha * r;
    v_W_ += (beta / dt) * r;
    const double predicted = yaw_ + yaw_rate_ * dt;
    const double r_yaw = std::remainder(fix.yaw - predicted, 2.0 * kPi);  // the heading unwrapped
    yaw_ = predicted + alpha * r_yaw;
    yaw_rate_ += (beta / dt) * r_yaw;
  }
  t_ = fix.t;
  ShipEstimate e;
  e.t = t_;
  e.p_W = p_W_;
  e.yaw = yaw_;
  const double cy = std::cos(yaw_), sy = std::sin(yaw_);
  e.v_S = Eigen::Vector3d(cy * v_W_.x() + sy * v_W_.y(), -sy * v_W_.x() + cy * v_W_.y(), v_W_.z());
  e.yaw_rate = yaw_rate_;
  return e;
}

}  // namespace tow_sim
