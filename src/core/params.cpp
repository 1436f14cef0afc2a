#include "tow_sim/core/params.h"

#include "tow_sim/core/constants.h"
#include "tow_sim/core/param_tables.h"

#include <algorithm>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace tow_sim
{
namespace
{

std::string formatValue(double value)
{
  std::ostringstream os;
  os.precision(10);
  os << value;
  return os.str();
}
}  // namespace

void requireInRange(const std::string& name, double value, double lo, double hi, const char* unit, bool lo_open)
{
  const bool ok = std::isfinite(value) && (lo_open ? value > lo : value >= lo) && value <= hi;
  if (ok)
    return;
  std::ostringstream os;
  os << name << " = " << formatValue(value) << " is out of range: must be a finite number in " << (lo_open ? "(" : "[")
     << formatValue(lo) << ", " << formatValue(hi) << "] " << unit;
  throw std::invalid_argument(os.str());
}

double CableParams::c1Value(const Environment& env) const
{
  return c1 ? *c1 : 0.5 * env.water_density * tangential_drag_coefficient * kPi * diameter;
}

double CableParams::c2Value(const Environment& env) const
{
  return c2 ? *c2 : 0.5 * env.water_density * normal_drag_coefficient * diameter;
}

double CableParams::normalDragAmplification() const
{
  switch (strumming)
  {
    case StrummingLaw::kVandiver:
      return 1.0 + 1.043 * std::pow(std::sqrt(2.0) * strumming_amplitude, 0.65);
    case StrummingLaw::kBlevins:
      return 1.0 + 2.1 * strumming_amplitude;
    case StrummingLaw::kNone:
      break;
  }
  return 1.0;
}

double EndElementParams::transverseInertia() const
{
  if (transverse_inertia)
    return *transverse_inertia;
  // Thin uniform rod over the bail-tail length, moved to the CG (parallel axes).
  const double offset = 0.5 * length - cg_from_bail;
  return mass * (length * length / 12.0 + offset * offset);
}

Eigen::Vector3d Environment::profileAt(double depth) const
{
  const std::vector<CurrentSample>& c = current_profile;
  if (std::isnan(depth))  // a diverging stage: let the step's finiteness check catch it
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  if (depth <= c.front().depth)
    return c.front().velocity_W;
  if (depth >= c.back().depth)
    return c.back().velocity_W;
  // First sample deeper than `depth`; the profile is short, a binary search keeps long ones cheap.
  const auto hi = std::upper_bound(c.begin(), c.end(), depth,
                                   [](double d, const CurrentSample& sample) { return d < sample.depth; });
  const auto lo = hi - 1;
  const double f = (depth - lo->depth) / (hi->depth - lo->depth);
  return (1.0 - f) * lo->velocity_W + f * hi->velocity_W;
}

void validate(const Environment& env, const std::string& p)
{
  validateParams(environmentParams(), env, p);
  requireInRange(p + ".current_profile (number of samples)", static_cast<double>(env.current_profile.size()), 0.0,
                 10000.0, "[-]");
  for (std::size_t j = 0; j < env.current_profile.size(); ++j)
  {
    const std::string item = p + ".current_profile[" + std::to_string(j) + "]";
    const CurrentSample& sample = env.current_profile[j];
    const double shallowest = j == 0 ? 0.0 : env.current_profile[j - 1].depth;
    requireInRange(item + ".depth", sample.depth, shallowest, 12000.0,
                   j == 0 ? "[m]" : "[m] (depths strictly increasing)", j > 0);
    for (int i = 0; i < 3; ++i)
      requireInRange(item + ".velocity[" + std::to_string(i) + "]", sample.velocity_W[i], -20.0, 20.0, "[m/s]");
  }
  if (env.waves.type != WaveParams::Type::kNone)
    requireInRange(p + ".gravity", env.gravity, 0.0, 100.0, "[m/s^2] (waves need gravity)", true);
}

WaveKinematics Environment::flowOver(const Eigen::Vector3d& p_f, const Eigen::Vector3d& p_a, double t) const
{
  const Eigen::Vector3d centre = p_f + 0.5 * (p_a - p_f);  // as ElementKinematics::pointAt(0.5)
  WaveKinematics flow;
  if (wave_field)
  {
    // The wet part [lo, hi] of p_f + eta (p_a - p_f), eta in [0, 1], where z <= 0.
    double lo = 0.0, hi = 1.0;
    const double zf = p_f.z(), za = p_a.z();
    if (zf > 0.0 && za > 0.0)
      hi = lo = 0.0;
    else if (zf > 0.0 || za > 0.0)
      (zf > 0.0 ? lo : hi) = zf / (zf - za);
    if (hi > lo)
    {
      const double wet = hi - lo;
      Eigen::Vector3d p = p_f + 0.5 * (lo + hi) * (p_a - p_f);
      p.z() = std::min(p.z(), -1e-12);  // within the wet part (rounding)
      flow = wave_field->kinematics(p, t + wave_time);
      flow.velocity_W *= wet;
      flow.acceleration_W *= wet;
    }
  }
  flow.velocity_W += currentAt(centre.z());
  return flow;
}

void prepareWaves(Environment& env)
{
  validate(env);
  env.wave_field =
      env.waves.type == WaveParams::Type::kNone ? nullptr : std::make_shared<const WaveField>(env.waves, env.gravity);
}

void validate(const CableParams& c, const std::string& p)
{
  validateParams(cableParams(), c, p);
  if (c.break_at_breaking_load && !c.breaking_load)
    throw std::invalid_argument(paramName(p, "break_at_breaking_load") + ": needs " + paramName(p, "breaking_load"));
  if (c.safe_working_load && c.breaking_load)
    requireInRange(paramName(p, "breaking_load"), *c.breaking_load, *c.safe_working_load, 1e9,
                   "[N] (at least safe_working_load)");
  if (c.depressor)
  {
    validate(*c.depressor, p + ".depressor");
    if (c.segments != 1 || c.length != c.depressor->length)
      throw std::invalid_argument(p + ": a depressor is one element of its own length (segments 1, length " +
                                  std::to_string(c.depressor->length) + " m)");
    if (c.elastic())
      throw std::invalid_argument(paramName(p, "depressor") + ": not in an elastic cable (cable.axial_stiffness set)");
  }
  if (!c.elastic() && c.axial_damping != 0.0)
    requireInRange(paramName(p, "axial_damping"), c.axial_damping, 0.0, 0.0, "[N s] (0 unless axial_stiffness is set)");
  if (c.loading && c.strumming != StrummingLaw::kNone)
    throw std::invalid_argument(paramName(p, "strumming") +
                                ": must be none with a faired cable's loading (fairing stops the strumming)");
}

void validate(const EndElementParams& e, const std::string& p)
{
  validateParams(endElementParams(), e, p);
}

void validate(const DepressorParams& d, const std::string& p)
{
  validateParams(depressorParams(), d, p);
}

void validate(const NumericsParams& n, const std::string& p)
{
  validateParams(numericsParams(), n, p);
}

void validate(const WinchParams& w, const CableParams& c, const std::string& p)
{
  validateParams(winchParams(), w, p);  // the table's ranges; then those that depend on the cable
  // They only matter when the winch runs.
  const double d = c.segmentLength();
  if (w.enabled)
    requireInRange(p + ".min_length", w.min_length, w.segment_min_fraction * d, 1e5,
                   "[m] (at least segment_min_fraction * cable.length / cable.segments)");
  if (w.enabled)  // the winch adds segments of the nominal length: at most cable.segments' limit of them
    requireInRange(p + ".max_length", w.max_length, w.min_length, std::min(1e5, 1e5 * d),
                   "[m] (at least min_length, at most 100000 segments of cable.length / cable.segments)");
  const std::string root = p.size() >= 5 && p.compare(p.size() - 5, 5, "winch") == 0 ? p.substr(0, p.size() - 5) : "";
  if (w.enabled)
    requireInRange(root + "cable.length", c.length, w.min_length, w.max_length,
                   "[m] (within winch.min_length .. winch.max_length)");
  if (w.enabled && c.elastic())
    throw std::invalid_argument(p + ".enabled: the winch needs the rigid cable (cable.axial_stiffness unset)");
}

}  // namespace tow_sim
