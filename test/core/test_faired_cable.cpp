// A faired cable's loading functions (docs/physics.md §11, (P56)): the loads against the bare cable's closed form when
// the table is the bare cable's, their derivative against central differences, the lift's side by hand, a steady
// tow whose cable lies at the critical angle the table's own normal function gives (solved here by bisection),
// the implicit stepper's J against the right-hand side, and the configuration's keys and refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/config_error.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/analysis/jacobian_check.h"
#include "tow_sim/core/chain/element.h"
#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
constexpr double kDeg = kPi / 180.0;

// A faired-like table: angles every 15 degrees, the normal load rising to 0.32 across the flow, the
// tangential one falling from 0.03, some lift.
CableLoading fairedTable(bool with_lift = true)
{
  std::vector<double> angles;
  for (int i = 0; i <= 6; ++i)
    angles.push_back(15.0 * i * kDeg);
  const std::vector<double> lift =
      with_lift ? std::vector<double>{ 0.0, 0.02, 0.05, 0.06, 0.05, 0.03, 0.0 } : std::vector<double>{};
  return CableLoading(angles, { 0.0, 0.05, 0.12, 0.2, 0.26, 0.3, 0.32 },
                      { 0.03, 0.03, 0.028, 0.025, 0.02, 0.015, 0.01 }, lift, "test table");
}

Eigen::Matrix3d centralDifferences(const CableLoading& table, double scale, const Eigen::Vector3d& s,
                                   const Eigen::Vector3d& u, double smoothing, double step)
{
  Eigen::Matrix3d J;
  for (int j = 0; j < 3; ++j)
  {
    const Eigen::Vector3d du = step * Eigen::Vector3d::Unit(j);
    J.col(j) = (fairedForce(table, scale, s, u + du, smoothing) - fairedForce(table, scale, s, u - du, smoothing)) /
               (2.0 * step);
  }
  return J;
}

TEST(FairedLoading, TheBareCablesTableGivesTheBareCablesLoads)
{
  // C_n = C_dn sin^2(phi) at every degree and C_t = pi C_dt: Pode's loads (Appendix D) up to the linear
  // interpolation of sin^2 (at most h^2/8 |f''| = 7.6e-5 of C_dn between degrees).
  const double rho = 1025.0, D = 0.03, d = 5.0, C_dn = 1.2, C_dt = 0.01, smoothing = 0.01;
  std::vector<double> angles, normal, tangential;
  for (int i = 0; i <= 90; ++i)
  {
    angles.push_back(i * kDeg);
    normal.push_back(C_dn * std::pow(std::sin(i * kDeg), 2));
    tangential.push_back(kPi * C_dt);
  }
  const CableLoading bare(angles, normal, tangential, {}, "bare as a table");
  const double c1 = 0.5 * rho * C_dt * kPi * D, c2 = 0.5 * rho * C_dn * D;
  std::mt19937 rng(5);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 200; ++trial)
  {
    const Eigen::Vector3d s = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Eigen::Vector3d u = 2.0 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    const ElementKinematics k = ElementKinematics::fromJoints(Eigen::Vector3d::Zero(), d * s, u, u);
    const Eigen::Vector3d pode =
        velocityForces(k, Eigen::Vector3d::Zero(), c1, c2, TangentialDragModel::kPode, smoothing).force;
    const Eigen::Vector3d table = fairedForce(bare, 0.5 * rho * D * d, s, u, smoothing);
    EXPECT_LT((table - pode).norm(), 1e-4 * 0.5 * rho * D * d * u.squaredNorm()) << trial;
  }
}

