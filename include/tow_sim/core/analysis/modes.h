// Natural periods and mode shapes of a rigid chain about an equilibrium (issue 31, item 2; docs/physics.md
// §12): each element's direction turned by two small angles normal to its axis (about the horizontal normal
// to it: in the vertical plane through it, "in-plane"; and about the third axis: "out-of-plane"), so every
// length is kept exactly; the angles' accelerations from the full solve (ChainSolver), differenced
// centrally in the angles (stiffness) and in their rates (damping); the eigenvalues of the first-order
// system [[0, I], [K, D]] give the modes. The tow point holds its motion. Dense: O(elements^3).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
struct Mode
{
  double period = 0.0;         // [s] 2 pi / the damped angular frequency; infinity for a mode that does not oscillate
  double frequency = 0.0;      // [rad/s] the undamped natural angular frequency |lambda|
  double damping_ratio = 0.0;  // [-] -Re(lambda) / |lambda|
  // The part that moves most: "in-plane" or "out-of-plane" (the cable), "vehicle pitch" or "vehicle yaw"
  // (the end body turning more than the cable's joints move).
  std::string dominant;
  Eigen::Matrix3Xd shape;  // [m] the joints' displacements x_2 .. x_{nu+2} (the largest 1), at the phase of its peak
};

// The modes at the state (x, v) with the tow point `ship` (an equilibrium: the accelerations about zero; in a
// steady tow v is the ship's velocity everywhere), longest period first, one per pair of conjugate
// eigenvalues. `step` [rad] is the differencing step of the angles (and [rad/s] of their rates).
// Throws std::invalid_argument for an elastic cable (its stretch is not a coordinate here).
std::vector<Mode> naturalModes(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                               const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                               double step = 1e-6);

}  // namespace tow_sim
