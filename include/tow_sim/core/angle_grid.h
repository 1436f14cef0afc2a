// The angles a coefficient table is given at: from 0 to pi/2, strictly increasing, and where an angle falls
// between them (the fins' lift and drag tables, a faired cable's loading functions).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace tow_sim
{
class AngleGrid
{
public:
  // Where an angle lies: in [angles[i - 1], angles[i]] at the fraction w from angles[i - 1], width apart.
  struct Place
  {
    size_t i = 1;
    double w = 0.0;
    double width = 1.0;
  };

  AngleGrid() = default;
  // Throws std::invalid_argument naming `name` unless there are at least 2 finite angles [rad], strictly
  // increasing, from exactly 0 to pi/2 within 1e-4 (so that 1.5708 will do: the last is then taken as pi/2).
  AngleGrid(std::vector<double> angles, const std::string& name);

  // The interval of phi [rad], clamped to [0, pi/2].
  Place locate(double phi) const;
  // Values at the angles (as many), linear between them: the value at p and the slope [1/rad] of its interval.
  static double value(const std::vector<double>& values, const Place& p)
  {
    return (1.0 - p.w) * values[p.i - 1] + p.w * values[p.i];
  }
  static double slope(const std::vector<double>& values, const Place& p)
  {
    return (values[p.i] - values[p.i - 1]) / p.width;
  }

  const std::vector<double>& angles() const { return angles_; }
  size_t size() const { return angles_.size(); }

private:
  std::vector<double> angles_;
};

}  // namespace tow_sim
