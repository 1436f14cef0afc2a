// A current that varies with depth: the table interpolates as documented, a uniform profile is the
// same as a moving ship (Galilean), and a sheared cross-current pushes the deeper cable farther
// downstream, where the dynamics settle on the equilibrium solver's shape.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/chain_fixtures.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
std::vector<CurrentSample> profile(std::initializer_list<std::pair<double, Eigen::Vector3d>> points)
{
  std::vector<CurrentSample> out;
  for (const auto& p : points)
    out.push_back(CurrentSample{ p.first, p.second });
  return out;
}

TEST(CurrentProfile, InterpolatesLinearlyAndHoldsItsEndValues)
{
  Environment env;
  env.current_W = Eigen::Vector3d(0.1, 0.0, 0.0);
  env.current_profile = profile({ { 10.0, Eigen::Vector3d(0.0, 1.0, 0.0) },
                                  { 30.0, Eigen::Vector3d(0.0, 3.0, 0.0) },
                                  { 50.0, Eigen::Vector3d(2.0, 3.0, 0.0) } });
  validate(env);
  auto at_depth = [&](double depth) { return env.currentAt(-depth); };
  EXPECT_TRUE(at_depth(0.0).isApprox(Eigen::Vector3d(0.1, 1.0, 0.0)));   // above the first sample
  EXPECT_TRUE(at_depth(20.0).isApprox(Eigen::Vector3d(0.1, 2.0, 0.0)));  // halfway
  EXPECT_TRUE(at_depth(40.0).isApprox(Eigen::Vector3d(1.1, 3.0, 0.0)));
  EXPECT_TRUE(at_depth(45.0).isApprox(Eigen::Vector3d(1.6, 3.0, 0.0)));
  EXPECT_TRUE(at_depth(500.0).isApprox(Eigen::Vector3d(2.1, 3.0, 0.0)));  // below the last
  env.current_profile.clear();
  EXPECT_TRUE(env.currentAt(-20.0).isApprox(Eigen::Vector3d(0.1, 0.0, 0.0)));
}

TEST(CurrentProfile, RejectsUnorderedDepthsAndFastCurrentsNamingTheSample)
{
  Environment env;
  env.current_profile = profile({ { 10.0, Eigen::Vector3d::Zero() }, { 10.0, Eigen::Vector3d::Zero() } });
  try
  {
    validate(env);
    FAIL() << "repeated depth accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("environment.current_profile[1].depth"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("strictly increasing"), std::string::npos) << e.what();
  }
  env.current_profile = profile({ { 10.0, Eigen::Vector3d(0.0, 25.0, 0.0) } });
  EXPECT_THROW(validate(env), std::invalid_argument);
  env.current_profile = profile({ { -1.0, Eigen::Vector3d::Zero() } });
  EXPECT_THROW(validate(env), std::invalid_argument);
}

struct Tow
{
  std::shared_ptr<ChainModel> model;
  std::unique_ptr<Simulator> sim;
};

Tow makeTow(const Eigen::Vector3d& ship_velocity, const Eigen::Vector3d& current,
            const std::vector<CurrentSample>& current_profile, double length = 300.0, int segments = 60)
{
  CableParams cable;
  cable.length = length;
  cable.segments = segments;
  Environment env;
  env.current_W = current;
  env.current_profile = current_profile;
  auto vehicle = std::make_shared<Vehicle>(VehicleParams());
  Tow tow;
  tow.model = std::make_shared<ChainModel>(cable, vehicle, env, test::suiteNumerics());
  tow.sim = std::make_unique<Simulator>(tow.model, constantVelocityShip(Eigen::Vector3d::Zero(), ship_velocity));
  return tow;
}

