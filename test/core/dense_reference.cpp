#include "core/dense_reference.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "tow_sim/core/chain/chain_solver.h"

namespace tow_sim
{
namespace test
{
namespace
{
Eigen::Matrix3d cross(const Eigen::Vector3d& r)
{
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

// The bending moment on cable segment e from its joints with its neighbours (physics.md §11), from the
// definition: at the joint between segments i-1 and i, kappa theta about n = s_{i-1} x s_i / |...| on the
// forward one and its opposite on the aft one, theta = acos(s_{i-1} . s_i), kappa the two half-segments'
// flexibilities l/(2 EI) in series.
Eigen::Vector3d bendingOn(const ChainModel& model, const ChainGeometry& geometry, const ShipEndState& ship,
                          const Eigen::Matrix3Xd& x, int e)
{
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  if (e >= geometry.segments)
    return moment;
  auto axis = [&](int i) -> Eigen::Vector3d
  { return (x.col(i) - (i == 0 ? ship.p_W : Eigen::Vector3d(x.col(i - 1)))).normalized(); };
  auto jointMoment = [&](int i) -> Eigen::Vector3d  // on segment i-1
  {
    const double ei_f = model.segmentCable(i - 1, geometry).bending_stiffness;
    const double ei_a = model.segmentCable(i, geometry).bending_stiffness;
    const Eigen::Vector3d n = axis(i - 1).cross(axis(i));
    if (ei_f == 0.0 || ei_a == 0.0 || n.norm() == 0.0)
      return Eigen::Vector3d::Zero();
    const double kappa =
        1.0 / (geometry.elementLength(i - 1) / (2.0 * ei_f) + geometry.elementLength(i) / (2.0 * ei_a));
    return kappa * std::acos(std::clamp(axis(i - 1).dot(axis(i)), -1.0, 1.0)) * n.normalized();
  };
  if (e >= 1)
    moment -= jointMoment(e);
  if (e + 1 < geometry.segments)
    moment += jointMoment(e + 1);
  return moment;
}
}  // namespace

DenseSolution solveDense(const ChainModel& model, double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                         const Eigen::Matrix3Xd& v)
{
  const ChainData data = model.initialData(t);
  return solveDense(model, model.initialGeometry(), data, t, ship, x, v);
}

namespace
{
// Element e's six rows of the dense system (from row 6 e): its linear momentum, its angular momentum about
// its CG normal to its axis, and its length constraint, in the joint accelerations a_j (at 3 j) and the
// tensions T_e (at 3 n + 3 e). A point body at its aft joint is part of the element's free body: its
// inertia and loads act at that joint, so they enter the linear momentum and, about the CG, with the arm
// (1 - gamma) l s.
void addElementRows(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                    const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, int e,
                    Eigen::MatrixXd& A, Eigen::VectorXd& b)
{
  const int n = geometry.elementCount();
  auto acc = [](int joint) { return 3 * joint; };
  auto ten = [n](int element) { return 3 * n + 3 * element; };
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d x_f = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
  const Eigen::Vector3d v_f = e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1));
  const ElementKinematics k = ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
  BodyDynamics body;
  model.elementDynamics(e, t, k, geometry, data, body);
  // A winch changes the first segment's length L(t): differentiating s = (x_a - x_f)/L twice,
  // s x d2s/dt2 = s x (a_a - a_f)/L - 2 (L'/L) s x ds/dt, and w = s x ds/dt: the angular acceleration
  // has the known part -2 (L'/L) w, moved here to the loads.
  if (e == 0)
    body.wrench -= body.mass.rightCols<3>() * (-2.0 * geometry.first_rate / k.length * k.omega);
  body.wrench.tail<3>() += bendingOn(model, geometry, ship, x, e);
  const double g = body.cg_fraction;
  const double l = k.length;
  const Eigen::Vector3d& s = k.s;

