// The linearly implicit step's stage solve (docs/solver.md §7; these comments use its symbols, whose table in §7
// maps them to the code's names). The Rosenbrock-W methods (ROS34PW2 by default, ROS2; rosenbrock_tableau.h;
// the stage loop: stages()) solve each stage with the same matrix W = I - gamma h J:
//   W k_i = f(t + c_i h, y + h sum a_ij k_j) + sum c_ij k_j + gamma h k_t,i df/dt.            (S15)
// J is an approximation of the right-hand side's Jacobian taken once per step (a W-method keeps its order
// with any J). Each stage solve (I - gamma h J) k = r costs O(nu): with k = (k_x, k_v) for the positions
// and velocities, k_x = r_x + gamma h k_v, and k_v with the multipliers solves equations of the solver's
// own form, element by element (the tilde marks the stage's quantities),
//   N_ff k_v,f + N_fa k_v,a - w~_f = T~_fwd - mu~ s,  N_af k_v,f + N_aa k_v,a - w~_a = -T~_aft + mu~ s,
//   s.(k_v,a - k_v,f) = Psi~,                                                                   (S18)
//   N_XY = M_XY - gamma h D_XY - (gamma h)^2 K_XY,  w~_X = sum_Y (M_XY r_v,Y + gamma h K_XY r_x,Y),
//   Psi~ = s.(r_v,a - r_v,f),                                                                   (S19)
// (the linearised element (S17) scaled by gamma h; M_XY the projected inertia, D and K the load derivatives
// (S16) of chain_jacobian.h), so ChainSweep solves them:
// the matrix pass once per step size, a vector pass per stage. The winch's cable out and rate form their
// own 2 x 2 block. In the code the stage vectors k are `K` (solve()) and `stage_k_` (stages()); the load
// stiffness K is ElementJacobian::dh_dx.
// The right-hand side depends on time through the tow point x_1, which moves as the ship says. The
// method is applied to the autonomous system in (t, y): its stages then carry the time derivative of f,
// W k_i = ... + gamma h k_t,i df/dt (k_t the time component of the stages, 1 in the first), and df/dt is
// the response of the chain to the tow point moving at the ship's velocity and acceleration: the stage
// takes the tow point's increments (k_t v_1, k_t a_1) as known joint values. Without them the tow point's
// motion acts explicitly on the first element, the stiffest spring of a fine chain.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

#include "tow_sim/core/chain/chain.h"
#include "tow_sim/core/chain/chain_jacobian.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/chain/chain_state.h"
#include "tow_sim/core/integration/rosenbrock_tableau.h"

namespace tow_sim
{
// The tow point's increments in a stage (docs/solver.md §7): position and velocity rows, x = k_t v_1 and
// v = k_t a_1 of (S15).
struct TowPointRates
{
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
};

class ImplicitStepper
{
public:
  static constexpr double kGamma = 1.7071067811865475;  // ROS2's, 1 + 1/sqrt(2): the default

  // The method's gamma of (S15) (rosenbrock_tableau.h), and whether its stages are taken in the tow point's
  // frame (docs/solver.md (S28)) instead of the world's; factor() must follow.
  void setMethod(double gamma, bool tow_point_frame)
  {
    gamma_ = gamma;
    tow_point_frame_ = tow_point_frame;
    h_ = 0.0;
  }
  double gamma() const { return gamma_; }

  // (S16)-(S17): the linearisation at a state of one chain whose block is StateLayout{joints} (tests): `terms`,
  // `multipliers` and accelerations a of a ChainSolver::solve at it (the projected inertia, the axes, the
  // axial forces), its joints x, v (3 x (nu+1)), the tow point's motion, and the winch's rate law's
  // derivatives d(payout acceleration)/d(cable out) [1/s^2] and /d(rate) [1/s]. The simulator's form is
  // beginLinearisation and lineariseChain per chain.
  void linearise(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                 const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                 const Eigen::Ref<const Eigen::Matrix3Xd>& v, const Eigen::Ref<const Eigen::Matrix3Xd>& a,
                 const std::vector<ElementTerms>& terms, const std::vector<double>& multipliers, double winch_d_length,
                 double winch_d_rate);
  // The linearisation of `chains` chains, each its own block of the state (a parted cable has two, which
  // do not act on each other: W is block-diagonal over them), then lineariseChain for each. The winch's
  // derivatives are those of the block that holds the cable out (the first).
  void beginLinearisation(std::size_t chains, double winch_d_length, double winch_d_rate);
  // Chain `index` at `layout` in the state: its first joint `first` (the tow point, or a free end with its
  // acceleration), x, v, a of its other joints, and its solve's terms and multipliers as linearise(). A free
  // first joint's acceleration is an unknown of the stage (docs/solver.md (S27)); `first_dF_dx`,
  // `first_dF_dv` are the derivatives of the force on it from outside (the seabed's; zero otherwise).
  void lineariseChain(std::size_t index, const StateLayout& layout, const ChainModel& model,
                      const ChainGeometry& geometry, const ChainData& data, double t, const ShipEndState& first,
                      const Eigen::Ref<const Eigen::Matrix3Xd>& x, const Eigen::Ref<const Eigen::Matrix3Xd>& v,
                      const Eigen::Ref<const Eigen::Matrix3Xd>& a, const std::vector<ElementTerms>& terms,
                      const std::vector<double>& multipliers,
                      const Eigen::Matrix3d& first_dF_dx = Eigen::Matrix3d::Zero(),
                      const Eigen::Matrix3d& first_dF_dv = Eigen::Matrix3d::Zero(),
                      const Eigen::Vector2d& end_roll = Eigen::Vector2d::Zero());
  // The same for the simulator's chain `index` at its state in y (its accelerations dydt, its solve's terms as
  // last refreshed), the ship's tow point `ship` at t.
  void lineariseChain(std::size_t index, const Chain& chain, const ChainModel& model, const ChainData& data, double t,
                      const ShipEndState& ship, const std::vector<double>& y, const std::vector<double>& dydt);
  // (S19): the stage matrix N_XY for the step h [s] and its matrix pass (S8)-(S13) (after linearise; again
  // after each change of h).
  void factor(double h);
  // (S18)-(S19), (S27): the stage k = (I - gamma h J)^-1 (r + gamma h df/dt-part), returned in K, for r laid
  // out as the linearised chains' blocks, the tow point's increments `tow` known (position, velocity:
  // k_t (v_1, a_1)) for the chains that hang from it.
  void solve(const std::vector<double>& r, const TowPointRates& tow, std::vector<double>& K);

