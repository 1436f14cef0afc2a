// The right-hand side of the chain: joint accelerations and every joint's tension in O(nu).
//
// Stages (physics.md §6): ship end -> element kinematics -> element loads (BodyDynamics) ->
// backward sweep from the end body to the ship -> forward sweep for accelerations and tensions.
//
// Each element's Newton-Euler equations are written on its two joint accelerations through the
// no-roll kinematics a_G = (1-gamma) a_f + gamma a_a, dw/dt = s x (a_a - a_f)/d, and closed with its
// length constraint s.(a_a - a_f) = -|v_a - v_f|^2/d. The backward sweep expresses the tension at
// each joint as an affine function of that joint's acceleration, T = K a + k (K is the apparent
// inertia of everything aft of it), so the sweep from the ship forward is explicit. This is the
// report's summation of the linear-momentum equations from the vehicle forward, done recursively.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tow_sim/core/chain_model.h"

namespace tow_sim
{
class ChainSolver
{
public:
  explicit ChainSolver(const ChainModel& model);

  // t: time [s]; x, v: joints x_2 .. x_{nu+2} (3 x (nu+1)), world. Writes their accelerations into a and, when
  // tensions is not null, T_1 .. T_{nu+1} (3 x (nu+1)): the force on element lambda at its forward
  // joint, i.e. the pull toward the ship; T_1 is the tow force the ship applies.
  void solve(double t, const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
             const Eigen::Ref<const Eigen::Matrix3Xd>& v, Eigen::Ref<Eigen::Matrix3Xd> a,
             Eigen::Matrix3Xd* tensions = nullptr);

  const ChainModel& model() const { return model_; }

private:
  const ChainModel& model_;
  // Workspace, one entry per element: a_aft = X a_fwd + y and T_fwd = K a_fwd + k.
  std::vector<Eigen::Matrix3d> X_, K_;
  std::vector<Eigen::Vector3d> y_, k_;
};

}  // namespace tow_sim