TEST(CurrentProfile, UniformProfileIsGalilean)
{
  const Eigen::Vector3d u(1.5, 0.4, 0.0), down_astern(-1.0, -0.2, -0.6);
  Tow moving_ship = makeTow(u, Eigen::Vector3d::Zero(), {});
  Tow moving_water =
      makeTow(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), profile({ { 0.0, -u }, { 50.0, -u }, { 3000.0, -u } }));
  for (Tow* tow : { &moving_ship, &moving_water })
  {
    const Eigen::Vector3d v = tow == &moving_ship ? u : Eigen::Vector3d::Zero();
    tow->sim->reset(0.0, straightChain(*tow->model, Eigen::Vector3d::Zero(), down_astern, v));
    tow->sim->advanceTo(60.0);
  }
  const Eigen::Matrix3Xd a = moving_ship.sim->jointPositions().colwise() - moving_ship.sim->shipEnd().p_W;
  const Eigen::Matrix3Xd b = moving_water.sim->jointPositions().colwise() - moving_water.sim->shipEnd().p_W;
  const double gap = (a - b).cwiseAbs().maxCoeff();
  const double tension_gap = (moving_ship.sim->tensions() - moving_water.sim->tensions()).cwiseAbs().maxCoeff();
  std::printf("uniform profile vs moving ship after 60 s: joints %.2e m, tensions %.2e N\n", gap, tension_gap);
  // The two runs differ by the integration's error only: dopri5 at 1e-7 measured 2.7e-8 m and 6e-9
  // relative; the implicit stepper at its tolerances of 1e-5 with steps of up to max_step (5 s), 3.2e-5 m
  // (4.9e-6 m with steps of at most 0.5 s). Treating the current as the ship's motion wrongly moves the
  // joints by metres.
  const bool implicit = test::suiteNumerics().stepper == StepperType::kImplicit;
  EXPECT_LT(gap, implicit ? 1e-4 : 1e-6);  // [m]
  EXPECT_LT(tension_gap, (implicit ? 1e-5 : 1e-7) * moving_ship.sim->tensions().cwiseAbs().maxCoeff());
  // The cable did move: the comparison is not of two copies of the start.
  const Eigen::Matrix3Xd start = straightChain(*moving_ship.model, Eigen::Vector3d::Zero(), down_astern, u).x;
  EXPECT_GT((a.rightCols(a.cols() - 1) - start).cwiseAbs().maxCoeff(), 1.0);
}

// Ship east at 2 m/s; a cross-current toward the north (port) that grows from 0 at the surface to
// 0.5 m/s at 200 m. Documented: the cable is carried downstream, the deeper parts farther.
TEST(CurrentProfile, ShearCarriesTheDeeperCableFartherDownstream)
{
  const Eigen::Vector3d u(2.0, 0.0, 0.0), north(0.0, 0.5, 0.0);
  const std::vector<CurrentSample> shear = profile({ { 0.0, Eigen::Vector3d::Zero() }, { 200.0, north } });
  Tow tow = makeTow(u, Eigen::Vector3d::Zero(), shear);
  tow.sim->reset(0.0, straightChain(*tow.model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -0.5), u));
  tow.sim->advanceTo(900.0);
  const Eigen::Matrix3Xd joints = tow.sim->jointPositions().colwise() - tow.sim->shipEnd().p_W;

  // Two independent routes to the same steady shape: time integration and element-wise shooting.
  const EquilibriumResult eq = steadyTowEquilibrium(*tow.model, 900.0, tow.sim->shipEnd().p_W, u);
  const double gap = (tow.sim->state().x - eq.state.x).colwise().norm().maxCoeff();

  // The same tow in a uniform current equal to the deepest value, and in none (the surface value).
  Tow deep = makeTow(u, north, {});
  const EquilibriumResult eq_deep = steadyTowEquilibrium(*deep.model, 0.0, Eigen::Vector3d::Zero(), u);
  Tow none = makeTow(u, Eigen::Vector3d::Zero(), {});
  const EquilibriumResult eq_none = steadyTowEquilibrium(*none.model, 0.0, Eigen::Vector3d::Zero(), u);

  const int n = static_cast<int>(joints.cols());
  const double vehicle_offset = joints(1, n - 1);
  std::printf(
      "sheared cross-current: vehicle at depth %.1f m, %.2f m to port (uniform 0.5 m/s: %.2f m, none: "
      "%.2f m); dynamics vs equilibrium %.2e m\n",
      -joints(2, n - 1), vehicle_offset, eq_deep.state.x(1, n - 2), eq_none.state.x(1, n - 2), gap);
  EXPECT_LT(gap, 1e-4);                     // [m], measured 2.1e-5
  EXPECT_NEAR(vehicle_offset, 23.96, 0.1);  // regression of the documented 24.0 m
  // Downstream (north = +y) and farther the deeper: y grows monotonically along the cable.
  for (int j = 1; j < n; ++j)
    EXPECT_GE(joints(1, j), joints(1, j - 1) - 1e-9) << "joint " << j;
  // Less than in the deep current throughout, more than with none.
  EXPECT_LT(vehicle_offset, eq_deep.state.x(1, n - 2));
  EXPECT_NEAR(eq_none.state.x(1, n - 2), 0.0, 1e-9);
  // Curved in plan view, unlike the uniform case: the lower half turns more than the upper half.
  const int mid = n / 2;
  const double upper_slope = (joints(1, mid) - joints(1, 0)) / std::abs(joints(0, mid) - joints(0, 0));
  const double lower_slope = (joints(1, n - 2) - joints(1, mid)) / std::abs(joints(0, n - 2) - joints(0, mid));
  EXPECT_GT(lower_slope, upper_slope);
}

}  // namespace
}  // namespace tow_sim
