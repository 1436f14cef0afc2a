// Steady-tow equilibrium: it stays put under the dynamics, equals where the dynamics settle, matches
// the critical angle for a free cable, and converges or fails cleanly over speeds and currents.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/chain_fixtures.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{

std::shared_ptr<ChainModel> vehicleModel(double length, int segments, const Eigen::Vector3d& current,
                                         std::shared_ptr<Vehicle>* vehicle_out = nullptr)
{
  CableParams cable;
  cable.length = length;
  cable.segments = segments;
  Environment env;
  env.current_W = current;
  auto vehicle = std::make_shared<Vehicle>(VehicleParams());
  if (vehicle_out)
    *vehicle_out = vehicle;
  return std::make_shared<ChainModel>(cable, vehicle, env, NumericsParams());
}

double largestOffset(const Simulator& sim, const Eigen::Matrix3Xd& relative_start)
{
  const Eigen::Matrix3Xd now = sim.jointPositions().colwise() - sim.shipEnd().p_W;
  return (now - relative_start).colwise().norm().maxCoeff();
}

TEST(Equilibrium, SteadyTowStartedThereStaysThere)
{
  auto model = vehicleModel(500.0, 100, Eigen::Vector3d(0.2, -0.3, 0.0));
  const Eigen::Vector3d u(1.6, 1.2, 0.0);  // 2 m/s, heading 37 deg
  const EquilibriumResult eq = steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), u);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), u));
  sim.reset(0.0, eq.state);
  const Eigen::Matrix3Xd start = sim.jointPositions().colwise() - sim.shipEnd().p_W;
  // The tensions it found are the dynamics' tensions at rest in the ship's frame.
  EXPECT_LT((sim.tensions() - eq.tensions).cwiseAbs().maxCoeff(), 1e-6 * eq.tensions.cwiseAbs().maxCoeff());
  EXPECT_LT(sim.accelerations().cwiseAbs().maxCoeff(), 1e-6);
  double worst = 0.0;
  for (int i = 1; i <= 60; ++i)
  {
    sim.advanceTo(i * 1.0);
    worst = std::max(worst, largestOffset(sim, start));
  }
  std::printf("started at equilibrium (%d Newton iterations): largest joint motion in 60 s %.2e m\n", eq.iterations,
              worst);
  EXPECT_LT(worst, 1e-5);  // measured 7e-7 m
}

TEST(Equilibrium, EqualsWhereTheDynamicsSettle)
{
  auto model = vehicleModel(100.0, 20, Eigen::Vector3d(0.0, 0.4, 0.0));
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), u));
  sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -0.3), u));
  sim.advanceTo(900.0);
  const EquilibriumResult eq = steadyTowEquilibrium(*model, 900.0, sim.shipEnd().p_W, u);
  const double gap = (sim.state().x - eq.state.x).colwise().norm().maxCoeff();
  std::printf("equilibrium vs 900 s of dynamics from a straight line: largest joint gap %.2e m\n", gap);
  EXPECT_LT(gap, 1e-5);  // measured 1.6e-7 m
}

TEST(Equilibrium, FreeCableLiesAtTheCriticalAngle)
{
  CableParams cable;
  cable.segments = 50;
  cable.length = 200.0;
  cable.tangential_drag_coefficient = 0.0;
  const Environment env;
  auto model = test::makeModel(cable, test::endLikeSegment(cable), env);
  const double speed = 2.0;
  const EquilibriumResult eq = steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(speed, 0, 0));
  const double w =
      (cable.mass_per_length - env.water_density * kPi * 0.25 * cable.diameter * cable.diameter) * env.gravity;
  const double c2u2 = 0.5 * env.water_density * cable.normal_drag_coefficient * cable.diameter * speed * speed;
  const double phi_c = std::acos((-w + std::sqrt(w * w + 4.0 * c2u2 * c2u2)) / (2.0 * c2u2));
  const Eigen::Vector3d s = eq.state.x.col(25) - eq.state.x.col(24);
  const double phi = std::atan2(-s.z(), s.head<2>().norm());
  std::printf("equilibrium: middle of a free cable at %.4f deg, closed form %.4f deg\n", phi * 180 / kPi,
              phi_c * 180 / kPi);
  EXPECT_NEAR(phi, phi_c, 0.02 * kPi / 180);  // a normal drag off by 1 % moves it by about 0.1 deg
}

TEST(Equilibrium, ConvergesOrFailsClearlyOverSpeedsAndCurrents)
{
  int converged = 0, failed = 0;
  const auto start = std::chrono::steady_clock::now();
  for (double speed : { 0.0, 0.5, 2.0, 5.0, 10.0 })
    for (int direction = 0; direction < 8; ++direction)
    {
      const double a = direction * kPi / 4;
      auto model = vehicleModel(300.0, 60, 0.5 * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0));
      try
      {
        const EquilibriumResult eq =
            steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(speed, 0.0, 0.0));
        EXPECT_TRUE(eq.state.x.allFinite() && eq.tensions.allFinite());
        // The cable hangs below the tow point and the ship pulls.
        EXPECT_LT(eq.state.x.row(2).maxCoeff(), 0.0);
        EXPECT_GT(eq.tensions.col(0).norm(), 0.0);
        ++converged;
      }
      catch (const std::runtime_error& e)
      {
        ++failed;
        EXPECT_NE(std::string(e.what()).find("equilibrium: no stable direction balances element"), std::string::npos);
      }
    }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("equilibrium over 5 speeds x 8 current directions: %d converged, %d failed cleanly, %.2f s\n", converged,
              failed, seconds);
  EXPECT_EQ(converged, 40);
  // Hanging at rest in still water: straight down, carrying the weight in water.
  auto still = vehicleModel(300.0, 60, Eigen::Vector3d::Zero());
  const EquilibriumResult hang = steadyTowEquilibrium(*still, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_LT(hang.state.x.topRows(2).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_THROW(steadyTowEquilibrium(*still, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(NAN, 0, 0)),
               std::runtime_error);
}

}  // namespace
}  // namespace tow_sim
