// Added mass of the towed vehicle for Approach B (report Appendix E, Kirchhoff): 6x6 matrices in body
// axes (FLU), Lamb's coefficients of a prolate spheroid, moving a matrix between reference points.
#pragma once

#include <Eigen/Core>
#include <string>

#include "tow_sim/core/chain/element.h"

namespace tow_sim
{
// Lamb's inertia coefficients of a prolate spheroid (Hydrodynamics §373): k1 axial, k2 transverse,
// k' rotational about a transverse axis; added masses k1 m_d, k2 m_d, k2 m_d and k' I_d with m_d the
// displaced mass and I_d its transverse moment of inertia about the centre, m_d (a^2 + b^2) / 5.
struct LambCoefficients
{
  double k1 = 0.0, k2 = 0.0, k_rot = 0.0;
};
LambCoefficients lambCoefficients(double length, double diameter);

// 6x6 added mass [kg, kg m, kg m^2] of a prolate spheroid about its centre, body axes (x along the axis).
Matrix6d prolateSpheroidAddedMass(double length, double diameter, double water_density);

// Moves a 6x6 mass matrix given about point C to point G, r_GC = C - G in the same axes:
// M_G = T^T M_C T with T = [I, -[r x]; 0, I] (velocity of C = v_G + w x r_GC).
Matrix6d moveMassMatrix(const Matrix6d& M_C, const Eigen::Vector3d& r_GC);

// Throws std::invalid_argument naming `name` unless M is finite, symmetric and positive semi-definite.
void validateAddedMass(const Matrix6d& M, const std::string& name);

// The velocity-product (Munk) terms of Kirchhoff's equations for added mass A about the body origin,
// body axes: force = A11 (w x v) - w x P, moment = A21 (w x v) - w x L - v x P, with P = A11 v + A12 w,
// L = A21 v + A22 w. Together with -A [a; dw/dt] (a the inertial acceleration of the origin in body
// axes) they give -(d/dt P + w x P), -(d/dt L + w x L + v x P).
Vector6d munkWrench(const Matrix6d& A, const Eigen::Vector3d& v_B, const Eigen::Vector3d& w_B);

}  // namespace tow_sim
