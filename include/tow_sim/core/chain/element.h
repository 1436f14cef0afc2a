// One rigid element of the chain: a cable segment (lambda = 1..nu) or the end body (lambda = nu+1).
// Every element is described to the solver the same way: its Newton-Euler equations about its CG in
// world axes, M_body [a_G; dw/dt] = wrench + (tension forces and moments), with the accelerations of
// its CG and its angular acceleration linear in the accelerations of its two joints (no roll).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tow_sim/core/params.h"
#include "tow_sim/core/vehicle/fins.h"

namespace tow_sim
{
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// Element kinematics from its forward joint x_f (toward the ship) and aft joint x_a (Appendix A).
struct ElementKinematics
{
  Eigen::Vector3d x_f, x_a, v_f, v_a;  // [m], [m/s] joints, world
  Eigen::Vector3d s;                   // [-] s_lambda, unit axis from x_f to x_a
  double length = 0.0;                 // [m] |x_a - x_f| (equals d_lambda up to the length error)
  Eigen::Vector3d s_dot;               // [1/s] ds/dt
  Eigen::Vector3d omega;               // [rad/s] s x ds/dt (no roll)
  // A rolling end body's roll (physics.md §5b): the angle phi [rad] from its zero-roll frame (P1) about x_b = -s
  // and its spin p = omega_B . x_b [rad/s], which adds p x_b to omega. Zero for every other element.
  double roll = 0.0, roll_rate = 0.0;

  static ElementKinematics fromJoints(const Eigen::Vector3d& x_f, const Eigen::Vector3d& x_a,
                                      const Eigen::Vector3d& v_f, const Eigen::Vector3d& v_a);
  // A point a fraction eta of the way from x_f to x_a: position and velocity.
  Eigen::Vector3d pointAt(double eta) const { return x_f + eta * (x_a - x_f); }
  Eigen::Vector3d velocityAt(double eta) const { return v_f + eta * (v_a - v_f); }
};

// Newton-Euler description of one element about its CG, world axes.
struct BodyDynamics
{
  Matrix6d mass;       // [kg, kg m, kg m^2] rigid-body plus added mass: [F; M] = mass [a_G; dw/dt]
  Vector6d wrench;     // [N; N m] all loads but the joint tensions: force at the CG, moment about it
  double cg_fraction;  // [-] gamma: the CG lies at x_f + gamma (x_a - x_f)
};

// Constant description of a uniform cable segment (physics.md §4).
struct CableSegmentModel
{
  double length = 0.0;          // [m] d_lambda
  double mass = 0.0;            // [kg] m_lambda = w d / g (mass in air)
  double net_weight = 0.0;      // [N] (w - b) d, weight in water
  double c1 = 0.0;              // [N s^2/m^3] tangential drag constant
  double c2 = 0.0;              // [N s^2/m^3] normal drag constant
  double added_mass = 0.0;      // [kg] e_lambda, Walton-Polachek, acts on the normal acceleration
  double displaced_mass = 0.0;  // [kg] rho (pi D^2/4) d: the Froude-Krylov force of the waves' acceleration
  TangentialDragModel tangential_model = TangentialDragModel::kPode;
  // A faired cable's loading functions (null: bare, c1 and c2); with them c1 = 1/2 rho D C_t(0) and
  // c2 = 1/2 rho D C_n(pi/2), the latter for the rotation-drag moment M_V alone. Points to the CableParams'
  // `loading` it was made from (shared and constant: valid while any copy of those parameters lives, as the
  // chain model's own copy does); a plain pointer, so that the per-segment copies cost nothing more.
  const CableLoading* loading = nullptr;
  double loading_scale = 0.0;     // [kg/m^2] 1/2 rho D (0 in vacuum): the faired loads per metre over |u|^2 C
  double smoothing_speed = 0.01;  // [m/s] width of the smooth sign of u.s (Pode model)
  bool stretches = false;         // elastic cable: the rotary inertia m d^2/12 at the actual length d

