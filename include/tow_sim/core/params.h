// Constant model parameters of the towed system: cable, end element, water and numerics.
// Plain structs with SI defaults; validate() throws std::invalid_argument naming the parameter,
// the value and the allowed range. Symbols follow Strandhagen & Thomas (1963).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tow_sim/core/cable_loading.h"
#include "tow_sim/core/environment/waves.h"
#include "tow_sim/core/param_table.h"

namespace tow_sim
{
// How the tangential (skin-friction) drag of a cable element depends on the flow (physics.md §4).
enum class TangentialDragModel
{
  kPode,      // report: magnitude C1 d |u|^2 whatever the orientation, along s against the tangential flow
  kQuadratic  // -C1 d |u.s| (u.s) s
};

// The normal drag of a strumming cable (physics.md §13, (P55)): none (the report's), or amplified by a
// published empirical law of the cross-flow amplitude A/D.
enum class StrummingLaw
{
  kNone,
  kVandiver,  // Vandiver (1983): 1 + 1.043 (2 A_rms / D)^0.65, A_rms = A / sqrt(2)
  kBlevins    // Blevins (1990): 1 + 2.1 A / D
};

// One point of a current profile: the current at a depth.
struct CurrentSample
{
  double depth = 0.0;                                    // [m] below the surface, 0 .. 12000
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();  // [m/s] world ENU, each component -20 .. 20
};

struct Environment
{
  double gravity = 9.81;                                // [m/s^2] g, 0 .. 100
  double water_density = 1025.0;                        // [kg/m^3] rho, 0 (vacuum) .. 2000
  Eigen::Vector3d current_W = Eigen::Vector3d::Zero();  // [m/s] uniform current, world ENU, |.| <= 20
  // Depth-dependent part, added to current_W: linear between samples (depths strictly increasing),
  // the end values beyond them, nothing when empty. At most 10000 samples.
  std::vector<CurrentSample> current_profile;

  WaveParams waves;  // calm water by default
  // The sea of `waves`, built by prepareWaves() (ChainModel does); none: calm water.
  std::shared_ptr<const WaveField> wave_field;
  // [s] the sea's clock at the run's t = 0: the waves at run time t are the field's at t + wave_time (the
  // node sets its time origin's ROS time, so that ship_motion_node's ship heaves in the same sea).
  double wave_time = 0.0;

  // [m/s] the current at height z_W [m] (world, z up; depth = -z).
  Eigen::Vector3d currentAt(double z_W) const
  {
    if (current_profile.empty())
      return current_W;
    return current_W + profileAt(-z_W);
  }
  // The water's velocity (current plus waves) and acceleration (the waves') at p_W [m], time t [s].
  WaveKinematics flowAt(const Eigen::Vector3d& p_W, double t) const
  {
    WaveKinematics flow = wave_field ? wave_field->kinematics(p_W, t + wave_time) : WaveKinematics();
    flow.velocity_W += currentAt(p_W.z());
    return flow;
  }
  // The flow a segment from p_f to p_a [m] sees at time t [s]: the current at its centre; the waves at the
  // centre of its part below the mean surface z = 0, times that part's fraction of its length, so that
  // the waves fade in and out continuously as a segment crosses the surface (the splash zone).
  WaveKinematics flowOver(const Eigen::Vector3d& p_f, const Eigen::Vector3d& p_a, double t) const;

private:
  Eigen::Vector3d profileAt(double depth) const;
};

// The simple rigid end element (element nu+1) of the cable core: an axisymmetric rigid body on the
// axis bail -> tail point, with weight at its CG, buoyancy at its CB and cable-like velocity forces.
// Distances are measured from the bail (cable attachment) aft along the body axis.
struct EndElementParams
{
  double length = 2.0;                        // [m] d_{nu+1}, bail to tail point, > 0 .. 100
  double mass = 200.0;                        // [kg] in air, > 0 .. 1e6
  double displaced_volume = 0.1414;           // [m^3] buoyancy rho g V acts at the CB, >= 0 .. 1e3
  double cg_from_bail = 1.0;                  // [m] d_{nu+2}, 0 .. length
  double cb_from_bail = 1.0;                  // [m] d_{nu+6}, 0 .. length
  std::optional<double> transverse_inertia;   // [kg m^2] about the CG; default: thin rod over `length`
  double diameter = 0.3;                      // [m] for drag and added mass, > 0 .. 10
  double normal_drag_coefficient = 1.0;       // [-] >= 0 .. 10
  double tangential_drag_coefficient = 0.05;  // [-] >= 0 .. 10
  double added_mass_coefficient = 1.0;        // [-] >= 0 .. 10

