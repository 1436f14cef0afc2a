// Fins of the towed vehicle (report Appendix F, physics.md §5): lift and drag tables, the servo that
// moves a fin toward its command, and the loads on a fin pair.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tow_sim/core/angle_grid.h"
#include "tow_sim/core/param_table.h"

namespace tow_sim
{
// A coefficient as a function of the angle of attack, given on [0, pi/2] by (angle [rad], value)
// points and linearly interpolated. `odd` tables (lift) satisfy F(-a) = -F(a), even ones (drag)
// F(-a) = F(a). Past pi/2 the flow comes from behind: F(a) = -F(pi - a) (lift), F(pi - a) (drag).
class AngleTable
{
public:
  AngleTable() = default;
  // Throws std::invalid_argument naming `name` unless the angles make an AngleGrid (from 0 to pi/2 within
  // 1e-4, strictly increasing) and there is one finite value within [-100, 100] per angle; an odd table
  // must be 0 at 0.
  AngleTable(std::vector<double> angles, std::vector<double> values, bool odd, const std::string& name);

  double operator()(double angle_of_attack) const;
  const std::vector<double>& angles() const { return grid_.angles(); }
  const std::vector<double>& values() const { return values_; }

  // Default low-aspect-ratio fin curves, normalised so that F_L ~ a [rad] before the stall at 18 deg.
  static AngleTable defaultLift();
  static AngleTable defaultDrag();

private:
  AngleGrid grid_;
  std::vector<double> values_;
  bool odd_ = true;
};

struct FinPairParams
{
  double lift_constant = 150.0;                 // [N s^2/m^2] C3 (vertical) or C5 (horizontal), >= 0
  double drag_constant = 50.0;                  // [N s^2/m^2] C4 or C6, >= 0
  AngleTable lift = AngleTable::defaultLift();  // F_L, odd
  AngleTable drag = AngleTable::defaultDrag();  // F_D, even
  double max_deflection = 0.436;                // [rad] commands saturate at +-this (25 deg), (0, pi/2]
  double max_rate = 0.35;                       // [rad/s] servo slew rate (20 deg/s), > 0
  double center_of_pressure_offset = 0.0;       // [m] chord-wise, aft of the fin's hinge axis, for the hinge moment
};
// The parameter table of a fin pair (param_table.h): every key with its unit, range, default and meaning.
const ParamTable<FinPairParams>& finParams();

void validate(const FinPairParams& fin, const std::string& prefix);

// Rate-limited servo: the fin moves from where it was toward the saturated command at max_rate. Its
// angle is known in closed form at any time, so the integrator sees a continuous input.
class FinServo
{
public:
  explicit FinServo(double max_deflection = 0.436, double max_rate = 0.35)
      : max_deflection_(max_deflection), max_rate_(max_rate)
  {
  }
  // New command at time t [s]; returns the saturated target [rad].
  double command(double t, double angle);
  double angleAt(double t) const;  // [rad]
  double target() const { return target_; }
  void reset(double t, double angle);

  // Where the servo is (a saved state): the command's time [s], the angle then [rad] and the target [rad].
  struct State
  {
    double t0 = 0.0, angle0 = 0.0, target = 0.0;
  };
  State state() const { return { t0_, angle0_, target_ }; }
  void restore(const State& s)
  {
    t0_ = s.t0;
    angle0_ = s.angle0;
    target_ = s.target;
  }

private:
  double max_deflection_, max_rate_;
  double t0_ = 0.0, angle0_ = 0.0, target_ = 0.0;
};

// Loads on one fin pair, body or world axes as stated.
struct FinPairLoads
{
  double angle = 0.0;                                     // [rad] actual deflection
  double angle_of_attack = 0.0;                           // [rad] deflection minus inflow angle (alpha - alpha_1)
  double inflow_angle = 0.0;                              // [rad] alpha_1 or beta_1
  Eigen::Vector3d lift_W = Eigen::Vector3d::Zero();       // [N]
  Eigen::Vector3d drag_W = Eigen::Vector3d::Zero();       // [N]
  Eigen::Vector3d moment_cg_W = Eigen::Vector3d::Zero();  // [N m] of lift + drag about the vehicle CG
  Eigen::Vector3d lift_B = Eigen::Vector3d::Zero();       // [N] the same three in body axes (FLU),
  Eigen::Vector3d drag_B = Eigen::Vector3d::Zero();       //     filled by Vehicle::outputs()
  Eigen::Vector3d moment_cg_B = Eigen::Vector3d::Zero();  // [N m]
  double hinge_moment = 0.0;  // [N m] about the hinge axis (z_b vertical fins, y_b horizontal), from the
                              // centre-of-pressure offset
};

enum class FinPlane
{
  kVertical,   // rudder: deflects in the x_b-y_b plane, positive pushes the fins to port (+y_b)
  kHorizontal  // elevator: deflects in the x_b-z_b plane, positive pushes the fins up (+z_b)
};

// Loads of a fin pair whose point moves through the water at v_W (world), body axes x_b, y_b, z_b (world),
// deflected by `angle`, lying `arm` metres aft of the CG along s = -x_b.
FinPairLoads finPairLoads(const FinPairParams& fin, FinPlane plane, double angle, const Eigen::Vector3d& v_W,
                          const Eigen::Vector3d& x_b, const Eigen::Vector3d& y_b, const Eigen::Vector3d& z_b,
                          double arm);

}  // namespace tow_sim
