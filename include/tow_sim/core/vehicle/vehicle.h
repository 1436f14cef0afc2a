// The towed vehicle, element nu+1 (physics.md §5): rigid body with full inertia tensor, weight at the
// CG, buoyancy at the CB, cable-like velocity forces, propeller thrust, two fin pairs on servos, and
// Approach A or Approach B (Kirchhoff, optional Munk terms) added mass.
//
// Geometry on the body axis, distances from the bail (cable attachment) measured aft along
// s = -x_b, except the nose, measured forward. Body frame FLU with zero roll (Appendix G):
// x_b = -s forward, y_b = z x x_b / |z x x_b| (horizontal, to port), z_b = x_b x y_b.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "tow_sim/core/chain/element.h"
#include "tow_sim/core/param_table.h"
#include "tow_sim/core/vehicle/fins.h"

namespace tow_sim
{
enum class AddedMassApproach
{
  kA,  // report Approach A: like a cable element, -e (a - (a.s) s) at the bail-tail midpoint
  kB   // report Approach B: Kirchhoff, a symmetric 6x6 matrix about the CG in body axes
};

// Whether the vehicle rolls (physics.md §5b).
enum class VehicleRoll
{
  kFixed,  // the report's: no roll, a roll-stabilised body (or a swivel at the bail)
  kFree    // a roll degree of freedom about the axis: restoring, damping and heel moments act on it
};

struct ProlateSpheroid
{
  double length = 2.0;            // [m] 2a, > 0
  double diameter = 0.3;          // [m] 2b, (0, length]
  double center_from_bail = 0.2;  // [m] where its centre lies, aft of the bail
};

struct VehicleParams
{
  // Geometry [m], from the bail.
  double tail_from_bail = 1.2;            // d_{nu+1}, the tail point, (0, 100]
  double cg_from_bail = 0.1;              // d_{nu+2}, [-nose, tail]
  double horizontal_fin_from_bail = 1.0;  // d_{nu+3}, [-nose, tail]
  double vertical_fin_from_bail = 1.0;    // d_{nu+4}, [-nose, tail]
  double nose_from_bail = 0.8;            // d_{nu+5}, measured forward, [0, 100]
  double cb_from_bail = 0.08;             // d_{nu+6}, [-nose, tail]
  // Mass properties.
  double mass = 180.0;             // [kg] in air, (0, 1e6]
  double displaced_volume = 0.12;  // [m^3] buoyancy rho g V at the CB, [0, 1e3]
  Eigen::Matrix3d inertia_B = Eigen::Vector3d(2.0, 61.0, 61.0).asDiagonal();  // [kg m^2] about the CG, FLU
  // Velocity forces over the bail-tail length, as for a cable element (Appendix D). Hydrodynamic
  // constants (c1, c2, fins, Approach A e, a given Approach B matrix) hold in water; with
  // water_density = 0 (vacuum) every hydrodynamic load is off.
  double c1 = 25.0;   // [N s^2/m^3] tangential, Pode form, [0, 1e6]
  double c2 = 250.0;  // [N s^2/m^3] normal, [0, 1e6]
  // Added mass.
  AddedMassApproach added_mass_approach = AddedMassApproach::kA;
  double added_mass_a = 145.0;                      // [kg] e_{nu+1} of Approach A, [0, 1e6]
  Matrix6d added_mass_b = Matrix6d::Zero();         // [kg, kg m, kg m^2] Approach B about the CG, FLU body axes
  std::optional<ProlateSpheroid> prolate_spheroid;  // Approach B: fills added_mass_b from Lamb's k1, k2, k'
  bool munk_terms = false;                          // Approach B: keep Kirchhoff's velocity-product terms
  // Propulsion.
  double max_thrust = 500.0;     // [N] commands saturate at +-this, [0, 1e6]
  double thrust_offset_z = 0.0;  // [m] line of action above (+z_b) the axis, [-10, 10]
  // Fins: vertical pair (rudder, alpha) and horizontal pair (elevator, beta).
  FinPairParams rudder;
  FinPairParams elevator;
  // Roll (physics.md §5b). cb_above_cg and rudder_height act in both modes (0 by default: the report's body).
  VehicleRoll roll = VehicleRoll::kFixed;
  double cb_above_cg = 0.0;         // [m] h_BG: the CB above the CG along z_b, [-10, 10]
  double rudder_height = 0.0;       // [m] the rudder's centre of pressure above the axis (+z_b), [-10, 10]
  double roll_damping = 0.0;        // [N m s/rad] the hull's, linear, against the spin, [0, 1e9]
  double roll_added_inertia = 0.0;  // [kg m^2] Approach A's added inertia about x_b, [0, 1e9]
  double elevator_span = 0.25;      // [m] each elevator fin's centre of pressure out from the axis, [0, 10]
};
// The parameter table of the vehicle (param_table.h): every key with its unit, range, default and meaning.
const ParamTable<VehicleParams>& vehicleParams();

// Throws std::invalid_argument naming the parameter ("vehicle.<key>"), the value and the range.
void validate(const VehicleParams& vehicle, const std::string& prefix = "vehicle");

// Body frame with zero roll from the axis s (bail -> tail). When the axis is vertical (within 1e-6 rad)
// y_b is taken normal to `heading_hint` (a horizontal forward direction) instead.
struct BodyFrame
{
  Eigen::Vector3d x, y, z;  // world components of x_b, y_b, z_b
  bool vertical = false;
  Eigen::Matrix3d rotation() const;  // R_WB = [x_b y_b z_b]
};
BodyFrame bodyFrame(const Eigen::Vector3d& s, const Eigen::Vector3d& heading_hint = Eigen::Vector3d::UnitX());
// The frame f turned by the roll phi [rad] about its x_b (positive: starboard side down), physics.md (P57).
BodyFrame rolledFrame(const BodyFrame& f, double phi);
// The zero-roll frame's (P1) own turning rate about x_b [rad/s] for the axis s and its rate s_dot: the roll
// angle from that frame changes at the spin less this, (P58). Zero within 1e-6 rad of the vertical.
double zeroRollFrameSpin(const Eigen::Vector3d& s, const Eigen::Vector3d& s_dot);

// The attitude to publish. The upright zero-roll frame has no heading when the axis is vertical, and
// near it the heading follows the tiny horizontal part of the axis, so a vehicle hanging almost still
// would spin in the published attitude. Within `hold_cone` of the vertical the last heading from
// outside the cone is held; between hold_cone and 2 hold_cone it blends into the axis' own heading;
// beyond that it is the zero-roll frame of the dynamics. A swing through the vertical wider than the
// cone still turns the heading by 180 degrees (inherent in a zero-roll frame), spread over the band.
class AttitudeHold
{
public:
  explicit AttitudeHold(double hold_cone = 0.087) : cone_(hold_cone) {}  // [rad], 5 deg
  Eigen::Quaterniond update(const Eigen::Vector3d& x_b_W);               // the body's forward axis, world
  void reset() { has_heading_ = false; }
  double cone() const { return cone_; }
  // The held yaw [rad] (a saved state); NaN: none held.
  double heldHeading() const { return has_heading_ ? heading_ : std::numeric_limits<double>::quiet_NaN(); }
  void restoreHeading(double heading)
  {
    has_heading_ = std::isfinite(heading);
    heading_ = has_heading_ ? heading : 0.0;
  }

private:
  double cone_;
  bool has_heading_ = false;
  double heading_ = 0.0;  // [rad] held yaw
};

// What the vehicle reports at one instant.
struct VehicleOutputs
{
  Eigen::Vector3d p_cg_W;               // [m] CG position, world
  Eigen::Quaterniond q_WB;              // body (FLU, zero roll unless the vehicle rolls) to world
  Eigen::Vector3d v_cg_W, v_cg_B;       // [m/s] CG velocity over ground, world and body axes
  Eigen::Vector3d omega_W, omega_B;     // [rad/s] angular velocity s x ds/dt (+ p x_b rolling), world and body axes
  double roll = 0.0;                    // [rad] from the zero-roll frame, positive starboard down (0: roll fixed)
  double depth = 0.0;                   // [m] of the CG, -z
  double pitch = 0.0;                   // [rad] REP-103 Euler pitch: rotation about y_b, positive nose DOWN
  double yaw = 0.0;                     // [rad] heading of x_b from world x, counter-clockwise (ENU)
  double rudder = 0.0, elevator = 0.0;  // [rad] actual fin angles
  double differential = 0.0;            // [rad] the elevator's actual differential (starboard fin +, port -)
  double thrust = 0.0;                  // [N] actual thrust
  FinPairLoads rudder_loads, elevator_loads;
};

// Constant after construction: the fin angles and the thrust are Actuators, held by the running chain.
class Vehicle : public EndBody
{
public:
  // Validates (std::invalid_argument naming "vehicle.<key>"); the Approach B matrix is checked here.
  explicit Vehicle(const VehicleParams& params, const NumericsParams& numerics = NumericsParams());

