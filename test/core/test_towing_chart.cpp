// Towing charts (tow_sim_chart): chart points against the settled dynamics of a tow run (the batch
// runner's), the long cable's angle at the ship against the critical-angle closed form, ranges, and the
// CSV's marking of points without an equilibrium.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/ship_path.h"
#include "tow_sim/scenario/towing_chart.h"

namespace tow_sim
{
namespace
{

// The default configuration with 10 m segments, towed from a straight line 30 degrees down for 1500 s at a
// constant speed: its settled state.
TowSnapshot settledTow(double speed, double cable_out)
{
  SimulationConfig c;
  c.cable.length = cable_out;
  c.cable.segments = static_cast<int>(cable_out / 10.0);
  const auto ship = straightShip(speed, -2.0, 1600.0);
  InitialShape line;
  line.type = InitialShape::Type::kLine;
  line.line_direction_S = Eigen::Vector3d(-1.0, 0.0, -0.577);
  TowRun run(c, ship, line);
  run.start(0.0);
  run.advanceTo(1500.0);
  return run.snapshot();
}

TEST(TowingChart, PointsAreTheSettledDynamicsOfATowRun)
{
  SimulationConfig config;
  config.cable.segments = static_cast<int>(config.cable.length / 10.0);  // 10 m segments, as settledTow's
  for (auto [speed, cable_out] : { std::pair<double, double>{ 1.0, 100.0 }, { 2.0, 200.0 }, { 3.0, 150.0 } })
  {
    const ChartPoint p = chartPoint(config, speed, cable_out, Eigen::Vector3d::Zero());
    ASSERT_TRUE(p.converged) << p.error;
    const TowSnapshot s = settledTow(speed, cable_out);
    std::printf(
        "%.0f m/s, %.0f m: depth %.3f / %.3f m, layback %.3f / %.3f m, tensions %.2f / %.2f, %.2f / %.2f N "
        "(chart / settled dynamics)\n",
        speed, cable_out, p.depth, s.depth, p.layback, s.layback, p.tension_ship, s.tension_ship, p.tension_vehicle,
        s.tension_vehicle);
    EXPECT_NEAR(p.depth, s.depth, 1e-3 * s.depth);
    EXPECT_NEAR(p.layback, s.layback, 1e-3 * s.layback);
    EXPECT_NEAR(p.tension_ship, s.tension_ship, 1e-3 * s.tension_ship);
    EXPECT_NEAR(p.tension_vehicle, s.tension_vehicle, 1e-3 * s.tension_vehicle);
    EXPECT_NEAR(p.max_tension, p.tension_ship, 1e-9 * p.tension_ship);  // the top carries the most here
  }
}

// A long cable without tangential drag towed at U lies, far from its end, at the critical angle:
// (w - b) cos(phi) = C2 U^2 sin^2(phi) (physics.md §8), whatever the vehicle does 3 km below.
TEST(TowingChart, TheLongCablesAngleAtTheShipIsTheCriticalAngle)
{
  SimulationConfig config;
  config.cable.tangential_drag_coefficient = 0.0;
  config.cable.segments = 100;
  config.cable.length = 1000.0;  // 10 m segments
  const CableParams& cable = config.cable;
  const double rho = config.environment.water_density, g = config.environment.gravity;
  const double net = (cable.mass_per_length - rho * kPi * cable.diameter * cable.diameter / 4.0) * g;  // w - b
  const double c2 = 0.5 * rho * cable.normal_drag_coefficient * cable.diameter;
  for (double speed : { 1.0, 2.0, 3.0 })
  {
    // Solve the closed form by bisection in phi.
    double lo = 0.0, hi = kPi / 2.0;
    for (int i = 0; i < 200; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      (net * std::cos(mid) - c2 * speed * speed * std::sin(mid) * std::sin(mid) > 0.0 ? lo : hi) = mid;
    }
    const double critical = 0.5 * (lo + hi) * 180.0 / kPi;
    const ChartPoint p = chartPoint(config, speed, 3000.0, Eigen::Vector3d::Zero());
    ASSERT_TRUE(p.converged) << p.error;
    std::printf("%.0f m/s: angle at the ship %.4f deg, critical angle %.4f deg\n", speed, p.ship_angle, critical);
    EXPECT_NEAR(p.ship_angle, critical, 0.01);
  }
}

TEST(TowingChart, AFollowingCurrentIsTheSameAsASlowerShip)
{
  // Galilean: the ship at 2.5 m/s in a 0.5 m/s current running with it tows as the ship at 2 m/s in still
  // water (the chart's current direction 0 runs along the ship's heading).
  const SimulationConfig config;
  const ChartPoint a = chartPoint(config, 2.5, 300.0, Eigen::Vector3d(0.5, 0.0, 0.0));
  const ChartPoint b = chartPoint(config, 2.0, 300.0, Eigen::Vector3d::Zero());
  EXPECT_NEAR(a.depth, b.depth, 1e-6);
  EXPECT_NEAR(a.tension_ship, b.tension_ship, 1e-6);
}

TEST(TowingChart, RangesAndTheMarkingOfPointsWithoutAnEquilibrium)
{
  EXPECT_EQ(parseRange("0.5:2:0.5", "--speeds"), (std::vector<double>{ 0.5, 1.0, 1.5, 2.0 }));
  EXPECT_EQ(parseRange("300", "--cable-out"), (std::vector<double>{ 300.0 }));
  EXPECT_EQ(parseRange("0.1:0.3:0.1", "--speeds").size(), 3u);  // TO included despite rounding
  for (const char* bad : { "1:2", "a:2:1", "2:1:0.5", "1:2:0", "1:2:-1", "0:1e9:1e-3", "1::2" })
  {
    try
    {
      parseRange(bad, "--speeds");
      ADD_FAILURE() << bad << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("--speeds"), std::string::npos) << e.what();
    }
  }
  ChartPoint failed;
  failed.speed = 1.5;
  failed.cable_out = 200.0;
  failed.depth = failed.layback = failed.tension_ship = failed.tension_vehicle = NAN;
  failed.ship_angle = failed.max_tension = NAN;
  std::ostringstream row;
  writeChartRow(row, failed);
  EXPECT_EQ(row.str(), "1.5,200,0,,,,,,,0\n");
  EXPECT_EQ(std::string(chartHeader()),
            "speed,cable_out,current,depth,layback,tension_ship,tension_vehicle,ship_angle,max_tension,converged");
}

// Inverse planning round trip: the planned cable out puts the steady vehicle within 0.1 m of the target;
// a depth beyond the winch's limits is reported, with the reachable range. The speed window's ends put the
// vehicle on the band's edges.
TEST(TowingChart, PlanningFindsTheCableOutForADepthAndTheSpeedsForABand)
{
  const SimulationConfig config;
  for (auto [depth, speed] : { std::pair<double, double>{ 150.0, 2.0 }, { 60.0, 1.0 }, { 400.0, 3.0 } })
  {
    const CableOutPlan plan = planCableOut(config, depth, speed, Eigen::Vector3d::Zero(), 50.0, 2000.0);
    ASSERT_TRUE(plan.reachable) << plan.reason;
    const ChartPoint check = chartPoint(config, speed, plan.cable_out, Eigen::Vector3d::Zero());
    std::printf("%.0f m at %.0f m/s: %.2f m out, steady depth %.3f m\n", depth, speed, plan.cable_out, check.depth);
    EXPECT_NEAR(check.depth, depth, 0.1);
  }
  const CableOutPlan deep = planCableOut(config, 3000.0, 2.0, Eigen::Vector3d::Zero(), 50.0, 2000.0);
  EXPECT_FALSE(deep.reachable);
  EXPECT_NE(deep.reason.find("out of reach"), std::string::npos) << deep.reason;
  const CableOutPlan shallow = planCableOut(config, 5.0, 1.0, Eigen::Vector3d::Zero(), 50.0, 2000.0);
  EXPECT_FALSE(shallow.reachable);

  const SpeedWindow w = speedWindow(config, 500.0, 100.0, 200.0, Eigen::Vector3d::Zero());
  ASSERT_TRUE(w.found) << w.reason;
  std::printf("500 m out, 100 .. 200 m: %.3f .. %.3f m/s\n", w.slowest, w.fastest);
  EXPECT_NEAR(chartPoint(config, w.slowest, 500.0, Eigen::Vector3d::Zero()).depth, 200.0, 0.05);
  EXPECT_NEAR(chartPoint(config, w.fastest, 500.0, Eigen::Vector3d::Zero()).depth, 100.0, 0.05);
  EXPECT_GT(chartPoint(config, 0.5 * (w.slowest + w.fastest), 500.0, Eigen::Vector3d::Zero()).depth, 100.0);
  EXPECT_FALSE(speedWindow(config, 100.0, 300.0, 400.0, Eigen::Vector3d::Zero()).found);
}

// The tool end to end: a 3 x 2 chart with a head current, and a refusal.
TEST(TowingChart, TheToolWritesTheChartAndRefusesBadArguments)
{
  const std::string batch = TOW_SIM_BATCH_BINARY;
  const std::string tool = batch.substr(0, batch.rfind('/') + 1) + "tow_sim_chart";
  char folder[] = "/tmp/tow_sim_chart_test.XXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  const std::string config = std::string(TOW_SIM_SOURCE_DIR) + "/config/tow_sim.yaml";
  ASSERT_EQ(std::system((tool + " --config " + config + " --speeds 1:2:0.5 --cable-out 100:200:100 --current 0.5:180 " +
                         "--out " + folder + " --no-plot > /dev/null")
                            .c_str()),
            0);
  std::ifstream csv(std::string(folder) + "/chart.csv");
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(csv, line))
    lines.push_back(line);
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[0], chartHeader());
  // Against a 0.5 m/s current at 1 m/s the cable sees 1.5 m/s: the library's point in still water.
  std::vector<double> row;
  std::stringstream cells(lines[1]);
  std::string cell;
  while (std::getline(cells, cell, ','))
    row.push_back(std::stod(cell));
  const ChartPoint still = chartPoint(SimulationConfig(), 1.5, 100.0, Eigen::Vector3d::Zero());
  ASSERT_EQ(row.size(), 10u);
  EXPECT_EQ(row[0], 1.0);
  EXPECT_EQ(row[2], 0.5);
  EXPECT_NEAR(row[3], still.depth, 1e-6);
  EXPECT_NEAR(row[5], still.tension_ship, 1e-5);
  EXPECT_EQ(row[9], 1.0);
  EXPECT_NE(
      std::system(
          (tool + " --config " + config + " --speeds 1:2 --cable-out 100 --out " + folder + " 2> /dev/null").c_str()),
      0);
}

}  // namespace
}  // namespace tow_sim
