// The loading functions of a faired cable (docs/physics.md §11, (P56)): its normal, tangential and lift
// coefficients as functions of the angle phi between the cable's axis and the flow, given at points and
// interpolated linearly. The bare cable (the report's Pode loading) needs none.
#pragma once

#include <string>
#include <vector>

#include "tow_sim/core/angle_grid.h"

namespace tow_sim
{
class CableLoading
{
public:
  // The coefficients at one angle, and their slopes d/dphi [1/rad] (of the interval phi lies in); and
  // C_n(phi) / sin(phi), C_l(phi) / sin(phi) with their slopes d/dphi: the loads over the cross-flow speed,
  // smooth where the flow runs along the axis (at phi = 0 they take their limits, the first slopes, and
  // slopes 0).
  struct Coefficients
  {
    double normal = 0.0, tangential = 0.0, lift = 0.0;
    double normal_slope = 0.0, tangential_slope = 0.0, lift_slope = 0.0;
    double normal_per_sine = 0.0, lift_per_sine = 0.0;
    double normal_per_sine_slope = 0.0, lift_per_sine_slope = 0.0;
  };

  // Throws std::invalid_argument naming `name`, the entry and the rule unless: the angles [rad] make an
  // AngleGrid (from 0 to pi/2 within 1e-4, strictly increasing, at least 2 points); normal, tangential and lift (lift
  // may be empty: zero) have one finite value per angle, each within [-100, 100]; normal >= 0 and tangential >= 0 (they
  // oppose the flow); normal and lift are 0 at 0 (no cross-flow along the axis).
  CableLoading(std::vector<double> angles, std::vector<double> normal, std::vector<double> tangential,
               std::vector<double> lift, const std::string& name);

  // phi [rad] in [0, pi/2] (clamped).
  Coefficients at(double phi) const;

  // The same functions with every coefficient times k >= 0 (its name for errors: `name`).
  CableLoading scaled(double k, const std::string& name) const;

  const std::vector<double>& angles() const { return grid_.angles(); }
  const std::vector<double>& normal() const { return normal_; }
  const std::vector<double>& tangential() const { return tangential_; }
  const std::vector<double>& lift() const { return lift_; }

private:
  AngleGrid grid_;
  std::vector<double> normal_, tangential_, lift_;
};

}  // namespace tow_sim
