// The elastic cable (cable.axial_stiffness, docs/solver.md §8) in a tow: it converges to the rigid chain as
// EA grows (the turn_180 scenario's series), its steady-tow start is steady, an irregular sea's tow stays
// bounded, and malformed parameters are refused by name. (test_elastic_cable.cpp: energy, hanging stretch,
// axial period, forced heave and snaps.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/chain_fixtures.h"
#include "core/config_error.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/seabed.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
namespace
{
// The 180 degree turn (scenarios/turn_180.yaml: 300 m of cable in 50 segments) to 390 s, past the turn's end,
// at tight tolerances, with the cable's EA set and an axial damping of EA x 0.01 s (unset: the rigid
// chain): the timeseries' columns by name.
std::map<std::string, std::vector<double>> turnSeries(std::optional<double> ea)
{
  Scenario sc = loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/turn_180.yaml");
  sc.config.cable.axial_stiffness = ea;
  sc.config.cable.axial_damping = ea ? 0.01 * *ea : 0.0;
  sc.config.numerics.max_step = 0.05;
  sc.config.numerics.implicit_position_tol = sc.config.numerics.implicit_velocity_tol = 1e-8;
  sc.config.numerics.implicit_rel_tol = 1e-8;
  sc.duration = 390.0;
  std::ostringstream series, shapes;
  BatchResult result;
  runScenario(sc, series, shapes, result);
  std::istringstream in(series.str());
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream header(line); std::getline(header, cell, ',');)
    names.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line))
  {
    std::stringstream cells(line);
    for (size_t c = 0; std::getline(cells, cell, ','); ++c)
      columns[names[c]].push_back(cell.empty() ? 0.0 : std::stod(cell));
  }
  return columns;
}

// Largest difference between two runs over some columns, each relative to the rigid run's largest magnitude.
double scaledDifference(const std::map<std::string, std::vector<double>>& a,
                        const std::map<std::string, std::vector<double>>& rigid, std::vector<const char*> columns)
{
  double worst = 0.0;
  for (const char* column : columns)
  {
    const std::vector<double>&x = a.at(column), &y = rigid.at(column);
    double scale = 0.0, largest = 0.0;
    for (size_t i = 0; i < y.size(); ++i)
    {
      scale = std::max(scale, std::abs(y[i]));
      largest = std::max(largest, std::abs(x[i] - y[i]));
    }
    worst = std::max(worst, largest / scale);
  }
  return worst;
}

// EA -> infinity: the steady tow, the 180 degree turn and its end against the rigid chain. The vehicle's
// depth, layback and diversion converge like 1/EA (within 0.1 % at EA 1e7 N, 10 times closer per decade
// until the integration's tolerance, 1e-8 m, is reached); the tensions at the ship and the vehicle within
// 0.1 % at 1e7 N. A stiffer cable's tension is EA/d times its stretch, so its accuracy is the position
// tolerance's times EA/d (docs/limitations.md): within 0.2 % at 1e8 and 1e9 N here.
TEST(ElasticCable, ConvergesToTheRigidChainAsEAGrows)
{
  const auto rigid = turnSeries(std::nullopt);
  double previous = 1.0;
  for (double ea : { 1.0e7, 1.0e8, 1.0e9 })
  {
    const auto elastic = turnSeries(ea);
    ASSERT_EQ(elastic.at("t").size(), rigid.at("t").size());
    const double shape = scaledDifference(elastic, rigid, { "depth", "layback", "diversion" });
    const double tension = scaledDifference(elastic, rigid, { "tension_ship", "tension_vehicle" });
    std::printf("EA %.0e N: largest difference from the rigid chain, shape %.2e, tensions %.2e\n", ea, shape, tension);
    EXPECT_LT(shape, 1e-3);
    if (ea > 1.0e7)
    {
      EXPECT_LT(shape, std::max(0.2 * previous, 5e-6));
    }
    EXPECT_LT(tension, ea < 1.0e8 ? 1e-3 : 2e-3);
    previous = shape;
  }
}

