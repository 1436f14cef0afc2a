#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/constants.h"

#include <algorithm>

namespace tow_sim
{
namespace
{
constexpr bool kOpen = true;     // (lo, hi]
constexpr bool kClosed = false;  // [lo, hi]
}  // namespace

const ParamTable<CableParams>& cableParams()
{
  using C = CableParams;
  static const ParamTable<C> table =
      ParamTable<C>()
          .number("length", &C::length, "m", 0.0, 1e5, kOpen, "total cable length L")
          .integer("segments", &C::segments, "-", 1, 100000, "number of rigid segments ν (segment length L/ν)")
          .number("diameter", &C::diameter, "m", 0.0, 1.0, kOpen, "D")
          .number("mass_per_length", &C::mass_per_length, "kg/m", 0.0, 1000.0, kOpen,
                  "mass per length in air (w = mass_per_length · g)")
          .number("normal_drag_coefficient", &C::normal_drag_coefficient, "-", 0.0, 10.0, kClosed,
                  "C_dn; C₂ = ½ρ C_dn D")
          .number("tangential_drag_coefficient", &C::tangential_drag_coefficient, "-", 0.0, 1.0, kClosed,
                  "C_dt; C₁ = ½ρ C_dt π D")
          .optionalNumber("c1", &C::c1, "N s^2/m^3", 0.0, 1e5, kClosed, "unset",
                          "C₁ given directly (overrides tangential_drag_coefficient)")
          .optionalNumber("c2", &C::c2, "N s^2/m^3", 0.0, 1e5, kClosed, "unset",
                          "C₂ given directly (overrides normal_drag_coefficient)")
          .number("added_mass_coefficient", &C::added_mass_coefficient, "-", 0.0, 10.0, kClosed,
                  "C_a; e = C_a ρ (πD²/4) d (Walton–Polachek)")
          .choice("tangential_drag_model", &C::tangential_drag_model,
                  { { "pode", TangentialDragModel::kPode }, { "quadratic", TangentialDragModel::kQuadratic } },
                  "pode (the report's): C₁ d ‖u‖² along s against the tangential flow; quadratic: −C₁ d |u·s|(u·s) s")
          .optionalNumber("safe_working_load", &C::safe_working_load, "N", 0.0, 1e9, kOpen, "unset",
                          "the node's diagnostics WARN while a tension exceeds it")
          .optionalNumber("breaking_load", &C::breaking_load, "N", 0.0, 1e9, kOpen, "unset",
                          "≥ safe_working_load; the node's diagnostics report an ERROR while a tension exceeds it")
          .boolean("break_at_breaking_load", &C::break_at_breaking_load,
                   "the cable parts where a tension first exceeds breaking_load (needs it); the vehicle side goes "
                   "on with a free end")
          .optionalNumber("axial_stiffness", &C::axial_stiffness, "N", 0.0, 1e11, kOpen, "unset",
                          "EA: set, the cable stretches and carries tension only, T = max(0, EA ε + c ε̇); "
                          "unset, the rigid chain (the report's)")
          .number("axial_damping", &C::axial_damping, "N s", 0.0, 1e10, kClosed,
                  "c of the elastic cable, the axial force per unit strain rate (needs axial_stiffness)");
  return table;
}

const ParamTable<WaveParams>& waveParams()
{
  using W = WaveParams;
  constexpr double kTwoPi = 4.0 * kHalfPi;
  static const ParamTable<W> table =
      ParamTable<W>()
          .choice("type", &W::type,
                  { { "none", W::Type::kNone }, { "regular", W::Type::kRegular }, { "jonswap", W::Type::kJonswap } },
                  "none: calm water (the report's); regular: one Airy wave; jonswap: an irregular sea")
          .number("water_depth", &W::water_depth, "m", 0.0, 12000.0, kClosed,
                  "h of the wave kinematics and dispersion (cosh k(z+h)/sinh kh); 0: deep water (e^{kz})")
          .number("direction", &W::direction, "rad", -kTwoPi, kTwoPi, kClosed,
                  "the waves (jonswap: their mean) travel toward this, ENU, counter-clockwise from +x")
          .number("height", &W::height, "m", 0.0, 30.0, kOpen, "regular: crest to trough H = 2a")
          .number("period", &W::period, "s", 1.0, 60.0, kClosed, "regular: T")
          .number("phase", &W::phase, "rad", -kTwoPi, kTwoPi, kClosed, "regular: φ in ζ = a cos(ωt − k·x + φ)")
          .number("significant_height", &W::significant_height, "m", 0.0, 30.0, kOpen,
                  "jonswap: Hs = 4√m₀ of the spectrum")
          .number("peak_period", &W::peak_period, "s", 1.0, 60.0, kClosed, "jonswap: Tp")
          .number("peak_enhancement", &W::peak_enhancement, "-", 1.0, 10.0, kClosed,
                  "jonswap: γ (σ 0.07 below the peak, 0.09 above); 1 is Pierson–Moskowitz")
          .number("spreading", &W::spreading, "-", 0.0, 100.0, kClosed,
                  "jonswap: s of the cos^2s((θ − direction)/2) spreading, one direction per component; 0: long-crested")
          .integer("components", &W::components, "-", 1, 2000,
                   "jonswap: frequencies in equal bins over [0.5, 4] ω_p, each at a random point of its bin")
          .integer("seed", &W::seed, "-", 0, 2147483647,
                   "jonswap: the random phases, frequencies and directions (the same seed, the same sea)");
  return table;
}

const ParamTable<Environment>& environmentParams()
{
  using E = Environment;
  static const ParamTable<E> table =
      ParamTable<E>()
          .number("gravity", &E::gravity, "m/s^2", 0.0, 100.0, kClosed, "g")
          .number("water_density", &E::water_density, "kg/m^3", 0.0, 2000.0, kClosed,
                  "ρ; 0 is vacuum (no buoyancy, drag, fin loads or added mass)")
          .vector3("current", &E::current_W, "m/s", -20.0, 20.0,
                   "uniform current, world ENU (each component); may change while running")
          .custom("current_profile", "m, m/s", "[]",
                  "depth [0, 12000] strictly increasing; velocity components [−20, 20]; ≤ 10000 samples",
                  "[{depth: 0, velocity: [vx, vy, vz]}, …]: added to current, linear in depth between samples, the "
                  "end values above and below them; each element (the vehicle at its CG) sees it at its depth")
          .nest("waves", &E::waves, waveParams());
  return table;
}

const ParamTable<NumericsParams>& numericsParams()
{
  using N = NumericsParams;
  static const ParamTable<N> table =
      ParamTable<N>()
          .choice("stepper", &N::stepper,
                  { { "dopri5", StepperType::kDopri5 },
                    { "rk4", StepperType::kRk4 },
                    { "implicit", StepperType::kImplicit },
                    { "implicit_fixed", StepperType::kImplicitFixed } },
                  "dopri5: adaptive Dormand–Prince 5(4); rk4: fixed steps; implicit: linearly implicit "
                  "Rosenbrock-W (implicit_method), adaptive, O(ν) per stage; implicit_fixed: the same with fixed "
                  "steps")
          .choice("implicit_method", &N::implicit_method,
                  { { "ros34pw2", ImplicitMethod::kRos34pw2 }, { "ros2", ImplicitMethod::kRos2 } },
                  "the implicit steppers' Rosenbrock-W method: ros34pw2 (4 stages, order 3, embedded order 2) "
                  "or ros2 (2 stages, order 2, embedded order 1)")
          .number("abs_tol", &N::abs_tol, "-", 0.0, 1.0, kOpen, "absolute error tolerance of dopri5 (m, m/s)")
          .number("rel_tol", &N::rel_tol, "-", 0.0, 1.0, kOpen, "relative error tolerance of dopri5")
          .number("implicit_position_tol", &N::implicit_position_tol, "m", 0.0, 10.0, kOpen,
                  "absolute error tolerance of implicit on the joint positions")
          .number("implicit_velocity_tol", &N::implicit_velocity_tol, "m/s", 0.0, 10.0, kOpen,
                  "absolute error tolerance of implicit on the joint velocities")
          .number("implicit_rel_tol", &N::implicit_rel_tol, "-", 0.0, 1.0, kOpen,
                  "relative error tolerance of implicit (positions relative to the tow point)")
          .number("max_step", &N::max_step, "s", 0.0, 10.0, kOpen, "largest step of dopri5 and implicit")
          .number("fixed_step", &N::fixed_step, "s", 0.0, 1.0, kOpen, "step of rk4 and implicit_fixed")
          .number("tangential_smoothing_speed", &N::tangential_smoothing_speed, "m/s", 0.0, 1.0, kOpen,
                  "the Pode drag changes sign smoothly over this |u·s|");
  return table;
}

const ParamTable<WinchParams>& winchParams()
{
  using W = WinchParams;
  // The lengths' limits depend on the cable too: validate(WinchParams, CableParams) checks them.
  static const ParamTable<W> table =
      ParamTable<W>()
          .boolean("enabled", &W::enabled, "off: fixed length, winch commands refused")
          .bounded(
              "min_length", &W::min_length, "m", [](const W&) { return std::make_pair(0.0, 1e5); },
              "[segment_min_fraction L/ν, 1e5]", "least cable out; cable.length must lie within the limits")
          .bounded(
              "max_length", &W::max_length, "m", [](const W& w) { return std::make_pair(w.min_length, 1e5); },
              "[min_length, min(1e5, 100000 L/ν)]", "most cable out (at most 100000 segments)")
          .number("max_rate", &W::max_rate, "m/s", 0.0, 20.0, kOpen, "payout and haul-in speed limit")
          .number("max_acceleration", &W::max_acceleration, "m/s^2", 0.0, 100.0, kOpen, "limit on the change of rate")
          .number("response_time", &W::response_time, "s", 0.01, 100.0, kClosed,
                  "the rate follows the command with this first-order lag")
          .bounded(
              "segment_min_fraction", &W::segment_min_fraction, "-",
              [](const W&) { return std::make_pair(0.1, 0.999999); }, "[0.1, 1)",
              "the first segment merges into the next below this × L/ν")
          .bounded(
              "segment_max_fraction", &W::segment_max_fraction, "-",
              [](const W& w) { return std::make_pair(w.segment_min_fraction + 1.0, 10.0); },
              "[segment_min_fraction + 1, 10]", "and splits above this × L/ν");
  return table;
}

const ParamTable<SeabedParams>& seabedParams()
{
  using B = SeabedParams;
  static const ParamTable<B> table =
      ParamTable<B>()
          .choice("type", &B::type,
                  { { "none", SeabedParams::Type::kNone },
                    { "flat", SeabedParams::Type::kFlat },
                    { "grid", SeabedParams::Type::kGrid } },
                  "no bottom, flat at depth, or a bathymetry grid")
          .number("depth", &B::depth, "m", 0.0, 12000.0, kOpen, "flat bottom")
          .text("grid_file", &B::grid_file, "a readable file",
                "YAML {origin: [x, y], spacing: [dx, dy], depth: [[row at y0], …]} [m], depths ≥ 0, at least 2 × 2; "
                "relative to the configuration's folder (offline), else absolute")
          .number("stiffness", &B::stiffness, "N/m per m", 0.0, 1e8, kOpen,
                  "cable: normal force per metre of penetration, per metre of cable")
          .number("damping", &B::damping, "N s/m per m", 0.0, 1e8, kClosed, "cable: on the rate of penetration")
          .number("vehicle_stiffness", &B::vehicle_stiffness, "N/m", 0.0, 1e9, kOpen,
                  "at each of the vehicle's nose and tail points")
          .number("vehicle_damping", &B::vehicle_damping, "N s/m", 0.0, 1e9, kClosed, "at each of them")
          .number("friction", &B::friction, "-", 0.0, 5.0, kClosed, "Coulomb coefficient: sliding ≤ friction × normal")
          .number("friction_speed", &B::friction_speed, "m/s", 0.0, 10.0, kOpen,
                  "the friction force builds up over this sliding speed");
  return table;
}

const ParamTable<FinPairParams>& finParams()
{
  using F = FinPairParams;
  static const ParamTable<F> table =
      ParamTable<F>()
          .number("lift_constant", &F::lift_constant, "N s^2/m^2", 0.0, 1e7, kClosed,
                  "C₃ (rudder), C₅ (elevator): lift = C F_L(angle of attack) ‖v_p‖²")
          .number("drag_constant", &F::drag_constant, "N s^2/m^2", 0.0, 1e7, kClosed,
                  "C₄, C₆: drag = C F_D(angle of attack) ‖v_p‖²")
          .number("max_deflection", &F::max_deflection, "rad", 0.0, kHalfPi, kOpen, "commands saturate at ±this")
          .number("max_rate", &F::max_rate, "rad/s", 0.0, 100.0, kOpen, "servo slew rate")
          .number("center_of_pressure_offset", &F::center_of_pressure_offset, "m", -10.0, 10.0, kClosed,
                  "chord-wise, aft of the hinge, for the hinge moment")
          .custom("lift_table", "rad → -", "stalls at 18°", "angles 0 … π/2 increasing; 0 at 0",
                  "F_L: {angles: [...], values: [...]}, linear between points, odd; reversed flow past π/2")
          .custom("drag_table", "rad → -", "stalls at 18°", "angles 0 … π/2 increasing", "F_D, likewise, even");
  return table;
}

const ParamTable<VehicleParams>& vehicleParams()
{
  using V = VehicleParams;
  const auto along = [](const V& v) { return std::make_pair(-v.nose_from_bail, v.tail_from_bail); };
  const char* along_text = "from -nose_from_bail to tail_from_bail";
  // Inertia entries: a product of inertia sets both of its (symmetric) places.
  auto get = [](int i, int j) { return [i, j](const V& v) { return v.inertia_B(i, j); }; };
  auto set = [](int i, int j)
  {
    return [i, j](V& v, double value)
    {
      v.inertia_B(i, j) = value;
      v.inertia_B(j, i) = value;
    };
  };
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
          .nest("elevator", &V::elevator, finParams());
  return table;
}

const ParamTable<EndElementParams>& endElementParams()
{
  using E = EndElementParams;
  const auto along = [](const E& e) { return std::make_pair(0.0, e.length); };
  static const ParamTable<E> table =
      ParamTable<E>()
          .number("length", &E::length, "m", 0.0, 100.0, kOpen, "d_{ν+1}, bail to tail point")
          .number("mass", &E::mass, "kg", 0.0, 1e6, kOpen, "in air")
          .number("displaced_volume", &E::displaced_volume, "m^3", 0.0, 1e3, kClosed, "buoyancy at the CB")
          .bounded("cg_from_bail", &E::cg_from_bail, "m", along, "0 .. length", "centre of gravity")
          .bounded("cb_from_bail", &E::cb_from_bail, "m", along, "0 .. length", "centre of buoyancy")
          .optionalNumber("transverse_inertia", &E::transverse_inertia, "kg m^2", 0.0, 1e9, kOpen, "thin rod",
                          "about the CG")
          .number("diameter", &E::diameter, "m", 0.0, 10.0, kOpen, "for drag and added mass")
          .number("normal_drag_coefficient", &E::normal_drag_coefficient, "-", 0.0, 10.0, kClosed, "C_dn")
          .number("tangential_drag_coefficient", &E::tangential_drag_coefficient, "-", 0.0, 10.0, kClosed, "C_dt")
          .number("added_mass_coefficient", &E::added_mass_coefficient, "-", 0.0, 10.0, kClosed, "C_a");
  return table;
}

const ParamTable<DepthAutopilotParams>& autopilotParams()
{
  using A = DepthAutopilotParams;
  static const ParamTable<A> table =
      ParamTable<A>()
          .number("kp", &A::kp, "rad/m", 0.0, 10.0, kClosed, "elevator per metre of depth error")
          .number("ki", &A::ki, "rad/(m s)", 0.0, 10.0, kClosed, "elevator per metre-second of integrated error")
          .number("kd", &A::kd, "rad/(m/s)", 0.0, 100.0, kClosed, "elevator per m/s of vertical velocity (world, up)")
          .number("max_elevator", &A::max_elevator, "rad", 0.0, kHalfPi, kOpen,
                  "elevator limit (the default vehicle's max_deflection)")
          .boolean("track_keeping", &A::track_keeping, "steer on the ship's track; false: rudder 0")
          .number("rudder_kp", &A::rudder_kp, "rad/m", 0.0, 10.0, kClosed, "rudder per metre of lateral offset")
          .number("rudder_kd", &A::rudder_kd, "rad/(m/s)", 0.0, 100.0, kClosed, "rudder per m/s of offset rate")
          .number("max_rudder", &A::max_rudder, "rad", 0.0, kHalfPi, kOpen, "rudder limit")
          .number("track_spacing", &A::track_spacing, "m", 0.01, 1000.0, kClosed,
                  "a ship position is stored each time the ship has moved this far")
          .bounded(
              "track_length", &A::track_length, "m",
              [](const A& a) { return std::make_pair(std::max(10.0, 2.0 * a.track_spacing), 1e6); },
              "at least 10 m and two track_spacing", "past track kept (older points dropped)")
          .number("thrust", &A::thrust, "N", -1e6, 1e6, kClosed, "constant thrust command")
          .number("odom_timeout", &A::odom_timeout, "s", 0.0, 3600.0, kOpen,
                  "no new vehicle odometry for this long (since it arrived): fins centred")
          .number("max_depth", &A::max_depth, "m", 0.0, 1e5, kOpen, "setpoints above it are rejected")
          .choice("actuator", &A::actuator,
                  { { "elevator", A::Actuator::kElevator },
                    { "winch", A::Actuator::kWinch },
                    { "both", A::Actuator::kBoth } },
                  "what holds the depth: the elevator (PID above), the winch (payout rate; needs winch.enabled), "
                  "or both")
          .number("winch_kp", &A::winch_kp, "m/m", 0.0, 1000.0, kClosed,
                  "winch: cable out aimed at per metre of depth error, on top of the planner's steady cable out")
          .number("winch_ki", &A::winch_ki, "m/(m s)", 0.0, 100.0, kClosed,
                  "winch: cable out per metre-second of integrated depth error")
          .number("winch_time_constant", &A::winch_time_constant, "s", 0.0, 1000.0, kOpen,
                  "winch: payout rate = (cable out aimed at − cable out) / this")
          .number("max_payout_rate", &A::max_payout_rate, "m/s", 0.0, 100.0, kOpen, "winch: payout command limit");
  return table;
}

}  // namespace tow_sim
