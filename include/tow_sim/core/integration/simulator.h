// Time integration of the chain (MoorDyn's Time / MuJoCo's mj_step role): Boost.Odeint steppers,
// projection back onto the segment lengths after every step, and the outputs at the current state.
// The core never reads a clock: the caller says up to which time to integrate.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "tow_sim/core/chain/chain.h"
#include "tow_sim/core/chain/chain_model.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/chain/chain_state.h"
#include "tow_sim/core/integration/explicit_stepper.h"
#include "tow_sim/core/integration/implicit_stepper.h"
#include "tow_sim/core/integration/rosenbrock_tableau.h"
#include "tow_sim/core/integration/run_report.h"
#include "tow_sim/core/vehicle/fins.h"

namespace tow_sim
{
// Tow-point motion as a function of time [s] (position, velocity, acceleration, world).
using ShipMotion = std::function<ShipEndState(double t)>;

// A tow point moving with constant velocity: p(t) = p0 + v t.
ShipMotion constantVelocityShip(const Eigen::Vector3d& p0_W, const Eigen::Vector3d& v_W);

// What the simulator holds between steps (a saved state): enough to go on bit-identically. The model, the
// ship and the environment (currents, the sea's clock) are the caller's, not part of it.
struct SimulatorState
{
  double t = 0.0;         // [s]
  double dt = 0.0;        // [s] the adaptive steppers' next step
  int segments = 0;       // nu now (the winch changes it)
  std::vector<double> y;  // StateLayout for segments + 1 joints
  FinServo::State rudder, elevator, differential;
  double thrust = 0.0;         // [N] as saturated
  double winch_command = 0.0;  // [m/s]
  std::vector<char> slack;     // elastic cable: each segment slack (empty: none counted yet)
};

class Simulator
{
public:
  using StateVector = std::vector<double>;  // laid out as StateLayout says

  // The winch (validated against the model's cable) is off by default: the cable length is fixed. The
  // chain starts with the model's initial data (its currents, the end body's actuators at rest at t = 0).
  Simulator(std::shared_ptr<const ChainModel> model, ShipMotion ship, const WinchParams& winch = WinchParams());
  ~Simulator();

  // Restart at time t from the given state, projected onto the segment lengths. Throws
  // std::invalid_argument for a wrong size or a non-finite value. The cable out and the layout are kept;
  // the winch restarts from rest with its command cleared; the actuators are not touched.
  void reset(double t, const ChainState& state);

  // Integrate to t_end (>= time()). Throws std::runtime_error if the state stops being finite, a joint
  // runs away (faster than 200 m/s relative to the tow point) or the step size collapses; the
  // simulator then keeps the last good state.
  StepReport advanceTo(double t_end);

  // Takes the layout of a saved state (or a test's): nu segments and the cable out [m] (the first segment
  // gets the rest). A reset() with as many joints must follow. Throws std::invalid_argument for a layout
  // the cable cannot have (no segment or more than 100000, a first segment not longer than 0, cable out
  // beyond the winch's limits while it is enabled, or other than the configured cable without the winch).
  void restoreLayout(int segments, double cable_out);

  // The state now, and back: restoreState() takes the layout (as restoreLayout, whose errors it throws), the
  // state vector, time, step and actuators as they were, without projecting, so that advancing from it is
  // bit-identical to advancing from where it was taken. Throws std::invalid_argument (naming the field) for a
  // state of the wrong size or with a non-finite value; nothing changes then.
  SimulatorState saveState() const;
  void restoreState(const SimulatorState& state);

