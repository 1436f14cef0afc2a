// The implicit stepper's part of the Simulator: its linearisation, its error norm and its step (ROS2,
// implicit_stepper.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tow_sim/core/simulator.h"

namespace tow_sim
{
double Simulator::nextStep() const
{
  const NumericsParams& num = model_->numerics();
  if (num.stepper == StepperType::kRk4 || num.stepper == StepperType::kImplicitFixed)
    return num.fixed_step;
  return std::min(dt_, num.max_step);
}

bool Simulator::implicit() const
{
  const StepperType s = model_->numerics().stepper;
  return s == StepperType::kImplicit || s == StepperType::kImplicitFixed;
}

void Simulator::linearise()
{
  // The winch's rate law in the cable out and the rate, by central differences (it has corners: a
  // W-method needs no more).
  double d_length = 0.0, d_rate = 0.0;
  if (winch_.enabled)
  {
    const StateLayout L = layout();
    const double length = L.cableOut(y_), rate = L.payoutRate(y_);
    const double dl = 1e-6 * std::max(1.0, length), dr = 1e-6;
    d_length = (winchAcceleration(length + dl, rate) - winchAcceleration(length - dl, rate)) / (2.0 * dl);
    d_rate = (winchAcceleration(length, rate + dr) - winchAcceleration(length, rate - dr)) / (2.0 * dr);
  }
  const StateLayout L = layout();
  implicit_.linearise(*model_, data_.geometry, data_, t_, ship_(t_), L.positions(y_), L.velocities(y_), accelerations_,
                      solver_.terms(), multipliers_, d_length, d_rate);
}

double Simulator::errorNorm(const StateVector& error, const StateVector& y_next, double t_next) const
{
  // Weighted RMS: each component against atol + rtol |value| (the larger of the two ends of the step),
  // positions measured from the tow point so that the norm does not depend on where the world's origin is.
  const NumericsParams& num = model_->numerics();
  const StateLayout L = layout();
  const Eigen::Vector3d p0 = ship_(t_).p_W, p1 = ship_(t_next).p_W;
  const auto e_x = L.positions(error), e_v = L.velocities(error);
  const auto x0 = L.positions(y_), x1 = L.positions(y_next);
  const auto v0 = L.velocities(y_), v1 = L.velocities(y_next);
  double sum = 0.0;
  for (int j = 0; j < L.joints; ++j)
    for (int i = 0; i < 3; ++i)
    {
      const double scale_x = num.implicit_position_tol +
                             num.implicit_rel_tol * std::max(std::abs(x0(i, j) - p0[i]), std::abs(x1(i, j) - p1[i]));
      const double scale_v =
          num.implicit_velocity_tol + num.implicit_rel_tol * std::max(std::abs(v0(i, j)), std::abs(v1(i, j)));
      sum += std::pow(e_x(i, j) / scale_x, 2) + std::pow(e_v(i, j) / scale_v, 2);
    }
  double count = 6.0 * L.joints;
  if (winch_.enabled)
  {
    const double scale_l = num.implicit_position_tol +
                           num.implicit_rel_tol * std::max(std::abs(L.cableOut(y_)), std::abs(L.cableOut(y_next)));
    const double scale_r = num.implicit_velocity_tol +
                           num.implicit_rel_tol * std::max(std::abs(L.payoutRate(y_)), std::abs(L.payoutRate(y_next)));
    sum += std::pow(L.cableOut(error) / scale_l, 2) + std::pow(L.payoutRate(error) / scale_r, 2);
    count += 2.0;
  }
  return std::sqrt(sum / count);
}

bool Simulator::stepImplicit(double t_end, double winch_step, StepReport& report)
{
  const NumericsParams& num = model_->numerics();
  const bool fixed = num.stepper == StepperType::kImplicitFixed;
  const double remaining = t_end - t_;
  const double h = fixed ? std::min({ num.fixed_step, winch_step, remaining })
                         : std::min({ dt_, remaining, num.max_step, winch_step });
  if (h != implicit_.step())
    implicit_.factor(h);
  // ROS2: W K1 = f(t, y); W K2 = f(t + h, y + h K1) - 2 K1; y + h (3/2 K1 + 1/2 K2).
  const size_t n = y_.size();
  // The tow point's increments, K_t (v, a) at t: K_t = 1, then -1 (implicit_stepper.h).
  const ShipEndState ship = ship_(t_);
  implicit_.solve(dydt_, TowPointRates{ ship.v_W, ship.a_W }, k1_);
  stage_y_.resize(n);
  for (size_t i = 0; i < n; ++i)
    stage_y_[i] = y_[i] + h * k1_[i];
  stage_f_.resize(n);
  derivative(t_ + h, stage_y_, stage_f_);
  for (size_t i = 0; i < n; ++i)
    stage_f_[i] -= 2.0 * k1_[i];
  implicit_.solve(stage_f_, TowPointRates{ -ship.v_W, -ship.a_W }, k2_);
  y_next_.resize(n);
  error_.resize(n);
  for (size_t i = 0; i < n; ++i)
  {
    y_next_[i] = y_[i] + h * (1.5 * k1_[i] + 0.5 * k2_[i]);
    error_[i] = 0.5 * h * (k1_[i] + k2_[i]);  // against the first-order y + h K1
  }
  const bool clamped = h == remaining;
  const double t_next = clamped ? t_end : t_ + h;
  if (!fixed)
  {
    const double err = errorNorm(error_, y_next_, t_next);
    // Order 2 with an embedded order 1: the error goes like h^2.
    const double grow = std::isfinite(err) ? 0.9 / std::sqrt(std::max(err, 1e-10)) : 0.2;
    if (!(err <= 1.0))
    {
      ++report.rejected;
      dt_ = h * std::clamp(grow, 0.2, 0.9);
      if (dt_ < kMinStep)
        throw std::runtime_error(
            "integration failed: the implicit step fell below 1e-10 s at t = " + std::to_string(t_) + " s");
      return false;
    }
    // A step cut short by t_end says little about the next one: keep the longer of the two.
    const double next = h * std::clamp(grow, 0.2, 5.0);
    dt_ = clamped ? std::max(dt_, next) : next;
    dt_ = std::min(dt_, num.max_step);
  }
  y_.swap(y_next_);
  t_ = t_next;
  return true;
}

}  // namespace tow_sim