  double length() const override { return p_.tail_from_bail; }
  // The hull's ends touch the seabed: the nose and the tail point.
  std::vector<double> contactFractions() const override { return { -p_.nose_from_bail / p_.tail_from_bail, 1.0 }; }
  // Rolling, the equations with the spin's acceleration eliminated (physics.md (P59)).
  void dynamics(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
                BodyDynamics& out) const override;
  bool rolls() const override { return p_.roll == VehicleRoll::kFree; }
  // (P58)-(P59): the roll angle's and the spin's rates; zero when the roll is fixed.
  Eigen::Vector2d rollRates(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
                            const Eigen::Vector3d& a_f, const Eigen::Vector3d& a_a) const override;

  // Fins centred on servos with this vehicle's limits, no thrust, at time t [s].
  Actuators restingActuators(double t) const override;
  // Fin and thrust commands from time t on; values beyond the limits saturate. Returns true when
  // something saturated (the caller may warn).
  bool command(Actuators& actuators, double t, double rudder, double elevator, double thrust) const override;
  bool commandDifferential(Actuators& actuators, double t, double differential) const override;

  VehicleOutputs outputs(double t, const ElementKinematics& k, const Environment& env,
                         const Actuators& actuators) const;
  const VehicleParams& params() const { return p_; }
  const Matrix6d& addedMassB() const { return added_mass_b_; }  // about the CG, body axes

private:
  struct Loads;
  Loads loads(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
              const BodyFrame& frame) const;
  // The rudder's and the elevator's angles and loads into `out`, each fin in the flow at its own point.
  void finLoads(double t, const ElementKinematics& k, const Eigen::Vector3d& current, double wet,
                const Actuators& actuators, const BodyFrame& frame, Loads& out) const;
  // Newton-Euler about the CG at the body's roll, the spin's acceleration not yet eliminated.
  void fullDynamics(double t, const ElementKinematics& k, const Environment& env, const Actuators& actuators,
                    BodyDynamics& out) const;
  // The body frame at k's axis and roll; the flow's heading hint from the CG's velocity through the water.
  BodyFrame frameAt(const ElementKinematics& k, const Eigen::Vector3d& v_cg_through_water) const;
  // The level (zero-roll) frame turned by the roll, when the vehicle rolls (physics.md (P57)).
  BodyFrame rolled(const BodyFrame& level, const ElementKinematics& k) const;
  // omega = s x ds/dt, plus p x_b when it rolls (P57).
  Eigen::Vector3d angularVelocity(const ElementKinematics& k, const BodyFrame& frame) const;

  VehicleParams p_;
  double smoothing_speed_;
  Matrix6d added_mass_b_;
};

}  // namespace tow_sim
