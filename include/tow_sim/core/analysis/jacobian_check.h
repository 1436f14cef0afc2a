// How far the implicit stepper's J is from the true derivative of the right-hand side (issue 32, item 1;
// docs/solver.md §7): on a state of a chain, the accelerations the stepper's linearisation (S17) gives for a
// displacement (dx, dv) of the joints, against central differences of the full solve (ChainSolver) along
// the same displacement. Used by test_jacobian_check and bench_jacobian.
#pragma once

#include <Eigen/Core>
#include <random>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
// a' of (S17): M a' = K dx + D dv - mu' s, s.(a'_a - a'_f) = 0, the tow point's a' zero, with D and K
// as the implicit stepper builds them (elementJacobian, addBendingStiffness) at the state (x, v).
Eigen::Matrix3Xd linearisedAccelerations(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                         double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                                         const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& dx,
                                         const Eigen::Matrix3Xd& dv);

// (a(x + e dx, v + e dv) - a(x - e dx, v - e dv)) / (2 e) from ChainSolver, e = step / max|(dx, dv)|:
// the true directional derivative to O(e^2) (the loads are smooth where the cross-flow does not vanish).
Eigen::Matrix3Xd differencedAccelerations(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                          double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                                          const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& dx,
                                          const Eigen::Matrix3Xd& dv, double step = 1e-6);

// A displacement that keeps the chain's lengths to first order: each element turned about its forward joint
// by a random small rotation normal to its axis (its aft joint moves by d_prev + l (r x s)), the tow point
// fixed. Scaled so that its largest joint displacement is 1.
Eigen::Matrix3Xd lengthKeepingDisplacement(const ShipEndState& ship, const Eigen::Matrix3Xd& x, std::mt19937& rng);

// The relative error of J on the position block (dx alone) and the velocity block (dv alone), each over
// `trials` random length-keeping displacements: max ||a'_J - a'_fd|| / ||a'_fd|| (the velocity block's
// divided by at least 1 s^-1 per unit displacement: at rest nothing depends on the velocities).
struct JacobianError
{
  double position = 0.0;  // [-] K's part
  double velocity = 0.0;  // [-] D's part
};
JacobianError jacobianError(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                            const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                            int trials = 4, unsigned seed = 1);

}  // namespace tow_sim
