#include "tow_sim/core/chain/chain_jacobian.h"

#include <algorithm>
#include <cmath>

#include "tow_sim/core/geometry.h"

namespace tow_sim
{
namespace
{
using Matrix63d = Eigen::Matrix<double, 6, 3>;
using Matrix36d = Eigen::Matrix<double, 3, 6>;

// J^T X for a cable segment's J = [J_f J_a] (jointMap at vartheta = 1/2): J_f^T X = X_t/2 - S^T X_r and
// J_a^T X = X_t/2 + S^T X_r, X_t and X_r X's force and moment rows, S = [s]x / d; the product J^T X
// to rounding at a third of its arithmetic.
Matrix6d projectOntoJoints(const ElementKinematics& k, const Matrix6d& X)
{
  const Eigen::Matrix3d S_t = skew(k.s).transpose() / k.length;
  const Matrix36d r = S_t * X.bottomRows<3>();
  Matrix6d out;
  out.topRows<3>() = 0.5 * X.topRows<3>() - r;
  out.bottomRows<3>() = 0.5 * X.topRows<3>() + r;
  return out;
}

// (S16) for cable segment e: d w / d(v_f, v_a) and d w / d(x_f, x_a) of its wrench w at the CG (the centre,
// vartheta = 1/2), then projected with [J_f J_a]^T as (S5) projects w: out.dh_dv is D, out.dh_dx is K.
void segmentJacobian(const ChainModel& model, int e, double t, const ElementKinematics& k,
                     const ChainGeometry& geometry, const ChainData& data, ElementJacobian& out)
{
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const CableSegmentModel seg = model.segmentModel(e, geometry);
  const double rate = e == 0 ? geometry.first_rate : 0.0;
  // The first segment's cable moves at the payout rate along it (ChainModel::elementDynamics): the same
  // derivatives, at the shifted velocity.
  const ElementKinematics kw = rate != 0.0 ? ElementKinematics::fromJoints(k.x_f, k.x_a, k.v_f + rate * k.s, k.v_a) : k;
  // The waves' velocity and acceleration vary along the wave (k a omega per metre): left out of J, which
  // a W-method may approximate (their forcing is not stiff).
  const VelocityForceJacobian vf =
      segmentVelocityForceJacobian(seg, kw, data.environment.flowOver(kw.x_f, kw.x_a, t).velocity_W);
  // u = (v_f + v_a)/2 - current, dv = v_a - v_f.
  Matrix6d dw_dv;
  dw_dv << 0.5 * vf.force_u, 0.5 * vf.force_u, 0.5 * vf.moment_u - vf.moment_dv, 0.5 * vf.moment_u + vf.moment_dv;
  if (rate != 0.0)
  {
    // ChainSolver: wrench += (2 L'/L) I_rot w with w = s x dv / L (the segment's rotary inertia m L^2 / 12).
    const double rotary = seg.mass * seg.length * seg.length / 12.0;
    const Eigen::Matrix3d dm = (2.0 * rate / k.length) * rotary * skew(k.s) / k.length;
    dw_dv.bottomLeftCorner<3, 3>() -= dm;
    dw_dv.bottomRightCorner<3, 3>() += dm;
  }
  Matrix6d dw_dx = Matrix6d::Zero();
  // An elastic segment takes the contact at its aft joint on that joint itself (ChainSolver).
  const bool elastic = model.elastic();
  Eigen::Matrix3d contact_p = Eigen::Matrix3d::Zero(), contact_v = Eigen::Matrix3d::Zero();
  if (const Seabed* bottom = model.seabed())
  {
    const Eigen::Vector3d x_G = k.pointAt(0.5);
    model.forEachContact(e, geometry,
                         [&](double eta, double stiffness, double damping)
                         {
                           const Eigen::Vector3d p = k.pointAt(eta);
                           Eigen::Matrix3d df_dp, df_dv;
                           bottom->contactJacobian(p, k.velocityAt(eta), stiffness, damping, df_dp, df_dv);
                           if (elastic)
                           {
                             contact_p += df_dp;
                             contact_v += df_dv;
                             return;
                           }
                           Matrix63d arm;  // a force at p as a wrench at the CG
                           arm << I3, skew(p - x_G);
                           Matrix36d at;  // p and its velocity from the joints'
                           at << (1.0 - eta) * I3, eta * I3;
                           dw_dv += arm * df_dv * at;
                           dw_dx += arm * df_dp * at;
                         });
  }
  // (S16): D = d(w_f, w_a)/d(v_f, v_a), K = d(w_f, w_a)/d(x_f, x_a), the wrench's derivatives projected as (S5).
  out.dh_dv = projectOntoJoints(k, dw_dv);
  out.dh_dx = projectOntoJoints(k, dw_dx);
  out.dh_dv.bottomRightCorner<3, 3>() += contact_v;
  out.dh_dx.bottomRightCorner<3, 3>() += contact_p;
  if (const JointBody* point = model.bodyAft(e, geometry))  // its drag on the aft joint (S23): D_aa
    out.dh_dv.bottomRightCorner<3, 3>() += point->forceVelocityJacobian(data.environment, t, k.x_a, k.v_a);
}

// (S16) for the end body: central differences of its projected loads w_f, w_a over x_f, x_a (K) and v_f, v_a
// (D), less its projected inertia's force at the state's accelerations (its turning inertia -dM/dx a).
void endBodyJacobian(const ChainModel& model, int e, double t, const ElementKinematics& k,
                     const ChainGeometry& geometry, const ChainData& data, const Vector6d* accelerations,
                     ElementJacobian& out)
{
  BodyDynamics body;
  // The projected loads less the projected inertia's force at the state's accelerations, J^T (w - M_b J a)
  // (M_b: the body's M of (S2); J = [J_f J_a] of (S1)).
  auto loads = [&](const ElementKinematics& kk) -> Vector6d
  {
    model.elementDynamics(e, t, kk, geometry, data, body);
    const Matrix6d J = jointMap(kk.s, kk.length, body.cg_fraction);
    if (accelerations)
      return J.transpose() * (body.wrench - body.mass * (J * *accelerations));
    return J.transpose() * body.wrench;
  };
  // Central differences: the loads have corners (|u_n| where the cross-flow vanishes, as at a steady
  // tow), where one-sided differences taken from the two joints would not cancel for a translation.
  Eigen::Vector3d joint[4] = { k.x_f, k.x_a, k.v_f, k.v_a };
  auto perturbed = [&]
  {
    ElementKinematics kk = ElementKinematics::fromJoints(joint[0], joint[1], joint[2], joint[3]);
    kk.roll = k.roll;  // a rolling end body's roll held
    kk.roll_rate = k.roll_rate;
    return kk;
  };
  for (int j = 0; j < 12; ++j)
  {
    Eigen::Vector3d& component_of = joint[j / 3];
    const double saved = component_of[j % 3];
    const bool position = j < 6;
    // About the cube root of machine epsilon of the scale of what is perturbed: the element's length, the speed.
    const double step = 1e-5 * (position ? std::max(1.0, k.length) : std::max(1.0, std::abs(saved)));
    component_of[j % 3] = saved + step;
    const Vector6d plus = loads(perturbed());
    component_of[j % 3] = saved - step;
    const Vector6d minus = loads(perturbed());
    component_of[j % 3] = saved;
    (position ? out.dh_dx : out.dh_dv).col(j % 6) = (plus - minus) / (2.0 * step);  // a column of K or D
  }
}
}  // namespace

// (S16): the geometric stiffness of the multiplier mu (S5a) in K, pattern (-, +; +, -) over (forward, aft).
void addGeometricStiffness(const ElementKinematics& k, double mu, ElementJacobian& out)
{
  // The axial force (-mu s on the forward joint, +mu s on the aft one) turns with s = (x_a - x_f)/d:
  // d(mu s)/d x_a = mu (I - s s^T)/d. Only a tension (mu < 0) stiffens.
  const double tension = std::max(-mu, 0.0);
  const Eigen::Matrix3d G = tension / k.length * (Eigen::Matrix3d::Identity() - k.s * k.s.transpose());
  out.dh_dx.topLeftCorner<3, 3>() -= G;
  out.dh_dx.topRightCorner<3, 3>() += G;
  out.dh_dx.bottomLeftCorner<3, 3>() += G;
  out.dh_dx.bottomRightCorner<3, 3>() -= G;
}

// (S16) for an elastic segment (docs/solver.md §8): the derivatives of (S20)'s T s in K and D.
void addAxialStiffness(const CableParams& cable, double rest_length, const ElementKinematics& k, ElementJacobian& out)
{
  // The elastic segment's tension T = max(0, EA eps + C deps/dt) (S20) on its joints (+T s forward, -T s aft)
  // through its length and stretch rate along s (the axis held fixed): EA/d0 and C/d0 on s s^T, while taut
  // (C, the axial damping, is cable.axial_damping).
  const double rate = k.s.dot(k.v_a - k.v_f);
  if (cable.axialTension(k.length, rate, rest_length) <= 0.0)
    return;
  const Eigen::Matrix3d ss = k.s * k.s.transpose();
  // The stretch rate s.(v_a - v_f) turns with the axis too: d(s.dv)/dx_a = ((I - s s^T) dv)^T / d. In a turn,
  // where the segments rotate, that term of the damping dominates K (bench_jacobian: without it J's position
  // block was 97 % off on the turn with C = 1e6 N s, 5 % with C = 0).
  const Eigen::Vector3d dv = k.v_a - k.v_f;
  // Kx: EA/d0 s s^T + C/(d0 d) s ((I - s s^T) dv)^T, the 3 x 3 block of K; Dv: C/d0 s s^T, that of D.
  const Eigen::Matrix3d Kx = (*cable.axial_stiffness / rest_length) * ss +
                             (cable.axial_damping / (rest_length * k.length)) * k.s * (dv - rate * k.s).transpose();
  const Eigen::Matrix3d Dv = (cable.axial_damping / rest_length) * ss;
  for (Matrix6d* m : { &out.dh_dx, &out.dh_dv })
  {
    const Eigen::Matrix3d& G = m == &out.dh_dx ? Kx : Dv;
    m->topLeftCorner<3, 3>() -= G;
    m->topRightCorner<3, 3>() += G;
    m->bottomLeftCorner<3, 3>() += G;
    m->bottomRightCorner<3, 3>() -= G;
  }
}

// (S16), bending (docs/solver.md §11): the Gauss-Newton Hessian kappa_b B^T B of the springs at segment e's two
// joints in its K. Here kappa (Spring::kappa) is kappa_b, the spring's stiffness (physics.md (P48)), not the
// regularisation kappa of (S9).
void addBendingStiffness(const ChainModel& model, const ChainGeometry& geometry, const Eigen::Vector3d& first,
                         const Eigen::Ref<const Eigen::Matrix3Xd>& x, int e, ElementJacobian& out)
{
  if (e >= geometry.segments)
    return;
  auto joint = [&](int j) -> Eigen::Vector3d { return j < 0 ? first : Eigen::Vector3d(x.col(j)); };
  // The spring at the joint between segments i - 1 and i (x.col(i - 1)): beta = s_f x s_a, d beta = B_o dx_o +
  // B_m dx_m + B_n dx_n over the joints before, at and after it (o, m, n: joints i - 2, i - 1, i), with
  // ds = (I - s s^T) d(x_a - x_f) / l.
  struct Spring
  {
    double kappa;
    Eigen::Matrix3d o, m, n;
  };
  auto spring = [&](int i) -> Spring
  {
    const Eigen::Vector3d d_f = joint(i - 1) - joint(i - 2), d_a = joint(i) - joint(i - 1);
    const double l_f = d_f.norm(), l_a = d_a.norm();
    const Eigen::Vector3d s_f = d_f / l_f, s_a = d_a / l_a;
    const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d A = skew(s_a) * (I3 - s_f * s_f.transpose()) / l_f;  // d beta / d(x_m - x_o) = -A
    const Eigen::Matrix3d C = skew(s_f) * (I3 - s_a * s_a.transpose()) / l_a;  // d beta / d(x_n - x_m) = C
    return { model.jointBendingStiffness(i, geometry), A, -A - C, C };
  };
  auto add =
      [&](double w_ff, const Eigen::Matrix3d& B_f, double w_fa, const Eigen::Matrix3d& B_a, double w_aa, double kappa)
  {
    out.dh_dx.topLeftCorner<3, 3>() -= w_ff * kappa * B_f.transpose() * B_f;
    out.dh_dx.topRightCorner<3, 3>() -= w_fa * kappa * B_f.transpose() * B_a;
    out.dh_dx.bottomLeftCorner<3, 3>() -= w_fa * kappa * B_a.transpose() * B_f;
    out.dh_dx.bottomRightCorner<3, 3>() -= w_aa * kappa * B_a.transpose() * B_a;
  };
  if (e >= 1)  // at its forward joint: segment e holds (m, n); m's diagonal shared, n's with o's moved onto it
  {
    const Spring sp = spring(e);
    add(0.5, sp.m, 1.0, sp.n, 2.0, sp.kappa);
  }
  if (e + 1 < geometry.segments)  // at its aft joint: segment e holds (o, m)
  {
    const Spring sp = spring(e + 1);
    add(2.0, sp.o, 1.0, sp.m, 0.5, sp.kappa);
  }
}

// (S16) for element e: D (out.dh_dv) and K (out.dh_dx) of its projected loads, with the geometric stiffness of mu
// and, for an elastic segment, its axial spring and damping (§8).
void elementJacobian(const ChainModel& model, int e, double t, const ElementKinematics& k,
                     const ChainGeometry& geometry, const ChainData& data, double mu, ElementJacobian& out,
                     const Vector6d* accelerations)
{
  if (e < geometry.segments && !model.depressorAt(e, geometry))
    segmentJacobian(model, e, t, k, geometry, data, out);
  else  // the end body, or a depressor: by central differences
    endBodyJacobian(model, e, t, k, geometry, data, accelerations, out);
  addGeometricStiffness(k, mu, out);
  if (model.elastic() && e < geometry.segments)
    addAxialStiffness(model.segmentCable(e, geometry), geometry.elementLength(e), k, out);
}

}  // namespace tow_sim
