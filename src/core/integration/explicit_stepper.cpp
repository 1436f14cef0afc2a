#include "tow_sim/core/integration/explicit_stepper.h"

#include <algorithm>
#include <boost/numeric/odeint.hpp>

namespace tow_sim
{
namespace odeint = boost::numeric::odeint;

struct ExplicitStepper::Odeint
{
  using Dopri5 = odeint::runge_kutta_dopri5<StateVector>;
  explicit Odeint(const NumericsParams& num) : controlled(odeint::make_controlled(num.abs_tol, num.rel_tol, Dopri5()))
  {
  }
  odeint::controlled_runge_kutta<Dopri5> controlled;
  odeint::runge_kutta4<StateVector> rk4;
};

ExplicitStepper::ExplicitStepper(const NumericsParams& num) : odeint_(std::make_unique<Odeint>(num)), num_(num) {}

ExplicitStepper::~ExplicitStepper() = default;

void ExplicitStepper::rk4(const System& f, StateVector& y, const StateVector& dydt, double t, double h)
{
  odeint_->rk4.do_step(f, y, dydt, t, h);
}

bool ExplicitStepper::dopri5(const System& f, StateVector& y, StateVector& dydt, double& t, double& h)
{
  return odeint_->controlled.try_step(f, y, dydt, t, h) != odeint::fail;
}

bool ExplicitStepper::step(StepperType stepper, const System& f, StateVector& y, StateVector& dydt, double& t,
                           double& dt, double t_end, double limit)
{
  if (stepper == StepperType::kRk4)
  {
    const double h = std::min({ num_.fixed_step, limit, t_end - t });
    rk4(f, y, dydt, t, h);
    t = h == t_end - t ? t_end : t + h;
    return true;
  }
  const double t_prev = t;
  const double remaining = t_end - t;
  const bool clamped = dt >= remaining;
  double h = std::min({ dt, remaining, num_.max_step, limit });
  // dopri5 is first-same-as-last: dydt holds f(y) and is advanced with the step.
  if (!dopri5(f, y, dydt, t, h))
  {
    dt = h;
    return false;
  }
  if (!clamped || h > dt)
    dt = std::min(h, num_.max_step);
  if (clamped && remaining - (t - t_prev) < 1e-12)
    t = t_end;
  return true;
}

}  // namespace tow_sim
