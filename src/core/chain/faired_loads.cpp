// A faired cable's loads (docs/physics.md §11, (P56)) and the dispatch between them and the bare cable's.
#include <Eigen/Geometry>
#include <cmath>

#include "tow_sim/core/chain/element.h"
#include "tow_sim/core/geometry.h"

namespace tow_sim
{
namespace
{
// Below this cross-flow speed [m/s] its direction n is undefined: the loads take their limits there.
constexpr double kTinyCrossFlow = 1e-12;

// The flow's parts along and across the axis s.
struct FlowParts
{
  double u_t = 0.0;       // u.s
  Eigen::Vector3d u_n;    // u - (u.s) s
  double cross = 0.0;     // |u_n|
  double speed = 0.0;     // |u|
  double phi = 0.0;       // atan2(|u_n|, |u.s|), in [0, pi/2]
  double sg = 0.0;        // the smooth sign of u_t
  double sg_prime = 0.0;  // its derivative

  FlowParts(const Eigen::Vector3d& s, const Eigen::Vector3d& u, double smoothing_speed)
      : u_t(u.dot(s)), u_n(u - u_t * s), cross(u_n.norm()), speed(u.norm()), phi(std::atan2(cross, std::abs(u_t)))
  {
    const double e2 = smoothing_speed * smoothing_speed;
    const double root = std::sqrt(u_t * u_t + e2);
    sg = u_t / root;
    sg_prime = e2 / (root * root * root);
  }
  // |u|^2 d phi / d u = (|u_t| n - |u_n| sign(u_t) s): zero where phi is not differentiable (u along s).
  Eigen::Vector3d phiGradientTimesSpeedSquared(const Eigen::Vector3d& s) const
  {
    if (cross < kTinyCrossFlow)
      return Eigen::Vector3d::Zero();
    const double sign = u_t > 0.0 ? 1.0 : (u_t < 0.0 ? -1.0 : 0.0);
    return (std::abs(u_t) / cross) * u_n - cross * sign * s;
  }
};

}  // namespace

Eigen::Vector3d fairedForce(const CableLoading& loading, double scale, const Eigen::Vector3d& s,
                            const Eigen::Vector3d& u, double smoothing_speed)
{
  const FlowParts f(s, u, smoothing_speed);
  const CableLoading::Coefficients c = loading.at(f.phi);
  // C(phi) |u|^2 n = (C(phi) / sin(phi)) |u| u_n, as sin(phi) = |u_n| / |u|.
  return scale * (-c.normal_per_sine * f.speed * f.u_n - c.tangential * f.speed * f.speed * f.sg * s +
                  c.lift_per_sine * f.speed * s.cross(f.u_n));
}

Eigen::Matrix3d fairedForceJacobian(const CableLoading& loading, double scale, const Eigen::Vector3d& s,
                                    const Eigen::Vector3d& u, double smoothing_speed)
{
  const FlowParts f(s, u, smoothing_speed);
  if (f.speed == 0.0)
    return Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - s * s.transpose();
  const Eigen::Matrix3d S = skew(s);
  const CableLoading::Coefficients c = loading.at(f.phi);
  const Eigen::Vector3d grad_phi_u2 = f.phiGradientTimesSpeedSquared(s);  // |u|^2 d phi / d u
  const Eigen::Vector3d u_hat = u / f.speed;
  // d(r(phi) |u| u_n) = r (u_n u_hat^T + |u| P) + r'(phi) |u| u_n (d phi / d u)^T, r = C / sin.
  const Eigen::Matrix3d d_cross_flow = f.u_n * u_hat.transpose() + f.speed * P;
  const Eigen::Matrix3d normal =
      c.normal_per_sine * d_cross_flow + (c.normal_per_sine_slope / f.speed) * f.u_n * grad_phi_u2.transpose();
  const Eigen::Matrix3d lift =
      c.lift_per_sine * S * d_cross_flow + (c.lift_per_sine_slope / f.speed) * S * f.u_n * grad_phi_u2.transpose();
  // d(C_t(phi) |u|^2 sg(u_t) s) = s (2 C_t sg u + C_t |u|^2 sg' s + sg C_t' |u|^2 d phi / d u)^T.
  const Eigen::Vector3d tangential = 2.0 * c.tangential * f.sg * u + c.tangential * f.speed * f.speed * f.sg_prime * s +
                                     f.sg * c.tangential_slope * grad_phi_u2;
  return scale * (-normal - s * tangential.transpose() + lift);
}

VelocityForces segmentVelocityForces(const CableSegmentModel& seg, const ElementKinematics& k,
                                     const Eigen::Vector3d& flow_W)
{
  if (!seg.loading)
    return velocityForces(k, flow_W, seg.c1, seg.c2, seg.tangential_model, seg.smoothing_speed);
  VelocityForces f = velocityForces(k, flow_W, 0.0, seg.c2, seg.tangential_model, seg.smoothing_speed);  // M_V
  f.force =
      fairedForce(*seg.loading, seg.loading_scale * k.length, k.s, k.velocityAt(0.5) - flow_W, seg.smoothing_speed);
  return f;
}

VelocityForceJacobian segmentVelocityForceJacobian(const CableSegmentModel& seg, const ElementKinematics& k,
                                                   const Eigen::Vector3d& flow_W)
{
  if (!seg.loading)
    return velocityForceJacobian(k, flow_W, seg.c1, seg.c2, seg.tangential_model, seg.smoothing_speed);
  VelocityForceJacobian J = velocityForceJacobian(k, flow_W, 0.0, seg.c2, seg.tangential_model, seg.smoothing_speed);
  J.force_u = fairedForceJacobian(*seg.loading, seg.loading_scale * k.length, k.s, k.velocityAt(0.5) - flow_W,
                                  seg.smoothing_speed);
  return J;
}

}  // namespace tow_sim
