// Boost.Odeint's explicit steppers for the Simulator (numerics.stepper rk4 and dopri5): the one place that
// includes Odeint. Each call takes the system as dydt = f(y, t) and the
// state vector as StateLayout lays it out.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "tow_sim/core/params.h"

namespace tow_sim
{
class ExplicitStepper
{
public:
  using StateVector = std::vector<double>;
  using System = std::function<void(const StateVector& y, StateVector& dydt, double t)>;

  // dopri5's error control from num.abs_tol and num.rel_tol. Odeint sizes its buffers at the first step:
  // a new stepper for a state of another size (after re-meshing or a parting).
  explicit ExplicitStepper(const NumericsParams& num);
  ~ExplicitStepper();

  // The classical Runge-Kutta step of h [s] from (t, y); dydt holds f(y, t) (its first stage).
  void rk4(const System& f, StateVector& y, const StateVector& dydt, double t, double h);
  // Dormand-Prince 5(4) with error control, first-same-as-last: tries the step h [s] from (t, y) with dydt =
  // f(y, t). Accepted: true, y, dydt and t advanced, h the step proposed next. Rejected: false, nothing
  // moved, h the smaller step to try.
  bool dopri5(const System& f, StateVector& y, StateVector& dydt, double& t, double& h);

  // One step of `stepper` (rk4 or dopri5) toward t_end [s], no longer than `limit` [s] (the winch's): rk4's
  // fixed step, or dopri5's from the proposal dt [s] within max_step. Accepted: true, y, dydt = f(y, t) and t
  // advanced (to t_end exactly when the step reaches it), dt the next proposal. Rejected: false, nothing
  // moved, dt the smaller step to try.
  bool step(StepperType stepper, const System& f, StateVector& y, StateVector& dydt, double& t, double& dt,
            double t_end, double limit);

private:
  struct Odeint;
  std::unique_ptr<Odeint> odeint_;
  NumericsParams num_;
};

}  // namespace tow_sim
