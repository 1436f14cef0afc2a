// The loads on single elements (physics.md §4, §5) against values worked out by hand in this file from
// the formulas of physics.md, for explicit oblique states: the velocity forces of a cylinder element
// (normal drag, Pode and quadratic tangential drag, the rotation-drag moment M_V, the current), a cable
// segment's constants, mass matrix and wrench, the rigid end element, a fin pair, and the vehicle in
// Approach A. The expectations never call the load code under test: the dense reference and the
// equilibrium solver share ChainModel::elementDynamics with the fast solver, so a load bug cancels there.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "tow_sim/core/chain/element.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/params.h"
#include "tow_sim/core/vehicle/fins.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kDeg = kPi / 180.0;
constexpr double kRel = 1e-12;  // the hand values follow the same formulas: only rounding differs

// actual == expected within kRel times the largest of `scale`, the largest |expected| entry and 1.
template <typename A, typename B>
::testing::AssertionResult near(const Eigen::MatrixBase<A>& actual, const Eigen::MatrixBase<B>& expected,
                                double scale = 0.0)
{
  const double tol = kRel * std::max({ scale, expected.cwiseAbs().maxCoeff(), 1.0 });
  const double err = (actual - expected).cwiseAbs().maxCoeff();
  if (actual.allFinite() && err <= tol)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max |actual - expected| = " << err << " > " << tol << "\nactual:\n"
                                       << actual << "\nexpected:\n"
                                       << expected;
}

// [r x] written out, so the expectations do not use the library's helper.
Matrix3d crossMatrix(const Vector3d& r)
{
  Matrix3d m;
  m << 0.0, -r(2), r(1), r(2), 0.0, -r(0), -r(1), r(0), 0.0;
  return m;
}

// An element's two joints, forward (toward the ship) and aft: positions [m] and velocities [m/s], world.
struct Joints
{
  Vector3d x_f, x_a, v_f, v_a;
  ElementKinematics kinematics() const { return ElementKinematics::fromJoints(x_f, x_a, v_f, v_a); }
};

// State A: d = 3, s = (-2, 1, -2)/3 (aft and down), ds/dt = (0.1, 0.2, 0) normal to s; centre velocity
// (1.65, -0.1, 0.3), so with the current below u = (1.45, 0.25, 0.25), u.s = -1.05 (steady-tow sign).
const Joints kStateA{ Vector3d(10.0, -4.0, -25.0), Vector3d(8.0, -3.0, -27.0), Vector3d(1.5, -0.4, 0.3),
                      Vector3d(1.8, 0.2, 0.3) };
const Vector3d kCurrentA(0.2, -0.35, 0.05);

struct HandLoads
{
  Vector3d force = Vector3d::Zero();   // [N]
  Vector3d moment = Vector3d::Zero();  // [N m]
};

// physics.md §4 from the raw joints: u = centre velocity - current; normal drag in its second form
// C2 d |s x u|^2 q, q = -u_n/|u_n|; tangential drag C1 d |u|^2 against u.s with the smooth sign
// u_t/sqrt(u_t^2 + eps^2) (Pode) or -C1 d |u.s|(u.s) s; M_V = (C2 d^3/6)(u.(w x s))(s x q), w = s x ds/dt.
HandLoads handVelocityForces(const Joints& j, const Vector3d& current, double c1, double c2, bool pode, double eps)
{
  const double d = (j.x_a - j.x_f).norm();
  const Vector3d s = (j.x_a - j.x_f) / d;
  const Vector3d omega = s.cross((j.v_a - j.v_f) / d);
  const Vector3d u = 0.5 * (j.v_f + j.v_a) - current;
  const double u_t = u.dot(s);
  const Vector3d u_n = u - u_t * s;
  HandLoads h;
  if (u_n.norm() > 1e-9)
  {
    const Vector3d q = -u_n / u_n.norm();
    h.force = c2 * d * s.cross(u).squaredNorm() * q;
    h.moment = (c2 * d * d * d / 6.0) * u.dot(omega.cross(s)) * s.cross(q);
  }
  const double tangential =
      pode ? c1 * d * u.squaredNorm() * u_t / std::sqrt(u_t * u_t + eps * eps) : c1 * d * std::abs(u_t) * u_t;
  h.force -= tangential * s;
  return h;
}