  double transverseInertia() const;  // [kg m^2] about the CG
};

// A winged depressor in line in the cable (physics.md §11): a rigid element between two joints, the end element's
// body (its "bail" the fore attachment, its "tail point" the aft one) with a wing whose lift presses it down.
struct DepressorParams : EndElementParams
{
  double wing_area = 0.0;         // [m^2] S, >= 0 .. 100
  double lift_coefficient = 0.0;  // [-] C_L, >= 0 .. 5: lift 1/2 rho S C_L |u_p|^2, normal to the flow, downward
  double lift_from_bail = 1.0;    // [m] where the lift acts, 0 .. length
};

struct CableParams
{
  double length = 500.0;                      // [m] total cable length L, > 0 .. 1e5
  int segments = 100;                         // [-] number of rigid segments nu, 1 .. 100000
  double diameter = 0.02;                     // [m] D, > 0 .. 1
  double mass_per_length = 1.0;               // [kg/m] in air, > 0 .. 1000
  double normal_drag_coefficient = 1.2;       // [-] C_dn, >= 0 .. 10 (C2 = rho C_dn D / 2)
  double tangential_drag_coefficient = 0.01;  // [-] C_dt, >= 0 .. 1 (C1 = rho C_dt pi D / 2)
  std::optional<double> c1;                   // [N s^2/m^3] C1 given directly (overrides C_dt), >= 0
  std::optional<double> c2;                   // [N s^2/m^3] C2 given directly (overrides C_dn), >= 0
  double added_mass_coefficient = 1.0;        // [-] C_a, >= 0 .. 10 (e = C_a rho pi D^2/4 d)
  TangentialDragModel tangential_drag_model = TangentialDragModel::kPode;
  // A faired cable's loading functions (physics.md §11, (P56)) in place of the drag coefficients above; unset,
  // the bare cable's Pode loading (the report's). Shared and constant: copies of the cable share it.
  std::shared_ptr<const CableLoading> loading;
  std::optional<double> safe_working_load;  // [N] the node warns above it (unset: no limit), > 0 .. 1e9
  std::optional<double> breaking_load;      // [N] the node reports an error above it, >= safe_working_load .. 1e9
  // The cable parts at the joint where a tension first exceeds breaking_load (needs it): the part on the
  // vehicle side goes on with a free end (physics.md, docs/solver.md §9), the ship side hangs from the ship (§10).
  bool break_at_breaking_load = false;
  // The elastic, tension-only cable (physics.md §9): unset, the rigid inextensible chain (the report's).
  std::optional<double> axial_stiffness;  // [N] EA, > 0 .. 1e11
  double axial_damping = 0.0;             // [N s] c, the axial force per unit strain rate, >= 0 .. 1e10
  // Bending (physics.md §11): a restoring moment at each joint between two segments (0: none, the report's).
  double bending_stiffness = 0.0;  // [N m^2] EI, >= 0 .. 1e9
  // Strumming (physics.md §13): the vortices' shedding frequency St |u_n| / D, and while the cable strums
  // (strumming set) its normal drag C2 times the law's amplification at the amplitude A/D.
  StrummingLaw strumming = StrummingLaw::kNone;
  double strumming_amplitude = 1.0;  // [-] A/D, the cross-flow amplitude over the diameter, > 0 .. 3
  double strouhal_number = 0.2;      // [-] St, > 0 .. 1
  // A section may be a winged depressor instead of cable: one rigid element of the depressor's length (sections
  // only; set: segments 1, length the depressor's; the cable's other keys of this section are not used).
  std::optional<DepressorParams> depressor;

  bool elastic() const { return axial_stiffness.has_value(); }
  // [N] the tension of a segment of rest length rest [m] at length length [m] stretching at rate [m/s]:
  // T = max(0, EA eps + c deps/dt), eps = length / rest - 1 (elastic cables only).
  double axialTension(double length, double rate, double rest) const
  {
    const double t = *axial_stiffness * (length / rest - 1.0) + axial_damping * rate / rest;
    return t > 0.0 ? t : 0.0;
  }