TEST(FairedLoading, ItsDerivativeMatchesCentralDifferences)
{
  const CableLoading table = fairedTable();
  std::mt19937 rng(17);
  std::normal_distribution<double> gauss;
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    const Eigen::Vector3d s = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    Eigen::Vector3d u = 1.5 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    if (trial % 4 == 1)  // nearly along the axis: the loads' limits where n is undefined
      u = (1.0 + gauss(rng)) * s + 1e-3 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    const double phi = std::atan2((u - u.dot(s) * s).norm(), std::abs(u.dot(s)));
    // Central differences need the table smooth over the step: away from its corners (every 15 degrees)
    // and from phi = 90 degrees, where |u.s| has one.
    const double to_corner = std::abs(std::remainder(phi, 15.0 * kDeg));
    if (to_corner < 1e-4 || phi > 89.99 * kDeg)
      continue;
    const double scale = 7.0, smoothing = 0.05;
    const Eigen::Matrix3d J = fairedForceJacobian(table, scale, s, u, smoothing);
    const Eigen::Matrix3d reference = centralDifferences(table, scale, s, u, smoothing, 1e-6);
    EXPECT_LT((J - reference).norm(), 1e-5 * std::max(1.0, reference.norm())) << trial << "\n"
                                                                              << J << "\n"
                                                                              << reference;
    ++checked;
  }
  EXPECT_GT(checked, 300);
  // Exactly along the axis (phi = 0, n undefined): the limits C(phi) / sin(phi) -> C'(0) in place of the ratio.
  // The table's tangential function is flat there, so the loads are smooth and central differences apply.
  const Eigen::Vector3d s = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  for (const double along : { 1.3, -0.7 })
  {
    const Eigen::Vector3d u = along * s;
    const Eigen::Matrix3d J = fairedForceJacobian(table, 3.0, s, u, 0.02);
    const Eigen::Matrix3d reference = centralDifferences(table, 3.0, s, u, 0.02, 1e-7);
    EXPECT_LT((J - reference).norm(), 1e-6 * reference.norm()) << J << "\n" << reference;
    // Across the axis it is -scale C_n'(0) |u| on the cross-flow, plus the lift's turn of it.
    const Eigen::Vector3d e = s.unitOrthogonal();
    const double slope = 0.05 / (15.0 * kDeg), lift_slope = 0.02 / (15.0 * kDeg);
    EXPECT_NEAR((J * e).dot(e), -3.0 * slope * std::abs(along), 1e-9);
    EXPECT_NEAR((J * e).dot(s.cross(e)), 3.0 * lift_slope * std::abs(along), 1e-9);
  }
}

TEST(FairedLoading, TheSegmentModelTakesTheTablesScaleAndNothingInVacuum)
{
  CableParams cable;
  cable.diameter = 0.04;
  cable.loading = std::make_shared<const CableLoading>(fairedTable());
  Environment water;
  const CableSegmentModel seg = CableSegmentModel::fromParams(cable, water, NumericsParams());
  EXPECT_EQ(seg.loading, cable.loading.get());
  EXPECT_DOUBLE_EQ(seg.loading_scale, 0.5 * 1025.0 * 0.04);
  EXPECT_DOUBLE_EQ(seg.c2, 0.5 * 1025.0 * 0.04 * 0.32);  // the rotation-drag moment's: C_n(pi/2)
  Environment vacuum;
  vacuum.water_density = 0.0;
  const CableSegmentModel dry = CableSegmentModel::fromParams(cable, vacuum, NumericsParams());
  const ElementKinematics k =
      ElementKinematics::fromJoints(Eigen::Vector3d::Zero(), Eigen::Vector3d(3.0, 0.0, -4.0),
                                    Eigen::Vector3d(2.0, 1.0, 0.0), Eigen::Vector3d(2.0, 1.0, 0.0));
  EXPECT_EQ(segmentVelocityForces(dry, k, Eigen::Vector3d::Zero()).force.norm(), 0.0);
  EXPECT_GT(segmentVelocityForces(seg, k, Eigen::Vector3d::Zero()).force.norm(), 1.0);
}

TEST(FairedLoading, PositiveLiftPushesACableTowedAheadToStarboard)
{
  // A cable going aft and down 30 degrees from a ship heading +x (east), towed at 2 m/s: starboard is -y.
  const Eigen::Vector3d s(-std::cos(30 * kDeg), 0.0, -std::sin(30 * kDeg)), u(2.0, 0.0, 0.0);
  const CableLoading lift_only({ 0.0, kHalfPi }, { 0.0, 0.0 }, { 0.0, 0.0 }, { 0.0, 0.5 }, "lift only");
  const Eigen::Vector3d F = fairedForce(lift_only, 1.0, s, u, 0.01);
  // phi = 30 degrees: C_l = 0.5 / 3, so |F| = C_l |u|^2.
  EXPECT_NEAR(F.y(), -0.5 / 3.0 * 4.0, 1e-12);
  EXPECT_NEAR(F.x(), 0.0, 1e-12);
  EXPECT_NEAR(F.z(), 0.0, 1e-12);
}

