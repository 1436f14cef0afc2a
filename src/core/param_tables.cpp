#include "tow_sim/core/param_tables.h"

#include <algorithm>
#include <string>

#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
// The cable's own keys: its geometry, weight, drag, load limits, elasticity and bending (cableParams adds
// strumming and the lists of sections and bodies; a section takes every key but the limits).
ParamTable<CableParams> cableMaterialParams()
{
  using C = CableParams;
  return ParamTable<C>()
      .number("length", &C::length, "m", 0.0, 1e5, kOpen, "total cable length L")
      .integer("segments", &C::segments, "-", 1, 100000, "number of rigid segments ν (segment length L/ν)")
      .number("diameter", &C::diameter, "m", 0.0, 1.0, kOpen, "D")
      .number("mass_per_length", &C::mass_per_length, "kg/m", 0.0, 1000.0, kOpen,
              "mass per length in air (w = mass_per_length · g)")
      .number("normal_drag_coefficient", &C::normal_drag_coefficient, "-", 0.0, 10.0, kClosed, "C_dn; C₂ = ½ρ C_dn D")
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
      .custom("loading", "rad, -", "bare",
              "angles from 0 to π/2, strictly increasing; one finite value per angle in each list, within "
              "[−100, 100]; normal, tangential ≥ 0; normal and lift 0 at angle 0; not with strumming",
              "bare (the report's Pode loading, from the drag coefficients above) or a faired cable's loading "
              "functions {angles: [rad], normal: […], tangential: […], lift: […]}: the loads ½ρ D d C(φ) |u|² "
              "at the angle φ between the cable and the flow, interpolated linearly (lift may be left out: 0); "
              "physics.md §11, (P56)")
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
              "c of the elastic cable, the axial force per unit strain rate (needs axial_stiffness)")
      .number("bending_stiffness", &C::bending_stiffness, "N m^2", 0.0, 1e9, kClosed,
              "EI: a moment EI θ / ℓ̄ at each joint between two segments turned by θ, toward straight (ℓ̄ the "
              "mean of their lengths; between sections, the two halves in series); 0, none (the report's)");
}
}  // namespace

const ParamTable<CableParams>& cableParams()
{
  using C = CableParams;
  static const ParamTable<C> table =
      cableMaterialParams()
          .choice("strumming", &C::strumming,
                  { { "none", StrummingLaw::kNone },
                    { "vandiver", StrummingLaw::kVandiver },
                    { "blevins", StrummingLaw::kBlevins } },
                  "none (the report's); vandiver: the normal drag C_dn (or c2) times 1 + 1.043 (√2 A/D)^0.65 "
                  "(Vandiver 1983); blevins: times 1 + 2.1 A/D (Blevins 1990): the cable strums in lock-in along "
                  "its whole length (tow_sim_strumming says where it can)")
          .number("strumming_amplitude", &C::strumming_amplitude, "-", 0.0, 3.0, kOpen,
                  "A/D, the cross-flow amplitude of strumming over the diameter (1: about the largest measured on "
                  "lightly damped cylinders); used with strumming")
          .number("strouhal_number", &C::strouhal_number, "-", 0.0, 1.0, kOpen,
                  "St: vortices shed at St |u_n| / D [Hz] (tow_sim_strumming); 0.2 for a bare circular cable")
          .custom("sections", "", "[]",
                  "each needs length and segments; lengths add up to length; ≤ 100000 segments in all; all "
                  "elastic or all rigid",
                  "[{length: L, segments: n, diameter: …}, …] from the tow point aft: each entry takes this "
                  "level's keys (a key left out is this level's) but the load limits, which are the whole "
                  "cable's; length and segments here may be left out (the sums); empty: one uniform cable. The "
                  "winch pays out and hauls in the first section. An entry {depressor: {…}} alone is a winged "
                  "depressor, one rigid element (not the first section; the keys below)")
          .custom("bodies", "m, kg, m^3, m^2", "[]",
                  "at on a joint, in (0, length]; the rest ≥ 0; with the winch, not inside the first section; with "
                  "breaking_load, no body's own weight in water takes what hangs from it at rest over it",
                  "[{at: m, mass: kg, displaced_volume: m³, drag_area: m², added_mass: kg}, …]: point bodies at "
                  "joints (clumps, floats), at metres along the cable from the tow point; weight less buoyancy, "
                  "drag ½ρ C_D A |u| u against the flow with drag_area C_D A, isotropic added mass");
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
          .choice("implicit_frame", &N::implicit_frame,
                  { { "world", ImplicitFrame::kWorld }, { "tow_point", ImplicitFrame::kTowPoint } },
                  "the implicit steppers' stages: tow_point (the joints relative to the tow point's motion "
                  "continued with its acceleration: fine cables in turns take far longer steps) or world (the tow "
                  "point's motion enters through the first element); solver.md (S28)")
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

namespace
{
// The keys of an axisymmetric rigid body between two attachments (the end element's, a depressor's): S is
// EndElementParams or derives from it. `ends` says what length measures, `drag` what the diameter is for.
template <class S>
ParamTable<S> rigidBodyParams(const std::string& ends, const std::string& from, const std::string& drag)
{
  const auto along = [](const S& e) { return std::make_pair(0.0, e.length); };
  return ParamTable<S>()
      .number("length", &S::length, "m", 0.0, 100.0, kOpen, ends)
      .number("mass", &S::mass, "kg", 0.0, 1e6, kOpen, "in air")
      .number("displaced_volume", &S::displaced_volume, "m^3", 0.0, 1e3, kClosed, "buoyancy at the CB")
      .bounded("cg_from_bail", &S::cg_from_bail, "m", along, "0 .. length", "centre of gravity" + from)
      .bounded("cb_from_bail", &S::cb_from_bail, "m", along, "0 .. length", "centre of buoyancy")
      .optionalNumber("transverse_inertia", &S::transverse_inertia, "kg m^2", 0.0, 1e9, kOpen, "thin rod",
                      "about the CG")
      .number("diameter", &S::diameter, "m", 0.0, 10.0, kOpen, drag)
      .number("normal_drag_coefficient", &S::normal_drag_coefficient, "-", 0.0, 10.0, kClosed, "C_dn")
      .number("tangential_drag_coefficient", &S::tangential_drag_coefficient, "-", 0.0, 10.0, kClosed, "C_dt")
      .number("added_mass_coefficient", &S::added_mass_coefficient, "-", 0.0, 10.0, kClosed, "C_a");
}
}  // namespace

const ParamTable<EndElementParams>& endElementParams()
{
  static const ParamTable<EndElementParams> table =
      rigidBodyParams<EndElementParams>("d_{ν+1}, bail to tail point", "", "for drag and added mass");
  return table;
}

const ParamTable<DepressorParams>& depressorParams()
{
  using D = DepressorParams;
  const auto along = [](const D& d) { return std::make_pair(0.0, d.length); };
  static const ParamTable<D> table =
      rigidBodyParams<D>("fore attachment (its bail) to aft attachment", ", from the fore attachment",
                         "for the body's drag and added mass")
          .number("wing_area", &D::wing_area, "m^2", 0.0, 100.0, kClosed, "S of the wing")
          .number("lift_coefficient", &D::lift_coefficient, "-", 0.0, 5.0, kClosed,
                  "C_L: the lift ½ρ S C_L |w_p|², normal to the flow, presses the depressor down (physics.md (P49a))")
          .bounded("lift_from_bail", &D::lift_from_bail, "m", along, "0 .. length",
                   "where the lift acts, from the fore attachment");
  return table;
}

}  // namespace tow_sim