  // The cable parted (cable.break_at_breaking_load, or part()): the chain is the vehicle side, from a free
  // first joint; the winch is stopped; the configured stepper goes on (the implicit one over the vehicle
  // side and any cable left on the ship, docs/solver.md (S27)).
  bool parted() const { return vehicleSide().freeFirst(); }
  // The stepper that takes the steps: numerics.stepper, parted or not.
  StepperType stepper() const;
  // Where and when it parted at its breaking load (checkBreak; kept until rejoin() or restoreState(), so an
  // advance that throws after it does not lose it). Empty after a part() by hand.
  const std::optional<PartingEvent>& partingEvent() const { return parting_event_; }
  // The cable left on the ship after a parting at joint j > 1 (j - 1 segments, its last joint free, no end
  // body: docs/solver.md §10): its joints from the tow point (empty: none) and the force on each segment at
  // its forward joint [N]. shipTension() is |T_1| of whichever chain hangs from the ship (0: none).
  Eigen::Matrix3Xd shipSideJoints() const;
  const Eigen::Matrix3Xd& shipSideTensions() const;
  double shipTension() const;
  // Parts the cable now at element e's forward joint (0: the tow point .. nu: the bail): the elements
  // forward of it leave the simulation, the joint's position and velocity become the free end's. Throws
  // std::logic_error if already parted, std::out_of_range for another e.
  void part(int element);
  // The whole cable again, laid out as configured (the winch's cable out as configured too): a reset() must
  // follow. Nothing happens to a cable that has not parted.
  void rejoin();

  // The right-hand side dy/dt at (t, y) for the current data: no side effect (only the solver's
  // workspace changes), so equal arguments give bit-identical results whatever was evaluated before.
  void derivative(double t, const StateVector& y, StateVector& dydt) const;

  // The data that changes while running. Commands act from time(); the currents are validated first
  // (std::invalid_argument naming the field).
  const ChainData& data() const { return data_; }
  // How many times the implicit stepper has linearised (S16) so far: once per accepted step, and at an
  // advanceTo whose state or data changed since (tests and benchmarks count them).
  long linearisations() const { return linearisations_; }
  // Fin angles [rad], thrust [N] and the elevator's differential [rad] (physics.md §5b) from now, or from time t
  // [s] (a restart); true if something saturated.
  bool command(double rudder, double elevator, double thrust, double differential = 0.0)
  {
    return commandAt(t_, rudder, elevator, thrust, differential);
  }
  bool commandAt(double t, double rudder, double elevator, double thrust, double differential = 0.0)
  {
    const bool saturated = model_->endBody().command(changedData().actuators, t, rudder, elevator, thrust);
    return model_->endBody().commandDifferential(data_.actuators, t, differential) || saturated;
  }
  // Fins centred, no thrust, from time t [s].
  void resetActuators(double t) { changedData().actuators = model_->endBody().restingActuators(t); }
  void setCurrent(const Eigen::Vector3d& current_W) { tow_sim::setCurrent(changedData(), current_W); }
  void setCurrentProfile(const std::vector<CurrentSample>& p) { tow_sim::setCurrentProfile(changedData(), p); }
  void setWaveTime(double wave_time) { tow_sim::setWaveTime(changedData(), wave_time); }

  // Winch: the commanded payout rate [m/s] (positive pays out), saturated at +-max_rate (returned).
  // Throws std::invalid_argument if it is not finite or the winch is disabled. The rate follows the
  // command with the winch's response time, within max_acceleration, and slows down so as to stop at
  // min_length and max_length.
  double setWinchCommand(double payout_rate);
  double winchCommand() const { return data_.winch_command; }
  double cableLength() const { return layout().cableOut(y_); }   // [m] cable out
  double payoutRate() const { return layout().payoutRate(y_); }  // [m/s] its rate of change now
  const WinchParams& winch() const { return winch_; }

  double time() const { return t_; }
  // [s] the step the stepper takes next if nothing cuts it short: the fixed step, or the adaptive
  // steppers' proposal (at most max_step).
  double nextStep() const;
  ChainState state() const;
  const StateVector& stateVector() const { return y_; }         // the integrator's state, StateLayout
  ShipEndState shipEnd() const { return ship_(t_); }            // the ship's tow point, parted or not
  ShipEndState firstJoint() const { return towPoint(t_, y_); }  // x_1: the tow point, or the free end once parted
  // The element lengths now (the winch changes the layout): geometry().segments is nu now.
  const ChainGeometry& geometry() const { return vehicleSide().geometry(); }
  // Joints x_1 .. x_{nu+2} (3 x (nu+2)) with the tow point first.
  Eigen::Matrix3Xd jointPositions() const;
  // T_1 .. T_{nu+1} at the current state (force on element lambda at its forward joint) [N].
  const Eigen::Matrix3Xd& tensions() const { return vehicleSide().tensions(); }
  // Joint accelerations x_2 .. x_{nu+2} at the current state [m/s^2].
  const Eigen::Matrix3Xd& accelerations() const { return vehicleSide().accelerations(); }
  // Current relative length error (after projection): the end body's alone for an elastic cable.
  double lengthError() const;
  // Each element's axial multiplier mu at the current state [N], compression positive: an elastic
  // segment's is minus its tension (0 when slack).
  const std::vector<double>& axialMultipliers() const { return vehicleSide().axialMultipliers(); }
  // Kinematics of element e (0 .. nu) at the current state; e = nu is the vehicle.
  ElementKinematics elementKinematics(int e) const;

