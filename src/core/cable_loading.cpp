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
    : angles_(std::move(angles)), normal_(std::move(normal)), tangential_(std::move(tangential)), lift_(std::move(lift))
{
  if (lift_.empty())
    lift_.assign(angles_.size(), 0.0);
  std::ostringstream problem;
  // The last angle is pi/2 (within 1e-4, so that 1.5708 will do): taken as pi/2 before the order is checked.
  if (!angles_.empty() && std::abs(angles_.back() - kHalfPi) <= 1e-4)
    angles_.back() = kHalfPi;
  if (angles_.size() < 2)
    problem << "angles needs at least 2 points, from 0 to pi/2 [rad]; got " << angles_.size();
  for (size_t i = 0; problem.str().empty() && i < angles_.size(); ++i)
  {
    if (!std::isfinite(angles_[i]))
      problem << "angles[" << i << "] = " << angles_[i] << " must be finite";
    else if (i > 0 && !(angles_[i] > angles_[i - 1]))
      problem << "angles must increase strictly; angles[" << i << "] = " << angles_[i] << " [rad] follows "
              << angles_[i - 1];
  }
  if (problem.str().empty() && (angles_.front() != 0.0 || angles_.back() != kHalfPi))
    problem << "angles must run from 0 to pi/2 = 1.5707963 [rad] (within 1e-4); got " << angles_.front() << " .. "
            << angles_.back();
  if (problem.str().empty())
    problem << checkValues("normal", normal_, angles_.size(), true, true);
  if (problem.str().empty())
    problem << checkValues("tangential", tangential_, angles_.size(), true, false);
  if (problem.str().empty())
    problem << checkValues("lift", lift_, angles_.size(), false, true);
  if (!problem.str().empty())
    throw std::invalid_argument(name + ": " + problem.str());
}

CableLoading::Coefficients CableLoading::at(double phi) const
{
  phi = std::clamp(phi, 0.0, kHalfPi);
  const size_t upper = static_cast<size_t>(std::upper_bound(angles_.begin(), angles_.end(), phi) - angles_.begin());
  const size_t i = std::clamp<size_t>(upper, 1, angles_.size() - 1);  // phi in [angles[i-1], angles[i]]
  const double width = angles_[i] - angles_[i - 1];
  const double w = (phi - angles_[i - 1]) / width;
  auto value = [&](const std::vector<double>& v) { return (1.0 - w) * v[i - 1] + w * v[i]; };
  auto slope = [&](const std::vector<double>& v) { return (v[i] - v[i - 1]) / width; };
  Coefficients c;
  c.normal = value(normal_);
  c.tangential = value(tangential_);
  c.lift = value(lift_);
  c.normal_slope = slope(normal_);
  c.tangential_slope = slope(tangential_);
  c.lift_slope = slope(lift_);
  return c;
}

void CableLoading::perSine(double phi, double& normal, double& lift) const
{
  const double sine = std::sin(std::clamp(phi, 0.0, kHalfPi));
  if (sine < kTinySine)
  {
    normal = (normal_[1] - normal_[0]) / angles_[1];  // C(0) = 0: C(phi) / sin(phi) -> C'(0)
    lift = (lift_[1] - lift_[0]) / angles_[1];
    return;
  }
  const Coefficients c = at(phi);
  normal = c.normal / sine;
  lift = c.lift / sine;
}

CableLoading CableLoading::scaled(double k, const std::string& name) const
{
  auto times = [k](std::vector<double> v)
  {
    for (double& x : v)
      x *= k;
    return v;
  };
  return CableLoading(angles_, times(normal_), times(tangential_), times(lift_), name);
}

}  // namespace tow_sim