// 1000 m of 30 mm, 5 kg/m faired cable in 200 segments behind an end body that weighs nothing in water and has
// almost no drag: the cable hangs at its critical angle, where its weight across it balances the normal load.
struct CriticalCase
{
  CableParams cable;
  Environment env;
  double speed = 2.0;
  double end_mass = 1.0;  // [kg], its displaced volume neutral when 1 kg
  std::shared_ptr<ChainModel> model() const
  {
    EndElementParams end;
    end.mass = end_mass;
    end.displaced_volume = 1.0 / env.water_density;
    end.normal_drag_coefficient = 0.0;
    end.tangential_drag_coefficient = 1e-4;
    end.diameter = 0.01;
    return std::make_shared<ChainModel>(cable, std::make_shared<RigidEndElement>(end, NumericsParams()), env,
                                        NumericsParams());
  }
  CriticalCase()
  {
    cable.length = 1000.0;
    cable.segments = 200;
    cable.diameter = 0.03;
    cable.mass_per_length = 5.0;
    cable.loading = std::make_shared<const CableLoading>(fairedTable(false));
  }
};

TEST(FairedCable, ASteadyTowHangsAtTheCriticalAngleOfItsNormalLoadingFunction)
{
  const CriticalCase c;
  // w cos(phi) = 1/2 rho D U^2 C_n(phi), C_n interpolated linearly in the table: bisection on the table itself.
  const double w =
      (c.cable.mass_per_length - c.env.water_density * 0.25 * kPi * c.cable.diameter * c.cable.diameter) * 9.81;
  const double q = 0.5 * c.env.water_density * c.cable.diameter * c.speed * c.speed;
  const std::vector<double> angles = c.cable.loading->angles(), normal = c.cable.loading->normal();
  auto excess = [&](double phi)
  {
    size_t i = 1;
    while (i + 1 < angles.size() && angles[i] < phi)
      ++i;
    const double C_n =
        normal[i - 1] + (normal[i] - normal[i - 1]) * (phi - angles[i - 1]) / (angles[i] - angles[i - 1]);
    return q * C_n - w * std::cos(phi);
  };
  double lo = 0.0, hi = kHalfPi;
  for (int i = 0; i < 100; ++i)
    (excess(0.5 * (lo + hi)) > 0.0 ? hi : lo) = 0.5 * (lo + hi);
  const double critical = 0.5 * (lo + hi);
  ASSERT_GT(critical, 60.0 * kDeg);  // the table's 60-75 degree stretch
  ASSERT_LT(critical, 75.0 * kDeg);

  const auto model = c.model();
  const EquilibriumResult eq =
      steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(c.speed, 0, 0));
  for (int e = 1; e < 190; ++e)  // every segment but those next to the end body
  {
    const Eigen::Vector3d seg = eq.state.x.col(e) - eq.state.x.col(e - 1);
    const double angle = std::atan2(-seg.z(), -seg.x());  // below the horizontal, aft
    EXPECT_NEAR(angle, critical, 1e-4) << "segment " << e;
  }
  // The bare cable of the same drag across the flow (C_dn 0.32, Pode's sin^2) hangs 0.6 degrees away: the
  // bound above tells them apart fifty times over.
  CriticalCase bare;
  bare.cable.loading.reset();
  bare.cable.normal_drag_coefficient = 0.32;
  const EquilibriumResult beq =
      steadyTowEquilibrium(*bare.model(), 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(c.speed, 0, 0));
  const Eigen::Vector3d top = beq.state.x.col(10) - beq.state.x.col(9);
  EXPECT_GT(std::abs(std::atan2(-top.z(), -top.x()) - critical), 50 * 1e-4);
}

TEST(FairedCable, TheImplicitSteppersJacobianMatchesTheRightHandSide)
{
  // 250 m behind a 300 kg body at 4 m/s: the cable curves from steep at the body toward its critical angle, so that its
  // segments meet the flow at angles across several of the table's intervals; a cross current puts the flow out
  // of the cable's plane (the lift acts). The joints all move at the ship's velocity (the steady tow's), which
  // the rigid constraints allow; D then holds every derivative of (P56) and is exact, as the bare cable's is
  // (test_jacobian_check).
  CriticalCase c;
  c.cable.loading = std::make_shared<const CableLoading>(fairedTable(true));
  c.cable.segments = 50;
  c.cable.length = 250.0;
  c.end_mass = 300.0;
  c.speed = 4.0;
  c.env.current_W = Eigen::Vector3d(0.0, 0.6, 0.0);
  const auto model = c.model();
  const EquilibriumResult eq =
      steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(c.speed, 0, 0));
  double least = kHalfPi, most = 0.0;
  for (int e = 1; e < 50; ++e)
  {
    const Eigen::Vector3d s = (eq.state.x.col(e) - eq.state.x.col(e - 1)).normalized();
    const Eigen::Vector3d u = Eigen::Vector3d(c.speed, 0, 0) - c.env.current_W;
    const double phi = std::acos(std::abs(s.dot(u.normalized())));
    least = std::min(least, phi);
    most = std::max(most, phi);
  }
  EXPECT_LT(least, 45.0 * kDeg);  // the segments span two of the table's intervals or more
  EXPECT_GT(most, 60.0 * kDeg);
  ShipEndState ship;
  ship.v_W = Eigen::Vector3d(c.speed, 0, 0);
  const JacobianError error =
      jacobianError(*model, model->initialGeometry(), model->initialData(0.0), 0.0, ship, eq.state.x, eq.state.v, 8, 5);
  EXPECT_LT(error.velocity, 1e-6) << error.velocity;
}

