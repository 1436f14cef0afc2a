// Time integration of the chain (MoorDyn's Time / MuJoCo's mj_step role): Boost.Odeint steppers,
// projection back onto the segment lengths after every step, and the outputs at the current state.
// The core never reads a clock: the caller says up to which time to integrate.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "tow_sim/core/chain_model.h"
#include "tow_sim/core/chain_solver.h"

namespace tow_sim
{
// Tow-point motion as a function of time [s] (position, velocity, acceleration, world).
using ShipMotion = std::function<ShipEndState(double t)>;

// A tow point moving with constant velocity: p(t) = p0 + v t.
ShipMotion constantVelocityShip(const Eigen::Vector3d& p0_W, const Eigen::Vector3d& v_W);

// Joint positions and velocities x_2 .. x_{nu+2} (3 x (nu+1)), world.
struct ChainState
{
  Eigen::Matrix3Xd x;  // [m]
  Eigen::Matrix3Xd v;  // [m/s]
};

// A straight chain from the tow point along `direction`, every joint moving with `velocity`.
ChainState straightChain(const ChainModel& model, const Eigen::Vector3d& tow_point_W,
                         const Eigen::Vector3d& direction_W, const Eigen::Vector3d& velocity_W);

// Largest |(|x_{l+1} - x_l|) / d_l - 1| over the elements: the relative length error.
double maxRelativeLengthError(const ChainModel& model, const Eigen::Vector3d& tow_point_W, const ChainState& state);

// Lateral diversion (the report's): horizontal offset of a point from the line through the ship along
// the unit horizontal track direction, positive to port, and its rate for a fixed track direction.
struct Diversion
{
  double offset = 0.0;  // [m]
  double rate = 0.0;    // [m/s]
};
Diversion lateralDiversion(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, const ShipEndState& ship,
                           const Eigen::Vector3d& track_direction_W);

// Slack flags of the tensions T_1 .. T_{nu+1} (3 x (nu+1)) at joints x_1 .. x_{nu+2} (3 x (nu+2)): element
// lambda is slack where its tension pushes instead of pulls, T_lambda . (x_{lambda+1} - x_lambda) > 0 (the
// rigid links carry compression; a real cable would go slack there).
std::vector<bool> slackFlags(const Eigen::Matrix3Xd& joints, const Eigen::Matrix3Xd& tensions);

struct StepReport
{
  int steps = 0;                  // accepted steps
  int rejected = 0;               // steps the error control rejected
  double max_length_error = 0.0;  // [-] largest relative length error left by a step, before projection
};

class Simulator
{
public:
  // The winch (validated against the model's cable) is off by default: the cable length is fixed.
  Simulator(std::shared_ptr<ChainModel> model, ShipMotion ship, const WinchParams& winch = WinchParams());

  // Restart at time t from the given state, projected onto the segment lengths. Throws
  // std::invalid_argument for a wrong size or a non-finite value.
  void reset(double t, const ChainState& state);

  // Integrate to t_end (>= time()). Throws std::runtime_error if the state stops being finite, a joint
  // runs away (faster than 200 m/s relative to the tow point) or the step size collapses; the
  // simulator then keeps the last good state.
  StepReport advanceTo(double t_end);

  // Winch: the commanded payout rate [m/s] (positive pays out), saturated at +-max_rate (returned).
  // Throws std::invalid_argument if it is not finite or the winch is disabled. The rate follows the
  // command with the winch's response time, within max_acceleration, and slows down so as to stop at
  // min_length and max_length.
  double setWinchCommand(double payout_rate);
  double winchCommand() const { return winch_command_; }
  double cableLength() const;  // [m] cable out
  double payoutRate() const;   // [m/s] its rate of change now
  const WinchParams& winch() const { return winch_; }

  double time() const { return t_; }
  ChainState state() const;
  ShipEndState shipEnd() const { return ship_(t_); }
  // Joints x_1 .. x_{nu+2} (3 x (nu+2)) with the tow point first.
  Eigen::Matrix3Xd jointPositions() const;
  // T_1 .. T_{nu+1} at the current state (force on element lambda at its forward joint) [N].
  const Eigen::Matrix3Xd& tensions() const { return tensions_; }
  // Joint accelerations x_2 .. x_{nu+2} at the current state [m/s^2].
  const Eigen::Matrix3Xd& accelerations() const { return accelerations_; }
  // Current relative length error (after projection).
  double lengthError() const;
  // Kinematics of element e (0 .. nu) at the current state; e = nu is the vehicle.
  ElementKinematics elementKinematics(int e) const;

  ChainModel& model() { return *model_; }
  const ChainModel& model() const { return *model_; }

private:
  using StateVector = std::vector<double>;
  void rhs(const StateVector& y, StateVector& dydt, double t);
  double winchAcceleration(double length, double rate) const;  // [m/s^2] the winch's rate law
  void syncWinch(const StateVector& y);                        // the model's first segment from the winch entries of y
  bool remesh(double t);  // split or merge the first segment; true if the layout changed
  void project(double t);
  void refreshOutputs();
  double lengthErrorOf(const StateVector& y, double t) const;
  double largestRelativeSpeed(double t) const;  // [m/s] fastest joint relative to the tow point

  std::shared_ptr<ChainModel> model_;
  ShipMotion ship_;
  ChainSolver solver_;
  double t_ = 0.0;
  double dt_ = 0.0;  // next adaptive step
  StateVector y_;    // [x_2..x_{nu+2}, v_2..v_{nu+2}, cable out L_w, payout rate]
  StateVector dydt_;
  Eigen::Matrix3Xd tensions_, accelerations_;
  WinchParams winch_;
  double winch_command_ = 0.0;  // [m/s]
};

}  // namespace tow_sim
