// The vehicle's pieces against published numbers and closed forms: Lamb's prolate-spheroid
// coefficients, fin lift and drag symmetries and the inflow angle, Approach B reducing to Approach A,
// and a free body under Kirchhoff's equations keeping its energy and impulse.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/chain_fixtures.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/vehicle/added_mass.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
constexpr double kDeg = kPi / 180.0;

TEST(Lamb, ProlateSpheroidCoefficientsMatchLambsTable)
{
  // Lamb, "The inertia coefficients of an ellipsoid moving in fluid", ARC R&M 623 (1918), table of
  // c/a (length over breadth) against k1, k2 and k'. A negative entry is not compared.
  const double table[][4] = { { 1.00, 0.500, 0.500, 0.000 }, { 1.50, 0.305, -1, 0.094 },    { 2.00, 0.209, -1, -1 },
                              { 2.51, 0.156, -1, 0.367 },    { 2.99, 0.122, -1, 0.465 },    { 3.99, 0.082, 0.860, -1 },
                              { 4.99, 0.059, -1, -1 },       { 6.01, 0.045, -1, -1 },       { 6.97, 0.036, -1, 0.805 },
                              { 8.01, 0.029, -1, -1 },       { 9.02, 0.024, 0.954, 0.865 }, { 9.97, 0.021, -1, -1 } };
  for (const auto& row : table)
  {
    const LambCoefficients k = lambCoefficients(row[0], 1.0);
    EXPECT_NEAR(k.k1, row[1], 0.0015) << "c/a = " << row[0];
    if (row[2] >= 0.0)
    {
      EXPECT_NEAR(k.k2, row[2], 0.0015) << "c/a = " << row[0];
    }
    if (row[3] >= 0.0)
    {
      EXPECT_NEAR(k.k_rot, row[3], 0.0015) << "c/a = " << row[0];
    }
  }
  // Limits: a long slender body tends to k1 = 0, k2 = k' = 1.
  const LambCoefficients slender = lambCoefficients(1000.0, 1.0);
  EXPECT_LT(slender.k1, 1e-4);
  EXPECT_NEAR(slender.k2, 1.0, 1e-3);
  EXPECT_NEAR(slender.k_rot, 1.0, 1e-2);
  // A sphere's added mass is half the displaced mass.
  const Matrix6d sphere = prolateSpheroidAddedMass(1.0, 1.0, 1000.0);
  EXPECT_NEAR(sphere(0, 0), 0.5 * 1000.0 * 4.0 / 3.0 * kPi * 0.125, 1e-9);
  EXPECT_THROW(lambCoefficients(1.0, 2.0), std::invalid_argument);  // oblate: not prolate
}

TEST(Fins, TablesAreOddAndEvenAndStall)
{
  const AngleTable lift = AngleTable::defaultLift(), drag = AngleTable::defaultDrag();
  EXPECT_EQ(lift(0.0), 0.0);
  for (double a = -3.1; a <= 3.1; a += 0.05)
  {
    EXPECT_DOUBLE_EQ(lift(-a), -lift(a)) << a;
    EXPECT_DOUBLE_EQ(drag(-a), drag(a)) << a;
  }
  EXPECT_NEAR(lift(5 * kDeg), 5 * kDeg, 1e-12);  // F_L ~ a before the stall
  EXPECT_LT(lift(30 * kDeg), lift(18 * kDeg));   // and it stalls
  EXPECT_THROW(AngleTable({ 0.0, 1.0 }, { 0.0, 1.0 }, true, "vehicle.rudder.lift"), std::invalid_argument);
  EXPECT_THROW(AngleTable({ 0.0, kPi / 2 }, { 0.1, 1.0 }, true, "vehicle.rudder.lift"), std::invalid_argument);
}

