// The seabed: the grid interpolates and tilts its normal as the slope says; contact pushes out and never
// pulls, friction stays within mu N; a cable laid on the bottom at rest carries no tension gradient
// where it lies and sinks in by w/k; a vehicle towed into a rising slope is lifted over it; a parted
// cable's free end lies on the bottom like every other joint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/chain_fixtures.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/seabed.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
// Uniform across y; depth(x) from a list at spacing dx starting at x0.
SeabedParams ridge(double x0, double dx, const std::vector<double>& depths)
{
  SeabedParams p;
  p.type = SeabedParams::Type::kGrid;
  p.grid.origin = Eigen::Vector2d(x0, -5000.0);
  p.grid.spacing = Eigen::Vector2d(dx, 10000.0);
  p.grid.depth.resize(2, depths.size());
  for (std::size_t i = 0; i < depths.size(); ++i)
    p.grid.depth(0, i) = p.grid.depth(1, i) = depths[i];
  return p;
}

TEST(Seabed, GridInterpolatesAndTiltsItsNormalWithTheSlope)
{
  const Seabed bottom(ridge(0.0, 100.0, { 100.0, 100.0, 80.0, 80.0 }));
  EXPECT_DOUBLE_EQ(bottom.bottomZ(50.0, 3.0), -100.0);
  EXPECT_DOUBLE_EQ(bottom.bottomZ(150.0, -7.0), -90.0);   // halfway up the slope
  EXPECT_DOUBLE_EQ(bottom.bottomZ(-500.0, 0.0), -100.0);  // beyond the grid: its edge
  EXPECT_DOUBLE_EQ(bottom.bottomZ(900.0, 0.0), -80.0);
  // Rising 20 m over 100 m toward +x: the normal leans back toward -x by atan(0.2).
  const Eigen::Vector3d n = bottom.normal(150.0, 0.0);
  EXPECT_NEAR(std::atan2(-n.x(), n.z()), std::atan(0.2), 1e-12);
  EXPECT_NEAR(n.y(), 0.0, 1e-15);
  EXPECT_TRUE(bottom.normal(50.0, 0.0).isApprox(Eigen::Vector3d::UnitZ()));
}

TEST(Seabed, ContactPushesOutNeverPullsAndFrictionStaysWithinMuN)
{
  SeabedParams p;
  p.type = SeabedParams::Type::kFlat;
  p.depth = 50.0;
  p.friction = 0.4;
  const Seabed bottom(p);
  EXPECT_EQ(bottom.contactForce(Eigen::Vector3d(0, 0, -49.0), Eigen::Vector3d(0, 0, -1), 1e4, 100).norm(), 0.0);
  // 1 cm in, at rest: k x up.
  const Eigen::Vector3d f = bottom.contactForce(Eigen::Vector3d(0, 0, -50.01), Eigen::Vector3d::Zero(), 1e4, 100);
  EXPECT_TRUE(f.isApprox(Eigen::Vector3d(0, 0, 100.0)));
  // Leaving fast: the damping would pull; the contact does not.
  EXPECT_EQ(bottom.contactForce(Eigen::Vector3d(0, 0, -50.01), Eigen::Vector3d(0, 0, 5.0), 1e4, 100).norm(), 0.0);
  // Sliding: friction against the motion, below mu N, near it when fast.
  const Eigen::Vector3d g = bottom.contactForce(Eigen::Vector3d(0, 0, -50.01), Eigen::Vector3d(3.0, 0, 0), 1e4, 100);
  EXPECT_LT(g.x(), 0.0);
  EXPECT_LE(-g.x(), 0.4 * g.z());
  EXPECT_GT(-g.x(), 0.39 * g.z());
  SeabedParams bad = p;
  bad.stiffness = -1.0;
  try
  {
    validate(bad);
    FAIL() << "negative stiffness accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("seabed.stiffness = -1"), std::string::npos) << e.what();
  }
}

