#include "tow_sim/core/vehicle/vehicle.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/geometry.h"
#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/vehicle/added_mass.h"

namespace tow_sim
{
namespace
{
// Below this |z x x_b| the axis counts as vertical and y_b comes from the heading hint.
constexpr double kVerticalTolerance = 1e-6;

Eigen::Matrix<double, 6, 6> blockRotation(const Eigen::Matrix3d& R)
{
  Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Zero();
  T.topLeftCorner<3, 3>() = R;
  T.bottomRightCorner<3, 3>() = R;
  return T;
}

Eigen::Vector3d headingHint(const Eigen::Vector3d& v_through_water_W)
{
  const Eigen::Vector3d horizontal(v_through_water_W.x(), v_through_water_W.y(), 0.0);
  return horizontal.norm() > 1e-6 ? Eigen::Vector3d(horizontal.normalized()) : Eigen::Vector3d::UnitX();
}
// (P57a): the elevator as its two fins, each with half the pair's constants, the starboard one (span b toward
// -y_b) at elevator + differential, the port one (+y_b) at elevator - differential; their sum as the pair's
// loads, the moment with each fin's arm across the axis. (P57b): each fin in the flow at its own point, the
// spin p moving it by p x_b x (-+b y_b) = -+p b z_b.
FinPairLoads differentialElevatorLoads(FinPairParams fin, double elevator, double differential,
                                       const Eigen::Vector3d& v_W, const BodyFrame& f, double arm, double span,
                                       double spin)
{
  fin.lift_constant *= 0.5;
  fin.drag_constant *= 0.5;
  const Eigen::Vector3d spin_v = spin * span * f.z;
  const FinPairLoads starboard =
      finPairLoads(fin, FinPlane::kHorizontal, elevator + differential, v_W - spin_v, f.x, f.y, f.z, arm);
  const FinPairLoads port =
      finPairLoads(fin, FinPlane::kHorizontal, elevator - differential, v_W + spin_v, f.x, f.y, f.z, arm);
  FinPairLoads pair = starboard;
  pair.angle = elevator;
  pair.angle_of_attack = 0.5 * (starboard.angle_of_attack + port.angle_of_attack);
  pair.inflow_angle = 0.5 * (starboard.inflow_angle + port.inflow_angle);  // angle - angle_of_attack, as a pair's
  pair.lift_W = starboard.lift_W + port.lift_W;
  pair.drag_W = starboard.drag_W + port.drag_W;
  pair.moment_cg_W = starboard.moment_cg_W + port.moment_cg_W +
                     (-span * f.y).cross(starboard.lift_W + starboard.drag_W) +
                     (span * f.y).cross(port.lift_W + port.drag_W);
  pair.hinge_moment = starboard.hinge_moment + port.hinge_moment;
  return pair;
}

// The parameter table's inertia entries: a product of inertia sets both of its (symmetric) places.
std::function<double(const VehicleParams&)> inertiaGetter(int i, int j)
{
  return [i, j](const VehicleParams& v) { return v.inertia_B(i, j); };
}
// (P59)'s spin axis e = [0; x_b] (x_b = -s), M e and e^T M e: the Schur complement that eliminates the spin's
// acceleration, and the spin's acceleration from the joints' (Vehicle::dynamics, Vehicle::rollRates).
struct SpinAxis
{
  Vector6d e, Me;
  double m_ee;
};

SpinAxis spinAxis(const Eigen::Vector3d& s, const Matrix6d& mass)
{
  SpinAxis a;
  a.e << Eigen::Vector3d::Zero(), -s;
  a.Me = mass * a.e;
  a.m_ee = a.e.dot(a.Me);
  return a;
}

std::function<void(VehicleParams&, double)> inertiaSetter(int i, int j)
{
  return [i, j](VehicleParams& v, double value) { v.inertia_B(i, j) = v.inertia_B(j, i) = value; };
}
}  // namespace

void validate(const VehicleParams& v, const std::string& p)
{
  // The table checks every number (fins included); then what it cannot say.
  validateParams(vehicleParams(), v, p);
  if (!v.inertia_B.allFinite() ||
      (v.inertia_B - v.inertia_B.transpose()).cwiseAbs().maxCoeff() > 1e-9 * v.inertia_B.norm() ||
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(v.inertia_B).eigenvalues().minCoeff() <= 0.0)
    throw std::invalid_argument(p +
                                ".inertia must be a finite, symmetric, positive definite 3x3 matrix [kg m^2] "
                                "about the CG in body axes (xx, yy, zz > 0)");
  if (v.added_mass_approach == AddedMassApproach::kB && v.roll_added_inertia != 0.0)
    throw std::invalid_argument(p +
                                ".roll_added_inertia is Approach A's: with added_mass.approach B the matrix's "
                                "roll entry (row 4, column 4) is the added roll inertia; got " +
                                std::to_string(v.roll_added_inertia) + " kg m^2");
  if (v.prolate_spheroid)
    requireInRange(p + ".added_mass.prolate_spheroid.center_from_bail", v.prolate_spheroid->center_from_bail,
                   -v.nose_from_bail, v.tail_from_bail, "[m] (from -nose_from_bail to tail_from_bail)");
  else
    validateAddedMass(v.added_mass_b, p + ".added_mass.matrix");
}

Eigen::Matrix3d BodyFrame::rotation() const
{
  Eigen::Matrix3d R;
  R << x, y, z;
  return R;
}

BodyFrame bodyFrame(const Eigen::Vector3d& s, const Eigen::Vector3d& heading_hint)
{
  BodyFrame f;
  f.x = -s;
  Eigen::Vector3d y = Eigen::Vector3d::UnitZ().cross(f.x);
  if (y.norm() < kVerticalTolerance)
  {
    f.vertical = true;
    y = Eigen::Vector3d::UnitZ().cross(heading_hint);
    if (y.norm() < kVerticalTolerance)
      y = Eigen::Vector3d::UnitY();
    y -= y.dot(f.x) * f.x;  // keep the frame orthonormal
  }
  f.y = y.normalized();
  f.z = f.x.cross(f.y);
  return f;
}

BodyFrame rolledFrame(const BodyFrame& f, double phi)
{
  BodyFrame r = f;
  const double c = std::cos(phi), sn = std::sin(phi);
  r.y = c * f.y + sn * f.z;
  r.z = -sn * f.y + c * f.z;
  return r;
}

// (P58): y0 = z x x0 / n (n = |z x x0|, x0 = -s) turns about x0 at dy0/dt . z0 = (z x dx0/dt) . z0 / n.
double zeroRollFrameSpin(const Eigen::Vector3d& s, const Eigen::Vector3d& s_dot)
{
  const Eigen::Vector3d x0 = -s;
  const Eigen::Vector3d zx = Eigen::Vector3d::UnitZ().cross(x0);
  const double n = zx.norm();
  if (n < kVerticalTolerance)
    return 0.0;
  const Eigen::Vector3d z0 = x0.cross(zx / n);
  return Eigen::Vector3d::UnitZ().cross(-s_dot).dot(z0) / n;
}

Eigen::Quaterniond AttitudeHold::update(const Eigen::Vector3d& x_b_W)
{
  const Eigen::Vector3d x = x_b_W.normalized();
  const double tilt = std::atan2(x.head<2>().norm(), std::abs(x.z()));  // from the vertical
  const double own_heading = std::atan2(x.y(), x.x());
  const bool own_heading_defined = x.head<2>().norm() > kVerticalTolerance;
  if (tilt >= 2.0 * cone_ || (!has_heading_ && own_heading_defined))
  {
    heading_ = own_heading;
    has_heading_ = true;
  }
  double heading = heading_;
  if (tilt > cone_ && tilt < 2.0 * cone_)
  {
    const double w = (tilt - cone_) / cone_;  // 0 at the cone, 1 at twice the cone
    heading += w * std::atan2(std::sin(own_heading - heading_), std::cos(own_heading - heading_));
  }
  // y_b level and normal to the heading, then made normal to x_b.
  Eigen::Vector3d y(-std::sin(heading), std::cos(heading), 0.0);
  y = (y - y.dot(x) * x).normalized();
  Eigen::Matrix3d R;
  R << x, y, x.cross(y);
  return Eigen::Quaterniond(R).normalized();
}

struct Vehicle::Loads
{
  Vector6d wrench;  // at the CG, world
  double rudder = 0.0, elevator = 0.0, differential = 0.0, thrust = 0.0;
  FinPairLoads rudder_loads, elevator_loads;
};

Vehicle::Vehicle(const VehicleParams& params, const NumericsParams& numerics)
    : p_(params), smoothing_speed_(numerics.tangential_smoothing_speed)
{
  validate(p_);
  added_mass_b_ = p_.added_mass_b;
  if (p_.prolate_spheroid)
  {
    // Per unit water density here; dynamics() multiplies by the environment's density.
    const ProlateSpheroid& ps = *p_.prolate_spheroid;
    const Eigen::Vector3d r_cg_to_center(-(ps.center_from_bail - p_.cg_from_bail), 0.0, 0.0);  // body axes
    added_mass_b_ = moveMassMatrix(prolateSpheroidAddedMass(ps.length, ps.diameter, 1.0), r_cg_to_center);
  }
}

Actuators Vehicle::restingActuators(double t) const
{
  Actuators a;
  a.rudder = FinServo(p_.rudder.max_deflection, p_.rudder.max_rate);
  a.elevator = FinServo(p_.elevator.max_deflection, p_.elevator.max_rate);
  a.rudder.reset(t, 0.0);
  a.elevator.reset(t, 0.0);
  a.differential = FinServo(p_.elevator.max_deflection, p_.elevator.max_rate);
  a.differential.reset(t, 0.0);
  return a;
}

bool Vehicle::commandDifferential(Actuators& actuators, double t, double differential) const
{
  if (!std::isfinite(differential))
    throw std::invalid_argument("vehicle command: the differential elevator must be finite");
  actuators.differential.command(t, differential);
  return std::abs(differential) > p_.elevator.max_deflection;
}

bool Vehicle::command(Actuators& actuators, double t, double rudder, double elevator, double thrust) const
{
  if (!std::isfinite(rudder) || !std::isfinite(elevator) || !std::isfinite(thrust))
    throw std::invalid_argument("vehicle command: rudder, elevator and thrust must be finite");
  const bool saturated = std::abs(rudder) > p_.rudder.max_deflection ||
                         std::abs(elevator) > p_.elevator.max_deflection || std::abs(thrust) > p_.max_thrust;
  actuators.rudder.command(t, rudder);
  actuators.elevator.command(t, elevator);
  actuators.thrust = std::clamp(thrust, -p_.max_thrust, p_.max_thrust);
  return saturated;
}

Vehicle::Loads Vehicle::loads(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
                              const BodyFrame& frame) const
{
  const double tail = p_.tail_from_bail;
  const Eigen::Vector3d& s = k.s;
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  Loads out;
  // The vehicle is small beside the current's vertical scale and the waves' length: the flow at its CG
  // (current plus waves) for all its loads.
  const Eigen::Vector3d current = env.flowAt(k.pointAt(p_.cg_from_bail / tail), t).velocity_W;
  Eigen::Vector3d force = -p_.mass * env.gravity * up;
  const Eigen::Vector3d buoyancy = env.water_density * env.gravity * p_.displaced_volume * up;
  force += buoyancy;
  Eigen::Vector3d moment = ((p_.cb_from_bail - p_.cg_from_bail) * s).cross(buoyancy);
  if (p_.cb_above_cg != 0.0)  // (P57): the CB h_BG above the CG along z_b
    moment += (p_.cb_above_cg * frame.z).cross(buoyancy);

  // Velocity forces over the bail-tail length, at its midpoint (as for a cable element).
  const double wet = env.water_density > 0.0 ? 1.0 : 0.0;  // vacuum: no hydrodynamic loads
  const VelocityForces vf =
      velocityForces(k, current, wet * p_.c1, wet * p_.c2, TangentialDragModel::kPode, smoothing_speed_);
  force += vf.force;
  moment += ((0.5 * tail - p_.cg_from_bail) * s).cross(vf.force) + vf.moment;

  // Thrust along x_b at the tail, its line of action thrust_offset_z above the axis.
  out.thrust = actuators.thrust;
  const Eigen::Vector3d thrust_force = actuators.thrust * frame.x;
  force += thrust_force;
  moment += ((tail - p_.cg_from_bail) * s + p_.thrust_offset_z * frame.z).cross(thrust_force);

  finLoads(t, k, current, wet, actuators, frame, out);
  force += out.rudder_loads.lift_W + out.rudder_loads.drag_W + out.elevator_loads.lift_W + out.elevator_loads.drag_W;
  moment += out.rudder_loads.moment_cg_W + out.elevator_loads.moment_cg_W;
  if (rolls())  // (P57): the hull's roll damping against the spin (the fins' own: (P57b))
    moment -= wet * p_.roll_damping * k.roll_rate * frame.x;

  out.wrench << force, moment;
  return out;
}

// The fins at their servo angles, in the flow at their own point (`current` the flow there, `wet` 0 in vacuum).
void Vehicle::finLoads(double t, const ElementKinematics& k, const Eigen::Vector3d& current, double wet,
                       const Actuators& actuators, const BodyFrame& frame, Loads& out) const
{
  const double tail = p_.tail_from_bail;
  out.rudder = actuators.rudder.angleAt(t);
  out.elevator = actuators.elevator.angleAt(t);
  FinPairParams rudder = p_.rudder, elevator = p_.elevator;
  rudder.lift_constant *= wet;
  rudder.drag_constant *= wet;
  elevator.lift_constant *= wet;
  elevator.drag_constant *= wet;
  // (P57b): a rolling vehicle's spin p moves the rudder's centre of pressure, rudder_height above the axis, by
  // p x_b x (h_r z_b) = -p h_r y_b, and each elevator fin by its span (differentialElevatorLoads).
  const double spin = rolls() ? k.roll_rate : 0.0;
  const Eigen::Vector3d v_vf =
      k.velocityAt(p_.vertical_fin_from_bail / tail) - current - spin * p_.rudder_height * frame.y;
  const Eigen::Vector3d v_hf = k.velocityAt(p_.horizontal_fin_from_bail / tail) - current;
  out.rudder_loads = finPairLoads(rudder, FinPlane::kVertical, out.rudder, v_vf, frame.x, frame.y, frame.z,
                                  p_.vertical_fin_from_bail - p_.cg_from_bail);
  out.differential = actuators.differential.angleAt(t);
  if (out.differential == 0.0 && spin == 0.0)
    out.elevator_loads = finPairLoads(elevator, FinPlane::kHorizontal, out.elevator, v_hf, frame.x, frame.y, frame.z,
                                      p_.horizontal_fin_from_bail - p_.cg_from_bail);
  else
    out.elevator_loads =
        differentialElevatorLoads(elevator, out.elevator, out.differential, v_hf, frame,
                                  p_.horizontal_fin_from_bail - p_.cg_from_bail, p_.elevator_span, spin);
  if (p_.rudder_height != 0.0)  // (P57): the rudder's loads act rudder_height above the axis: its heel moment
    out.rudder_loads.moment_cg_W +=
        (p_.rudder_height * frame.z).cross(out.rudder_loads.lift_W + out.rudder_loads.drag_W);
}

BodyFrame Vehicle::frameAt(const ElementKinematics& k, const Eigen::Vector3d& v_cg_through_water) const
{
  return rolled(bodyFrame(k.s, headingHint(v_cg_through_water)), k);
}

BodyFrame Vehicle::rolled(const BodyFrame& level, const ElementKinematics& k) const
{
  return rolls() ? rolledFrame(level, k.roll) : level;
}

// (P57): rolling, the body also spins at p about x_b.
Eigen::Vector3d Vehicle::angularVelocity(const ElementKinematics& k, const BodyFrame& frame) const
{
  return rolls() ? Eigen::Vector3d(k.omega + k.roll_rate * frame.x) : k.omega;
}

void Vehicle::dynamics(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
                       BodyDynamics& out) const
{
  fullDynamics(t, k, env, actuators, out);
  if (!rolls())
    return;
  // (P59): domega/dt = S (a_a - a_f) + (dp/dt) x_b - p ds/dt. The known part -p ds/dt moves to the wrench; the
  // moment equation along x_b (which no tension reaches: the bail is on the axis) gives dp/dt, and its
  // elimination leaves M' = M - M e e^T M / (e^T M e), w' = w - M e (e^T w) / (e^T M e), e = [0; x_b].
  Vector6d bias;
  bias << Eigen::Vector3d::Zero(), -k.roll_rate * k.s_dot;
  out.wrench -= out.mass * bias;
  const SpinAxis axis = spinAxis(k.s, out.mass);
  out.wrench -= axis.Me * (axis.e.dot(out.wrench) / axis.m_ee);
  out.mass -= axis.Me * axis.Me.transpose() / axis.m_ee;
}

Eigen::Vector2d Vehicle::rollRates(double t, const ElementKinematics& k, const Environment& env,
                                   const Actuators& actuators, const Eigen::Vector3d& a_f,
                                   const Eigen::Vector3d& a_a) const
{
  if (!rolls())
    return Eigen::Vector2d::Zero();
  BodyDynamics full;
  fullDynamics(t, k, env, actuators, full);
  Vector6d joints;
  joints << a_f, a_a;
  Vector6d acceleration = jointMap(k.s, k.length, full.cg_fraction) * joints;  // [a_G; S (a_a - a_f)]
  acceleration.tail<3>() -= k.roll_rate * k.s_dot;
  const SpinAxis axis = spinAxis(k.s, full.mass);
  const double spin_acceleration = (axis.e.dot(full.wrench) - axis.Me.dot(acceleration)) / axis.m_ee;  // (P59)
  return { k.roll_rate - zeroRollFrameSpin(k.s, k.s_dot), spin_acceleration };                         // (P58)
}

void Vehicle::fullDynamics(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
                           BodyDynamics& out) const
{
  const double gamma = p_.cg_from_bail / p_.tail_from_bail;
  const Eigen::Vector3d v_cg = k.velocityAt(gamma);
  const WaveKinematics flow = env.flowAt(k.pointAt(gamma), t);
  const Eigen::Vector3d& current = flow.velocity_W;
  const BodyFrame frame = frameAt(k, v_cg - current);
  const Eigen::Matrix3d R = frame.rotation();
  const Eigen::Vector3d omega = angularVelocity(k, frame);
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d inertia_W = R * p_.inertia_B * R.transpose();
  out.cg_fraction = gamma;
  out.mass.setZero();
  out.mass.topLeftCorner<3, 3>() = p_.mass * I3;
  out.mass.bottomRightCorner<3, 3>() = inertia_W;

  const Loads l = loads(t, k, env, actuators, frame);
  out.wrench = l.wrench;
  // d(I w)/dt = I dw/dt + w x I w with w = s x ds/dt (+ p x_b rolling).
  out.wrench.tail<3>() -= omega.cross(inertia_W * omega);

  const Matrix6d rigid = out.mass;
  if (p_.added_mass_approach == AddedMassApproach::kA)
  {
    // -e P (a_mid), a_mid = a_G + dw/dt x r, r from the CG to the bail-tail midpoint.
    const double e = env.water_density > 0.0 ? p_.added_mass_a : 0.0;
    const Eigen::Matrix3d P = I3 - k.s * k.s.transpose();
    const Eigen::Matrix3d S = skew((0.5 * p_.tail_from_bail - p_.cg_from_bail) * k.s);
    out.mass.topLeftCorner<3, 3>() += e * P;
    out.mass.topRightCorner<3, 3>() -= e * S;
    out.mass.bottomLeftCorner<3, 3>() += e * S;
    out.mass.bottomRightCorner<3, 3>() -= e * S * S;
    if (rolls() && env.water_density > 0.0)  // (P57): the added inertia about the axis
      out.mass.bottomRightCorner<3, 3>() += p_.roll_added_inertia * frame.x * frame.x.transpose();
  }
  else
  {
    // The spheroid's matrix is per unit density; a given matrix holds in water and vanishes in vacuum.
    const double density_scale = p_.prolate_spheroid ? env.water_density : (env.water_density > 0.0 ? 1.0 : 0.0);
    const Matrix6d A = density_scale * added_mass_b_;
    const Matrix6d T = blockRotation(R);
    out.mass += T * A * T.transpose();
    if (p_.munk_terms)
    {
      const Vector6d munk = munkWrench(A, R.transpose() * (v_cg - current), R.transpose() * omega);
      out.wrench.head<3>() += R * munk.head<3>();
      out.wrench.tail<3>() += R * munk.tail<3>();
    }
  }
  if (env.wave_field)
  {
    const Matrix6d added = out.mass - rigid;
    out.wrench += waveInertiaWrench(added.topLeftCorner<3, 3>(), added.bottomLeftCorner<3, 3>(),
                                    env.water_density * p_.displaced_volume, (p_.cb_from_bail - p_.cg_from_bail) * k.s,
                                    flow.acceleration_W);
  }
}

VehicleOutputs Vehicle::outputs(double t, const ElementKinematics& k, const Environment& env,
                                const Actuators& actuators) const
{
  const double gamma = p_.cg_from_bail / p_.tail_from_bail;
  VehicleOutputs o;
  o.p_cg_W = k.pointAt(gamma);
  o.v_cg_W = k.velocityAt(gamma);
  const BodyFrame level = bodyFrame(k.s, headingHint(o.v_cg_W - env.flowAt(o.p_cg_W, t).velocity_W));
  const BodyFrame frame = rolled(level, k);
  const Eigen::Matrix3d R = frame.rotation();
  o.q_WB = Eigen::Quaterniond(R).normalized();
  o.v_cg_B = R.transpose() * o.v_cg_W;
  o.omega_W = angularVelocity(k, frame);
  o.omega_B = R.transpose() * o.omega_W;
  o.roll = rolls() ? std::remainder(k.roll, 2.0 * kPi) : 0.0;
  o.depth = -o.p_cg_W.z();
  o.pitch = pitchOf(level.x);
  o.yaw = yawOf(level.y);
  const Loads l = loads(t, k, env, actuators, frame);
  o.rudder = l.rudder;
  o.elevator = l.elevator;
  o.differential = l.differential;
  o.thrust = l.thrust;
  o.rudder_loads = l.rudder_loads;
  o.elevator_loads = l.elevator_loads;
  for (FinPairLoads* f : { &o.rudder_loads, &o.elevator_loads })
  {
    f->lift_B = R.transpose() * f->lift_W;
    f->drag_B = R.transpose() * f->drag_W;
    f->moment_cg_B = R.transpose() * f->moment_cg_W;
  }
  return o;
}

const ParamTable<VehicleParams>& vehicleParams()
{
  using V = VehicleParams;
  const auto along = [](const V& v) { return std::make_pair(-v.nose_from_bail, v.tail_from_bail); };
  const char* along_text = "from -nose_from_bail to tail_from_bail";
  auto get = inertiaGetter;
  auto set = inertiaSetter;
  static const ParamTable<V> table =
      ParamTable<V>()
          .number("tail_from_bail", &V::tail_from_bail, "m", 0.0, 100.0, kOpen,
                  "d_{ν+1}: the tail point, which fixes the axis")
          .bounded("cg_from_bail", &V::cg_from_bail, "m", along, along_text, "d_{ν+2}: centre of gravity")
          .bounded("horizontal_fin_from_bail", &V::horizontal_fin_from_bail, "m", along, along_text,
                   "d_{ν+3}: elevator axis")
          .bounded("vertical_fin_from_bail", &V::vertical_fin_from_bail, "m", along, along_text, "d_{ν+4}: rudder axis")
          .number("nose_from_bail", &V::nose_from_bail, "m", 0.0, 100.0, kClosed, "d_{ν+5}, measured forward")
          .bounded("cb_from_bail", &V::cb_from_bail, "m", along, along_text, "d_{ν+6}: centre of buoyancy")
          .number("mass", &V::mass, "kg", 0.0, 1e6, kOpen, "in air")
          .number("displaced_volume", &V::displaced_volume, "m^3", 0.0, 1e3, kClosed, "buoyancy ρgV at the CB")
          .numberAt("inertia.xx", get(0, 0), set(0, 0), "kg m^2", 0.0, 1e9, kOpen,
                    "roll inertia about the CG, body axes (FLU)")
          .numberAt("inertia.yy", get(1, 1), set(1, 1), "kg m^2", 0.0, 1e9, kOpen,
                    "pitch inertia (the matrix: positive definite)")
          .numberAt("inertia.zz", get(2, 2), set(2, 2), "kg m^2", 0.0, 1e9, kOpen, "yaw inertia")
          .numberAt("inertia.xy", get(0, 1), set(0, 1), "kg m^2", -1e9, 1e9, kClosed,
                    "product of inertia (the matrix symmetric)")
          .numberAt("inertia.xz", get(0, 2), set(0, 2), "kg m^2", -1e9, 1e9, kClosed, "product of inertia")
          .numberAt("inertia.yz", get(1, 2), set(1, 2), "kg m^2", -1e9, 1e9, kClosed, "product of inertia")
          .number("c1", &V::c1, "N s^2/m^3", 0.0, 1e6, kClosed, "tangential velocity-force constant (bail to tail)")
          .number("c2", &V::c2, "N s^2/m^3", 0.0, 1e6, kClosed, "normal one, with its rotation-drag moment")
          .choice("added_mass.approach", &V::added_mass_approach,
                  { { "A", AddedMassApproach::kA }, { "B", AddedMassApproach::kB } },
                  "A: −e(a − (a·s)s) at the bail–tail midpoint (report); B: Kirchhoff 6×6")
          .number("added_mass.e", &V::added_mass_a, "kg", 0.0, 1e6, kClosed, "e_{ν+1} of Approach A")
          .custom("added_mass.matrix", "kg, kg m, kg m^2", "zeros", "symmetric positive semi-definite",
                  "Approach B about the CG in body axes: 36 numbers row by row, or the 21 of its upper triangle")
          .custom("added_mass.prolate_spheroid", "m", "none", "length > 0, 0 < diameter ≤ length",
                  "{length, diameter, center_from_bail}: the matrix from Lamb's k₁, k₂, k′ (instead of matrix)")
          .boolean("added_mass.munk_terms", &V::munk_terms,
                   "Approach B: keep Kirchhoff's velocity-product (Munk) terms; the report drops them")
          .number("max_thrust", &V::max_thrust, "N", 0.0, 1e6, kClosed, "thrust commands saturate at ±this")
          .number("thrust_offset_z", &V::thrust_offset_z, "m", -10.0, 10.0, kClosed,
                  "the thrust's line of action above (+z_b) the axis")
          .nest("rudder", &V::rudder, finParams())
          .nest("elevator", &V::elevator, finParams())
          .choice("roll", &V::roll, { { "fixed", VehicleRoll::kFixed }, { "free", VehicleRoll::kFree } },
                  "fixed: no roll, the report's; free: a roll degree of freedom about the axis (physics.md §5b)")
          .number("cb_above_cg", &V::cb_above_cg, "m", -10.0, 10.0, kClosed,
                  "h_BG: the CB above the CG along z_b; ρgV h_BG sin φ restores roll (and pitch)")
          .number("rudder_height", &V::rudder_height, "m", -10.0, 10.0, kClosed,
                  "the rudder's centre of pressure above the axis: its lift and drag heel the vehicle")
          .number("roll_damping", &V::roll_damping, "N m s/rad", 0.0, 1e9, kClosed,
                  "the hull's linear roll damping against the spin (roll: free; the fins' own: physics.md (P57b))")
          .number("roll_added_inertia", &V::roll_added_inertia, "kg m^2", 0.0, 1e9, kClosed,
                  "Approach A's added inertia about x_b (roll: free; Approach B: its matrix's)")
          .number("elevator_span", &V::elevator_span, "m", 0.0, 10.0, kClosed,
                  "each elevator fin's centre of pressure out from the axis: the differential's roll arm, the spin's "
                  "lever");
  return table;
}

}  // namespace tow_sim