// Splits a force into its part along s and its part normal to s.
double along(const Vector3d& f, const Vector3d& s)
{
  return f.dot(s);
}
Vector3d normalPart(const Vector3d& f, const Vector3d& s)
{
  return f - f.dot(s) * s;
}

TEST(VelocityForces, ObliqueFlowOutsideTheSmoothingBand)
{
  const double c1 = 0.8, c2 = 12.3, d = 3.0, eps = 0.01;
  const VelocityForces f = velocityForces(kStateA.kinematics(), kCurrentA, c1, c2, TangentialDragModel::kPode, eps);
  const Vector3d s = Vector3d(-2.0, 1.0, -2.0) / 3.0;

  // By hand: u_n = u - (u.s) s = (0.75, 0.6, -0.45), |u_n|^2 = 1.125; |u|^2 = 2.2275.
  const Vector3d normal_drag = -c2 * d * std::sqrt(1.125) * Vector3d(0.75, 0.6, -0.45);
  const double smooth_sign = -1.05 / std::sqrt(1.05 * 1.05 + eps * eps);  // about -1: well outside the band
  EXPECT_NEAR(smooth_sign, -1.0, 1e-4);
  const double tangential = -c1 * d * 2.2275 * smooth_sign;  // +C1 d u^2 along s: against u.s < 0
  EXPECT_TRUE(near(normalPart(f.force, s), normal_drag));
  EXPECT_NEAR(along(f.force, s), tangential, kRel * std::abs(tangential));
  EXPECT_GT(along(f.force, s), 0.0);

  // M_V: w x s = ds/dt (s.ds/dt = 0), u.ds/dt = 0.195; s x q = -(s x u_n)/|u_n|, s x u_n = (0.25, -0.8, -0.65).
  const Vector3d m_v = (c2 * d * d * d / 6.0) * 0.195 * (-Vector3d(0.25, -0.8, -0.65) / std::sqrt(1.125));
  EXPECT_TRUE(near(f.moment, m_v));
}

TEST(VelocityForces, QuadraticTangentialDrag)
{
  const double c1 = 0.8, c2 = 12.3, d = 3.0;
  const VelocityForces f =
      velocityForces(kStateA.kinematics(), kCurrentA, c1, c2, TangentialDragModel::kQuadratic, 0.01);
  const Vector3d s = Vector3d(-2.0, 1.0, -2.0) / 3.0;
  // -C1 d |u.s| (u.s) s with u.s = -1.05; the normal drag and M_V do not depend on the model.
  EXPECT_NEAR(along(f.force, s), c1 * d * 1.05 * 1.05, kRel * c1 * d);
  EXPECT_TRUE(near(normalPart(f.force, s), -c2 * d * std::sqrt(1.125) * Vector3d(0.75, 0.6, -0.45)));
  EXPECT_TRUE(near(f.moment, (c2 * d * d * d / 6.0) * 0.195 * (-Vector3d(0.25, -0.8, -0.65) / std::sqrt(1.125))));
}

TEST(VelocityForces, TangentialFlowInsideTheSmoothingBand)
{
  // s = (-2, 1, -2)/3, d = 3, ds/dt = (0.1, -0.1, -0.15) normal to s; centre velocity (-0.2, 1.0, 0.2) in a
  // current (-0.3, 0.1, 0): u = (0.1, 0.9, 0.2), u.s = 0.1 = eps/2 with eps = 0.2.
  const Joints j{ Vector3d(1.0, 2.0, -3.0), Vector3d(-1.0, 3.0, -5.0), Vector3d(-0.35, 1.15, 0.425),
                  Vector3d(-0.05, 0.85, -0.025) };
  const Vector3d current(-0.3, 0.1, 0.0);
  const double c1 = 0.8, c2 = 12.3, d = 3.0, eps = 0.2;
  const VelocityForces f = velocityForces(j.kinematics(), current, c1, c2, TangentialDragModel::kPode, eps);
  const Vector3d s = Vector3d(-2.0, 1.0, -2.0) / 3.0;

  // u_n = u - 0.1 s = (0.5, 2.6, 0.8)/3, |u_n|^2 = 0.85, |u|^2 = 0.86; smooth sign 0.1/sqrt(0.01 + 0.04).
  const double smooth_sign = 0.1 / std::sqrt(0.05);
  EXPECT_NEAR(along(f.force, s), -c1 * d * 0.86 * smooth_sign, kRel * c1 * d);
  EXPECT_TRUE(near(normalPart(f.force, s), -c2 * d * std::sqrt(0.85) * Vector3d(0.5, 2.6, 0.8) / 3.0));
  // u.(w x s) = u.ds/dt = -0.11; s x u_n = s x u = (2.0, 0.2, -1.9)/3.
  const Vector3d m_v = (c2 * d * d * d / 6.0) * -0.11 * (-Vector3d(2.0, 0.2, -1.9) / 3.0 / std::sqrt(0.85));
  EXPECT_TRUE(near(f.moment, m_v));
}