// A table's angles are an AngleGrid, as a faired cable's: 1.5708 stands for pi/2 (within 1e-4), 1.57 does not;
// the errors name the table and what is wrong.
TEST(Fins, TablesEndAtHalfPiWithinTheGridsTolerance)
{
  const AngleTable drag({ 0.0, 0.5, 1.5708 }, { 0.1, 0.3, 1.0 }, false, "vehicle.rudder.drag_table");
  EXPECT_EQ(drag.angles().back(), kPi / 2);
  EXPECT_DOUBLE_EQ(drag(kPi / 2), 1.0);
  EXPECT_DOUBLE_EQ(drag(0.25), 0.2);  // halfway through the first interval
  auto message = [](const std::vector<double>& angles, const std::vector<double>& values)
  {
    try
    {
      AngleTable(angles, values, false, "vehicle.rudder.drag_table");
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({ 0.0, 1.57 }, { 0.1, 1.0 }).find("vehicle.rudder.drag_table: angles must run from 0 to pi/2"),
            std::string::npos);
  EXPECT_NE(message({ 0.0, 0.9, 0.8, kPi / 2 }, { 0.1, 0.2, 0.3, 1.0 }).find("angles must increase strictly"),
            std::string::npos);
  EXPECT_NE(message({ 0.0, kPi / 2 }, { 0.1 }).find("has 1 values for 2 angles"), std::string::npos);
  EXPECT_NE(message({ 0.0, kPi / 2 }, { 0.1, 200.0 }).find("value 1 = 200 must be finite with |value| <= 100"),
            std::string::npos);
}

TEST(Fins, NoLiftAtZeroAngleOfAttackAndTheInflowAngleIsMeasuredInTheFinPlane)
{
  FinPairParams fin;
  const Eigen::Vector3d x_b = Eigen::Vector3d::UnitX(), y_b = Eigen::Vector3d::UnitY(), z_b = Eigen::Vector3d::UnitZ();
  // Moving straight ahead with the fin centred: drag only.
  FinPairLoads l = finPairLoads(fin, FinPlane::kVertical, 0.0, 2.0 * x_b, x_b, y_b, z_b, 1.0);
  EXPECT_EQ(l.lift_W.norm(), 0.0);
  EXPECT_GT(l.drag_W.norm(), 0.0);
  EXPECT_LT(l.drag_W.x(), 0.0);
  // The fin moving forward and to port at 10 deg: alpha_1 = atan2(y_b.v, x_b.v) = +10 deg, and a
  // vertical velocity component does not change it (it is projected out of the x_b-y_b plane).
  const Eigen::Vector3d v = 2.0 * Eigen::Vector3d(std::cos(10 * kDeg), std::sin(10 * kDeg), 0.0) + 0.7 * z_b;
  l = finPairLoads(fin, FinPlane::kVertical, 10 * kDeg, v, x_b, y_b, z_b, 1.0);
  EXPECT_NEAR(l.inflow_angle, 10 * kDeg, 1e-12);
  EXPECT_NEAR(l.angle_of_attack, 0.0, 1e-12);
  EXPECT_NEAR(l.lift_W.norm(), 0.0, 1e-12);
  // Sideslip to port with the rudder centred: the fins are pushed to starboard (restoring).
  l = finPairLoads(fin, FinPlane::kVertical, 0.0, v, x_b, y_b, z_b, 1.0);
  EXPECT_LT(l.lift_W.y(), 0.0);
  // Positive rudder pushes the fins to port (+y_b); positive elevator pushes them up (+z_b).
  l = finPairLoads(fin, FinPlane::kVertical, 5 * kDeg, 2.0 * x_b, x_b, y_b, z_b, 1.0);
  EXPECT_GT(l.lift_W.y(), 0.0);
  EXPECT_NEAR(l.lift_W.norm(), fin.lift_constant * 5 * kDeg * 4.0, 1e-9);
  EXPECT_LT(l.moment_cg_W.z(), 0.0);  // fins aft of the CG pushed to port turn the nose to starboard
  l = finPairLoads(fin, FinPlane::kHorizontal, 5 * kDeg, 2.0 * x_b, x_b, y_b, z_b, 1.0);
  EXPECT_GT(l.lift_W.z(), 0.0);
  EXPECT_NEAR(l.inflow_angle, 0.0, 1e-12);
  // Horizontal fins: beta_1 = atan2(z_b.v, x_b.v), a sideways component projected out.
  const Eigen::Vector3d w = 2.0 * Eigen::Vector3d(std::cos(7 * kDeg), 0.3, std::sin(7 * kDeg));
  l = finPairLoads(fin, FinPlane::kHorizontal, 0.0, w, x_b, y_b, z_b, 1.0);
  EXPECT_NEAR(l.inflow_angle, std::atan2(w.z(), w.x()), 1e-12);
}

TEST(Fins, ServoSaturatesAndSlewsAtItsRate)
{
  FinServo servo(0.4, 0.2);
  servo.reset(0.0, 0.0);
  EXPECT_DOUBLE_EQ(servo.command(1.0, 1.0), 0.4);  // saturated
  EXPECT_DOUBLE_EQ(servo.angleAt(1.0), 0.0);
  EXPECT_NEAR(servo.angleAt(2.0), 0.2, 1e-12);
  EXPECT_NEAR(servo.angleAt(5.0), 0.4, 1e-12);
  servo.command(2.0, -0.1);  // reverses from where it is
  EXPECT_NEAR(servo.angleAt(2.5), 0.1, 1e-12);
  EXPECT_NEAR(servo.angleAt(9.0), -0.1, 1e-12);
}

// HeldServos (the tow point's frame's df/dt, solver.md (S28)): while it lives both fins stay at their angles
// of t_held whatever the time; when it ends, also by an exception, they slew on as before.
TEST(Fins, HeldServosStayAtTheirAnglesAndSlewOnAfterwards)
{
  Actuators a;
  a.rudder = FinServo(0.4, 0.2);
  a.elevator = FinServo(0.4, 0.2);
  a.rudder.reset(0.0, 0.0);
  a.elevator.reset(0.0, 0.1);
  a.rudder.command(1.0, 0.3);
  a.elevator.command(1.0, -0.1);
  auto expectSlewing = [&]
  {
    EXPECT_NEAR(a.rudder.angleAt(1.5), 0.1, 1e-12);
    EXPECT_NEAR(a.elevator.angleAt(1.5), 0.0, 1e-12);
    EXPECT_NEAR(a.rudder.angleAt(9.0), 0.3, 1e-12);
  };
  {
    const HeldServos held(a, 1.5);
    for (double t : { 1.5, 1.6, 3.0 })
    {
      EXPECT_NEAR(a.rudder.angleAt(t), 0.1, 1e-12) << t;
      EXPECT_NEAR(a.elevator.angleAt(t), 0.0, 1e-12) << t;
    }
  }
  expectSlewing();
  try
  {
    const HeldServos held(a, 1.5);
    throw std::runtime_error("f threw");
  }
  catch (const std::runtime_error&)
  {
  }
  expectSlewing();
}

TEST(AddedMass, RejectsAsymmetricOrIndefiniteMatrices)
{
  Matrix6d m = Matrix6d::Identity();
  m(0, 1) = 0.5;
  EXPECT_THROW(validateAddedMass(m, "vehicle.added_mass.matrix"), std::invalid_argument);
  m = Matrix6d::Identity();
  m(2, 2) = -1.0;
  try
  {
    validateAddedMass(m, "vehicle.added_mass.matrix");
    ADD_FAILURE() << "accepted an indefinite matrix";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("vehicle.added_mass.matrix"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("positive semi-definite"), std::string::npos);
  }
  VehicleParams p;
  p.added_mass_approach = AddedMassApproach::kB;
  p.added_mass_b = m;
  EXPECT_THROW(Vehicle v(p), std::invalid_argument);
}

// Approach B with M_A = diag(0, e, e, 0, 0, 0) about the bail-tail midpoint, moved to the CG, and no
// Munk terms, must give Approach A's accelerations and tensions.
TEST(AddedMass, ApproachBReducesToApproachA)
{
  VehicleParams a;
  a.cg_from_bail = 0.3;
  a.inertia_B << 2.0, 0.0, 0.3, 0.0, 55.0, 0.0, 0.3, 0.0, 61.0;
  a.added_mass_a = 145.0;
  VehicleParams b = a;
  b.added_mass_approach = AddedMassApproach::kB;
  Vector6d diag;
  diag << 0.0, a.added_mass_a, a.added_mass_a, 0.0, 0.0, 0.0;
  const Eigen::Vector3d r_cg_to_mid(-(0.5 * a.tail_from_bail - a.cg_from_bail), 0.0, 0.0);  // body axes
  b.added_mass_b = moveMassMatrix(diag.asDiagonal(), r_cg_to_mid);

  CableParams cable;
  cable.segments = 12;
  cable.length = 60.0;
  Environment env;
  env.current_W = Eigen::Vector3d(0.3, -0.2, 0.0);
  auto va = std::make_shared<Vehicle>(a), vb = std::make_shared<Vehicle>(b);
  auto ma = std::make_shared<ChainModel>(cable, va, env, NumericsParams());
  auto mb = std::make_shared<ChainModel>(cable, vb, env, NumericsParams());
  ChainData da = ma->initialData(0.0), db = mb->initialData(0.0);
  va->command(da.actuators, 0.0, 0.1, -0.15, 80.0);
  vb->command(db.actuators, 0.0, 0.1, -0.15, 80.0);

  // Random states: the right-hand sides agree.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ChainSolver sa, sb;
  for (int trial = 0; trial < 20; ++trial)
  {
    ShipEndState ship;
    ship.v_W = Eigen::Vector3d(2.0, 0.3 * u(rng), 0.0);
    ship.a_W = Eigen::Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.0);
    const int n = ma->jointCount();
    Eigen::Matrix3Xd x(3, n), v(3, n), aa(3, n), ab(3, n), ta(3, n), tb(3, n);
    Eigen::Vector3d xf = ship.p_W, vf = ship.v_W;
    for (int e = 0; e < n; ++e)
    {
      const Eigen::Vector3d s = Eigen::Vector3d(-1.0 + 0.3 * u(rng), 0.3 * u(rng), -0.5 + 0.3 * u(rng)).normalized();
      const Eigen::Vector3d w(0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng));
      x.col(e) = xf + ma->elementLength(e) * s;
      v.col(e) = vf + ma->elementLength(e) * w.cross(s);
      xf = x.col(e);
      vf = v.col(e);
    }
    sa.solve(*ma, ma->initialGeometry(), da, 0.5, ship, x, v, aa, &ta);
    sb.solve(*mb, mb->initialGeometry(), db, 0.5, ship, x, v, ab, &tb);
    EXPECT_LT((aa - ab).cwiseAbs().maxCoeff(), 1e-9 * aa.cwiseAbs().maxCoeff());
    EXPECT_LT((ta - tb).cwiseAbs().maxCoeff(), 1e-9 * ta.cwiseAbs().maxCoeff());
  }
  // And the motion agrees.
  const Eigen::Vector3d u0(2.0, 0.0, 0.0);
  Simulator sim_a(ma, constantVelocityShip(Eigen::Vector3d::Zero(), u0));
  Simulator sim_b(mb, constantVelocityShip(Eigen::Vector3d::Zero(), u0));
  sim_a.command(0.1, -0.15, 80.0);
  sim_b.command(0.1, -0.15, 80.0);
  const ChainState start = straightChain(*ma, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.2, -0.5), u0);
  sim_a.reset(0.0, start);
  sim_b.reset(0.0, start);
  sim_a.advanceTo(20.0);
  sim_b.advanceTo(20.0);
  EXPECT_LT((sim_a.state().x - sim_b.state().x).cwiseAbs().maxCoeff(), 1e-6);
}

