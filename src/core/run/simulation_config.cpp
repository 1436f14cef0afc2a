#include "tow_sim/core/run/simulation_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/constants.h"

namespace tow_sim
{
std::vector<CableParams> cableSections(const SimulationConfig& config)
{
  return config.sections.empty() ? std::vector<CableParams>{ config.cable } : config.sections;
}

namespace
{
std::string text(double value)
{
  std::ostringstream os;
  os.precision(10);
  os << value;
  return os.str();
}

// The distances of the joints from the tow point along the unstretched cable, joint 1 (x_2) to the bail.
std::vector<double> jointDistances(const std::vector<CableParams>& sections)
{
  std::vector<double> at;
  double start = 0.0;
  for (const CableParams& s : sections)
  {
    for (int k = 1; k <= s.segments; ++k)
      at.push_back(start + s.length * k / s.segments);
    start += s.length;
  }
  return at;
}

}  // namespace

std::vector<JointBody> jointBodies(const SimulationConfig& config, const std::string& prefix)
{
  const std::vector<double> joints = jointDistances(cableSections(config));
  const int nu = static_cast<int>(joints.size());
  std::vector<JointBody> bodies;
  for (size_t i = 0; i < config.bodies.size(); ++i)
  {
    const double at = config.bodies[i].at;
    const std::string key = prefix + "cable.bodies[" + std::to_string(i) + "].at";
    if (!std::isfinite(at) || at <= 0.0 || at > joints.back() + 1e-6)
      throw std::invalid_argument(key + " = " + text(at) + " must be in (0, " + text(joints.back()) +
                                  "] [m] (from the tow point to the bail, along the cable)");
    const auto nearest = std::lower_bound(joints.begin(), joints.end(), at);
    const size_t above = nearest == joints.begin() ? 0 : static_cast<size_t>(nearest - joints.begin()) - 1;
    const size_t below = std::min(static_cast<size_t>(nearest - joints.begin()), joints.size() - 1);
    const size_t closest = std::abs(joints[above] - at) <= std::abs(joints[below] - at) ? above : below;
    if (std::abs(joints[closest] - at) > 1e-6)
    {
      std::ostringstream os;
      os.precision(10);
      os << key << " = " << at << " [m] is not on a joint: the nearest joints are at " << joints[above] << " and "
         << joints[below] << " m from the tow point";
      throw std::invalid_argument(os.str());
    }
    JointBody b = config.bodies[i].body;
    b.joint = nu - 1 - static_cast<int>(closest);
    bodies.push_back(b);
  }
  return bodies;
}

namespace
{
// [N] the weight in water of what hangs below `at` [m] along the cable, at rest: the cable aft of it, the
// bodies from it aft, the vehicle.
double weightInWaterBelow(const SimulationConfig& config, double at)
{
  const double rho = config.environment.water_density, g = config.environment.gravity;
  double weight = (config.vehicle.mass - rho * config.vehicle.displaced_volume) * g, start = 0.0;
  for (const CableParams& s : cableSections(config))
  {
    const double below = std::clamp(start + s.length - at, 0.0, s.length);
    weight += (s.mass_per_length - rho * kPi * s.diameter * s.diameter / 4.0) * g * below;
    start += s.length;
  }
  for (const CableBodyParams& b : config.bodies)
    if (b.at >= at - 1e-6)
      weight += (b.body.mass - rho * b.body.displaced_volume) * g;
  return weight;
}

void checkBreakingLoad(const SimulationConfig& config, const std::string& prefix)
{
  if (!config.cable.breaking_load)
    return;
  const double rho = config.environment.water_density, g = config.environment.gravity;
  for (size_t i = 0; i < config.bodies.size(); ++i)
  {
    // The body's own weight must be what takes the load over: a cable and vehicle too heavy on their own
    // are no body's fault (nor refused without bodies), and a float never is.
    const JointBody& b = config.bodies[i].body;
    const double own = (b.mass - rho * b.displaced_volume) * g;
    const double weight = weightInWaterBelow(config, config.bodies[i].at);
    if (own > 0.0 && weight > *config.cable.breaking_load && weight - own <= *config.cable.breaking_load)
      throw std::invalid_argument(
          prefix + "cable.bodies[" + std::to_string(i) + "].mass = " + text(config.bodies[i].body.mass) +
          " [kg]: the cable cannot carry it: hanging at rest, the body and what hangs below it weigh " + text(weight) +
          " N in water, more than " + prefix + "cable.breaking_load = " + text(*config.cable.breaking_load) + " N");
  }
}
}  // namespace

void validateSectionsAndBodies(const SimulationConfig& config, const std::string& prefix)
{
  const std::string cable = prefix + "cable.";
  if (config.sections.size() > 1000 || config.bodies.size() > 1000)
    throw std::invalid_argument(cable + (config.sections.size() > 1000 ? "sections" : "bodies") + ": " +
                                std::to_string(std::max(config.sections.size(), config.bodies.size())) +
                                " entries; at most 1000");
  if (!config.sections.empty())
  {
    double length = 0.0;
    long segments = 0;
    for (const CableParams& s : config.sections)
    {
      length += s.length;
      segments += s.segments;
    }
    if (std::abs(length - config.cable.length) > 1e-9 * config.cable.length)
    {
      std::ostringstream os;
      os.precision(10);
      os << cable << "length = " << config.cable.length << " [m] must be the sections' lengths added up, " << length
         << " m";
      throw std::invalid_argument(os.str());
    }
    if (segments > 100000)
      throw std::invalid_argument(cable + "sections: " + std::to_string(segments) + " segments in all; at most 100000");
    if (segments != config.cable.segments)
      throw std::invalid_argument(cable + "segments = " + std::to_string(config.cable.segments) +
                                  " must be the sections' segments added up, " + std::to_string(segments));
    for (size_t i = 1; i < config.sections.size(); ++i)
      if (config.sections[i].elastic() != config.sections[0].elastic())
        throw std::invalid_argument(cable + "sections[" + std::to_string(i) +
                                    "].axial_stiffness: the sections are all elastic or all rigid (set it on every "
                                    "section or on none)");
  }
  const std::vector<JointBody> bodies = jointBodies(config, prefix);
  const int first_aft = config.sections.empty() ? 0 : config.cable.segments - config.sections.front().segments;
  for (size_t i = 0; i < bodies.size(); ++i)
  {
    validate(bodies[i], i, config.cable.segments);
    if (config.winch.enabled && bodies[i].joint > first_aft)
      throw std::invalid_argument(
          cable + "bodies[" + std::to_string(i) + "].at = " + text(config.bodies[i].at) +
          " [m] is inside the first section, which the winch pays out and hauls in: put it at or aft of " +
          text(config.sections.empty() ? config.cable.length : config.sections.front().length) +
          " m (the first section's end), or add a section");
  }
  checkBreakingLoad(config, prefix);
}

}  // namespace tow_sim