TEST(VelocityForces, FlowAlongTheAxisGivesNoNormalDragAndNoMoment)
{
  const double c1 = 0.8, c2 = 12.3, d = 3.0, eps = 0.01;
  const Vector3d s = Vector3d(-2.0, 1.0, -2.0) / 3.0;
  // u = (1.2, -0.6, 1.2) = -1.8 s through the water, the element turning at ds/dt = (0.1, 0.2, 0).
  const Joints j{ Vector3d(10.0, -4.0, -25.0), Vector3d(8.0, -3.0, -27.0), Vector3d(1.25, -1.25, 1.25),
                  Vector3d(1.55, -0.65, 1.25) };
  const VelocityForces f = velocityForces(j.kinematics(), kCurrentA, c1, c2, TangentialDragModel::kPode, eps);
  const double tangential = -c1 * d * 3.24 * (-1.8 / std::sqrt(3.24 + eps * eps));
  EXPECT_TRUE(near(f.force, tangential * s, tangential));
  EXPECT_TRUE(near(f.moment, Vector3d::Zero().eval()));

  // No flow at all while turning: the centre moves exactly with the current (binary-exact numbers, so
  // u = 0 and u_n = 0 exactly, where q is undefined). Nothing, and nothing NaN.
  const Vector3d current(0.25, -0.5, 0.125);
  const Joints still{ j.x_f, j.x_a, Vector3d(0.0, -1.0, 0.125), Vector3d(0.5, 0.0, 0.125) };
  const VelocityForces zero = velocityForces(still.kinematics(), current, c1, c2, TangentialDragModel::kPode, eps);
  EXPECT_TRUE(near(zero.force, Vector3d::Zero().eval()));
  EXPECT_TRUE(near(zero.moment, Vector3d::Zero().eval()));
}

TEST(VelocityForces, OnlyTheVelocityThroughTheWaterCounts)
{
  // The joints' velocities relative to the current, in still water, give the loads of state A.
  const Joints relative{ kStateA.x_f, kStateA.x_a, kStateA.v_f - kCurrentA, kStateA.v_a - kCurrentA };
  const VelocityForces moving =
      velocityForces(kStateA.kinematics(), kCurrentA, 0.8, 12.3, TangentialDragModel::kPode, 0.01);
  const VelocityForces still =
      velocityForces(relative.kinematics(), Vector3d::Zero(), 0.8, 12.3, TangentialDragModel::kPode, 0.01);
  EXPECT_TRUE(near(moving.force, still.force));
  EXPECT_TRUE(near(moving.moment, still.moment));
  const HandLoads hand = handVelocityForces(kStateA, kCurrentA, 0.8, 12.3, true, 0.01);
  EXPECT_TRUE(near(moving.force, hand.force));
  EXPECT_TRUE(near(moving.moment, hand.moment));
}

CableParams testCable()
{
  CableParams cable;
  cable.length = 120.0;
  cable.segments = 40;  // d = 3 m, as in state A
  cable.diameter = 0.025;
  cable.mass_per_length = 1.4;
  cable.normal_drag_coefficient = 1.1;
  cable.tangential_drag_coefficient = 0.012;
  cable.added_mass_coefficient = 0.9;
  return cable;
}

Environment testWater()
{
  Environment env;
  env.gravity = 9.81;
  env.water_density = 1025.0;
  env.current_W = kCurrentA;
  return env;
}