TEST(FairedCable, TheConfigurationReadsWritesAndRefusesItsLoading)
{
  const std::string table =
      "{angles: [0, 0.7853981634, 1.5707963268], normal: [0, 0.1, 0.3], tangential: [0.03, 0.02, 0.01]}";
  const std::string yaml = "cable:\n  loading: " + table +
                           "\n  sections:\n    - {length: 300, segments: 30}\n"
                           "    - {length: 200, segments: 20, loading: bare}\n";
  const SimulationConfig c = loadConfig(YAML::Load(yaml));
  ASSERT_TRUE(c.cable.loading);
  ASSERT_TRUE(c.sections.at(0).loading);  // inherited from the cable level
  EXPECT_FALSE(c.sections.at(1).loading);
  EXPECT_EQ(c.sections[0].loading->normal(), (std::vector<double>{ 0.0, 0.1, 0.3 }));
  EXPECT_EQ(c.sections[0].loading->lift(), (std::vector<double>{ 0.0, 0.0, 0.0 }));
  const SimulationConfig back = loadConfig(toYaml(c));
  for (const CableParams* p : { &back.cable, &back.sections.at(0) })
  {
    ASSERT_TRUE(p->loading);
    EXPECT_EQ(p->loading->angles(), c.sections[0].loading->angles());
    EXPECT_EQ(p->loading->normal(), c.sections[0].loading->normal());
    EXPECT_EQ(p->loading->tangential(), c.sections[0].loading->tangential());
    EXPECT_EQ(p->loading->lift(), c.sections[0].loading->lift());
  }
  EXPECT_FALSE(back.sections.at(1).loading);
  // The bare cable writes no loading, so that configurations saved before it read the same.
  EXPECT_FALSE(toYaml(SimulationConfig())["cable"]["loading"]);
  EXPECT_FALSE(loadConfig(YAML::Load("cable: {loading: " + table + "}\n")).cable.loading == nullptr);
  EXPECT_FALSE(
      loadConfig(YAML::Load("cable: {loading: bare, sections: [{length: 500, segments: 10, loading: " + table + "}]}"))
          .cable.loading);

  auto with = [&](const std::string& from, const std::string& to)
  {
    std::string t = table;
    t.replace(t.find(from), from.size(), to);
    return "cable:\n  loading: " + t + "\n";
  };
  const std::pair<std::string, std::string> cases[] = {
    { with("0.7853981634", "1.6"), "cable.loading: angles must increase strictly; angles[2] = 1.5708" },
    { with("[0, 0.7853981634, 1.5707963268]", "[0, 0.7853981634, 1.4]"), "angles must run from 0 to pi/2" },
    { with("[0, 0.7853981634, 1.5707963268]", "[0, 1.57081, 1.57085]"), "angles[2] = 1.5708 [rad] follows 1.5708" },
    { with("normal: [0, 0.1, 0.3]", "normal: [0, .nan, 0.3]"), "normal[1] = nan must be finite" },
    { with("normal: [0, 0.1, 0.3]", "normal: [0.1, 0.1, 0.3]"), "normal[0] = 0.1 must be 0" },
    { with("normal: [0, 0.1, 0.3]", "normal: [0, -0.1, 0.3]"), "normal[1] = -0.1 must be >= 0" },
    { with("tangential: [0.03, 0.02, 0.01]", "tangential: [0.03, 0.02]"), "tangential has 2 values for 3 angles" },
    { with("tangential:", "tangental:"), "cable.loading.tangental: unknown key; did you mean 'tangential'?" },
    { "cable: {loading: faired}", "cable.loading: must be bare or a mapping {angles, normal, tangential, lift}" },
    { "cable:\n  strumming: vandiver\n  loading: " + table + "\n", "cable.strumming: must be none with a faired" },
  };
  for (size_t i = 0; i < std::size(cases); ++i)
  {
    const std::string error = test::configError(cases[i].first);
    EXPECT_NE(error.find(cases[i].second), std::string::npos) << "case " << i << ": " << error;
  }
}

}  // namespace
}  // namespace tow_sim