// A free rigid body with Kirchhoff added mass (Munk terms on), no cable, gravity or drag, integrated
// here in body axes with its own rotation: energy 1/2 nu^T (M_RB + M_A) nu and the world-frame linear
// and angular impulse stay constant.
TEST(AddedMass, FreeBodyKeepsEnergyAndImpulse)
{
  VehicleParams p;
  p.added_mass_approach = AddedMassApproach::kB;
  p.munk_terms = true;
  p.prolate_spheroid = ProlateSpheroid{ 2.0, 0.3, 0.4 };  // centre 0.3 m aft of the CG: coupled terms
  p.inertia_B = Eigen::Vector3d(2.0, 61.0, 61.0).asDiagonal();
  const Vehicle vehicle(p);
  const double rho = 1025.0;
  const Matrix6d A = rho * vehicle.addedMassB();
  Matrix6d M = A;
  M.topLeftCorner<3, 3>() += p.mass * Eigen::Matrix3d::Identity();
  M.bottomRightCorner<3, 3>() += p.inertia_B;
  const Matrix6d M_inv = M.inverse();

  struct Body
  {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
    Vector6d nu;  // [v_B; w_B]
  };
  auto derivative = [&](const Body& b)
  {
    const Eigen::Vector3d v = b.nu.head<3>(), w = b.nu.tail<3>();
    Vector6d rhs;
    rhs.head<3>() = -p.mass * w.cross(v) - A.topLeftCorner<3, 3>() * w.cross(v);
    rhs.tail<3>() = -w.cross(p.inertia_B * w) - A.bottomLeftCorner<3, 3>() * w.cross(v);
    rhs += munkWrench(A, v, w);
    Body d;
    d.p = b.R * v;
    Eigen::Matrix3d W;
    W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
    d.R = b.R * W;
    d.nu = M_inv * rhs;
    return d;
  };
  auto add = [](const Body& b, const Body& d, double h) {
    return Body{ b.p + h * d.p, b.R + h * d.R, b.nu + h * d.nu };
  };
  auto energy = [&](const Body& b) { return 0.5 * b.nu.dot(M * b.nu); };
  auto impulse = [&](const Body& b)
  {
    const Vector6d h = M * b.nu;  // body-axis impulse about the CG
    const Eigen::Vector3d linear = b.R * h.head<3>();
    Vector6d out;
    out << linear, b.R * h.tail<3>() + b.p.cross(linear);
    return out;
  };

  Body b{ Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), Vector6d() };
  b.nu << 2.0, 0.2, -0.1, 0.05, 0.1, -0.05;
  const double e0 = energy(b);
  const Vector6d i0 = impulse(b);
  const double h = 1e-3;
  for (int i = 0; i < 20000; ++i)
  {
    const Body k1 = derivative(b), k2 = derivative(add(b, k1, h / 2)), k3 = derivative(add(b, k2, h / 2)),
               k4 = derivative(add(b, k3, h));
    b = Body{ b.p + h / 6 * (k1.p + 2 * k2.p + 2 * k3.p + k4.p), b.R + h / 6 * (k1.R + 2 * k2.R + 2 * k3.R + k4.R),
              b.nu + h / 6 * (k1.nu + 2 * k2.nu + 2 * k3.nu + k4.nu) };
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(b.R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    b.R = svd.matrixU() * svd.matrixV().transpose();
  }
  EXPECT_NEAR(energy(b) / e0, 1.0, 1e-6);
  EXPECT_LT((impulse(b) - i0).norm(), 1e-6 * i0.norm());
  // The Munk moment did turn it: its axis is no longer where it started.
  EXPECT_LT(b.R(0, 0), 0.99);
}