TEST(CableSegment, ConstantsFromTheParameters)
{
  const Environment env = testWater();
  NumericsParams numerics;
  numerics.tangential_smoothing_speed = 0.03;
  const CableSegmentModel seg = CableSegmentModel::fromParams(testCable(), env, numerics);
  const double area = kPi * 0.025 * 0.025 / 4.0;
  EXPECT_NEAR(seg.length, 3.0, 1e-15);
  EXPECT_NEAR(seg.mass, 1.4 * 3.0, kRel);                                        // w d / g, w = 1.4 g [N/m]
  EXPECT_NEAR(seg.net_weight, (1.4 * 9.81 - 1025.0 * 9.81 * area) * 3.0, kRel);  // (w - b) d
  EXPECT_NEAR(seg.c1, 0.5 * 1025.0 * 0.012 * kPi * 0.025, kRel);                 // 1/2 rho C_dt pi D
  EXPECT_NEAR(seg.c2, 0.5 * 1025.0 * 1.1 * 0.025, kRel);                         // 1/2 rho C_dn D
  EXPECT_NEAR(seg.added_mass, 0.9 * 1025.0 * area * 3.0, kRel);                  // C_a rho pi D^2/4 d
  EXPECT_EQ(seg.smoothing_speed, 0.03);
  EXPECT_EQ(seg.tangential_model, TangentialDragModel::kPode);

  CableParams given = testCable();
  given.c1 = 0.7;
  given.c2 = 9.5;
  const CableSegmentModel direct = CableSegmentModel::fromParams(given, env, numerics);
  EXPECT_EQ(direct.c1, 0.7);
  EXPECT_EQ(direct.c2, 9.5);
}

TEST(CableSegment, MassMatrixAndWrench)
{
  const Environment env = testWater();
  const NumericsParams numerics;
  const CableSegmentModel seg = CableSegmentModel::fromParams(testCable(), env, numerics);
  BodyDynamics out;
  cableSegmentDynamics(seg, 0.0, kStateA.kinematics(), env, out);

  const double area = kPi * 0.025 * 0.025 / 4.0;
  const double m = 4.2, e = 0.9 * 1025.0 * area * 3.0, d = 3.0;
  const Vector3d s = Vector3d(-2.0, 1.0, -2.0) / 3.0;
  Eigen::Matrix<double, 6, 6> mass = Eigen::Matrix<double, 6, 6>::Zero();
  mass.topLeftCorner<3, 3>() = m * Matrix3d::Identity() + e * (Matrix3d::Identity() - s * s.transpose());
  mass.bottomRightCorner<3, 3>() = (m * d * d / 12.0) * Matrix3d::Identity();
  EXPECT_TRUE(near(out.mass, mass));
  EXPECT_EQ(out.cg_fraction, 0.5);

  const double c1 = 0.5 * 1025.0 * 0.012 * kPi * 0.025, c2 = 0.5 * 1025.0 * 1.1 * 0.025;
  const HandLoads hand = handVelocityForces(kStateA, kCurrentA, c1, c2, true, numerics.tangential_smoothing_speed);
  const double net_weight = (1.4 - 1025.0 * area) * 9.81 * 3.0;
  EXPECT_TRUE(near(out.wrench.head<3>(), hand.force - net_weight * Vector3d::UnitZ()));
  EXPECT_TRUE(near(out.wrench.tail<3>(), hand.moment));

  // The segment's tangential model is the cable's.
  CableParams quadratic = testCable();
  quadratic.tangential_drag_model = TangentialDragModel::kQuadratic;
  cableSegmentDynamics(CableSegmentModel::fromParams(quadratic, env, numerics), 0.0, kStateA.kinematics(), env, out);
  const HandLoads hand_q = handVelocityForces(kStateA, kCurrentA, c1, c2, false, 0.0);
  EXPECT_TRUE(near(out.wrench.head<3>(), hand_q.force - net_weight * Vector3d::UnitZ()));
}

// The end element: d = 3.5 along s = (-6, 2, -3)/7, CG 1.3 and CB 1.1 aft of the bail.
EndElementParams testEnd()
{
  EndElementParams p;
  p.length = 3.5;
  p.mass = 210.0;
  p.displaced_volume = 0.19;
  p.cg_from_bail = 1.3;
  p.cb_from_bail = 1.1;
  p.diameter = 0.32;
  p.normal_drag_coefficient = 0.9;
  p.tangential_drag_coefficient = 0.04;
  p.added_mass_coefficient = 1.1;
  return p;
}

// ds/dt = 0.25 (1, 3, 0)/3.5, normal to s.
const Joints kEndState{ Vector3d(-40.0, 6.0, -55.0), Vector3d(-43.0, 7.0, -56.5), Vector3d(2.1, 0.3, -0.1),
                        Vector3d(2.35, 1.05, -0.1) };

