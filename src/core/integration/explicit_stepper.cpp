#include "tow_sim/core/integration/explicit_stepper.h"

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

ExplicitStepper::ExplicitStepper(const NumericsParams& num) : odeint_(std::make_unique<Odeint>(num)) {}

ExplicitStepper::~ExplicitStepper() = default;

void ExplicitStepper::rk4(const System& f, StateVector& y, const StateVector& dydt, double t, double h)
{
  odeint_->rk4.do_step(f, y, dydt, t, h);
}

bool ExplicitStepper::dopri5(const System& f, StateVector& y, StateVector& dydt, double& t, double& h)
{
  return odeint_->controlled.try_step(f, y, dydt, t, h) != odeint::fail;
}

}  // namespace tow_sim
