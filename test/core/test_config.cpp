// The YAML configuration: the shipped file documents the real defaults, and every bad key or value is
// reported with its full path.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/config_error.h"
#include "core/temp_file.h"
#include "tow_sim/config/config.h"
#include "tow_sim/config/param_yaml.h"
#include "tow_sim/core/param_tables.h"

namespace tow_sim
{
namespace
{
std::string errorOf(const std::string& yaml, const std::string& prefix = "")
{
  return test::configError(yaml, prefix);
}

void expectSameTable(const AngleTable& a, const AngleTable& b)
{
  ASSERT_EQ(a.angles().size(), b.angles().size());
  for (size_t i = 0; i < a.angles().size(); ++i)
  {
    EXPECT_NEAR(a.angles()[i], b.angles()[i], 1e-6);
    EXPECT_NEAR(a.values()[i], b.values()[i], 1e-6);
  }
}

void expectSameVehicle(const VehicleParams& v, const VehicleParams& w)
{
  EXPECT_EQ(v.tail_from_bail, w.tail_from_bail);
  EXPECT_EQ(v.cg_from_bail, w.cg_from_bail);
  EXPECT_EQ(v.horizontal_fin_from_bail, w.horizontal_fin_from_bail);
  EXPECT_EQ(v.vertical_fin_from_bail, w.vertical_fin_from_bail);
  EXPECT_EQ(v.nose_from_bail, w.nose_from_bail);
  EXPECT_EQ(v.cb_from_bail, w.cb_from_bail);
  EXPECT_EQ(v.mass, w.mass);
  EXPECT_EQ(v.displaced_volume, w.displaced_volume);
  EXPECT_EQ(v.inertia_B, w.inertia_B);
  EXPECT_EQ(v.c1, w.c1);
  EXPECT_EQ(v.c2, w.c2);
  EXPECT_EQ(v.added_mass_approach, w.added_mass_approach);
  EXPECT_EQ(v.added_mass_a, w.added_mass_a);
  EXPECT_EQ(v.added_mass_b, w.added_mass_b);
  EXPECT_EQ(v.prolate_spheroid.has_value(), w.prolate_spheroid.has_value());
  EXPECT_EQ(v.munk_terms, w.munk_terms);
  EXPECT_EQ(v.max_thrust, w.max_thrust);
  EXPECT_EQ(v.thrust_offset_z, w.thrust_offset_z);
  for (const auto& pair : { std::make_pair(&v.rudder, &w.rudder), std::make_pair(&v.elevator, &w.elevator) })
  {
    EXPECT_EQ(pair.first->lift_constant, pair.second->lift_constant);
    EXPECT_EQ(pair.first->drag_constant, pair.second->drag_constant);
    EXPECT_EQ(pair.first->max_deflection, pair.second->max_deflection);
    EXPECT_EQ(pair.first->max_rate, pair.second->max_rate);
    EXPECT_EQ(pair.first->center_of_pressure_offset, pair.second->center_of_pressure_offset);
    expectSameTable(pair.first->lift, pair.second->lift);
    expectSameTable(pair.first->drag, pair.second->drag);
  }
}

void expectSame(const SimulationConfig& a, const SimulationConfig& b)
{
  EXPECT_EQ(YAML::Dump(toYaml(a)).size() > 0, true);
  EXPECT_EQ(a.cable.length, b.cable.length);
  EXPECT_EQ(a.cable.segments, b.cable.segments);
  EXPECT_EQ(a.cable.diameter, b.cable.diameter);
  EXPECT_EQ(a.cable.mass_per_length, b.cable.mass_per_length);
  EXPECT_EQ(a.cable.normal_drag_coefficient, b.cable.normal_drag_coefficient);
  EXPECT_EQ(a.cable.tangential_drag_coefficient, b.cable.tangential_drag_coefficient);
  EXPECT_EQ(a.cable.c1, b.cable.c1);
  EXPECT_EQ(a.cable.c2, b.cable.c2);
  EXPECT_EQ(a.cable.added_mass_coefficient, b.cable.added_mass_coefficient);
  EXPECT_EQ(a.cable.tangential_drag_model, b.cable.tangential_drag_model);
  EXPECT_EQ(a.environment.gravity, b.environment.gravity);
  EXPECT_EQ(a.environment.water_density, b.environment.water_density);
  EXPECT_EQ(a.environment.current_W, b.environment.current_W);
  EXPECT_EQ(YAML::Dump(toYaml(a)).find("winch"), YAML::Dump(toYaml(b)).find("winch"));
  EXPECT_EQ(a.winch.enabled, b.winch.enabled);
  EXPECT_EQ(a.winch.min_length, b.winch.min_length);
  EXPECT_EQ(a.winch.max_length, b.winch.max_length);
  EXPECT_EQ(a.winch.max_rate, b.winch.max_rate);
  EXPECT_EQ(a.winch.max_acceleration, b.winch.max_acceleration);
  EXPECT_EQ(a.winch.response_time, b.winch.response_time);
  EXPECT_EQ(a.winch.segment_min_fraction, b.winch.segment_min_fraction);
  EXPECT_EQ(a.winch.segment_max_fraction, b.winch.segment_max_fraction);
  EXPECT_EQ(a.seabed.type, b.seabed.type);
  EXPECT_EQ(a.seabed.depth, b.seabed.depth);
  EXPECT_EQ(a.seabed.grid_file, b.seabed.grid_file);
  EXPECT_EQ(a.seabed.grid.depth, b.seabed.grid.depth);
  EXPECT_EQ(a.seabed.stiffness, b.seabed.stiffness);
  EXPECT_EQ(a.seabed.damping, b.seabed.damping);
  EXPECT_EQ(a.seabed.vehicle_stiffness, b.seabed.vehicle_stiffness);
  EXPECT_EQ(a.seabed.vehicle_damping, b.seabed.vehicle_damping);
  EXPECT_EQ(a.seabed.friction, b.seabed.friction);
  EXPECT_EQ(a.seabed.friction_speed, b.seabed.friction_speed);
  const WaveParams &wa = a.environment.waves, &wb = b.environment.waves;
  EXPECT_EQ(wa.type, wb.type);
  for (auto member : { &WaveParams::water_depth, &WaveParams::direction, &WaveParams::height, &WaveParams::period,
                       &WaveParams::phase, &WaveParams::significant_height, &WaveParams::peak_period,
                       &WaveParams::peak_enhancement, &WaveParams::spreading })
    EXPECT_EQ(wa.*member, wb.*member);
  EXPECT_EQ(wa.components, wb.components);
  EXPECT_EQ(wa.seed, wb.seed);
  ASSERT_EQ(a.environment.current_profile.size(), b.environment.current_profile.size());
  for (std::size_t i = 0; i < a.environment.current_profile.size(); ++i)
  {
    EXPECT_EQ(a.environment.current_profile[i].depth, b.environment.current_profile[i].depth);
    EXPECT_EQ(a.environment.current_profile[i].velocity_W, b.environment.current_profile[i].velocity_W);
  }
  EXPECT_EQ(a.numerics.stepper, b.numerics.stepper);
  EXPECT_EQ(a.numerics.abs_tol, b.numerics.abs_tol);
  EXPECT_EQ(a.numerics.rel_tol, b.numerics.rel_tol);
  EXPECT_EQ(a.numerics.max_step, b.numerics.max_step);
  EXPECT_EQ(a.numerics.fixed_step, b.numerics.fixed_step);
  EXPECT_EQ(a.numerics.tangential_smoothing_speed, b.numerics.tangential_smoothing_speed);
  expectSameVehicle(a.vehicle, b.vehicle);
}

TEST(Config, ShippedFileDocumentsTheBuiltInDefaults)
{
  const SimulationConfig file = loadConfigFile(std::string(TOW_SIM_SOURCE_DIR) + "/config/tow_sim.yaml");
  expectSame(file, SimulationConfig());
  expectSame(loadConfig(YAML::Load("{}")), SimulationConfig());
}

TEST(Config, RoundTripsThroughYaml)
{
  SimulationConfig c = loadConfig(YAML::Load(R"(
cable: {length: 320, segments: 40, c2: 14.5, tangential_drag_model: quadratic}
environment:
  current: [0.3, -0.2, 0.0]
  current_profile: [{depth: 0, velocity: [0, 0, 0]}, {depth: 150, velocity: [0, 0.6, 0]}]
  waves: {type: jonswap, water_depth: 80, direction: 2.5, significant_height: 3.5, peak_period: 9, spreading: 6,
          components: 64, seed: 11}
numerics: {stepper: rk4, fixed_step: 0.02}
winch: {enabled: true, min_length: 100, max_length: 900, max_rate: 1.5}
seabed: {type: flat, depth: 400, friction: 0.3}
vehicle:
  inertia: {xx: 3, yy: 50, zz: 55, xz: 1.5}
  added_mass: {approach: B, munk_terms: true, prolate_spheroid: {length: 2.0, diameter: 0.3, center_from_bail: 0.2}}
  rudder: {lift_constant: 210, lift_table: {angles: [0, 0.5, 1.5707963], values: [0, 0.5, 0]}}
)"));
  EXPECT_EQ(c.cable.segments, 40);
  EXPECT_EQ(*c.cable.c2, 14.5);
  EXPECT_EQ(c.numerics.stepper, StepperType::kRk4);
  EXPECT_EQ(c.environment.waves.type, WaveParams::Type::kJonswap);
  EXPECT_EQ(c.environment.waves.components, 64);
  EXPECT_EQ(c.vehicle.inertia_B(2, 0), 1.5);
  EXPECT_TRUE(c.vehicle.prolate_spheroid.has_value());
  EXPECT_NEAR(c.vehicle.rudder.lift(0.25), 0.25, 1e-12);
  expectSame(loadConfig(toYaml(c)), c);
}

TEST(Config, AGridFileGivenRelativeToTheConfigurationIsWrittenBackAbsolute)
{
  // The batch runner writes scenario.yaml into its output folder: a grid path relative to the scenario's
  // folder (or to the working directory) must still find the grid from there.
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "tow_sim_grid_config_test";
  fs::create_directories(dir);
  std::ofstream(dir / "grid.yaml") << "{origin: [0, 0], spacing: [10, 10], depth: [[50, 60], [70, 80]]}";
  const std::string relative_dir = fs::relative(dir, fs::current_path()).string() + "/";
  const SimulationConfig c = loadConfig(YAML::Load("seabed: {type: grid, grid_file: grid.yaml}"), "", relative_dir);
  EXPECT_TRUE(fs::path(c.seabed.grid_file).is_absolute()) << c.seabed.grid_file;
  EXPECT_TRUE(fs::equivalent(c.seabed.grid_file, dir / "grid.yaml"));
  const SimulationConfig again = loadConfig(toYaml(c), "", "/nonexistent/");
  EXPECT_EQ(again.seabed.grid.depth, c.seabed.grid.depth);
  EXPECT_EQ(again.seabed.grid.depth(1, 1), 80.0);
}

TEST(Config, AcceptsTheUpperTriangleOfTheAddedMassMatrix)
{
  const SimulationConfig c = loadConfig(YAML::Load(
      "vehicle: {added_mass: {approach: B, matrix: [10, 1, 0, 0, 0, 0,  20, 0, 0, 0, 0,  20, 0, 0, 0,  0, 0, 0,  "
      "5, 0,  5]}}"));
  EXPECT_EQ(c.vehicle.added_mass_b(0, 1), 1.0);
  EXPECT_EQ(c.vehicle.added_mass_b(1, 0), 1.0);
  EXPECT_EQ(c.vehicle.added_mass_b(5, 5), 5.0);
}

TEST(Config, ErrorsNameTheFullKeyPathTheValueAndTheRange)
{
  std::string e = errorOf("cable: {length: -1}", "/tow_sim/");
  EXPECT_NE(e.find("/tow_sim/cable.length = -1"), std::string::npos) << e;
  EXPECT_NE(e.find("(0, 100000] [m]"), std::string::npos) << e;
  e = errorOf("vehicle: {rudder: {lift_constnt: 3}}");
  EXPECT_NE(e.find("vehicle.rudder.lift_constnt: unknown key"), std::string::npos) << e;
  EXPECT_NE(e.find("lift_constant"), std::string::npos) << e;  // lists the known keys
  e = errorOf("cable: {segments: many}");
  EXPECT_NE(e.find("cable.segments: must be a number, got 'many'"), std::string::npos) << e;
  e = errorOf("cable: {segments: 2.5}");
  EXPECT_NE(e.find("cable.segments: must be a whole number"), std::string::npos) << e;
  e = errorOf("environment: {current: [1, 2]}");
  EXPECT_NE(e.find("environment.current: must be a list of 3 numbers"), std::string::npos) << e;
  e = errorOf("environment: {water_density: .nan}");
  EXPECT_NE(e.find("environment.water_density = nan"), std::string::npos) << e;
  e = errorOf("vehicle: {added_mass: {approach: B, matrix: [1, 2, 3]}}");
  EXPECT_NE(e.find("vehicle.added_mass.matrix: must hold 36 numbers"), std::string::npos) << e;
  e = errorOf(
      "vehicle: {added_mass: {approach: B, matrix: [1, 0, 0, 0, 0, 0,  -1, 0, 0, 0, 0,  1, 0, 0, 0,  1, 0, "
      "0,  1, 0,  1]}}");
  EXPECT_NE(e.find("vehicle.added_mass.matrix is not positive semi-definite"), std::string::npos) << e;
  e = errorOf("vehicle: {inertia: {xx: -1}}");
  EXPECT_NE(e.find("vehicle.inertia"), std::string::npos) << e;
  e = errorOf("vehicle: {cg_from_bail: 5}");
  EXPECT_NE(e.find("vehicle.cg_from_bail = 5"), std::string::npos) << e;
  e = errorOf("vehicle: {elevator: {drag_table: {angles: [0, 1], values: [0.1, 0.2]}}}");
  EXPECT_NE(e.find("vehicle.elevator.drag_table: angles must run from 0 to pi/2"), std::string::npos) << e;
  e = errorOf("numerics: {stepper: euler}");
  EXPECT_NE(e.find("numerics.stepper: 'euler' must be 'dopri5', 'rk4', 'implicit' or 'implicit_fixed'"),
            std::string::npos)
      << e;
  e = errorOf("cable: 3");
  EXPECT_NE(e.find("cable: must be a mapping"), std::string::npos) << e;
  EXPECT_THROW(loadConfigFile("/nonexistent/tow_sim.yaml"), std::invalid_argument);
  // Found by fuzzing: a mapping used as a key is refused like any other bad key.
  e = errorOf("cable: {{a: 1}: 2}");
  EXPECT_NE(e.find("cable: has a key that is not a plain name"), std::string::npos) << e;
}

}  // namespace
}  // namespace tow_sim

// No silent typo (issue 28): a configuration file's top-level key outside the sections, tow_sim_node's own
// parameters and tow_sim_urdf's sensor_frames is refused, naming it and the nearest known key; so is a
// misspelt key inside a section. The keys a file legitimately holds pass.
TEST(Config, AMisspeltTopLevelKeyIsRefusedWithTheNearestKnownOne)
{
  auto refusal = [](const std::string& name, const std::string& text)
  {
    try
    {
      tow_sim::loadConfigFile(test::writeTempFile(name, text));
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string e = refusal("typo_top.yaml", "cabel: {length: 500}\n");
  EXPECT_NE(e.find("typo_top.yaml: cabel: unknown key; did you mean 'cable'?"), std::string::npos) << e;
  e = refusal("typo_node.yaml", "vehicle_fram: fish\n");
  EXPECT_NE(e.find("vehicle_fram: unknown key; did you mean 'vehicle_frame'?"), std::string::npos) << e;
  e = refusal("typo_far.yaml", "zzzz: 1\n");
  EXPECT_NE(e.find("zzzz: unknown key (known keys:"), std::string::npos) << e;  // nothing near: no guess
  e = refusal("typo_inner.yaml", "winch: {max_rat: 1.0}\n");
  EXPECT_NE(e.find("winch.max_rat: unknown key; did you mean 'max_rate'?"), std::string::npos) << e;
  EXPECT_EQ(refusal("fine.yaml",
                    "cable: {length: 500}\nvehicle_frame: fish\nworld_frame: map\n"
                    "sensor_frames: []\ninitial_shape: line\n"),
            "");
  for (const char* file : { "/config/tow_sim.yaml", "/test/ros/urdf_config.yaml", "/test/ros/test_config.yaml" })
    EXPECT_NO_THROW(tow_sim::loadConfigFile(std::string(TOW_SIM_SOURCE_DIR) + file)) << file;
}

// The names a namespace may hold at its top level, from a table with nested keys (environment.waves.*).
TEST(Config, TopLevelKeysOfATableNameEachNestedSectionOnce)
{
  const std::vector<std::string> keys = tow_sim::topLevelKeys(tow_sim::environmentParams());
  EXPECT_EQ(std::count(keys.begin(), keys.end(), "waves"), 1) << "waves.* is one section";
  EXPECT_EQ(std::count(keys.begin(), keys.end(), "current"), 1);
  for (const std::string& key : keys)
    EXPECT_EQ(key.find('.'), std::string::npos) << key;
}
