#include "tow_sim/core/analysis/jacobian_check.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "tow_sim/core/chain/chain_jacobian.h"
#include "tow_sim/core/chain/chain_solver.h"

namespace tow_sim
{
Eigen::Matrix3Xd linearisedAccelerations(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                         double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                                         const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& dx,
                                         const Eigen::Matrix3Xd& dv)
{
  // The state's own solve gives the element equations (M, s) and the multipliers mu, as the stepper's.
  ChainSolver solver;
  Eigen::Matrix3Xd a(3, x.cols());
  std::vector<double> mu;
  solver.solve(model, geometry, data, t, ship, x, v, a, nullptr, &mu);
  std::vector<ElementTerms> terms = solver.terms();
  for (size_t i = 0; i < terms.size(); ++i)
  {
    const int e = static_cast<int>(i);
    const Eigen::Vector3d x_f = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
    const Eigen::Vector3d v_f = e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1));
    Vector6d a_joints;
    a_joints << (e == 0 ? ship.a_W : Eigen::Vector3d(a.col(e - 1))), a.col(e);
    ElementJacobian J;
    elementJacobian(model, e, t, ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e)), geometry, data, mu[i], J,
                    &a_joints);
    if (model.bends())
      addBendingStiffness(model, geometry, ship.p_W, x, e, J);
    Vector6d d_x, d_v;  // the tow point does not move with the state
    d_x << (e == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(dx.col(e - 1))), dx.col(e);
    d_v << (e == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(dv.col(e - 1))), dv.col(e);
    const Vector6d h = J.dh_dx * d_x + J.dh_dv * d_v;
    terms[i].h_f = h.head<3>();
    terms[i].h_a = h.tail<3>();
    terms[i].c = 0.0;
  }
  ChainSweep sweep;
  sweep.factor(terms);
  Eigen::Matrix3Xd out(3, x.cols());
  sweep.solve(terms, Eigen::Vector3d::Zero(), out);
  return out;
}

Eigen::Matrix3Xd differencedAccelerations(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                          double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                                          const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& dx,
                                          const Eigen::Matrix3Xd& dv, double step)
{
  const double scale = std::max(dx.cwiseAbs().maxCoeff(), dv.cwiseAbs().maxCoeff());
  const double e = scale > 0.0 ? step / scale : step;
  ChainSolver solver;
  Eigen::Matrix3Xd plus(3, x.cols()), minus(3, x.cols());
  solver.solve(model, geometry, data, t, ship, x + e * dx, v + e * dv, plus);
  solver.solve(model, geometry, data, t, ship, x - e * dx, v - e * dv, minus);
  return (plus - minus) / (2.0 * e);
}

Eigen::Matrix3Xd lengthKeepingDisplacement(const ShipEndState& ship, const Eigen::Matrix3Xd& x, std::mt19937& rng)
{
  std::normal_distribution<double> n01;
  Eigen::Matrix3Xd d(3, x.cols());
  Eigen::Vector3d prev = Eigen::Vector3d::Zero(), x_f = ship.p_W;
  for (Eigen::Index j = 0; j < x.cols(); ++j)
  {
    const Eigen::Vector3d r(n01(rng), n01(rng), n01(rng));
    d.col(j) = prev + r.cross(x.col(j) - x_f);  // r x (l s): normal to the axis
    prev = d.col(j);
    x_f = x.col(j);
  }
  return d / d.cwiseAbs().maxCoeff();
}

JacobianError jacobianError(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                            const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, int trials,
                            unsigned seed)
{
  std::mt19937 rng(seed);
  const Eigen::Matrix3Xd zero = Eigen::Matrix3Xd::Zero(3, x.cols());
  JacobianError out;
  for (int i = 0; i < trials; ++i)
  {
    const Eigen::Matrix3Xd dx = lengthKeepingDisplacement(ship, x, rng);
    const Eigen::Matrix3Xd dv = lengthKeepingDisplacement(ship, x, rng);
    const Eigen::Matrix3Xd fd_x = differencedAccelerations(model, geometry, data, t, ship, x, v, dx, zero);
    const Eigen::Matrix3Xd fd_v = differencedAccelerations(model, geometry, data, t, ship, x, v, zero, dv);
    const Eigen::Matrix3Xd j_x = linearisedAccelerations(model, geometry, data, t, ship, x, v, dx, zero);
    const Eigen::Matrix3Xd j_v = linearisedAccelerations(model, geometry, data, t, ship, x, v, zero, dv);
    // Relative to the true response; where that is zero (no velocity dependence at rest), absolute.
    out.position = std::max(out.position, (j_x - fd_x).norm() / std::max(fd_x.norm(), 1e-300));
    out.velocity = std::max(out.velocity, (j_v - fd_v).norm() / std::max(fd_v.norm(), 1.0));
  }
  return out;
}

}  // namespace tow_sim
