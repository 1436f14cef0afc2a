#include "tow_sim/core/chain/element.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/geometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tow_sim
{
namespace
{

// Below this normal speed [m/s] the direction q of the normal flow is undefined; M_V vanishes there.
constexpr double kTinySpeed = 1e-12;
}  // namespace

ElementKinematics ElementKinematics::fromJoints(const Eigen::Vector3d& x_f, const Eigen::Vector3d& x_a,
                                                const Eigen::Vector3d& v_f, const Eigen::Vector3d& v_a)
{
  ElementKinematics k;
  k.x_f = x_f;
  k.x_a = x_a;
  k.v_f = v_f;
  k.v_a = v_a;
  const Eigen::Vector3d delta = x_a - x_f;
  k.length = delta.norm();
  k.s = delta / k.length;
  k.s_dot = (v_a - v_f) / k.length;
  k.omega = k.s.cross(k.s_dot);
  return k;
}

CableSegmentModel CableSegmentModel::fromParams(const CableParams& cable, const Environment& env,
                                                const NumericsParams& numerics)
{
  CableSegmentModel m;
  m.length = cable.segmentLength();
  m.mass = cable.mass_per_length * m.length;
  const double area = 0.25 * kPi * cable.diameter * cable.diameter;
  m.net_weight = (cable.mass_per_length - env.water_density * area) * env.gravity * m.length;  // (w - b) d
  const double wet = env.water_density > 0.0 ? 1.0 : 0.0;  // vacuum: no drag even for given C1, C2
  m.c1 = wet * cable.c1Value(env);
  m.c2 = wet * cable.c2Value(env) * cable.normalDragAmplification();  // strumming: (P55)
  m.added_mass = cable.added_mass_coefficient * env.water_density * area * m.length;
  m.displaced_mass = env.water_density * area * m.length;
  m.tangential_model = cable.tangential_drag_model;
  if (cable.loading)
  {
    m.loading = cable.loading.get();
    m.loading_scale = wet * 0.5 * env.water_density * cable.diameter;
    m.c1 = m.loading_scale * cable.loading->tangential().front();
    m.c2 = m.loading_scale * cable.loading->normal().back();
  }
  m.smoothing_speed = numerics.tangential_smoothing_speed;
  m.stretches = cable.elastic();
  return m;
}

Eigen::Vector3d bendingMoment(const Eigen::Vector3d& s_f, const Eigen::Vector3d& s_a, double k)
{
  const Eigen::Vector3d b = s_f.cross(s_a);  // |b| = sin theta
  const double sin_theta = b.norm();
  const double theta = std::atan2(sin_theta, s_f.dot(s_a));
  // theta / sin theta -> 1 as theta -> 0 (its series to theta^4 below 1e-4 rad); folded back flat (theta = pi,
  // b = 0) there is no preferred way to unfold and no moment.
  const double ratio =
      sin_theta > 1e-4 || s_f.dot(s_a) < 0.0 ? theta / std::max(sin_theta, 1e-300) : 1.0 + theta * theta / 6.0;
  return k * ratio * b;
}

VelocityForces velocityForces(const ElementKinematics& k, const Eigen::Vector3d& current_W, double c1, double c2,
                              TangentialDragModel model, double smoothing_speed)
{
  const double d = k.length;
  const Eigen::Vector3d u = k.velocityAt(0.5) - current_W;  // u_lambda, through the water
  const double u_t = u.dot(k.s);
  const Eigen::Vector3d u_n = u - u_t * k.s;
  const double u_n_norm = u_n.norm();

  VelocityForces f;
  // Normal drag, Appendix D: -C2 d |u_n| u_n.
  f.force = -c2 * d * u_n_norm * u_n;
  // Tangential drag along s, against the tangential flow.
  if (model == TangentialDragModel::kPode)
  {
    const double smooth_sign = u_t / std::sqrt(u_t * u_t + smoothing_speed * smoothing_speed);
    f.force -= c1 * d * u.squaredNorm() * smooth_sign * k.s;
  }
  else
  {
    f.force -= c1 * d * std::abs(u_t) * u_t * k.s;
  }
  // Rotation-drag moment, Appendix D: M_V = (C2 d^3 / 6) (u . (w x s)) (s x q), q = -u_n/|u_n|.
  f.moment.setZero();
  if (u_n_norm > kTinySpeed)
  {
    const Eigen::Vector3d q = -u_n / u_n_norm;
    f.moment = (c2 * d * d * d / 6.0) * u.dot(k.omega.cross(k.s)) * k.s.cross(q);
  }
  return f;
}

VelocityForceJacobian velocityForceJacobian(const ElementKinematics& k, const Eigen::Vector3d& current_W, double c1,
                                            double c2, TangentialDragModel model, double smoothing_speed)
{
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const double d = k.length;
  const Eigen::Vector3d& s = k.s;
  const Eigen::Matrix3d P = I3 - s * s.transpose();
  const Eigen::Vector3d u = k.velocityAt(0.5) - current_W;
  const double u_t = u.dot(s);
  const Eigen::Vector3d u_n = u - u_t * s;
  const double u_n_norm = u_n.norm();

  VelocityForceJacobian J;
  J.force_u.setZero();
  J.moment_u.setZero();
  J.moment_dv.setZero();
  // Normal drag -C2 d |u_n| u_n, u_n = P u: d/du = -C2 d (|u_n| P + u_n u_n^T / |u_n|) (zero at u_n = 0).
  if (u_n_norm > 0.0)
    J.force_u = -c2 * d * (u_n_norm * P + u_n * u_n.transpose() / u_n_norm);
  if (model == TangentialDragModel::kPode)
  {
    // -C1 d |u|^2 sg(u_t) s with sg(x) = x / sqrt(x^2 + e^2), sg'(x) = e^2 / (x^2 + e^2)^(3/2).
    const double e2 = smoothing_speed * smoothing_speed;
    const double root = std::sqrt(u_t * u_t + e2);
    const double sg = u_t / root, sg_prime = e2 / (root * root * root);
    J.force_u -= c1 * d * s * (2.0 * sg * u + u.squaredNorm() * sg_prime * s).transpose();
  }
  else
  {
    J.force_u -= 2.0 * c1 * d * std::abs(u_t) * s * s.transpose();  // -C1 d |u_t| u_t s
  }
  // M_V = (C2 d^3 / 6) (u.(w x s)) (s x q) with w x s = P dv / d and q = -n, n = u_n / |u_n|:
  // M_V = -beta (u_n . dv) [s]x n, beta = C2 d^2 / 6.
  if (u_n_norm > 1e-12)  // velocityForces' kTinySpeed: M_V is zero below it
  {
    const double beta = c2 * d * d / 6.0;
    const Eigen::Vector3d dv = k.v_a - k.v_f;
    const Eigen::Vector3d n = u_n / u_n_norm;
    const Eigen::Matrix3d S = skew(s);
    J.moment_dv = -beta * (S * n) * u_n.transpose();
    // d(u_n . dv)/du = (P dv)^T; d n / du = (P - n n^T) / |u_n|.
    J.moment_u = -beta * ((S * n) * (P * dv).transpose() + (u_n.dot(dv) / u_n_norm) * S * (P - n * n.transpose()));
  }
  return J;
}

Matrix6d jointMap(const Eigen::Vector3d& s, double length, double cg_fraction)
{
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S = skew(s) / length;
  Matrix6d J;
  J << (1.0 - cg_fraction) * I3, cg_fraction * I3, -S, S;
  return J;
}

Vector6d waveInertiaWrench(const Eigen::Matrix3d& added_force, const Eigen::Matrix3d& added_moment,
                           double displaced_mass, const Eigen::Vector3d& r_cb, const Eigen::Vector3d& a_w)
{
  const Eigen::Vector3d froude_krylov = displaced_mass * a_w;
  Vector6d w;
  w << added_force * a_w + froude_krylov, added_moment * a_w + r_cb.cross(froude_krylov);
  return w;
}

void cableSegmentDynamics(const CableSegmentModel& seg, double t, const ElementKinematics& k, const Environment& env,
                          BodyDynamics& out)
{
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d P = I3 - k.s * k.s.transpose();  // projection normal to the axis
  out.cg_fraction = 0.5;
  out.mass.setZero();
  // Walton-Polachek added mass acts on the normal acceleration of the centre (= CG).
  out.mass.topLeftCorner<3, 3>() = seg.mass * I3 + seg.added_mass * P;
  // A stretching segment keeps its mass: its rotary inertia follows its length (with no correction for
  // the stretch rate, d(I w)/dt = I s x (a_a - a_f)/d exactly; docs/solver.md §8).
  const double d = seg.stretches ? k.length : seg.length;
  out.mass.bottomRightCorner<3, 3>() = (seg.mass * d * d / 12.0) * I3;

  const WaveKinematics flow = env.flowOver(k.x_f, k.x_a, t);
  const VelocityForces vf = segmentVelocityForces(seg, k, flow.velocity_W);
  out.wrench.head<3>() = vf.force - seg.net_weight * Eigen::Vector3d::UnitZ();
  out.wrench.tail<3>() = vf.moment;
  // The waves' acceleration a_w (physics.md §9, Morison): Froude-Krylov rho A d a_w plus the added mass
  // e a_w, both on the normal part, as the added mass acts on the segment's own normal acceleration.
  if (env.wave_field)
    out.wrench.head<3>() += (seg.displaced_mass + seg.added_mass) * (P * flow.acceleration_W);
}

RigidEndElement::RigidEndElement(const EndElementParams& params, const NumericsParams& numerics)
    : p_(params), smoothing_speed_(numerics.tangential_smoothing_speed)
{
  validate(p_);
}

Depressor::Depressor(const DepressorParams& params, const NumericsParams& numerics)
    : p_(params), body_(params, numerics)
{
  validate(p_, "depressor");
}

Eigen::Vector3d Depressor::lift(const ElementKinematics& k, const Eigen::Vector3d& flow_W, double water_density) const
{
  const double cg = p_.cg_from_bail / p_.length;
  const Eigen::Vector3d w = flow_W - k.velocityAt(cg);  // the water past the body
  Eigen::Vector3d y_b = Eigen::Vector3d::UnitZ().cross(k.s);
  y_b = y_b.norm() > 1e-9 ? Eigen::Vector3d(y_b.normalized()) : Eigen::Vector3d::UnitY();  // hanging vertically
  const Eigen::Vector3d w_p = w - w.dot(y_b) * y_b;
  const double speed = w_p.norm();
  if (speed < kTinySpeed)
    return Eigen::Vector3d::Zero();
  Eigen::Vector3d down = y_b.cross(w_p) / speed;  // normal to w_p in the plane of symmetry
  if (down.z() > 0.0)                             // (P49a): the side of the flow that points down
    down = -down;
  return (0.5 * water_density * p_.wing_area * p_.lift_coefficient * speed * speed) * down;
}

void Depressor::dynamics(double t, const ElementKinematics& k, const Environment& env, BodyDynamics& out) const
{
  static const Actuators none;
  body_.dynamics(t, k, env, none, out);
  if (p_.wing_area <= 0.0 || p_.lift_coefficient <= 0.0)
    return;
  const Eigen::Vector3d x_G = k.pointAt(out.cg_fraction);
  const Eigen::Vector3d L = lift(k, env.flowAt(x_G, t).velocity_W, env.water_density);
  out.wrench.head<3>() += L;
  out.wrench.tail<3>() += (k.pointAt(p_.lift_from_bail / p_.length) - x_G).cross(L);
}

HeldServos::HeldServos(Actuators& actuators, double t_held)
    : actuators_(actuators),
      rudder_(actuators.rudder.state()),
      elevator_(actuators.elevator.state()),
      differential_(actuators.differential.state())
{
  actuators.rudder.reset(t_held, actuators.rudder.angleAt(t_held));
  actuators.elevator.reset(t_held, actuators.elevator.angleAt(t_held));
  actuators.differential.reset(t_held, actuators.differential.angleAt(t_held));
}

HeldServos::~HeldServos()
{
  actuators_.rudder.restore(rudder_);
  actuators_.elevator.restore(elevator_);
  actuators_.differential.restore(differential_);
}

Actuators EndBody::restingActuators(double t) const
{
  Actuators a;
  a.rudder.reset(t, 0.0);
  a.elevator.reset(t, 0.0);
  a.differential.reset(t, 0.0);
  return a;
}

bool EndBody::command(Actuators&, double, double, double, double) const
{
  throw std::invalid_argument("command: this end body has no fins or propeller");
}

bool EndBody::commandDifferential(Actuators&, double, double) const
{
  throw std::invalid_argument("command: this end body has no fins");
}

Eigen::Vector2d EndBody::rollRates(double, const ElementKinematics&, const Environment&, const Actuators&,
                                   const Eigen::Vector3d&, const Eigen::Vector3d&) const
{
  return Eigen::Vector2d::Zero();
}

void RigidEndElement::dynamics(double t, const ElementKinematics& k, const Environment& env,
                               const Actuators& /*actuators*/, BodyDynamics& out) const
{
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d P = I3 - k.s * k.s.transpose();
  const double gamma = p_.cg_from_bail / p_.length;
  out.cg_fraction = gamma;

  const double area = 0.25 * kPi * p_.diameter * p_.diameter;
  const double e = p_.added_mass_coefficient * env.water_density * area * p_.length;
  // Approach A added mass acts at the bail-tail midpoint, r from the CG: F_A = -e P (a_G + dw/dt x r).
  const Eigen::Vector3d r_mid = (0.5 - gamma) * p_.length * k.s;
  const Eigen::Matrix3d R = skew(r_mid);
  out.mass.topLeftCorner<3, 3>() = p_.mass * I3 + e * P;
  out.mass.topRightCorner<3, 3>() = -e * R;
  out.mass.bottomLeftCorner<3, 3>() = e * R;
  out.mass.bottomRightCorner<3, 3>() = p_.transverseInertia() * I3 - e * R * R;

  const double c1 = 0.5 * env.water_density * p_.tangential_drag_coefficient * kPi * p_.diameter;
  const double c2 = 0.5 * env.water_density * p_.normal_drag_coefficient * p_.diameter;
  // The body is small beside the waves' length: the flow at its midpoint for all its loads.
  const WaveKinematics flow = env.flowAt(k.pointAt(0.5), t);
  const VelocityForces vf = velocityForces(k, flow.velocity_W, c1, c2, TangentialDragModel::kPode, smoothing_speed_);

  const Eigen::Vector3d weight = -p_.mass * env.gravity * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d buoyancy = env.water_density * env.gravity * p_.displaced_volume * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d r_cb = (p_.cb_from_bail - p_.cg_from_bail) * k.s;

  out.wrench.head<3>() = weight + buoyancy + vf.force;
  out.wrench.tail<3>() = r_cb.cross(buoyancy) + r_mid.cross(vf.force) + vf.moment;
  if (env.wave_field)
    out.wrench += waveInertiaWrench(out.mass.topLeftCorner<3, 3>() - p_.mass * I3, out.mass.bottomLeftCorner<3, 3>(),
                                    env.water_density * p_.displaced_volume, r_cb, flow.acceleration_W);
}

}  // namespace tow_sim
