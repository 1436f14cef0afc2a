#include "tow_sim/core/cable_loading.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
// Below this sin(phi) the ratios C(phi) / sin(phi) take their limit at 0, the first slope.
constexpr double kTinySine = 1e-6;

std::string checkValues(const char* key, const std::vector<double>& values, size_t count, bool non_negative,
                        bool zero_at_zero)
{
  std::ostringstream problem;
  if (values.size() != count)
    problem << key << " has " << values.size() << " values for " << count << " angles; give one per angle";
  for (size_t i = 0; problem.str().empty() && i < values.size(); ++i)
  {
    if (!std::isfinite(values[i]) || std::abs(values[i]) > 100.0)
      problem << key << "[" << i << "] = " << values[i] << " must be finite, within [-100, 100]";
    else if (non_negative && values[i] < 0.0)
      problem << key << "[" << i << "] = " << values[i] << " must be >= 0 (the load opposes the flow)";
  }
  if (problem.str().empty() && zero_at_zero && !values.empty() && values.front() != 0.0)
    problem << key << "[0] = " << values.front() << " must be 0: at phi = 0 the flow runs along the cable";
  return problem.str();
}
}  // namespace

CableLoading::CableLoading(std::vector<double> angles, std::vector<double> normal, std::vector<double> tangential,
                           std::vector<double> lift, const std::string& name)
    : grid_(std::move(angles), name),
      normal_(std::move(normal)),
      tangential_(std::move(tangential)),
      lift_(std::move(lift))
{
  if (lift_.empty())
    lift_.assign(grid_.size(), 0.0);
  std::ostringstream problem;
  problem << checkValues("normal", normal_, grid_.size(), true, true);
  if (problem.str().empty())
    problem << checkValues("tangential", tangential_, grid_.size(), true, false);
  if (problem.str().empty())
    problem << checkValues("lift", lift_, grid_.size(), false, true);
  if (!problem.str().empty())
    throw std::invalid_argument(name + ": " + problem.str());
}

CableLoading::Coefficients CableLoading::at(double phi) const
{
  phi = std::clamp(phi, 0.0, kHalfPi);
  const AngleGrid::Place p = grid_.locate(phi);
  Coefficients c;
  c.normal = AngleGrid::value(normal_, p);
  c.tangential = AngleGrid::value(tangential_, p);
  c.lift = AngleGrid::value(lift_, p);
  c.normal_slope = AngleGrid::slope(normal_, p);
  c.tangential_slope = AngleGrid::slope(tangential_, p);
  c.lift_slope = AngleGrid::slope(lift_, p);
  const double sine = std::sin(phi);
  if (sine < kTinySine)  // C(0) = 0: C(phi) / sin(phi) -> C'(0), its slope -> 0 (taken as 0 here)
  {
    const AngleGrid::Place first = grid_.locate(0.0);
    c.normal_per_sine = AngleGrid::slope(normal_, first);
    c.lift_per_sine = AngleGrid::slope(lift_, first);
    return c;
  }
  // d(C / sin) / d phi = (C' sin - C cos) / sin^2.
  const double cosine = std::cos(phi);
  c.normal_per_sine = c.normal / sine;
  c.lift_per_sine = c.lift / sine;
  c.normal_per_sine_slope = (c.normal_slope * sine - c.normal * cosine) / (sine * sine);
  c.lift_per_sine_slope = (c.lift_slope * sine - c.lift * cosine) / (sine * sine);
  return c;
}

CableLoading CableLoading::scaled(double k, const std::string& name) const
{
  auto times = [k](std::vector<double> v)
  {
    for (double& x : v)
      x *= k;
    return v;
  };
  return CableLoading(grid_.angles(), times(normal_), times(tangential_), times(lift_), name);
}

}  // namespace tow_sim
