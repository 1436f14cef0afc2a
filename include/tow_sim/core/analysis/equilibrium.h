// Steady-tow equilibrium of the discrete chain (Pode's shooting, done element by element): every joint
// moving with the ship's constant velocity, no accelerations. From the vehicle up, each element's force
// balance gives the tension at its forward joint and its moment balance about the CG fixes its
// direction; the shape hangs from the tow point at the end. Fin angles and thrust are the vehicle's
// current ones; the currents are the chain's now.
#pragma once

#include <Eigen/Core>
#include <string>

#include "tow_sim/core/chain/chain_model.h"
#include "tow_sim/core/chain/chain_state.h"

namespace tow_sim
{
struct EquilibriumResult
{
  ChainState state;               // joints x_2 .. x_{nu+2}, all moving with the ship
  Eigen::Matrix3Xd tensions;      // [N] T_1 .. T_{nu+1}
  int iterations = 0;             // Newton iterations, all elements
  double largest_residual = 0.0;  // [N m] largest moment residual left
};

// Throws std::runtime_error naming the element when no direction balances it (or the speed or current
// is not finite). The element lengths are `geometry`'s, the currents and actuators `data`'s (the model's
// initial geometry and data in the second form); t is the time at which the fin angles are taken.
EquilibriumResult steadyTowEquilibrium(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                       double t, const Eigen::Vector3d& tow_point_W,
                                       const Eigen::Vector3d& ship_velocity_W);
EquilibriumResult steadyTowEquilibrium(const ChainModel& model, double t, const Eigen::Vector3d& tow_point_W,
                                       const Eigen::Vector3d& ship_velocity_W);

}  // namespace tow_sim