TEST(RigidEndElement, MassMatrixAndWrench)
{
  const Environment env = testWater();
  const NumericsParams numerics;
  const RigidEndElement end(testEnd(), numerics);
  BodyDynamics out;
  end.dynamics(0.0, kEndState.kinematics(), env, end.restingActuators(0.0), out);

  const Vector3d s = Vector3d(-6.0, 2.0, -3.0) / 7.0;
  const double rho = 1025.0, g = 9.81, m = 210.0;
  const double e = 1.1 * rho * kPi * 0.32 * 0.32 / 4.0 * 3.5;
  const double inertia = m * (3.5 * 3.5 / 12.0 + 0.45 * 0.45);  // thin rod about the CG, 1.75 - 1.3 off centre
  const Vector3d r_mid = 0.45 * s, r_cb = -0.2 * s;             // from the CG
  const Matrix3d I3 = Matrix3d::Identity(), P = I3 - s * s.transpose(), R = crossMatrix(r_mid);
  // F_A = -e P (a_G + dw/dt x r_mid); its moment r_mid x F_A about the CG (P r x = r x as r is along s).
  Eigen::Matrix<double, 6, 6> mass;
  mass << m * I3 + e * P, -e * R, e * R, inertia * I3 - e * R * R;
  EXPECT_TRUE(near(out.mass, mass));
  EXPECT_NEAR(out.cg_fraction, 1.3 / 3.5, 1e-15);

  // The same matrix from its action: [m a - F_A; I dw/dt - r_mid x F_A] for some accelerations.
  const Vector3d a(0.3, -1.2, 0.7), dw = Vector3d(0.4, 0.9, -0.2).cross(s);
  const Vector3d f_a = -e * P * (a + dw.cross(r_mid));
  Eigen::Matrix<double, 6, 1> acc, action;
  acc << a, dw;
  action << m * a - f_a, inertia * dw - r_mid.cross(f_a);
  EXPECT_TRUE(near(out.mass * acc, action));

  const double c1 = 0.5 * rho * 0.04 * kPi * 0.32, c2 = 0.5 * rho * 0.9 * 0.32;
  const HandLoads vf = handVelocityForces(kEndState, kCurrentA, c1, c2, true, numerics.tangential_smoothing_speed);
  const Vector3d weight = -m * g * Vector3d::UnitZ(), buoyancy = rho * g * 0.19 * Vector3d::UnitZ();
  EXPECT_TRUE(near(out.wrench.head<3>(), weight + buoyancy + vf.force));
  EXPECT_TRUE(near(out.wrench.tail<3>(), r_cb.cross(buoyancy) + r_mid.cross(vf.force) + vf.moment));
}

// A vehicle pitched 20 deg nose up and yawed 30 deg: the zero-roll FLU frame written out (physics.md §2).
struct Frame
{
  Vector3d x, y, z;
};
Frame tiltedFrame()
{
  const double cp = std::cos(20 * kDeg), sp = std::sin(20 * kDeg), cy = std::cos(30 * kDeg), sy = std::sin(30 * kDeg);
  return { Vector3d(cp * cy, cp * sy, sp), Vector3d(-sy, cy, 0.0), Vector3d(-sp * cy, -sp * sy, cp) };
}

// Lift and drag tables with known points: F_L(0.2) = 0.3, F_L(0.5) = 0.6; F_D(0.2) = 0.1, F_D(0.5) = 0.4.
FinPairParams tableFin()
{
  FinPairParams fin;
  fin.lift_constant = 140.0;
  fin.drag_constant = 45.0;
  fin.lift = AngleTable({ 0.0, 0.2, 0.5, 0.5 * kPi }, { 0.0, 0.3, 0.6, 0.1 }, true, "test lift");
  fin.drag = AngleTable({ 0.0, 0.2, 0.5, 0.5 * kPi }, { 0.05, 0.1, 0.4, 1.2 }, false, "test drag");
  fin.center_of_pressure_offset = 0.04;
  return fin;
}