  // `loading` points into cable.loading: keep a copy of `cable` (or of its loading) alive while it is used.
  static CableSegmentModel fromParams(const CableParams& cable, const Environment& env, const NumericsParams& numerics);
};

// The bending moment [N m] on the forward of two cable segments with unit axes s_f and s_a that meet at a
// joint of rotational stiffness k [N m/rad] (physics.md §11): k theta about s_f x s_a, theta the angle between
// them, turning s_f toward s_a; the aft segment carries its opposite. Smooth through theta = 0.
Eigen::Vector3d bendingMoment(const Eigen::Vector3d& s_f, const Eigen::Vector3d& s_a, double k);

// Velocity forces of a cylinder-like element through the water (Appendix D), evaluated at the element
// centre: normal drag, tangential drag and the rotation-drag moment M_V. Returns force, adds moment.
struct VelocityForces
{
  Eigen::Vector3d force;   // [N] at the element centre
  Eigen::Vector3d moment;  // [N m] couple
};
VelocityForces velocityForces(const ElementKinematics& k, const Eigen::Vector3d& current_W, double c1, double c2,
                              TangentialDragModel model, double smoothing_speed);

// Derivatives of velocityForces at the same arguments (for the implicit stepper): with respect to the
// centre's velocity through the water u and to the joints' relative velocity dv = v_a - v_f (through the
// rotation w = s x dv / d), the axis held fixed.
struct VelocityForceJacobian
{
  Eigen::Matrix3d force_u;    // [N s/m] d force / d u
  Eigen::Matrix3d moment_u;   // [N s] d moment / d u
  Eigen::Matrix3d moment_dv;  // [N s] d moment / d dv
};
VelocityForceJacobian velocityForceJacobian(const ElementKinematics& k, const Eigen::Vector3d& current_W, double c1,
                                            double c2, TangentialDragModel model, double smoothing_speed);

// The force [N] of a faired cable's loading functions on a segment with unit axis s moving at u [m/s] through
// the water (physics.md §11, (P56)): scale |u|^2 (-C_n(phi) n - C_t(phi) sg(u.s) s + C_l(phi) s x n), scale =
// 1/2 rho D d, n = u_n / |u_n| the cross-flow's direction, phi = atan2(|u_n|, |u.s|), sg the Pode model's
// smooth sign over smoothing_speed. The normal load and the lift are smooth where u runs along s (C_n(0) =
// C_l(0) = 0); the tangential load has a corner there unless C_t's first slope is 0.
Eigen::Vector3d fairedForce(const CableLoading& loading, double scale, const Eigen::Vector3d& s,
                            const Eigen::Vector3d& u, double smoothing_speed);
// Its derivative d force / d u [N s/m], s held fixed.
Eigen::Matrix3d fairedForceJacobian(const CableLoading& loading, double scale, const Eigen::Vector3d& s,
                                    const Eigen::Vector3d& u, double smoothing_speed);

// A cable segment's velocity forces in the flow flow_W [m/s] at its centre: velocityForces with its c1, c2
// when bare; with a faired loading, fairedForce and the rotation-drag moment of c2. And their derivatives.
VelocityForces segmentVelocityForces(const CableSegmentModel& seg, const ElementKinematics& k,
                                     const Eigen::Vector3d& flow_W);
VelocityForceJacobian segmentVelocityForceJacobian(const CableSegmentModel& seg, const ElementKinematics& k,
                                                   const Eigen::Vector3d& flow_W);

// The joint accelerations to the CG acceleration and angular acceleration of an element with axis s,
// length d and CG fraction gamma (docs/solver.md (S1)): [a_G; dw/dt] = J_f a_f + J_a a_a. Returns
// [J_f J_a] (6 x 6); its transpose projects a wrench at the CG onto the two joints (S5).
Matrix6d jointMap(const Eigen::Vector3d& s, double length, double cg_fraction);

// The load of the waves' acceleration a_w [m/s^2] on a closed body (physics.md §9), as a wrench at its CG:
// the added mass acting on [a_w; 0] (the force and moment rows' translational blocks of its added-mass
// matrix about the CG) plus the Froude-Krylov force rho V a_w at its centre of buoyancy r_cb from the CG.
Vector6d waveInertiaWrench(const Eigen::Matrix3d& added_force, const Eigen::Matrix3d& added_moment,
                           double displaced_mass, const Eigen::Vector3d& r_cb, const Eigen::Vector3d& a_w);

// Cable segment at time t [s] (the waves move in time).
void cableSegmentDynamics(const CableSegmentModel& seg, double t, const ElementKinematics& k, const Environment& env,
                          BodyDynamics& out);

// What an operator sets on the end body while it runs (the vehicle's fins and propeller); part of the
// chain's mutable data, not of the model. A rigid end body has none and ignores them.
struct Actuators
{
  FinServo rudder, elevator;  // rate-limited fin servos (their angles are known at any time)
  FinServo differential;      // the elevator's differential (physics.md §5b): starboard fin +, port fin -
  double thrust = 0.0;        // [N] propeller thrust along x_b, saturated
};

// For its lifetime, holds the fin servos of `actuators` where they are at t_held [s] (their angles then
// constant; the tow point's frame takes df/dt so, docs/solver.md (S28)); restores them when it ends.
class HeldServos
{
public:
  HeldServos(Actuators& actuators, double t_held);
  ~HeldServos();
  HeldServos(const HeldServos&) = delete;
  HeldServos& operator=(const HeldServos&) = delete;

private:
  Actuators& actuators_;
  const FinServo::State rudder_, elevator_, differential_;
};

// Element nu+1. Implementations: RigidEndElement here; the full towed vehicle plugs in the same way. An
// end body is constant: whatever changes while running comes in as Actuators.
class EndBody
{
public:
  virtual ~EndBody() = default;
  virtual double length() const = 0;  // [m] d_{nu+1}, bail to tail point
  // Newton-Euler description at time t [s] (fin servos move in time) in the environment `env`.
  virtual void dynamics(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
                        BodyDynamics& out) const = 0;
  // Points that touch the seabed, as fractions of the way from the bail (0) to the tail point (1);
  // negative ahead of the bail. Default: the tail point (the bail is the cable's last joint).
  virtual std::vector<double> contactFractions() const { return { 1.0 }; }
  // The actuators at rest at time t [s]: fins centred (with this body's servo limits), no thrust.
  virtual Actuators restingActuators(double t) const;
  // Commands the actuators from time t [s] on; values beyond the limits saturate. Returns true when
  // something saturated. Throws std::invalid_argument for a non-finite value or a body without actuators.
  virtual bool command(Actuators& actuators, double t, double rudder, double elevator, double thrust) const;
  // The elevator's differential deflection [rad] from time t [s] on (physics.md §5b), saturated like the
  // elevator (returns true then). Throws std::invalid_argument for a non-finite value or a body without fins.
  virtual bool commandDifferential(Actuators& actuators, double t, double differential) const;
  // A body that rolls (physics.md §5b) has two more states, its roll angle and spin (ElementKinematics::roll,
  // roll_rate); dynamics() then gives its equations with the spin's acceleration eliminated, and rollRates()
  // the angle's and the spin's rates once the joints' accelerations a_f (bail) and a_a (tail point) are known.
  virtual bool rolls() const { return false; }
  virtual Eigen::Vector2d rollRates(double t, const ElementKinematics& k, const Environment& env,
                                    const Actuators& actuators, const Eigen::Vector3d& a_f,
                                    const Eigen::Vector3d& a_a) const;
};

// Axisymmetric rigid end body: weight at the CG, buoyancy at the CB, cable-like velocity forces and
// Approach A added mass at the bail-tail midpoint.
class RigidEndElement : public EndBody
{
public:
  RigidEndElement(const EndElementParams& params, const NumericsParams& numerics);
  double length() const override { return p_.length; }
  void dynamics(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
                BodyDynamics& out) const override;
  const EndElementParams& params() const { return p_; }

private:
  EndElementParams p_;
  double smoothing_speed_;
};

// A winged depressor in line in the cable (physics.md §11, (P49a)): the rigid end element's body between a fore
// and an aft attachment, plus a wing's lift 1/2 rho S C_L |w_p|^2 at lift_from_bail, normal to w_p (the water's
// velocity relative to the body, less its component along the body's horizontal lateral axis y_b = z x s) in the
// body's plane of symmetry, on the side that points down.
class Depressor
{
public:
  Depressor(const DepressorParams& params, const NumericsParams& numerics);
  double length() const { return p_.length; }
  void dynamics(double t, const ElementKinematics& k, const Environment& env, BodyDynamics& out) const;
  // [N] the lift alone, for a body along k in the water's flow flow_W [m/s] (world) at its CG.
  Eigen::Vector3d lift(const ElementKinematics& k, const Eigen::Vector3d& flow_W, double water_density) const;
  const DepressorParams& params() const { return p_; }

private:
  DepressorParams p_;
  RigidEndElement body_;
};

}  // namespace tow_sim