TEST(Vehicle, LateralDiversionIsTheOffsetToPortOfTheShipsTrack)
{
  ShipEndState ship;
  ship.p_W = Eigen::Vector3d(100.0, 50.0, 0.0);
  ship.v_W = Eigen::Vector3d(2.0, 0.0, 0.0);
  Diversion d = lateralDiversion(Eigen::Vector3d(10.0, 53.0, -40.0), Eigen::Vector3d(2.0, 0.5, 0.1), ship,
                                 Eigen::Vector3d::UnitX());
  EXPECT_DOUBLE_EQ(d.offset, 3.0);
  EXPECT_DOUBLE_EQ(d.rate, 0.5);
  d = lateralDiversion(Eigen::Vector3d(103.0, 0.0, -40.0), Eigen::Vector3d::Zero(), ship, Eigen::Vector3d::UnitY());
  EXPECT_DOUBLE_EQ(d.offset, -3.0);  // heading north, 3 m east is to starboard
}

TEST(Vehicle, BodyFrameIsUprightZeroRollAndDefinedWhenVertical)
{
  const Eigen::Vector3d s = Eigen::Vector3d(-1.0, -0.5, 0.3).normalized();  // tail aft, nose up-ish
  const BodyFrame f = bodyFrame(s);
  EXPECT_NEAR(f.y.z(), 0.0, 1e-15);  // zero roll: y_b horizontal
  EXPECT_GT(f.z.z(), 0.0);           // upright
  EXPECT_NEAR((f.rotation().transpose() * f.rotation() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
  EXPECT_NEAR(f.rotation().determinant(), 1.0, 1e-14);
  const BodyFrame v = bodyFrame(-Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0.0, 1.0, 0.0));
  EXPECT_TRUE(v.vertical);
  EXPECT_TRUE(v.rotation().allFinite());
  EXPECT_NEAR(v.y.dot(Eigen::Vector3d(-1.0, 0.0, 0.0)), 1.0, 1e-12);  // normal to the hint, to its left
}

TEST(Vehicle, PublishedAttitudeHoldsItsHeadingNearTheVertical)
{
  AttitudeHold hold;
  const double cone = hold.cone();
  // Leaning 30 deg toward +x, then rocking within the cone round the vertical in every direction: the
  // heading stays the one it had, with no jump, and x_b follows the axis.
  const Eigen::Quaterniond leaning = hold.update(Eigen::Vector3d(std::sin(0.5), 0.0, std::cos(0.5)));
  Eigen::Quaterniond previous = leaning;
  double largest_step = 0.0;
  for (int i = 1; i <= 2000; ++i)
  {
    const double t = 0.01 * i;
    const double tilt = std::max(0.0, 0.5 - t) + 0.8 * cone * std::sin(3.0 * t) * (t > 0.5 ? 1.0 : 0.0);
    const double azimuth = 2.0 * t;  // the rocking plane turns right round
    const Eigen::Vector3d x_b(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt));
    const Eigen::Quaterniond q = hold.update(x_b);
    ASSERT_TRUE(q.coeffs().allFinite());
    EXPECT_NEAR((q * Eigen::Vector3d::UnitX() - x_b.normalized()).norm(), 0.0, 1e-12);
    const double axis_step = 0.02 * 3.0 + 0.02;  // bound on how far the axis moves per step
    largest_step = std::max(largest_step, q.angularDistance(previous) / axis_step);
    previous = q;
  }
  EXPECT_LT(largest_step, 3.0);
  // Exactly vertical from the start: finite, with a default heading.
  AttitudeHold fresh;
  EXPECT_TRUE(fresh.update(Eigen::Vector3d::UnitZ()).coeffs().allFinite());
  // Far from the vertical it is the zero-roll frame.
  const Eigen::Vector3d x_b = Eigen::Vector3d(1.0, 2.0, 0.5).normalized();
  EXPECT_LT(fresh.update(x_b).angularDistance(Eigen::Quaterniond(bodyFrame(-x_b).rotation())), 1e-12);
}

}  // namespace
}  // namespace tow_sim