TEST(Fins, VerticalPairAtATableAngle)
{
  const Frame b = tiltedFrame();
  // Inflow 0.15 rad toward +y_b at 2.5 m/s in the x_b-y_b plane (the z_b part is dropped); rudder 0.35 rad:
  // angle of attack 0.2, F_L = 0.3, F_D = 0.1.
  const double a1 = 0.15, speed2 = 6.25, arm = 0.9;
  const Vector3d v = 2.5 * (std::cos(a1) * b.x + std::sin(a1) * b.y) - 0.7 * b.z;
  const FinPairLoads l = finPairLoads(tableFin(), FinPlane::kVertical, 0.35, v, b.x, b.y, b.z, arm);
  EXPECT_NEAR(l.inflow_angle, a1, 1e-14);
  EXPECT_NEAR(l.angle_of_attack, 0.2, 1e-14);

  // z_b x v_hat = cos(a1) y_b - sin(a1) x_b.
  const Vector3d lift = 140.0 * 0.3 * speed2 * (std::cos(a1) * b.y - std::sin(a1) * b.x);
  const Vector3d drag = -45.0 * 0.1 * speed2 * (std::cos(a1) * b.x + std::sin(a1) * b.y);
  EXPECT_TRUE(near(l.lift_W, lift));
  EXPECT_TRUE(near(l.drag_W, drag));
  // arm s x F with s = -x_b and F = F_x x_b + F_y y_b: -arm F_y z_b.
  const double f_x = (lift + drag).dot(b.x), f_y = (lift + drag).dot(b.y);
  EXPECT_TRUE(near(l.moment_cg_W, -arm * f_y * b.z));
  // Centre of pressure 0.04 m aft of the hinge along the chord (cos 0.35 x_b + sin 0.35 y_b); about z_b.
  EXPECT_NEAR(l.hinge_moment, -0.04 * (std::cos(0.35) * f_y - std::sin(0.35) * f_x), kRel * 0.04 * lift.norm());
}

TEST(Fins, HorizontalPairAtATableAngle)
{
  const Frame b = tiltedFrame();
  // Inflow -0.3 rad (toward -z_b) at 1.8 m/s in the x_b-z_b plane (the y_b part is dropped); elevator -0.8 rad:
  // angle of attack -0.5, F_L = -0.6 (odd), F_D = 0.4 (even).
  const double b1 = -0.3, speed2 = 3.24, arm = 0.75;
  const Vector3d v = 1.8 * (std::cos(b1) * b.x + std::sin(b1) * b.z) + 0.4 * b.y;
  const FinPairLoads l = finPairLoads(tableFin(), FinPlane::kHorizontal, -0.8, v, b.x, b.y, b.z, arm);
  EXPECT_NEAR(l.inflow_angle, b1, 1e-14);
  EXPECT_NEAR(l.angle_of_attack, -0.5, 1e-14);

  // v_hat x y_b = cos(b1) z_b - sin(b1) x_b.
  const Vector3d lift = 140.0 * -0.6 * speed2 * (std::cos(b1) * b.z - std::sin(b1) * b.x);
  const Vector3d drag = -45.0 * 0.4 * speed2 * (std::cos(b1) * b.x + std::sin(b1) * b.z);
  EXPECT_TRUE(near(l.lift_W, lift));
  EXPECT_TRUE(near(l.drag_W, drag));
  // arm s x F with s = -x_b and F = F_x x_b + F_z z_b: +arm F_z y_b.
  const double f_x = (lift + drag).dot(b.x), f_z = (lift + drag).dot(b.z);
  EXPECT_TRUE(near(l.moment_cg_W, arm * f_z * b.y));
  // Centre of pressure along -(cos(-0.8) x_b + sin(-0.8) z_b) * 0.04; moment about y_b.
  EXPECT_NEAR(l.hinge_moment, 0.04 * (std::cos(-0.8) * f_z - std::sin(-0.8) * f_x), kRel * 0.04 * lift.norm());
}

TEST(Fins, PositiveCommandsPushTheFinsToPortAndUp)
{
  // physics.md §5: a positive rudder pushes the fins toward +y_b, a positive elevator toward +z_b.
  const Frame b = tiltedFrame();
  const Vector3d ahead = 2.0 * b.x;  // the fins move straight ahead through the water
  const FinPairLoads rudder = finPairLoads(tableFin(), FinPlane::kVertical, 0.2, ahead, b.x, b.y, b.z, 0.9);
  const FinPairLoads elevator = finPairLoads(tableFin(), FinPlane::kHorizontal, 0.2, ahead, b.x, b.y, b.z, 0.9);
  EXPECT_TRUE(near(rudder.lift_W, 140.0 * 0.3 * 4.0 * b.y));
  EXPECT_TRUE(near(elevator.lift_W, 140.0 * 0.3 * 4.0 * b.z));
  EXPECT_TRUE(near(rudder.drag_W, -45.0 * 0.1 * 4.0 * b.x));
  EXPECT_TRUE(near(elevator.drag_W, -45.0 * 0.1 * 4.0 * b.x));
  // Fins aft of the CG pushed to port turn the nose to starboard (-z_b moment); pushed up, nose down (+y_b).
  EXPECT_TRUE(near(rudder.moment_cg_W, -0.9 * 140.0 * 0.3 * 4.0 * b.z));
  EXPECT_TRUE(near(elevator.moment_cg_W, 0.9 * 140.0 * 0.3 * 4.0 * b.y));

  // No flow in the fin's plane: no loads.
  const FinPairLoads none = finPairLoads(tableFin(), FinPlane::kVertical, 0.2, 1.3 * b.z, b.x, b.y, b.z, 0.9);
  EXPECT_TRUE(near((none.lift_W + none.drag_W + none.moment_cg_W).eval(), Vector3d::Zero().eval()));
}

