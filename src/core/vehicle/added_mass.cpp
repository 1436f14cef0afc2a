#include "tow_sim/core/vehicle/added_mass.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/geometry.h"
#include "tow_sim/core/params.h"

namespace tow_sim
{
namespace
{
}

LambCoefficients lambCoefficients(double length, double diameter)
{
  requireInRange("prolate_spheroid.length", length, 0.0, 1e3, "[m]", true);
  requireInRange("prolate_spheroid.diameter", diameter, 0.0, length, "[m] (0 .. length: prolate)", true);
  const double a = 0.5 * length, b = 0.5 * diameter;
  const double e2 = 1.0 - (b * b) / (a * a);
  LambCoefficients k;
  if (e2 < 1e-6)  // a sphere: k1 = k2 = 1/2, k' = 0
  {
    k.k1 = k.k2 = 0.5;
    return k;
  }
  const double e = std::sqrt(e2);
  const double log_term = std::log((1.0 + e) / (1.0 - e));
  const double alpha0 = 2.0 * (1.0 - e2) / (e2 * e) * (0.5 * log_term - e);
  const double beta0 = 1.0 / e2 - (1.0 - e2) / (2.0 * e2 * e) * log_term;
  k.k1 = alpha0 / (2.0 - alpha0);
  k.k2 = beta0 / (2.0 - beta0);
  k.k_rot = e2 * e2 * (beta0 - alpha0) / ((2.0 - e2) * (2.0 * e2 - (2.0 - e2) * (beta0 - alpha0)));
  return k;
}

Matrix6d prolateSpheroidAddedMass(double length, double diameter, double water_density)
{
  const LambCoefficients k = lambCoefficients(length, diameter);
  const double a = 0.5 * length, b = 0.5 * diameter;
  const double m_d = water_density * 4.0 / 3.0 * kPi * a * b * b;
  const double I_d = m_d * (a * a + b * b) / 5.0;
  Vector6d diag;
  diag << k.k1 * m_d, k.k2 * m_d, k.k2 * m_d, 0.0, k.k_rot * I_d, k.k_rot * I_d;
  return diag.asDiagonal();
}

Matrix6d moveMassMatrix(const Matrix6d& M_C, const Eigen::Vector3d& r_GC)
{
  Matrix6d T = Matrix6d::Identity();
  T.topRightCorner<3, 3>() = -skew(r_GC);
  return T.transpose() * M_C * T;
}

void validateAddedMass(const Matrix6d& M, const std::string& name)
{
  std::ostringstream problem;
  const double scale = std::max(1.0, M.cwiseAbs().maxCoeff());
  if (!M.allFinite())
    problem << "has a non-finite entry";
  else if ((M - M.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    problem << "is not symmetric (largest |M_ij - M_ji| = " << (M - M.transpose()).cwiseAbs().maxCoeff() << ")";
  else
  {
    const double min_eig = Eigen::SelfAdjointEigenSolver<Matrix6d>(M).eigenvalues().minCoeff();
    if (min_eig < -1e-9 * scale)
      problem << "is not positive semi-definite (smallest eigenvalue " << min_eig << ")";
  }
  if (!problem.str().empty())
    throw std::invalid_argument(name + " " + problem.str() +
                                ": must be a symmetric positive semi-definite 6x6 matrix [kg, kg m, kg m^2]");
}

Vector6d munkWrench(const Matrix6d& A, const Eigen::Vector3d& v_B, const Eigen::Vector3d& w_B)
{
  const Eigen::Vector3d P = A.topLeftCorner<3, 3>() * v_B + A.topRightCorner<3, 3>() * w_B;
  const Eigen::Vector3d L = A.bottomLeftCorner<3, 3>() * v_B + A.bottomRightCorner<3, 3>() * w_B;
  const Eigen::Vector3d wxv = w_B.cross(v_B);
  Vector6d out;
  out.head<3>() = A.topLeftCorner<3, 3>() * wxv - w_B.cross(P);
  out.tail<3>() = A.bottomLeftCorner<3, 3>() * wxv - w_B.cross(L) - v_B.cross(P);
  return out;
}

}  // namespace tow_sim