  const ChainModel& model() const { return *model_; }

private:
  // The chains in the state vector's order (docs/solver.md §10): the first ends at the end body and holds the
  // cable out and the payout rate (the whole cable, or its vehicle side from a free first joint once parted);
  // a second, after a parting aft of the tow point, is the cable left on the ship, its last joint free.
  Chain& vehicleSide() { return chains_.front(); }
  const Chain& vehicleSide() const { return chains_.front(); }
  const StateLayout& layout() const { return vehicleSide().layout(); }
  // The chain's first joint at (t, y): the ship's tow point, or the free end of a parted cable.
  ShipEndState towPoint(double t, const StateVector& y) const { return vehicleSide().firstJoint(ship_(t), y); }
  void wholeCable();                    // one chain as configured, the cable out as configured, at rest
  void checkBreak(StepReport& report);  // parts the cable where a tension exceeds breaking_load
  // The vehicle side's element lengths for the state y: the first segment's from the cable out and the
  // winch's rate law while it runs (paidOut), as they are otherwise.
  ChainGeometry geometryOf(const StateVector& y) const;
  bool remesh(double t);  // split or merge the first segment (remeshFirstSegment, winch.h)
  void project(double t);
  void refreshOutputs(bool keep_linearisation = false);
  void stepOnce(double t_end, double winch_step, StepReport& report);  // one accepted or rejected step
  void acceptStep(StepReport& report);  // after an accepted step: re-mesh, project, outputs, snaps, parting
  // The implicit stepper's step: false when rejected (dt_ then holds the step to try next).
  bool stepImplicit(double t_end, double winch_step, StepReport& report);
  bool implicit() const;                        // numerics.stepper is implicit or implicit_fixed
  void linearise();                             // the implicit stepper's J at the current state (after refreshOutputs)
  double largestRelativeSpeed(double t) const;  // [m/s] fastest joint relative to its chain's first joint
  void countSnaps(StepReport& report)           // an elastic cable's vehicle side
  {
    if (model_->elastic())
      tow_sim::countSnaps(geometry(), jointPositions(), axialMultipliers(), slack_, report);
  }

  static constexpr double kMinStep = 1e-10;  // [s] smallest adaptive step before the integration fails

  std::shared_ptr<const ChainModel> model_;
  ShipMotion ship_;
  std::unique_ptr<ExplicitStepper> explicit_;  // sized for the state (re-made when it changes size)
  WinchParams winch_;
  ChainData data_;             // shared by the chains
  std::vector<Chain> chains_;  // at least one: vehicleSide()
  double t_ = 0.0;
  double dt_ = 0.0;  // next adaptive step
  // The time and state size the implicit stepper last linearised at (NaN: none, or the data changed since):
  // advanceTo keeps that J when it starts there (docs/solver.md §7, "When J is taken").
  double linearised_t_ = std::numeric_limits<double>::quiet_NaN();
  std::size_t linearised_size_ = 0;
  long linearisations_ = 0;
  void forgetLinearisation() { linearised_t_ = std::numeric_limits<double>::quiet_NaN(); }
  ChainData& changedData() { return forgetLinearisation(), data_; }
  StateVector y_;  // the chains' blocks in order
  StateVector dydt_;
  std::vector<char> slack_;  // elastic cable: each segment slack (for counting snaps)
  std::optional<PartingEvent> parting_event_;
  ImplicitStepper implicit_;
  const RosenbrockTableau* tableau_ = nullptr;  // the implicit steppers' method
  StateVector y_next_, error_;                  // the implicit step's
};

}  // namespace tow_sim