// The vehicle along s = (-6, 2, -3)/7, bail to tail 1.4 m, with a full inertia tensor and linear fin tables
// (F_L(a) = 0.9 a / (pi/2), F_D = 0.05) so every load is known in closed form.
VehicleParams testVehicle()
{
  VehicleParams p;
  p.tail_from_bail = 1.4;
  p.cg_from_bail = 0.3;
  p.cb_from_bail = 0.22;
  p.horizontal_fin_from_bail = 1.05;
  p.vertical_fin_from_bail = 0.95;
  p.mass = 180.0;
  p.displaced_volume = 0.12;
  p.inertia_B << 3.0, 0.1, -0.2, 0.1, 55.0, 0.5, -0.2, 0.5, 70.0;
  p.c1 = 25.0;
  p.c2 = 250.0;
  p.added_mass_approach = AddedMassApproach::kA;
  p.added_mass_a = 145.0;
  p.thrust_offset_z = 0.03;
  for (FinPairParams* fin : { &p.rudder, &p.elevator })
  {
    fin->lift = AngleTable({ 0.0, 0.5 * kPi }, { 0.0, 0.9 }, true, "linear lift");
    fin->drag = AngleTable({ 0.0, 0.5 * kPi }, { 0.05, 0.05 }, false, "constant drag");
  }
  p.rudder.lift_constant = 120.0;
  p.rudder.drag_constant = 40.0;
  p.elevator.lift_constant = 90.0;
  p.elevator.drag_constant = 30.0;
  return p;
}

// physics.md §2: x_b = -s, y_b = z x x_b normalised, z_b = x_b x y_b.
Frame zeroRollFrame(const Vector3d& s)
{
  Frame b;
  b.x = -s;
  b.y = Vector3d(-b.x.y(), b.x.x(), 0.0).normalized();
  b.z = b.x.cross(b.y);
  return b;
}

// Approach A mass matrix of the vehicle about the CG: [m I + e P, -e [r]x; e [r]x, I_W - e [r]x [r]x].
Eigen::Matrix<double, 6, 6> handVehicleMass(const VehicleParams& p, const Vector3d& s)
{
  const Frame b = zeroRollFrame(s);
  Matrix3d R;
  R << b.x, b.y, b.z;
  const Matrix3d I3 = Matrix3d::Identity(), P = I3 - s * s.transpose();
  const Matrix3d S = crossMatrix((0.5 * p.tail_from_bail - p.cg_from_bail) * s);
  Eigen::Matrix<double, 6, 6> mass;
  mass << p.mass * I3 + p.added_mass_a * P, -p.added_mass_a * S, p.added_mass_a * S,
      R * p.inertia_B * R.transpose() - p.added_mass_a * S * S;
  return mass;
}

TEST(VehicleApproachA, AtRestCarriesWeightAndBuoyancyOnly)
{
  const VehicleParams p = testVehicle();
  const Vehicle vehicle(p);
  const Joints rest{ Vector3d(5.0, 1.0, -60.0), Vector3d(3.8, 1.4, -60.6), Vector3d::Zero(), Vector3d::Zero() };
  Environment env = testWater();
  env.current_W.setZero();
  BodyDynamics out;
  vehicle.dynamics(0.0, rest.kinematics(), env, vehicle.restingActuators(0.0), out);

  const Vector3d s = Vector3d(-6.0, 2.0, -3.0) / 7.0;
  const Vector3d buoyancy = 1025.0 * 9.81 * 0.12 * Vector3d::UnitZ();
  EXPECT_TRUE(near(out.wrench.head<3>(), (buoyancy - 180.0 * 9.81 * Vector3d::UnitZ()).eval()));
  EXPECT_TRUE(near(out.wrench.tail<3>(), ((0.22 - 0.3) * s).cross(buoyancy)));  // CB 0.08 m ahead of the CG
  EXPECT_TRUE(near(out.mass, handVehicleMass(p, s)));
  EXPECT_NEAR(out.cg_fraction, 0.3 / 1.4, 1e-15);
}

