// The ship in waves (physics.md §9): the tow point of a heaving, rolling, pitching ship against the
// rigid-body lever arm written out here (for the scripted ship and for odometry), the RAO table's
// interpolation, the generic vessel following the surface in long waves (the elevation's own slopes), the
// motion's rates against its time differences, and a measured motion file replayed with continuous
// acceleration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/temp_file.h"
#include "tow_sim/core/attitude.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/ship_response.h"
#include "tow_sim/core/run/odometry_check.h"
#include "tow_sim/scenario/scenario.h"
#include "tow_sim/scenario/ship_path.h"

namespace tow_sim
{
namespace
{
constexpr double kG = 9.81;

// Elementary rotations, written out.
Eigen::Matrix3d rotX(double a)
{
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return r;
}
Eigen::Matrix3d rotY(double a)
{
  Eigen::Matrix3d r;
  r << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return r;
}
Eigen::Matrix3d rotZ(double a)
{
  Eigen::Matrix3d r;
  r << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return r;
}

// A smooth prescribed ship motion and the tow point r_S by the lever arm: p + Rz Ry Rx r_S.
struct Prescribed
{
  Eigen::Vector3d r_S{ -20.0, 1.5, 3.0 };
  ShipRigidMotion at(double t) const
  {
    ShipRigidMotion m;
    m.p_W = Eigen::Vector3d(2.0 * t, 0.3 * t, 1.2 * std::sin(0.7 * t));
    m.v_W = Eigen::Vector3d(2.0, 0.3, 1.2 * 0.7 * std::cos(0.7 * t));
    m.roll = 0.15 * std::sin(0.5 * t + 1.0);
    m.roll_rate = 0.15 * 0.5 * std::cos(0.5 * t + 1.0);
    m.pitch = 0.08 * std::cos(0.9 * t);
    m.pitch_rate = -0.08 * 0.9 * std::sin(0.9 * t);
    m.yaw = 0.4 + 0.02 * t;
    m.yaw_rate = 0.02;
    return m;
  }
  Eigen::Vector3d lever(double t) const
  {
    const ShipRigidMotion m = at(t);
    return m.p_W + rotZ(m.yaw) * rotY(m.pitch) * rotX(m.roll) * r_S;
  }
};

TEST(ShipResponse, TheTowPointOfAHeavingRollingPitchingShipIsTheLeverArms)
{
  const Prescribed ship;
  for (double t : { 0.0, 1.7, 4.2, 9.9 })
  {
    Eigen::Vector3d p, v;
    towPointOf(ship.at(t), ship.r_S, p, v);
    EXPECT_LT((p - ship.lever(t)).norm(), 1e-12) << t;
    const double h = 1e-5;
    const Eigen::Vector3d dp = (ship.lever(t + h) - ship.lever(t - h)) / (2.0 * h);
    EXPECT_LT((v - dp).norm(), 1e-8) << t;
  }
  // Positive pitch puts the bow down (REP-103): a tow point aft rises; positive roll lifts the port side.
  ShipRigidMotion m;
  m.pitch = 0.1;
  Eigen::Vector3d p, v;
  towPointOf(m, Eigen::Vector3d(-20.0, 0.0, 0.0), p, v);
  EXPECT_NEAR(p.z(), 20.0 * std::sin(0.1), 1e-12);
  m.pitch = 0.0;
  m.roll = 0.1;
  towPointOf(m, Eigen::Vector3d(0.0, 5.0, 0.0), p, v);
  EXPECT_NEAR(p.z(), 5.0 * std::sin(0.1), 1e-12);
}

// The REP-103 Z-Y-X helpers (attitude.h): the rotation is Rz Ry Rx written out here by hand, its angles come
// back from eulerOf over the whole range (pitch short of +-pi/2), and a nose-down pitch puts the bow down.
TEST(ShipResponse, TheEulerHelpersAreRzRyRxAndTheirInverse)
{
  for (double roll : { -2.9, -0.2, 0.0, 0.4, 3.0 })
    for (double pitch : { -1.5, -0.1, 0.0, 0.7, 1.5 })
      for (double yaw : { -3.1, -1.0, 0.0, 0.7, 2.5 })
      {
        const Eigen::Matrix3d R = rotationFromEuler(roll, pitch, yaw);
        EXPECT_LT((R - rotZ(yaw) * rotY(pitch) * rotX(roll)).norm(), 1e-14) << roll << " " << pitch << " " << yaw;
        const EulerAngles a = eulerOf(R);
        EXPECT_NEAR(a.roll, roll, 1e-12);
        EXPECT_NEAR(a.pitch, pitch, 1e-12);
        EXPECT_NEAR(a.yaw, yaw, 1e-12);
      }
  EXPECT_NEAR((rotationFromEuler(0.0, 0.3, 0.0) * Eigen::Vector3d::UnitX()).z(), -std::sin(0.3), 1e-15);
  EXPECT_NEAR((rotationFromEuler(0.3, 0.0, 0.0) * Eigen::Vector3d::UnitY()).z(), std::sin(0.3), 1e-15);
}

// The node's tow point from odometry (checkOdometry) takes the full pose: z, roll and pitch move it by the
// same lever arm, and its velocity is the pose's time derivative (twist in the ship frame, REP-105).
TEST(ShipResponse, OdometryMovesTheTowPointWithHeaveRollAndPitch)
{
  const Prescribed ship;
  OdometryLimits limits;
  limits.tow_point_S = ship.r_S;
  for (double t : { 0.5, 3.0, 7.5 })
  {
    const ShipRigidMotion m = ship.at(t);
    const Eigen::Matrix3d R = rotZ(m.yaw) * rotY(m.pitch) * rotX(m.roll);
    const Eigen::Quaterniond q(R);
    OdometryInput in;
    in.t = t;
    in.frame_id = limits.world_frame;
    in.p_W = m.p_W;
    in.q_wxyz = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    in.v_S = R.transpose() * m.v_W;
    in.w_S = R.transpose() * shipAngularVelocity(m);
    const OdometryResult r = checkOdometry(in, limits, ShipTrack(), t);
    ASSERT_TRUE(r.accepted) << r.reason;
    EXPECT_LT((r.tow_p_W - ship.lever(t)).norm(), 1e-9) << t;
    const double h = 1e-5;
    EXPECT_LT((r.tow_v_W - (ship.lever(t + h) - ship.lever(t - h)) / (2.0 * h)).norm(), 1e-7) << t;
  }
}

TEST(ShipResponse, TheTableInterpolatesLinearlyAndWrapsInDirection)
{
  // Values linear in omega and beta over a cell are reproduced inside it; across 2 pi it wraps.
  const std::vector<double> f{ 0.5, 1.0, 2.0 }, d{ 0.0, 1.0, 4.0 };
  auto value = [](double omega, double beta) {
    return RaoValue{ { omega + beta, 0.0 }, { 0.0, 2.0 * omega - beta }, { 3.0, omega * 0.5 } };
  };
  std::vector<RaoValue> values;
  for (double beta : d)
    for (double omega : f)
      values.push_back(value(omega, beta));
  const RaoTable table(f, d, values);
  for (double omega : { 0.6, 1.0, 1.7 })
    for (double beta : { 0.2, 1.0, 3.1 })
    {
      const RaoValue r = table.at(omega, beta), e = value(omega, beta);
      EXPECT_NEAR(std::abs(r.heave - e.heave) + std::abs(r.roll - e.roll) + std::abs(r.pitch - e.pitch), 0.0, 1e-12);
    }
  // Between 4 and 2 pi: halfway from beta = 4 to beta = 2 pi (= 0) at 5.14.
  const double mid = 0.5 * (4.0 + 2.0 * kPi);
  EXPECT_NEAR(table.at(1.0, mid).heave.real(), 0.5 * (value(1.0, 4.0).heave.real() + value(1.0, 0.0).heave.real()),
              1e-12);
  EXPECT_NEAR(table.at(1.0, mid - 2.0 * kPi).heave.real(), table.at(1.0, mid).heave.real(), 1e-12);
  // Beyond the frequencies: the end values.
  EXPECT_NEAR(std::abs(table.at(0.1, 1.0).heave - value(0.5, 1.0).heave), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(table.at(9.0, 1.0).heave - value(2.0, 1.0).heave), 0.0, 1e-12);
  // Refusals name the source.
  EXPECT_THROW(RaoTable({ 1.0, 0.5 }, { 0.0 }, std::vector<RaoValue>(2), "t"), std::invalid_argument);
  EXPECT_THROW(RaoTable({ 1.0 }, { 7.0 }, std::vector<RaoValue>(1), "t"), std::invalid_argument);
  EXPECT_THROW(RaoTable({ 1.0 }, { 0.0 }, std::vector<RaoValue>(2), "t"), std::invalid_argument);
}

// In waves much longer than the ship, the generic vessel rides the surface: heave = the elevation at its
// reference point, pitch = -(slope toward the bow), roll = +(slope toward port), from the elevation
// itself by central differences in the ship's frame; for every relative direction.
TEST(ShipResponse, TheGenericVesselFollowsTheSurfaceInLongWaves)
{
  const double heading = 0.6;
  for (double direction : { 0.6, 1.6, 2.5, 3.74, 5.0 })  // following, beam, bow, head, quartering
  {
    WaveParams w;
    w.type = WaveParams::Type::kRegular;
    w.height = 2.0;
    w.period = 60.0;  // 5.6 km long
    w.direction = direction;
    w.phase = 0.3;
    const WaveField field(w, kG);
    const RaoTable rao = RaoTable::genericVessel(kG);
    const Eigen::Vector2d p(150.0, -40.0), v = Eigen::Vector2d::Zero();
    const Eigen::Vector2d bow(std::cos(heading), std::sin(heading)), port(-std::sin(heading), std::cos(heading));
    for (double t : { 0.0, 20.0, 47.0 })
    {
      const ShipWaveMotion m = shipWaveMotion(field, rao, t, p, v, heading);
      const double h = 10.0;
      auto zeta = [&](const Eigen::Vector2d& q) { return field.elevation(q.x(), q.y(), t); };
      const double slope_bow = (zeta(p + h * bow) - zeta(p - h * bow)) / (2.0 * h);
      const double slope_port = (zeta(p + h * port) - zeta(p - h * port)) / (2.0 * h);
      // a and a k. The resonances leave the quasi-static response by their phase lag 2 zeta r (r = T_n / 60 s):
      // 0.05 rad in heave and pitch, 0.034 in roll, so up to 5 % of the amplitude; a sign or a quarter
      // period wrong is 100 % or more.
      const double amplitude = 1.0, slope = std::pow(2.0 * kPi / 60.0, 2) / kG;
      EXPECT_NEAR(m.heave, zeta(p), 0.06 * amplitude) << direction << " " << t;
      EXPECT_NEAR(m.pitch, -slope_bow, 0.06 * slope) << direction << " " << t;
      EXPECT_NEAR(m.roll, slope_port, 0.06 * slope) << direction << " " << t;
    }
  }
}

// The rates are the motion's time derivative for a moving ship (the encounter frequency).
TEST(ShipResponse, RatesAreTheTimeDerivativeOfTheMotionOfAMovingShip)
{
  WaveParams w;
  w.type = WaveParams::Type::kJonswap;
  w.spreading = 3.0;
  w.direction = 2.0;
  const WaveField field(w, kG);
  const RaoTable rao = RaoTable::genericVessel(kG);
  const Eigen::Vector2d v(3.0, -1.0);
  auto at = [&](double t) { return shipWaveMotion(field, rao, t, Eigen::Vector2d(5.0, 2.0) + v * t, v, 0.4); };
  for (double t : { 3.0, 30.0 })
  {
    const double h = 1e-4;
    const ShipWaveMotion m = at(t), a = at(t + h), b = at(t - h);
    EXPECT_NEAR(m.heave_rate, (a.heave - b.heave) / (2.0 * h), 1e-6);
    EXPECT_NEAR(m.roll_rate, (a.roll - b.roll) / (2.0 * h), 1e-6);
    EXPECT_NEAR(m.pitch_rate, (a.pitch - b.pitch) / (2.0 * h), 1e-6);
    EXPECT_GT(std::abs(m.heave), 1e-3);
  }
}

using test::writeTempFile;

TEST(ShipResponse, AnRaoFileIsReadAsAFullGridAndBadOnesAreRefusedByLine)
{
  const std::string good = writeTempFile("tow_sim_rao_good.csv",
                                         "# a test table\n"
                                         "frequency,direction,heave_amplitude,heave_phase,roll_amplitude,roll_phase,"
                                         "pitch_amplitude,pitch_phase\n"
                                         "1.0, 0.0, 1, 0, 0, 0, 0.1, 1.5707963267948966\n"
                                         "0.5, 0.0, 1, 0, 0, 0, 0.05, 1.5707963267948966\n"
                                         "0.5, 3.14159, 0.5, 0.2, 0.01, 0, 0.05, -1.5707963267948966\n"
                                         "1.0, 3.14159, 0.5, 0.2, 0.01, 0, 0.1, -1.5707963267948966\n");
  const RaoTable t = RaoTable::fromCsvFile(good);
  EXPECT_EQ(t.frequencies(), (std::vector<double>{ 0.5, 1.0 }));
  EXPECT_NEAR(std::abs(t.at(0.75, 3.14159).heave - std::polar(0.5, 0.2)), 0.0, 1e-12);
  EXPECT_NEAR(t.at(0.75, 0.0).pitch.imag(), 0.075, 1e-12);
  auto error = [](const std::string& text)
  {
    try
    {
      RaoTable::fromCsvFile(writeTempFile("tow_sim_rao_bad.csv", text));
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string header = "frequency,direction,ha,hp,ra,rp,pa,pp\n";
  std::string e = error(header + "1, 0, 1, 0, 0, 0, 0\n");
  EXPECT_NE(e.find("line 2: needs 8 columns"), std::string::npos) << e;
  e = error(header + "1, 0, x, 0, 0, 0, 0, 0\n");
  EXPECT_NE(e.find("line 2: 'x' is not a finite number"), std::string::npos) << e;
  e = error(header + "1, 0, 1, 0, 0, 0, 0, 0\n2, 1, 1, 0, 0, 0, 0, 0\n");
  EXPECT_NE(e.find("not a full grid"), std::string::npos) << e;
  e = error(header + "1, 0, -1, 0, 0, 0, 0, 0\n");
  EXPECT_NE(e.find("amplitudes must be >= 0"), std::string::npos) << e;
  e = error(header + "1, 7, 1, 0, 0, 0, 0, 0\n");
  EXPECT_NE(e.find("directions must lie in [0, 2 pi)"), std::string::npos) << e;
  EXPECT_NE(error("").find("needs at least one frequency"), std::string::npos);
  EXPECT_THROW(RaoTable::fromCsvFile("/nonexistent/rao.csv"), std::invalid_argument);
}

// A measured motion: heave, roll, pitch, a steady heading and speed.
ShipRigidMotion measuredMotion(double t)
{
  ShipRigidMotion m;
  m.p_W = Eigen::Vector3d(2.0 * t, 0.0, 1.5 * std::sin(0.8 * t));
  m.roll = 0.1 * std::sin(0.5 * t);
  m.pitch = 0.05 * std::cos(0.6 * t);
  m.yaw = 0.3;
  return m;
}

// measuredMotion sampled at 10 Hz for 70 s, written as a motion file; returns its path.
std::string measuredMotionFile()
{
  std::string text = "t,x,y,z,roll,pitch,yaw\n";
  char row[256];
  for (int i = 0; i <= 700; ++i)
  {
    const double t = 0.1 * i;
    const ShipRigidMotion m = measuredMotion(t);
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, m.p_W.x(), m.p_W.y(), m.p_W.z(),
                  m.roll, m.pitch, m.yaw);
    text += row;
  }
  return writeTempFile("tow_sim_motion.csv", text);
}

// A measured motion (heave, roll, pitch, a steady heading and speed) sampled at 10 Hz and replayed: the tow
// point between the samples is the lever arm of the motion to within the interpolation's error, and its
// acceleration is continuous across the samples and close to the motion's own.
TEST(ShipResponse, AMeasuredMotionFileIsReplayedWithContinuousAcceleration)
{
  const Eigen::Vector3d r_S(-20.0, 0.0, 2.0);
  const auto motion = measuredMotion;
  auto lever = [&](double t)
  {
    const ShipRigidMotion m = motion(t);
    return Eigen::Vector3d(m.p_W + rotZ(m.yaw) * rotY(m.pitch) * rotX(m.roll) * r_S);
  };
  const std::string file = measuredMotionFile();
  const Scenario sc =
      loadScenario(YAML::Load("ship: {tow_point: [-20, 0, 2], motion_file: " + file + "}\nsimulation: {duration: 60}"));
  ASSERT_EQ(sc.motion.size(), 701u);
  const ShipHistory path = buildShipPath(sc);
  double worst_p = 0.0, worst_a = 0.0, worst_jump = 0.0;
  for (double t = 1.05; t < 59.0; t += 0.37)
  {
    worst_p = std::max(worst_p, (path.towPoint(t).p_W - lever(t)).norm());
    const double h = 1e-3;
    const Eigen::Vector3d a = (lever(t + h) - 2.0 * lever(t) + lever(t - h)) / (h * h);
    worst_a = std::max(worst_a, (path.towPoint(t).a_W - a).norm());
  }
  for (int i = 10; i < 590; i += 7)  // across a sample
  {
    const double t = 0.1 * i;
    worst_jump = std::max(worst_jump, (path.towPoint(t + 1e-9).a_W - path.towPoint(t - 1e-9).a_W).norm());
  }
  const double a_scale = 1.5 * 0.8 * 0.8;
  std::printf(
      "replayed motion: position within %.2e m, acceleration within %.2e m/s^2 (scale %.2f), largest jump "
      "across a sample %.2e\n",
      worst_p, worst_a, a_scale, worst_jump);
  EXPECT_LT(worst_p, 1e-5);
  EXPECT_LT(worst_a, 0.005 * a_scale);
  EXPECT_LT(worst_jump, 1e-6);
  EXPECT_NEAR(path.pose(20.0).z, motion(20.0).p_W.z(), 1e-9);
  EXPECT_NEAR(path.pose(20.0).roll, motion(20.0).roll, 1e-9);
  // Written back (the batch runner's scenario.yaml) it reads again: the file, no manoeuvres.
  EXPECT_EQ(loadScenario(toYaml(sc)).motion.size(), 701u);
}

// A motion file that cannot be replayed is refused by name: beside manoeuvres, too short, times not
// increasing or too close; and calm water needs no RAOs.
TEST(ShipResponse, ABadMotionFileIsRefusedByName)
{
  const std::string file = measuredMotionFile();
  auto error = [](const std::string& yaml)
  {
    try
    {
      loadScenario(YAML::Load(yaml));
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  std::string e = error("ship: {motion_file: " + file + ", manoeuvres: [{type: straight}]}");
  EXPECT_NE(e.find("ship.motion_file: replaces the manoeuvres"), std::string::npos) << e;
  e = error("ship: {motion_file: " + file + "}\nsimulation: {duration: 100}");
  EXPECT_NE(e.find("ship.motion_file: covers t = 0"), std::string::npos) << e;
  e = error("ship: {motion_file: " +
            writeTempFile("tow_sim_motion_bad.csv", "t,x,y,z,roll,pitch,yaw\n0,0,0,0,0,0,0\n0,1,0,0,0,0,0\n") + "}");
  EXPECT_NE(e.find("line 3: times must increase strictly"), std::string::npos) << e;
  e = error("ship: {rao_file: /nonexistent/rao.csv}");
  EXPECT_NE(e.find("ship.rao_file"), std::string::npos) << e;
  e = error("ship: {motion_file: " +
            writeTempFile("tow_sim_motion_close.csv", "t,x,y,z,roll,pitch,yaw\n0,0,0,0,0,0,0\n1e-9,0,0,0,0,0,0\n") +
            "}");
  EXPECT_NE(e.find("line 3: times must increase strictly, by 1 us or more"), std::string::npos) << e;
  // Calm water needs no RAOs: a configuration without gravity (vacuum-like studies) still loads and runs.
  EXPECT_EQ(error("environment: {gravity: 0}\nsimulation: {duration: 10}"), "(accepted)");
  EXPECT_FALSE(
      buildShipPath(loadScenario(YAML::Load("environment: {gravity: 0}\nsimulation: {duration: 10}"))).empty());
}

}  // namespace
}  // namespace tow_sim
