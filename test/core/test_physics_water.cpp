// Checks in water against closed forms and invariances (physics.md §8): the critical angle of a towed
// cable, the static tensions of a hanging chain, Galilean and rotational invariance, and the length
// of every segment through 1000 s of towing with turns.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/chain_fixtures.h"

#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
constexpr double kDeg = kPi / 180.0;

// Angle of an element below the horizontal [rad].
double depressionAngle(const Eigen::Matrix3Xd& joints, int element)
{
  const Eigen::Vector3d s = joints.col(element + 1) - joints.col(element);
  return std::atan2(-s.z(), s.head<2>().norm());
}

TEST(Water, TowedCableLiesAtTheCriticalAngle)
{
  CableParams cable;
  cable.segments = 50;
  cable.length = 200.0;
  cable.diameter = 0.02;
  cable.mass_per_length = 1.0;
  cable.normal_drag_coefficient = 1.2;
  cable.tangential_drag_coefficient = 0.0;                   // the closed form has no tangential drag
  const EndElementParams end = test::endLikeSegment(cable);  // a free cable end
  const Environment env;
  auto model = test::makeModel(cable, end, env);
  const double speed = 2.0;
  const Eigen::Vector3d ship_velocity(speed, 0.0, 0.0);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), ship_velocity));
  sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -0.3), ship_velocity));
  sim.advanceTo(600.0);

  // (w - b) cos(phi) = C2 U^2 sin^2(phi): a quadratic in cos(phi).
  const double net_weight = (cable.mass_per_length - env.water_density * kPi * 0.25 * cable.diameter * cable.diameter) *
                            env.gravity;  // [N/m]
  const double drag = 0.5 * env.water_density * cable.normal_drag_coefficient * cable.diameter * speed * speed;
  const double cos_phi = (-net_weight + std::sqrt(net_weight * net_weight + 4.0 * drag * drag)) / (2.0 * drag);
  const double phi_c = std::acos(cos_phi);

  const Eigen::Matrix3Xd joints = sim.jointPositions();
  const double phi_mid = depressionAngle(joints, cable.segments / 2);
  double worst = 0.0;
  for (int e = cable.segments / 4; e < 3 * cable.segments / 4; ++e)
    worst = std::max(worst, std::abs(depressionAngle(joints, e) - phi_c));
  std::printf("critical angle: closed form %.4f deg, middle of the cable %.4f deg; middle half within %.1e deg\n",
              phi_c / kDeg, phi_mid / kDeg, worst / kDeg);
  // 0.02 deg: a normal drag off by 1 % moves the angle by about 0.1 deg.
  EXPECT_NEAR(phi_mid / kDeg, phi_c / kDeg, 0.02);
  // Straight away from its ends: the middle half of the cable lies at the same angle.
  EXPECT_LT(worst / kDeg, 0.02);
  // The cable trails astern in the vertical plane of the tow.
  EXPECT_LT(joints.row(1).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(Water, HangingChainCarriesTheWeightInWaterBelowEachJoint)
{
  CableParams cable;
  cable.segments = 20;
  cable.length = 100.0;
  EndElementParams end;  // default vehicle-like end body
  const Environment env;
  auto model = test::makeModel(cable, end, env);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d(3.0, -2.0, 0.0), Eigen::Vector3d::Zero()));
  sim.reset(0.0,
            straightChain(*model, Eigen::Vector3d(3.0, -2.0, 0.0), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()));

  const double area = 0.25 * kPi * cable.diameter * cable.diameter;
  const double segment_weight =
      (cable.mass_per_length - env.water_density * area) * env.gravity * cable.segmentLength();
  const double end_weight = (end.mass - env.water_density * end.displaced_volume) * env.gravity;
  for (int joint = 0; joint <= cable.segments; ++joint)
  {
    const double below = (cable.segments - joint) * segment_weight + end_weight;
    const Eigen::Vector3d expected(0.0, 0.0, below);  // pulls the element below up
    EXPECT_LT((sim.tensions().col(joint) - expected).norm(), 1e-9 * below) << "joint " << joint + 1;
  }
  EXPECT_LT(sim.accelerations().norm(), 1e-9);
}

struct RunResult
{
  Eigen::Matrix3Xd relative_joints;  // joints minus the tow point
  Eigen::Matrix3Xd tensions;
};

RunResult runTow(const Eigen::Vector3d& ship_velocity, const Eigen::Vector3d& current,
                 const Eigen::Vector3d& initial_direction, double duration, StepperType stepper = StepperType::kDopri5)
{
  CableParams cable;
  cable.segments = 20;
  cable.length = 100.0;
  EndElementParams end;
  end.cb_from_bail = 0.8;  // a buoyancy moment, so the end body's attitude matters
  Environment env;
  env.current_W = current;
  NumericsParams num;
  num.abs_tol = 1e-10;
  num.rel_tol = 1e-10;
  num.stepper = stepper;
  num.fixed_step = 0.01;
  auto model = test::makeModel(cable, end, env, num);
  const Eigen::Vector3d start(10.0, 20.0, 0.0);
  Simulator sim(model, constantVelocityShip(start, ship_velocity));
  sim.reset(0.0, straightChain(*model, start, initial_direction, ship_velocity));
  sim.advanceTo(duration);
  RunResult r;
  r.relative_joints = sim.jointPositions().colwise() - sim.shipEnd().p_W;
  r.tensions = sim.tensions();
  return r;
}