  double segmentLength() const { return length / segments; }
  double c1Value(const Environment& env) const;  // [N s^2/m^3]
  double c2Value(const Environment& env) const;  // [N s^2/m^3], the cable at rest in the flow
  double normalDragAmplification() const;        // [-] of strumming (P55): 1 without it
};

enum class StepperType
{
  kDopri5,        // adaptive Dormand-Prince 5(4) with error control
  kRk4,           // classical Runge-Kutta with a fixed step
  kImplicit,      // linearly implicit Rosenbrock-W (ROS2) with error control, O(nu) stages (default)
  kImplicitFixed  // the same with a fixed step, for hard real time
};

// The implicit steppers take whole steps of their own (the node interpolates its outputs between them).
inline bool isImplicit(StepperType s)
{
  return s == StepperType::kImplicit || s == StepperType::kImplicitFixed;
}

enum class ImplicitMethod
{
  kRos34pw2,  // 4 stages, order 3, embedded order 2 (Rang and Angermann 2005) (default)
  kRos2       // 2 stages, order 2, embedded order 1 (Verwer et al. 1999)
};

// The frame the implicit steppers' stages are taken in (docs/solver.md (S28)).
enum class ImplicitFrame
{
  kWorld,    // the joints as they are, the tow point's motion entering through the first element
  kTowPoint  // the joints relative to the tow point, its motion entering every joint alike (default)
};

struct NumericsParams
{
  StepperType stepper = StepperType::kImplicit;
  ImplicitMethod implicit_method = ImplicitMethod::kRos34pw2;
  ImplicitFrame implicit_frame = ImplicitFrame::kTowPoint;
  double abs_tol = 1e-7;                     // [-] absolute error tolerance of dopri5 (m, m/s), > 0 .. 1
  double rel_tol = 1e-7;                     // [-] relative error tolerance of dopri5, > 0 .. 1
  double implicit_position_tol = 1e-5;       // [m] absolute tolerance of implicit on positions, > 0 .. 10
  double implicit_velocity_tol = 1e-5;       // [m/s] absolute tolerance of implicit on velocities, > 0 .. 10
  double implicit_rel_tol = 1e-5;            // [-] relative tolerance of implicit, > 0 .. 1
  double max_step = 5.0;                     // [s] largest adaptive step, > 0 .. 10
  double fixed_step = 0.01;                  // [s] step of the fixed-step steppers, > 0 .. 1
  double tangential_smoothing_speed = 0.01;  // [m/s] Pode drag changes sign smoothly over this |u.s|, > 0 .. 1
};

// The winch at the tow point (physics: the first segment, at the ship, changes length; segments are
// split off or merged into it there so that it stays within its band).
struct WinchParams
{
  bool enabled = false;               // off: the cable length is fixed and winch commands are refused
  double min_length = 50.0;           // [m] least cable out, >= segment_min_fraction * L / nu
  double max_length = 2000.0;         // [m] most cable out, >= min_length, <= 1e5
  double max_rate = 2.0;              // [m/s] payout and haul-in rate limit, (0, 20]
  double max_acceleration = 0.5;      // [m/s^2] limit on the rate's change, (0, 100]
  double response_time = 1.0;         // [s] the rate follows the command with this lag (then the limits), [0.01, 100]
  double segment_min_fraction = 0.5;  // [-] the first segment is merged into the next below this * L / nu, [0.1, 1)
  double segment_max_fraction = 1.5;  // [-] and split above this * L / nu, >= segment_min_fraction + 1, <= 10
};

// Each throws std::invalid_argument("<prefix>.<name> = <value> is out of range: must be ...").
void validate(const Environment& env, const std::string& prefix = "environment");
// Builds env.wave_field from env.waves and env.gravity (none for calm water); validates them first.
void prepareWaves(Environment& env);
void validate(const CableParams& cable, const std::string& prefix = "cable");
void validate(const EndElementParams& end, const std::string& prefix = "end_element");
void validate(const DepressorParams& depressor, const std::string& prefix);
void validate(const NumericsParams& numerics, const std::string& prefix = "numerics");
// Also checks the winch against the cable (its length within the limits, the band against L / nu).
void validate(const WinchParams& winch, const CableParams& cable, const std::string& prefix = "winch");

}  // namespace tow_sim