// The steady tow's start for an elastic cable (each segment stretched by its tension in the rigid
// equilibrium) is steady: a soft cable (EA 1e6 N, strains near 1e-3) towed straight at 2 m/s for 60 s moves
// its vehicle by less than a millimetre and its tensions by less than 0.05 % against the ship. Started at
// its rest lengths instead, it would spring back by the stretch (about 0.2 m).
TEST(ElasticCable, TheSteadyTowStartIsSteady)
{
  const Scenario sc = loadScenario(YAML::Load(R"(
cable: {length: 300.0, segments: 30, axial_stiffness: 1.0e6, axial_damping: 1.0e4}
ship: {manoeuvres: [{type: straight, speed: 2.0, duration: 100.0}]}
simulation: {duration: 60.0, output_interval: 1.0, shape_interval: 100.0}
)"));
  std::ostringstream series, shapes;
  BatchResult result;
  runScenario(sc, series, shapes, result);
  std::istringstream in(series.str());
  std::string line;
  std::getline(in, line);
  double depth0 = 0.0, layback0 = 0.0, tension0 = 0.0, worst_position = 0.0, worst_tension = 0.0, strain = 0.0;
  for (int row = 0; std::getline(in, line); ++row)
  {
    std::vector<double> c;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');)
      c.push_back(cell.empty() ? 0.0 : std::stod(cell));
    if (row == 0)
    {
      depth0 = c[11];
      layback0 = c[12];
      tension0 = c[15];
    }
    worst_position = std::max({ worst_position, std::abs(c[11] - depth0), std::abs(c[12] - layback0) });
    worst_tension = std::max(worst_tension, std::abs(c[15] / tension0 - 1.0));
    strain = c[31];
  }
  std::printf("over 60 s: vehicle moved %.2e m, tension at the ship %.2e relative; strain %.2e\n", worst_position,
              worst_tension, strain);
  EXPECT_LT(worst_position, 1e-3);
  EXPECT_LT(worst_tension, 5e-4);
  EXPECT_GT(strain, 5e-4);
}

// A tow in an irregular sea (JONSWAP Hs 5 m, the ship heaving and pitching) on a steel-like elastic cable
// (EA 1e8 N): no divergence, the tension never negative nor jerked (a start with the segments stretching
// would pull some 50 kN), the stretch bounded by what the largest tension
// seen explains (strain <= T_max / EA, with room for the dynamics), the end body's length held. 600 s here;
// TOW_SIM_SEAWAY_SECONDS=3600 (make soak) runs the hour.
TEST(ElasticCable, AnIrregularSeaTowStaysBounded)
{
  const char* env = std::getenv("TOW_SIM_SEAWAY_SECONDS");
  const double seconds = env ? std::atof(env) : 600.0;
  const Scenario sc = loadScenario(YAML::Load(R"(
cable: {length: 300.0, segments: 30, axial_stiffness: 1.0e8, axial_damping: 1.0e6}
environment:
  waves: {type: jonswap, significant_height: 5.0, peak_period: 9.0, direction: 2.8, spreading: 4, seed: 3}
ship: {manoeuvres: [{type: straight, speed: 2.0, duration: 1.0e5}]}
simulation: {duration: )" + std::to_string(seconds) +
                                              R"(, output_interval: 1.0, shape_interval: 1.0e5}
)"));
  std::ostringstream series, shapes;
  BatchResult result;
  ASSERT_NO_THROW(runScenario(sc, series, shapes, result));
  EXPECT_EQ(result.t_reached, seconds);
  std::istringstream in(series.str());
  std::string line;
  std::getline(in, line);
  double t_lo = 1e12, t_hi = 0.0, strain = 0.0, worst_length = 0.0;
  long snaps = 0;
  while (std::getline(in, line))
  {
    std::vector<double> c;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');)
      c.push_back(cell.empty() ? 0.0 : std::stod(cell));
    t_lo = std::min({ t_lo, c[26], c[28] });
    t_hi = std::max({ t_hi, c[27], c[29] });
    strain = std::max(strain, c[31]);
    worst_length = std::max(worst_length, c[20]);
    snaps = static_cast<long>(c[30]);
  }
  std::printf(
      "%.0f s in Hs 5 m, EA 1e8 N: tensions %.0f .. %.0f N, largest strain %.2e (T_max/EA %.2e), %ld snaps, "
      "end body length error %.1e\n",
      seconds, t_lo, t_hi, strain, t_hi / 1e8, snaps, worst_length);
  EXPECT_GT(t_lo, 0.0);           // never slack at the ship or the vehicle in this sea
  EXPECT_LT(t_hi, 4.0 * 1667.0);  // four times the calm-water tow's tension at the ship (the rigid cable: 3515 N)
  EXPECT_GT(strain, 0.0);
  EXPECT_LT(strain, 2.0 * t_hi / 1e8);
  EXPECT_LT(worst_length, 1e-3);
}

// Malformed elastic parameters are refused with the parameter, the value and the range named; the winch
// (which re-meshes rigid segments) refuses an elastic cable.
TEST(ElasticCable, RefusesMalformedParameters)
{
  const auto refusal = [](const std::string& yaml) { return test::configError(yaml); };
  for (const char* bad : { "cable: {axial_stiffness: -1.0}", "cable: {axial_stiffness: 0.0}",
                           "cable: {axial_stiffness: .nan}", "cable: {axial_stiffness: 1.0e12}" })
  {
    const std::string what = refusal(bad);
    EXPECT_NE(what.find("cable.axial_stiffness"), std::string::npos) << bad << ": " << what;
    EXPECT_NE(what.find("1e+11"), std::string::npos) << bad << ": " << what;
  }
  std::string what = refusal("cable: {axial_stiffness: 1.0e8, axial_damping: -5.0}");
  EXPECT_NE(what.find("cable.axial_damping"), std::string::npos) << what;
  EXPECT_NE(what.find("-5"), std::string::npos) << what;
  what = refusal("cable: {axial_damping: 100.0}");
  EXPECT_NE(what.find("cable.axial_damping"), std::string::npos) << what;
  EXPECT_NE(what.find("axial_stiffness"), std::string::npos) << what;
  what = refusal("cable: {axial_stiffness: 1.0e8}\nwinch: {enabled: true}");
  EXPECT_NE(what.find("winch.enabled"), std::string::npos) << what;
  EXPECT_EQ(refusal("cable: {axial_stiffness: 1.0e8, axial_damping: 1.0e6}"), "(accepted)");
}

}  // namespace
}  // namespace tow_sim