  // One step of the method `rw` (S15) from (t, y), f0 = f(t, y), the stage matrix factored for h [s]:
  // y_next and error, err = h sum e_i k_i (y_next less the embedded solution). In the world's frame the tow
  // point's increments in stage i are k_t,i (v_1, a_1) of `ship` at t; in the tow point's, (S28), with df_z/dt
  // taken while `actuators`, those f reads, hold their fin servos as at t (HeldServos).
  using Derivative = std::function<void(double t, const std::vector<double>& y, std::vector<double>& dydt)>;
  using ShipMotion = std::function<ShipEndState(double t)>;
  void stages(const RosenbrockTableau& rw, double t, double h, const std::vector<double>& y,
              const std::vector<double>& f0, const ShipMotion& ship, Actuators& actuators, const Derivative& f,
              std::vector<double>& y_next, std::vector<double>& error);

  double step() const { return h_; }  // [s] as factored

private:
  // One chain's part of the stage (S18)-(S19): a block of W.
  struct Block
  {
    StateLayout layout;
    std::vector<ElementTerms> inertia;       // M_XY and s at the linearisation (their w_X, Psi unused)
    std::vector<ElementJacobian> jacobians;  // D and K per element (S16)
    std::vector<ElementTerms> stage;         // N_XY, and per stage w~_X (in h_f, h_a) and Psi~ (in c) (S19)
    ChainSweep sweep;
    Eigen::Matrix3Xd K_v;  // the stage's k_v at the block's joints (S18)
    // A rolling end body's dp/dphi [1/s^2] and dp/dp [1/s] of its spin's acceleration (solver.md (S29)).
    double roll_d_angle = 0.0, roll_d_rate = 0.0;
  };
  void solveBlock(Block& block, const std::vector<double>& r, const TowPointRates& tow, std::vector<double>& K);
  void stagesWorld(const RosenbrockTableau& rw, double t, double h, const std::vector<double>& y,
                   const std::vector<double>& f0, const ShipEndState& ship, const Derivative& f,
                   std::vector<double>& y_next, std::vector<double>& error);
  void stagesTowPoint(const RosenbrockTableau& rw, double t, double h, const std::vector<double>& y,
                      const std::vector<double>& f0, const ShipMotion& ship, Actuators& actuators, const Derivative& f,
                      std::vector<double>& y_next, std::vector<double>& error);
  void shift(std::vector<double>& y, const ShipEndState& from, const ShipEndState& to) const;
  void subtractFrameRate(std::vector<double>& dydt, const ShipEndState& frame) const;
  void relativeDerivative(const Derivative& f, const ShipEndState& at_t, double t, double tau,
                          const std::vector<double>& y, std::vector<double>& out);
  static constexpr double kTimeDerivativeStep = 1e-5;  // [s] per second of step (at least 1 s) for df_z/dt

  std::vector<Block> blocks_;
  double h_ = 0.0;
  double gamma_ = kGamma;
  bool tow_point_frame_ = false;
  double winch_d_length_ = 0.0, winch_d_rate_ = 0.0;
  std::vector<std::vector<double>> stage_k_;  // the stages' workspace: k_i of (S15)
  std::vector<double> stage_y_, stage_f_, f_t_, shifted_y_;
};

// (S24): the weighted RMS ||err|| of an implicit step's error, `error` (err) of the step from y to y_next
// (accepted when <= 1) over the chains' blocks: each component against atol + rtol |value| (numerics'
// implicit_*_tol, the larger of the two ends), the positions measured from the tow point x_1 (p0 at the start,
// p1 at the end) so that the norm does not depend on where the world's origin is; the cable out and the
// payout rate too when `winch` (in the block that holds them); a free first joint's position (absolute) and
// velocity, the positions of its chain measured from it.
double implicitErrorNorm(const NumericsParams& num, const std::vector<Chain>& chains, bool winch,
                         const std::vector<double>& error, const std::vector<double>& y,
                         const std::vector<double>& y_next, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1);

}  // namespace tow_sim
