#include "tow_sim/core/vehicle/fins.h"

#include "tow_sim/core/param_tables.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/params.h"

namespace tow_sim
{
namespace
{

double wrapAngle(double a)
{
  return std::atan2(std::sin(a), std::cos(a));
}
}  // namespace

AngleTable::AngleTable(std::vector<double> angles, std::vector<double> values, bool odd, const std::string& name)
    : grid_(std::move(angles), name), values_(std::move(values)), odd_(odd)
{
  std::ostringstream problem;
  if (values_.size() != grid_.size())
    problem << "has " << values_.size() << " values for " << grid_.size() << " angles; give one per angle";
  for (size_t i = 0; problem.str().empty() && i < values_.size(); ++i)
    if (!std::isfinite(values_[i]) || std::abs(values_[i]) > 100.0)
      problem << "value " << i << " = " << values_[i] << " must be finite with |value| <= 100";
  if (problem.str().empty() && odd_ && values_.front() != 0.0)
    problem << "a lift table must be 0 at 0 (lift is odd); got " << values_.front();
  if (!problem.str().empty())
    throw std::invalid_argument(name + ": " + problem.str());
}

double AngleTable::operator()(double angle_of_attack) const
{
  const double a = wrapAngle(angle_of_attack);
  const double magnitude = std::abs(a);
  const bool reversed = magnitude > kHalfPi;
  const double value = AngleGrid::value(values_, grid_.locate(reversed ? kPi - magnitude : magnitude));
  if (!odd_)
    return value;
  const double sign = a < 0.0 ? -1.0 : 1.0;
  return reversed ? -sign * value : sign * value;
}

AngleTable AngleTable::defaultLift()
{
  const double deg = kPi / 180.0;
  return AngleTable({ 0.0, 10 * deg, 18 * deg, 22 * deg, 30 * deg, 45 * deg, 90 * deg },
                    { 0.0, 10 * deg, 18 * deg, 0.26, 0.24, 0.22, 0.0 }, true, "default lift table");
}

AngleTable AngleTable::defaultDrag()
{
  const double deg = kPi / 180.0;
  return AngleTable({ 0.0, 10 * deg, 18 * deg, 22 * deg, 30 * deg, 45 * deg, 90 * deg },
                    { 0.02, 0.04, 0.08, 0.18, 0.30, 0.55, 1.0 }, false, "default drag table");
}

void validate(const FinPairParams& f, const std::string& p)
{
  validateParams(finParams(), f, p);
}

double FinServo::command(double t, double angle)
{
  angle0_ = angleAt(t);
  t0_ = t;
  target_ = std::isfinite(angle) ? std::clamp(angle, -max_deflection_, max_deflection_) : angle0_;
  return target_;
}

double FinServo::angleAt(double t) const
{
  const double gap = target_ - angle0_;
  const double travel = max_rate_ * std::max(0.0, t - t0_);
  return travel >= std::abs(gap) ? target_ : angle0_ + std::copysign(travel, gap);
}

void FinServo::reset(double t, double angle)
{
  t0_ = t;
  angle0_ = target_ = std::clamp(angle, -max_deflection_, max_deflection_);
}

FinPairLoads finPairLoads(const FinPairParams& fin, FinPlane plane, double angle, const Eigen::Vector3d& v_W,
                          const Eigen::Vector3d& x_b, const Eigen::Vector3d& y_b, const Eigen::Vector3d& z_b,
                          double arm)
{
  FinPairLoads out;
  out.angle = angle;
  const bool vertical = plane == FinPlane::kVertical;
  const Eigen::Vector3d& normal = vertical ? z_b : y_b;   // normal to the plane of deflection
  const Eigen::Vector3d& lateral = vertical ? y_b : z_b;  // where positive deflection pushes
  const Eigen::Vector3d v_p = v_W - v_W.dot(normal) * normal;
  const double speed2 = v_p.squaredNorm();
  if (speed2 < 1e-24)
    return out;
  const Eigen::Vector3d v_hat = v_p / std::sqrt(speed2);
  out.inflow_angle = std::atan2(lateral.dot(v_p), x_b.dot(v_p));
  out.angle_of_attack = wrapAngle(angle - out.inflow_angle);
  // Lift normal to the inflow in the plane of deflection: z_b x v (vertical), v x y_b (horizontal).
  const Eigen::Vector3d lift_dir = vertical ? z_b.cross(v_hat) : v_hat.cross(y_b);
  out.lift_W = fin.lift_constant * fin.lift(out.angle_of_attack) * speed2 * lift_dir;
  out.drag_W = -fin.drag_constant * fin.drag(out.angle_of_attack) * speed2 * v_hat;
  const Eigen::Vector3d force = out.lift_W + out.drag_W;
  out.moment_cg_W = (-arm * x_b).cross(force);  // the fin axis lies `arm` aft of the CG
  const Eigen::Vector3d chord_forward = std::cos(angle) * x_b + std::sin(angle) * lateral;
  const Eigen::Vector3d r_cp = -fin.center_of_pressure_offset * chord_forward;
  out.hinge_moment = r_cp.cross(force).dot(normal);
  return out;
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
          .custom("lift_table", "rad → -", "stalls at 18°", "angles 0 … π/2 (within 1e-4) increasing; 0 at 0",
                  "F_L: {angles: [...], values: [...]}, linear between points, odd; reversed flow past π/2")
          .custom("drag_table", "rad → -", "stalls at 18°", "angles 0 … π/2 (within 1e-4) increasing",
                  "F_D, likewise, even");
  return table;
}

}  // namespace tow_sim
