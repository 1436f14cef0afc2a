// The implicit stepper's part of the Simulator: linearisation, step and error control (docs/solver.md's symbols).
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
  return model_->numerics().stepper;
}

bool Simulator::implicit() const
{
  return isImplicit(stepper());
}

// (S16) per chain: the whole cable, or a parted cable's vehicle side (its free first joint's acceleration an
// unknown, (S27)) and the cable left on the ship; the winch's dL''/dL, dL''/dL' for its 2 x 2 block (§7).
void Simulator::linearise()
{
  const StateLayout& L = layout();
  const Eigen::Vector2d winch =
      !parted() ? winchAccelerationDerivatives(winch_, data_.winch_command, L.cableOut(y_), L.payoutRate(y_))
                : Eigen::Vector2d::Zero();
  ++linearisations_;
  implicit_.beginLinearisation(chains_.size(), winch.x(), winch.y());
  const ShipEndState ship = ship_(t_);
  for (std::size_t i = 0; i < chains_.size(); ++i)
    implicit_.lineariseChain(i, chains_[i], *model_, data_, t_, ship, y_, dydt_);
}

// One step of (S15) of size h, then (S24)-(S25): accept it when ||err|| <= 1, and choose the next h.
bool Simulator::stepImplicit(double t_end, double winch_step, StepReport& report)
{
  const NumericsParams& num = model_->numerics();
  const bool fixed = num.stepper == StepperType::kImplicitFixed;
  const double remaining = t_end - t_;
  const double h = fixed ? std::min({ num.fixed_step, winch_step, remaining })
                         : std::min({ dt_, remaining, num.max_step, winch_step });
  if (h != implicit_.step())
    implicit_.factor(h);  // (S19): N_XY for this h
  implicit_.stages(       // (S15): y_next = y + h sum m_i k_i and error_ = err = h sum e_i k_i
      *tableau_, t_, h, y_, dydt_, ship_, data_.actuators,
      [this](double t, const StateVector& y, StateVector& dydt) { derivative(t, y, dydt); }, y_next_, error_);
  const bool clamped = h == remaining;
  const double t_next = clamped ? t_end : t_ + h;
  if (!fixed)
  {
    const double err = implicitErrorNorm(model_->numerics(), chains_, winch_.enabled, error_, y_, y_next_,
                                         ship_(t_).p_W, ship_(t_next).p_W);  // (S24): ||err||
    // (S25): the error estimate goes like h^(p-hat + 1), p-hat the embedded order: 0.9 ||err||^(-1/(p-hat + 1)).
    const double grow =
        std::isfinite(err) ? 0.9 * std::pow(std::max(err, 1e-10), -1.0 / (tableau_->embedded_order + 1)) : 0.2;
    if (!(err <= 1.0))
    {
      ++report.rejected;
      dt_ = h * std::clamp(grow, 0.2, 0.9);  // (S25), rejected
      if (dt_ < kMinStep)
        throw std::runtime_error(
            "integration failed: the implicit step fell below 1e-10 s at t = " + std::to_string(t_) + " s");
      return false;
    }
    // A step cut short by t_end says little about the next one: keep the longer of the two.
    const double next = h * std::clamp(grow, 0.2, 5.0);  // (S25), accepted
    dt_ = clamped ? std::max(dt_, next) : next;
    dt_ = std::min(dt_, num.max_step);
  }
  y_.swap(y_next_);
  t_ = t_next;
  return true;
}

}  // namespace tow_sim