TEST(VehicleApproachA, TowedWithFinsAndThrust)
{
  const VehicleParams p = testVehicle();
  const Vehicle vehicle(p);
  Actuators actuators = vehicle.restingActuators(0.0);
  vehicle.command(actuators, 0.0, 0.12, -0.09, 150.0);  // the servos reach these within 0.35 s
  // ds/dt = 0.3 (1, 3, 0)/1.4, normal to s.
  const Joints j{ Vector3d(5.0, 1.0, -60.0), Vector3d(3.8, 1.4, -60.6), Vector3d(2.0, 0.5, -0.1),
                  Vector3d(2.3, 1.4, -0.1) };
  const Environment env = testWater();
  BodyDynamics out;
  vehicle.dynamics(5.0, j.kinematics(), env, actuators, out);

  const Vector3d s = Vector3d(-6.0, 2.0, -3.0) / 7.0, up = Vector3d::UnitZ();
  const Frame b = zeroRollFrame(s);
  const double tail = 1.4, cg = 0.3;
  // Velocity forces over the bail-tail length at its midpoint, as for a cable element (Pode, default eps).
  const HandLoads vf = handVelocityForces(j, kCurrentA, 25.0, 250.0, true, NumericsParams().tangential_smoothing_speed);
  Vector3d force = (1025.0 * 0.12 - 180.0) * 9.81 * up + vf.force;
  Vector3d moment =
      ((0.22 - cg) * s).cross(1025.0 * 9.81 * 0.12 * up) + ((0.5 * tail - cg) * s).cross(vf.force) + vf.moment;
  // Thrust 150 N along x_b at the tail point, 0.03 m above the axis.
  force += 150.0 * b.x;
  moment += ((tail - cg) * s + 0.03 * b.z).cross(150.0 * b.x);
  // Fins in the flow at their own points: v = v_bail + (d_f / d) (v_tail - v_bail) - U_c.
  const struct
  {
    bool vertical;
    double angle, from_bail, c_lift, c_drag;
  } pairs[] = { { true, 0.12, 0.95, 120.0, 40.0 }, { false, -0.09, 1.05, 90.0, 30.0 } };
  for (const auto& f : pairs)
  {
    const Vector3d v = j.v_f + (f.from_bail / tail) * (j.v_a - j.v_f) - kCurrentA;
    const Vector3d& lateral = f.vertical ? b.y : b.z;
    const Vector3d v_p = v - v.dot(f.vertical ? b.z : b.y) * (f.vertical ? b.z : b.y);
    const Vector3d v_hat = v_p.normalized();
    const double aoa = f.angle - std::atan2(lateral.dot(v_p), b.x.dot(v_p));
    ASSERT_LT(std::abs(aoa), 0.5 * kPi);  // on the linear part of the table
    const Vector3d lift_dir = f.vertical ? b.z.cross(v_hat) : v_hat.cross(b.y);
    const Vector3d fin = f.c_lift * (0.9 * aoa / (0.5 * kPi)) * v_p.squaredNorm() * lift_dir -
                         f.c_drag * 0.05 * v_p.squaredNorm() * v_hat;
    force += fin;
    moment += ((f.from_bail - cg) * s).cross(fin);
  }
  // d(I w)/dt = I dw/dt + w x I w with w = s x ds/dt: the gyroscopic part joins the loads.
  Matrix3d R;
  R << b.x, b.y, b.z;
  const Vector3d omega = s.cross((j.v_a - j.v_f) / tail);
  moment -= omega.cross(R * p.inertia_B * R.transpose() * omega);

  EXPECT_TRUE(near(out.wrench.head<3>(), force));
  EXPECT_TRUE(near(out.wrench.tail<3>(), moment));
  EXPECT_TRUE(near(out.mass, handVehicleMass(p, s)));
}

}  // namespace
}  // namespace tow_sim
