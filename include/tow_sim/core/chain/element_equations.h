// One element's equations on its two joints, (S1)-(S6) of docs/solver.md: what ChainSolver assembles for every
// element before its sweeps, for a caller that needs one element alone (the linearisation of modes.h
// differences it joint by joint).
#pragma once

#include <Eigen/Core>

#include "tow_sim/core/chain/chain_model.h"
#include "tow_sim/core/chain/chain_solver.h"

namespace tow_sim
{
// Element e (0-based; e = geometry.segments is the end body) at its kinematics k: its projected inertia M_XY,
// loads w_X, axis, constraint Psi (or, elastic, its tension) into m, as ChainSolver::solve forms them. `bending`:
// the bending couples on a segment from its neighbours (docs/solver.md §11), or null where there are none.
// `body` is workspace.
void elementEquations(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t, int e,
                      const ElementKinematics& k, const Eigen::Vector3d* bending, BodyDynamics& body, ElementTerms& m);

}  // namespace tow_sim