  // a_G = (1-g) a_f + g a_a ; dw/dt = s x (a_a - a_f) / l   (no roll, Appendix A)
  Eigen::Matrix<double, 6, 3> C_f, C_a;
  C_f << (1.0 - g) * I3, -cross(s) / l;
  C_a << g * I3, cross(s) / l;
  const Eigen::Matrix<double, 6, 3> MC_f = body.mass * C_f;
  Eigen::Matrix<double, 6, 3> MC_a = body.mass * C_a;
  if (const JointBody* point = model.bodyAft(e, geometry))
  {
    // m_p a_a on the linear rows and (1-g) l s x (m_p a_a) on the angular ones; its loads likewise.
    const Eigen::Vector3d f = point->force(data.environment, t, k.x_a, k.v_a);
    MC_a.topRows<3>() += point->inertia() * I3;
    MC_a.bottomRows<3>() += ((1.0 - g) * l) * cross(s) * point->inertia();
    body.wrench.head<3>() += f;
    body.wrench.tail<3>() += ((1.0 - g) * l) * s.cross(f);
  }

  // Two unit vectors normal to s for the angular-momentum rows.
  Eigen::Vector3d e1 = s.unitOrthogonal();
  Eigen::Vector3d e2 = s.cross(e1);
  Eigen::Matrix<double, 2, 3> E;
  E << e1.transpose(), e2.transpose();

  const int row = 6 * e;
  // Linear momentum: m a_G (+ added mass) - T_e + T_{e+1} = F*.
  A.block<3, 3>(row, acc(e)) += MC_a.topRows<3>();
  if (e > 0)
    A.block<3, 3>(row, acc(e - 1)) += MC_f.topRows<3>();
  else
    b.segment<3>(row) -= MC_f.topRows<3>() * ship.a_W;
  A.block<3, 3>(row, ten(e)) -= I3;
  if (e + 1 < n)
    A.block<3, 3>(row, ten(e + 1)) += I3;
  b.segment<3>(row) += body.wrench.head<3>();

  // Angular momentum about the CG, normal to s:
  // I dw/dt (+ added mass) + s x (g l T_e + (1-g) l T_{e+1}) = M*.
  A.block<2, 3>(row + 3, acc(e)) += E * MC_a.bottomRows<3>();
  if (e > 0)
    A.block<2, 3>(row + 3, acc(e - 1)) += E * MC_f.bottomRows<3>();
  else
    b.segment<2>(row + 3) -= E * MC_f.bottomRows<3>() * ship.a_W;
  A.block<2, 3>(row + 3, ten(e)) += E * cross(s) * (g * l);
  if (e + 1 < n)
    A.block<2, 3>(row + 3, ten(e + 1)) += E * cross(s) * ((1.0 - g) * l);
  b.segment<2>(row + 3) += E * body.wrench.tail<3>();

  // Length constraint: s.(a_a - a_f) = -|v_a - v_f|^2 / l.
  A.block<1, 3>(row + 5, acc(e)) += s.transpose();
  if (e > 0)
    A.block<1, 3>(row + 5, acc(e - 1)) -= s.transpose();
  else
    b(row + 5) += s.dot(ship.a_W);
  b(row + 5) -= (k.v_a - k.v_f).squaredNorm() / l;
  // A winch changes the first segment's length L(t): d^2/dt^2 |x_a - x_f|^2 / 2 = L'^2 + L L''.
  if (e == 0)
    b(row + 5) += (geometry.first_rate * geometry.first_rate + l * geometry.first_acceleration) / l;
}
}  // namespace

DenseSolution solveDense(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                         const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v)
{
  const int n = geometry.elementCount();
  const int size = 6 * n;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(size, size);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(size);
  for (int e = 0; e < n; ++e)
    addElementRows(model, geometry, data, t, ship, x, v, e, A, b);
  const Eigen::VectorXd z = A.fullPivLu().solve(b);
  DenseSolution out;
  out.accelerations = Eigen::Map<const Eigen::Matrix3Xd>(z.data(), 3, n);
  out.tensions = Eigen::Map<const Eigen::Matrix3Xd>(z.data() + 3 * n, 3, n);
  return out;
}

SweepDeviation sweepAgainstDense(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data,
                                 double t, const ShipEndState& ship, const Eigen::Matrix3Xd& x,
                                 const Eigen::Matrix3Xd& v)
{
  Eigen::Matrix3Xd a(3, x.cols()), T(3, x.cols());
  ChainSolver solver;
  solver.solve(model, geometry, data, t, ship, x, v, a, &T);
  const DenseSolution ref = solveDense(model, geometry, data, t, ship, x, v);
  return { (a - ref.accelerations).norm() / ref.accelerations.norm(), (T - ref.tensions).norm() / ref.tensions.norm() };
}

}  // namespace test
}  // namespace tow_sim
