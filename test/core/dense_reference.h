// Reference solution of the chain's equations for the tests and benchmarks: the 6(nu+1) Newton-Euler
// equations of physics.md §4/§6 (3 linear momentum, 2 angular momentum about the CG normal to the
// element axis, 1 length constraint per element) assembled into one dense matrix over the unknown
// joint accelerations and tension vectors, and solved with a full-pivot LU. Written independently of
// the O(nu) sweep in ChainSolver, which must reproduce it.
#pragma once

#include <Eigen/Core>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
namespace test
{
struct DenseSolution
{
  Eigen::Matrix3Xd accelerations;  // x_2 .. x_{nu+2}
  Eigen::Matrix3Xd tensions;       // T_1 .. T_{nu+1}
};

// For the chain's geometry and data at that instant (the model's initial ones in the second form).
DenseSolution solveDense(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                         const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v);
DenseSolution solveDense(const ChainModel& model, double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                         const Eigen::Matrix3Xd& v);

// The O(nu) sweep (ChainSolver) against solveDense on one state: ||a - a_ref|| / ||a_ref|| and the same for
// the tensions.
struct SweepDeviation
{
  double accelerations = 0.0, tensions = 0.0;  // [-]
};
SweepDeviation sweepAgainstDense(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                 double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                                 const Eigen::Matrix3Xd& v);

}  // namespace test
}  // namespace tow_sim