// Ship stopped, 250 m of cable in 100 m of water: 20 segments hang, 30 lie along the bottom. At rest
// the bottom carries the lying part: its tension does not change along it, while the hanging part's
// tension grows by the weight in water of each segment; each lying joint sinks in by (w - b)/k.
TEST(Seabed, CableLaidOnTheBottomAtRestHasNoTensionGradientWhereItLies)
{
  CableParams cable;
  cable.length = 250.0;
  cable.segments = 50;
  const EndElementParams end = test::endLikeSegment(cable);
  const Environment env;
  SeabedParams sp;
  sp.type = SeabedParams::Type::kFlat;
  sp.depth = 100.0;
  sp.vehicle_stiffness = sp.stiffness * cable.segmentLength();  // the end element is one more segment
  sp.vehicle_damping = sp.damping * cable.segmentLength();
  auto model = test::makeModel(cable, end, env, test::suiteNumerics(), std::make_shared<Seabed>(sp));
  const double d = cable.segmentLength();
  ChainState start;
  start.x.resize(3, 51);
  start.v.setZero(3, 51);
  for (int j = 0; j < 51; ++j)  // joint j + 2 of the report
    start.x.col(j) = j < 20 ? Eigen::Vector3d(0.0, 0.0, -(j + 1) * d) : Eigen::Vector3d((j - 19) * d, 0.0, -100.0);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  sim.reset(0.0, start);
  sim.advanceTo(600.0);

  const double w = model->segment().net_weight / d;  // [N/m] weight in water
  const Eigen::Matrix3Xd p = sim.jointPositions();
  Eigen::VectorXd T(51);
  for (int e = 0; e <= 50; ++e)
    T(e) = sim.tensions().col(e).norm();
  double worst_lying_gradient = 0.0, worst_hanging = 0.0, worst_sink = 0.0;
  int lying = 0;
  for (int j = 22; j <= 48; ++j)  // joints x_{j+1} resting on the bottom, away from touchdown and the end
  {
    ASSERT_LT(std::abs(p(2, j) + 100.0), 0.01) << "joint " << j + 1 << " is not on the bottom";
    ++lying;
    worst_lying_gradient = std::max(worst_lying_gradient, std::abs(T(j) - T(j - 1)) / d);
    worst_sink = std::max(worst_sink, std::abs((-100.0 - p(2, j)) - w / sp.stiffness));
  }
  for (int e = 1; e < 18; ++e)  // hanging segments
    worst_hanging = std::max(worst_hanging, std::abs((T(e - 1) - T(e)) / d - w));
  std::printf(
      "laid cable: w = %.3f N/m; %d lying joints: |dT/ds| <= %.2e N/m, sink-in w/k = %.3e m (off by at most "
      "%.1e m); hanging part dT/ds off w by at most %.2e N/m; tension at the ship %.1f N\n",
      w, lying, worst_lying_gradient, w / sp.stiffness, worst_sink, worst_hanging, T(0));
  EXPECT_LT(worst_lying_gradient, 1e-3 * w);
  EXPECT_LT(worst_hanging, 1e-3 * w);
  EXPECT_LT(worst_sink, 0.01 * w / sp.stiffness);
}

// A cable lying level on a flat bottom parts at its first joint (Simulator::part(0)): the free end stays
// on the bottom, sunk in by w/k like the joints aft of it, carrying half its segment's net weight w l/2.
TEST(Seabed, APartedCablesFreeEndLiesOnTheBottom)
{
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 10;
  SeabedParams flat;
  flat.type = SeabedParams::Type::kFlat;
  flat.depth = 50.0;
  const Environment env;
  auto model = test::makeModel(cable, EndElementParams(), env, NumericsParams(), std::make_shared<Seabed>(flat));
  const Eigen::Vector3d tow_point(0.0, 0.0, -50.0);  // the chain's first joint on the bottom, not a ship's
  Simulator sim(model, constantVelocityShip(tow_point, Eigen::Vector3d::Zero()));
  sim.reset(0.0, straightChain(*model, tow_point, Eigen::Vector3d(-1.0, 0.0, 0.0), Eigen::Vector3d::Zero()));
  sim.part(0);
  sim.advanceTo(30.0);
  const double area = 0.25 * kPi * cable.diameter * cable.diameter;
  const double w = (cable.mass_per_length - env.water_density * area) * env.gravity;  // [N/m]
  const double sunk = w / flat.stiffness;
  const Eigen::Matrix3Xd x = sim.jointPositions();  // the free end first
  std::printf(
      "parted on the bottom: free end %.3e m below it, the next joint %.3e m (w/k = %.3e m); T_1 %.4f N "
      "(w l/2 = %.4f N)\n",
      -50.0 - x(2, 0), -50.0 - x(2, 1), sunk, sim.tensions().col(0).norm(), 0.5 * w * 10.0);
  EXPECT_NEAR(-50.0 - x(2, 0), sunk, 1e-3 * sunk);
  EXPECT_NEAR(-50.0 - x(2, 1), sunk, 1e-3 * sunk);
  EXPECT_NEAR(sim.tensions().col(0).z(), 0.5 * w * 10.0, 1e-3 * w);  // the bottom's push on the free end
  EXPECT_LT(std::abs(x(0, 0)), 1e-4);                                // nothing pulled it along
}

