// The implicit stepper's part of the Simulator: its linearisation, its error norm and its step (ROS2,
// implicit_stepper.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tow_sim/core/integration/simulator.h"
#include "tow_sim/core/integration/winch.h"

namespace tow_sim
{
double Simulator::nextStep() const
{
  const NumericsParams& num = model_->numerics();
  if (stepper() == StepperType::kRk4 || stepper() == StepperType::kImplicitFixed)
    return num.fixed_step;
  return std::min(dt_, num.max_step);
}

StepperType Simulator::stepper() const
{
  // A parted cable's free end is not in the implicit stepper's linearisation (it takes the tow point's
  // motion as given): dopri5 from then on.
  const StepperType configured = model_->numerics().stepper;
  return free_ && isImplicit(configured) ? StepperType::kDopri5 : configured;
}

bool Simulator::implicit() const
{
  return isImplicit(stepper());
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
    d_length = (winchAcceleration(winch_, data_.winch_command, length + dl, rate) -
                winchAcceleration(winch_, data_.winch_command, length - dl, rate)) /
               (2.0 * dl);
    d_rate = (winchAcceleration(winch_, data_.winch_command, length, rate + dr) -
              winchAcceleration(winch_, data_.winch_command, length, rate - dr)) /
             (2.0 * dr);
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

// The stages (S15) of the tableau (rosenbrock_tableau.h) for the step h, factored: y_next_ and error_:
// W K_i = f(t + c_i h, y + h sum a_ij K_j) + sum c_ij K_j, each solved by ImplicitStepper::solve in O(nu).
// The tow point's increments in stage i are K_t,i (v, a) at t (implicit_stepper.h).
void Simulator::implicitStages(double h)
{
  const RosenbrockTableau& rw = *tableau_;
  const size_t n = y_.size();
  const ShipEndState ship = ship_(t_);
  stage_k_.resize(rw.stages);
  stage_y_.resize(n);
  stage_f_.resize(n);
  double K_t[RosenbrockTableau::kMaxStages];
  for (int i = 0; i < rw.stages; ++i)
  {
    double t_stage = t_;
    K_t[i] = 1.0;
    if (i == 0)
      stage_f_ = dydt_;  // f(t, y), from the linearisation
    else
    {
      stage_y_ = y_;
      for (int j = 0; j < i; ++j)
      {
        t_stage += h * rw.a[i][j] * K_t[j];
        K_t[i] += rw.c[i][j] * K_t[j];
        if (rw.a[i][j] != 0.0)
          for (size_t q = 0; q < n; ++q)
            stage_y_[q] += h * rw.a[i][j] * stage_k_[j][q];
      }
      derivative(t_stage, stage_y_, stage_f_);
      for (int j = 0; j < i; ++j)
        for (size_t q = 0; q < n; ++q)
          stage_f_[q] += rw.c[i][j] * stage_k_[j][q];
    }
    implicit_.solve(stage_f_, TowPointRates{ K_t[i] * ship.v_W, K_t[i] * ship.a_W }, stage_k_[i]);
  }
  y_next_ = y_;
  error_.assign(n, 0.0);
  for (int i = 0; i < rw.stages; ++i)
    for (size_t q = 0; q < n; ++q)
    {
      y_next_[q] += h * rw.m[i] * stage_k_[i][q];
      error_[q] += h * rw.e[i] * stage_k_[i][q];
    }
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
  implicitStages(h);
  const bool clamped = h == remaining;
  const double t_next = clamped ? t_end : t_ + h;
  if (!fixed)
  {
    const double err = errorNorm(error_, y_next_, t_next);
    // The error estimate goes like h^(embedded order + 1).
    const double grow =
        std::isfinite(err) ? 0.9 * std::pow(std::max(err, 1e-10), -1.0 / (tableau_->embedded_order + 1)) : 0.2;
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