double relativeDifference(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b)
{
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(Water, GalileanInvariance)
{
  const Eigen::Vector3d u(1.5, 0.4, 0.0);
  const Eigen::Vector3d down_astern(-1.0, 0.2, -0.6);
  const RunResult moving_ship = runTow(u, Eigen::Vector3d::Zero(), down_astern, 60.0);
  const RunResult moving_water = runTow(Eigen::Vector3d::Zero(), -u, down_astern, 60.0);
  EXPECT_LT(relativeDifference(moving_water.relative_joints, moving_ship.relative_joints), 1e-6);
  EXPECT_LT(relativeDifference(moving_water.tensions, moving_ship.tensions), 1e-6);
  // Not trivially equal to the start: the cable moved under drag.
  const RunResult short_run = runTow(u, Eigen::Vector3d::Zero(), down_astern, 1.0);
  EXPECT_GT(relativeDifference(short_run.relative_joints, moving_ship.relative_joints), 1e-3);
}

TEST(Water, RotatingTheHeadingRotatesTheSolution)
{
  const Eigen::Matrix3d R = Eigen::AngleAxisd(37.0 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d u(1.5, 0.0, 0.0), current(0.2, 0.3, 0.0), down_astern(-1.0, 0.1, -0.6);
  const RunResult a = runTow(u, current, down_astern, 60.0);
  const RunResult b = runTow(R * u, R * current, R * down_astern, 60.0);
  EXPECT_LT(relativeDifference(b.relative_joints, R * a.relative_joints), 1e-6);
  EXPECT_LT(relativeDifference(b.tensions, R * a.tensions), 1e-6);
}

TEST(Water, FixedStepRk4AgreesWithTheAdaptiveStepper)
{
  const Eigen::Vector3d u(1.5, 0.0, 0.0), current(0.2, 0.3, 0.0), down_astern(-1.0, 0.1, -0.6);
  const RunResult adaptive = runTow(u, current, down_astern, 30.0);
  const RunResult fixed = runTow(u, current, down_astern, 30.0, StepperType::kRk4);
  EXPECT_LT(relativeDifference(fixed.relative_joints, adaptive.relative_joints), 1e-6);
  EXPECT_LT(relativeDifference(fixed.tensions, adaptive.tensions), 1e-5);
}

// A ship path of straight legs and constant-radius turns at constant speed, in closed form.
class ManoeuvringShip
{
public:
  struct Leg
  {
    double duration;   // [s]
    double curvature;  // [1/m], positive turns to port
  };
  ManoeuvringShip(double speed, std::vector<Leg> legs) : speed_(speed), legs_(std::move(legs)) {}

  ShipEndState operator()(double t) const
  {
    Eigen::Vector2d p(0.0, 0.0);
    double heading = 0.0;
    for (const Leg& leg : legs_)
    {
      const double tau = std::min(t, leg.duration);
      const double k = leg.curvature;
      const double h1 = heading + k * speed_ * tau;
      if (k == 0.0)
        p += speed_ * tau * Eigen::Vector2d(std::cos(heading), std::sin(heading));
      else
        p += Eigen::Vector2d(std::sin(h1) - std::sin(heading), std::cos(heading) - std::cos(h1)) / k;
      heading = h1;
      if (t <= leg.duration)
      {
        ShipEndState s;
        s.p_W << p, 0.0;
        s.v_W << speed_ * std::cos(heading), speed_ * std::sin(heading), 0.0;
        s.a_W << -k * speed_ * speed_ * std::sin(heading), k * speed_ * speed_ * std::cos(heading), 0.0;
        return s;
      }
      t -= leg.duration;
    }
    ShipEndState s;  // past the last leg: keep going straight
    s.p_W << p + speed_ * t * Eigen::Vector2d(std::cos(heading), std::sin(heading)), 0.0;
    s.v_W << speed_ * std::cos(heading), speed_ * std::sin(heading), 0.0;
    return s;
  }

private:
  double speed_;
  std::vector<Leg> legs_;
};

TEST(Water, SegmentLengthsHoldThroughAThousandSecondsOfTurns)
{
  CableParams cable;
  cable.segments = 50;
  cable.length = 300.0;
  auto model = test::makeModel(cable, EndElementParams(), Environment());
  const double speed = 2.0;
  const double half_turn = kPi * 150.0 / speed, quarter_turn = 0.5 * kPi * 100.0 / speed;
  const ManoeuvringShip ship(speed, { { 150.0, 0.0 },
                                      { half_turn, 1.0 / 150.0 },
                                      { 150.0, 0.0 },
                                      { quarter_turn, -1.0 / 100.0 },
                                      { 100.0, 0.0 },
                                      { half_turn, -1.0 / 150.0 } });
  Simulator sim(model, ship);
  sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -0.4),
                               Eigen::Vector3d(speed, 0.0, 0.0)));
  double worst = 0.0, worst_before_projection = 0.0;
  for (int i = 1; i <= 1000; ++i)
  {
    const StepReport report = sim.advanceTo(i * 1.0);
    worst_before_projection = std::max(worst_before_projection, report.max_length_error);
    const Eigen::Matrix3Xd joints = sim.jointPositions();
    for (int e = 0; e < model->elementCount(); ++e)
    {
      const double length = (joints.col(e + 1) - joints.col(e)).norm();
      worst = std::max(worst, std::abs(length / model->elementLength(e) - 1.0));
    }
  }
  std::printf("largest relative length error: %.3g after projection, %.3g before\n", worst, worst_before_projection);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_before_projection, 1e-5);
  // The vehicle followed the ship round the turns: it ended up well to port of its start.
  EXPECT_GT(sim.jointPositions().row(1).maxCoeff(), 100.0);
}

}  // namespace
}  // namespace tow_sim