// A 300 m tow at 2 m/s over 125 m of water that shoals to 70 m between x = 400 and 900 m.
TEST(Seabed, VehicleTowedIntoARisingSlopeIsLiftedNotPushedThrough)
{
  CableParams cable;
  cable.length = 300.0;
  cable.segments = 60;
  auto vehicle = std::make_shared<Vehicle>(VehicleParams());
  std::vector<double> depths;
  for (double x = -1000.0; x <= 3000.0; x += 100.0)
    depths.push_back(x <= 400.0 ? 125.0 : (x >= 900.0 ? 70.0 : 125.0 - 55.0 * (x - 400.0) / 500.0));
  auto model = std::make_shared<ChainModel>(cable, vehicle, Environment(), test::suiteNumerics(),
                                            std::make_shared<Seabed>(ridge(-1000.0, 100.0, depths)));
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  const EquilibriumResult eq = steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), u);
  const Seabed& bottom = *model->seabed();
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), u));
  sim.reset(0.0, eq.state);
  const double start_depth = -sim.jointPositions().rightCols<1>().z();

  const double nose = -VehicleParams().nose_from_bail / VehicleParams().tail_from_bail;
  double lowest_hull = 1e9, lowest_joint = 1e9;
  // On the plateau (both hull ends past x = 950 m) the vehicle rides on the bottom: the lower hull end's
  // altitude stays at 0 within the penalty's few millimetres, it neither bounces nor digs in.
  double plateau_low = 1e9, plateau_high = -1e9;
  int plateau_samples = 0;
  for (int i = 1; i <= 800; ++i)
  {
    sim.advanceTo(i * 1.0);
    const ElementKinematics k = sim.elementKinematics(model->segments());
    const double lower_end = std::min(bottom.altitude(k.pointAt(nose)), bottom.altitude(k.pointAt(1.0)));
    lowest_hull = std::min(lowest_hull, lower_end);
    if (std::min(k.pointAt(nose).x(), k.pointAt(1.0).x()) > 950.0)
    {
      plateau_low = std::min(plateau_low, lower_end);
      plateau_high = std::max(plateau_high, lower_end);
      ++plateau_samples;
    }
    const Eigen::Matrix3Xd p = sim.jointPositions();
    for (int j = 1; j < p.cols(); ++j)
      lowest_joint = std::min(lowest_joint, bottom.altitude(p.col(j)));
  }
  const ElementKinematics k = sim.elementKinematics(model->segments());
  const Eigen::Vector3d cg = k.pointAt(VehicleParams().cg_from_bail / VehicleParams().tail_from_bail);
  std::printf(
      "slope: vehicle from %.1f m deep (bottom 125 m) to %.1f m at x = %.0f m (bottom %.1f m); lowest hull "
      "end %.3f m, lowest joint %.3f m above the bottom; on the plateau (%d s) the lower hull end at %.4f .. "
      "%.4f m\n",
      start_depth, -cg.z(), cg.x(), -bottom.bottomZ(cg.x(), cg.y()), lowest_hull, lowest_joint, plateau_samples,
      plateau_low, plateau_high);
  EXPECT_GT(cg.x(), 1000.0);  // past the slope, on the 70 m plateau
  EXPECT_LT(-cg.z(), 70.1);   // lifted onto it (riding on its hull ends)
  EXPECT_GT(plateau_samples, 100);
  EXPECT_GT(plateau_low, -0.01);  // riding on its hull ends: 0 within a centimetre
  EXPECT_LT(plateau_high, 0.01);
  EXPECT_GT(lowest_hull, -0.1);  // not pushed through on the slope either
  EXPECT_GT(lowest_joint, -0.1);
}

// A diverging stage hands the seabed and the current profile NaN positions: they answer NaN (which the
// step's finiteness check catches), never an index outside their tables.
TEST(Seabed, NonFinitePositionsGiveNaNNotACrash)
{
  const Seabed bottom(ridge(0.0, 100.0, { 100.0, 80.0 }));
  EXPECT_TRUE(std::isnan(bottom.bottomZ(NAN, 0.0)));
  EXPECT_TRUE(std::isnan(bottom.bottomZ(0.0, INFINITY)));
  EXPECT_FALSE(bottom.contactForce(Eigen::Vector3d(NAN, 0, -200), Eigen::Vector3d::Zero(), 1e4, 100).allFinite());
  Environment env;
  env.current_profile = { CurrentSample{ 0.0, Eigen::Vector3d::Zero() },
                          CurrentSample{ 50.0, Eigen::Vector3d::Ones() } };
  EXPECT_FALSE(env.currentAt(NAN).allFinite());

  // A ship motion that turns NaN: the simulator throws and keeps its last good state, seabed or not.
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 10;
  auto model = test::makeModel(cable, test::endLikeSegment(cable), env, test::suiteNumerics(),
                               std::make_shared<Seabed>(ridge(-1000.0, 1000.0, { 50.0, 60.0, 70.0 })));
  Simulator sim(model,
                [](double t)
                {
                  ShipEndState s;
                  s.v_W = Eigen::Vector3d(1.0, 0.0, 0.0);
                  s.p_W = t * s.v_W;
                  if (t > 1.0)
                    s.a_W = Eigen::Vector3d::Constant(NAN);
                  return s;
                });
  sim.reset(0.0,
            straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1, 0, -0.5), Eigen::Vector3d(1, 0, 0)));
  EXPECT_THROW(sim.advanceTo(5.0), std::runtime_error);
  EXPECT_TRUE(sim.jointPositions().allFinite());
}

}  // namespace
}  // namespace tow_sim
