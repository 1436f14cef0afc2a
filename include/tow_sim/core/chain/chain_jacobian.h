// Derivatives of the chain's element loads (S16), for the implicit stepper's stage matrix
// N = M - gamma h D - (gamma h)^2 K (S19) (docs/solver.md §7).
#pragma once

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
// The derivatives of one element's loads projected onto its joints (w_f, w_a of docs/solver.md (S5), the
// code's h_f, h_a): rows (w_f, w_a), columns (forward joint, aft joint).
struct ElementJacobian
{
  Matrix6d dh_dv;  // [N s/m] d(w_f, w_a) / d(v_f, v_a): D
  Matrix6d dh_dx;  // [N/m]   d(w_f, w_a) / d(x_f, x_a): K
};

// Element e at the joint kinematics k of a solve (ChainSolver's), mu its axial multiplier from that solve
// (compression positive). Included:
//   cable segments, analytically: the normal and tangential drag (Pode with its smooth sign, or quadratic)
//     and the rotation-drag moment in the velocities (velocityForceJacobian), the winch's turning term on
//     the first segment, the seabed contact at the aft joint through the point's position and velocity
//     (Seabed::contactJacobian);
//   the end body: all its loads (hydrodynamics, fins, thrust, Munk and gyroscopic terms, buoyancy moment,
//     contact) and its inertia's turning, by forward differences over its four joint vectors x_f, x_a,
//     v_f, v_a;
//   every element: the geometric stiffness of its tension T = max(-mu, 0) turning with the axis,
//     -T/d (I - s s^T) on the relative displacement of its joints (compression is left out: it would
//     soften N);
//   elastic segments: the axial stiffness and damping of their tension (addAxialStiffness);
//   (added by the implicit stepper, with the neighbours' positions) bending, addBendingStiffness.
// Left out (a W-method keeps its order with any matrix; only the step it can take changes): on cable
// segments the drag's and the weight's dependence on the direction, the current profile's on depth and the
// waves' dependence on position (and their acceleration's load);
// on cable segments the inertia's dependence on the direction; on every element the length constraint's
// dependence on the direction and its velocity term.
// When `accelerations` (a_f, a_a at the state) is given, the end body's derivatives include its inertia
// turning with its axis, -d(M)/dx (a_f, a_a): it matters while the body whips (a start from a line).
void elementJacobian(const ChainModel& model, int e, double t, const ElementKinematics& k,
                     const ChainGeometry& geometry, const ChainData& data, double mu, ElementJacobian& out,
                     const Vector6d* accelerations = nullptr);

// The geometric stiffness term alone (added by elementJacobian).
void addGeometricStiffness(const ElementKinematics& k, double mu, ElementJacobian& out);
// An elastic segment of rest length rest_length [m]: its tension's derivatives in the joints' positions and
// velocities along the axis (EA/d0, c/d0), while it is taut (added by elementJacobian).
void addAxialStiffness(const CableParams& cable, double rest_length, const ElementKinematics& k, ElementJacobian& out);

// Bending (physics.md (P48)) on cable segment e, whose joints are x_f = joint e - 1 (first: the tow point
// `first`) and x_a = joint e of the positions x: the stiffness of the springs at its two ends, added to
// out.dh_dx. A joint's spring couples three joints (the joint and its two neighbours); per element the
// stage matrix holds two. The Gauss-Newton Hessian kappa B^T B of the energy 1/2 kappa |s_f x s_a|^2 (exact
// on a straight chain) is split between the spring's two segments, and the block coupling the outer two
// joints, which neither segment holds, is moved onto their diagonals (B_o^T B_o each, which keeps the
// matrix positive semi-definite: the stage matrix stiffer, never softer, than the bending).
void addBendingStiffness(const ChainModel& model, const ChainGeometry& geometry, const Eigen::Vector3d& first,
                         const Eigen::Ref<const Eigen::Matrix3Xd>& x, int e, ElementJacobian& out);

}  // namespace tow_sim
