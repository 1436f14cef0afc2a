// Saved states know their configuration (docs/nodes.md, "Saved states"): a state carries the keys and values of the
// configuration it was saved under and their hash; restored under another configuration it is refused naming
// the keys that differ with both values, unless asked for (initial_state.any_configuration); an edited
// configuration line no longer matches the hash; a state of format 1 (no configuration) is read as before.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "temp_file.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/io/saved_state.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
namespace
{
Scenario shortTurn()
{
  Scenario sc = loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/turn_180.yaml");
  sc.duration = 10.0;
  sc.save_state_at = { 10.0 };
  return sc;
}

RunState savedAt10(const Scenario& sc)
{
  std::ostringstream series, shapes;
  BatchResult result;
  std::map<double, RunState> states;
  runScenario(sc, series, shapes, result, {}, [&states](double t, const RunState& s) { states[t] = s; });
  return states.at(10.0);
}

// The error of running `sc` from the state file at `path`, or "(ran)".
std::string restoreError(Scenario sc, const std::string& path, bool any_configuration)
{
  sc.initial.type = InitialShape::Type::kFile;
  sc.initial.path = path;
  sc.initial.any_configuration = any_configuration;
  sc.save_state_at.clear();
  std::ostringstream series, shapes;
  BatchResult result;
  try
  {
    runScenario(sc, series, shapes, result);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "(ran)";
}

TEST(SavedConfiguration, AStateCarriesTheKeysAndTheirHash)
{
  const Scenario sc = shortTurn();
  const RunState saved = savedAt10(sc);
  EXPECT_EQ(saved.configuration, configurationKeys(sc.config));
  EXPECT_EQ(saved.configuration.at("cable.length"), "300");
  EXPECT_EQ(saved.configuration.at("cable.sections"), "[]");
  EXPECT_EQ(saved.configuration.at("numerics.stepper"), "implicit");
  const std::string text = runStateText(saved);
  EXPECT_NE(text.find("tow_sim_state 2\n"), std::string::npos);
  EXPECT_NE(text.find("config_hash " + configurationHash(saved.configuration) + "\n"), std::string::npos);
  EXPECT_NE(text.find("config.cable.length 300\n"), std::string::npos);
  EXPECT_EQ(parseRunState(text, "saved.txt").configuration, saved.configuration);
  // The hash: FNV-1a 64 of "a=1\n" worked by hand from its offset basis and prime.
  std::uint64_t h = 14695981039346656037ULL;
  for (unsigned char c : std::string("a=1\n"))
    h = (h ^ c) * 1099511628211ULL;
  char expected[17];
  std::snprintf(expected, sizeof expected, "%016llx", static_cast<unsigned long long>(h));
  EXPECT_EQ(configurationHash({ { "a", "1" } }), expected);
}

TEST(SavedConfiguration, AnEditedLineOrAMissingHashIsRefusedAndFormatOneIsRead)
{
  const std::string text = runStateText(savedAt10(shortTurn()));
  auto refusal = [](const std::string& t)
  {
    try
    {
      parseRunState(t, "edited.txt");
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  std::string edited = text;
  edited.replace(edited.find("config.cable.length 300"), 23, "config.cable.length 600");
  EXPECT_NE(refusal(edited).find("does not match the config. lines"), std::string::npos) << refusal(edited);
  std::string no_hash = text;
  no_hash.erase(no_hash.find("config_hash"), 29);  // "config_hash " + 16 digits + "\n"
  EXPECT_NE(refusal(no_hash).find("config_hash is missing"), std::string::npos) << refusal(no_hash);
  // Format 1: the same state without its configuration lines.
  std::istringstream in(text);
  std::string format1, line;
  while (std::getline(in, line))
    if (line.rfind("config", 0) != 0)
      format1 += (line == "tow_sim_state 2" ? "tow_sim_state 1" : line) + "\n";
  EXPECT_TRUE(parseRunState(format1, "old.txt").configuration.empty());
  EXPECT_NE(refusal(format1 + "config.cable.length 300\n").find("format 1 has no configuration lines"),
            std::string::npos);
}

TEST(SavedConfiguration, RestoredUnderAnotherConfigurationItIsRefusedNamingTheKeys)
{
  const Scenario sc = shortTurn();
  const std::string path = test::writeTempFile("saved_configuration.txt", runStateText(savedAt10(sc)));
  EXPECT_EQ(restoreError(sc, path, false), "(ran)");
  Scenario other = sc;
  other.config.environment.current_W.y() = 0.25;
  other.config.numerics.max_step = 0.25;
  const std::string error = restoreError(other, path, false);
  EXPECT_NE(error.find("saved under another configuration: 2 keys differ: environment.current[1] (saved 0, now "
                       "0.25), numerics.max_step (saved 5, now 0.25); initial_state.any_configuration: true "
                       "loads it"),
            std::string::npos)
      << error;
  EXPECT_EQ(restoreError(other, path, true), "(ran)");  // asked for: it runs on the other configuration
  // A state without a configuration (format 1, or written by hand) is not checked.
  EXPECT_NO_THROW(requireSameConfiguration({}, other.config, "-"));
  // A key added after the state was saved: at its default (the model the state ran), no difference; set, one.
  std::map<std::string, std::string> older = configurationKeys(sc.config);
  ASSERT_EQ(older.erase("vehicle.roll"), 1u);
  EXPECT_NO_THROW(requireSameConfiguration(older, sc.config, "-"));
  Scenario rolling = sc;
  rolling.config.vehicle.roll = VehicleRoll::kFree;
  try
  {
    requireSameConfiguration(older, rolling.config, "-");
    ADD_FAILURE() << "a key set away from its default since the state was saved was not refused";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("1 key differs: vehicle.roll (saved (none), now free)"), std::string::npos)
        << e.what();
  }
}

// The bathymetry is compared by its content: the same grid from another folder is the same seabed, an edited
// depth another one.
TEST(SavedConfiguration, TheSeabedGridIsKeyedByItsContentNotItsPath)
{
  const Scenario sc = loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/seabed_shoal.yaml");
  ASSERT_EQ(sc.config.seabed.type, SeabedParams::Type::kGrid);
  const std::map<std::string, std::string> keys = configurationKeys(sc.config);
  EXPECT_EQ(keys.count("seabed.grid_file"), 0u);
  ASSERT_EQ(keys.count("seabed.grid"), 1u);
  SimulationConfig moved = sc.config;
  moved.seabed.grid_file = "/elsewhere/bathymetry_shoal.yaml";
  EXPECT_EQ(configurationKeys(moved), keys);
  SimulationConfig edited = sc.config;
  edited.seabed.grid.depth(0, 0) += 1.0;
  EXPECT_NE(configurationKeys(edited).at("seabed.grid"), keys.at("seabed.grid"));
  // Origins and spacings written at full precision: a grid that differs from another only in its last
  // spacing's last digits is another seabed (the four numbers once went through a 40-character buffer,
  // which cut the spacing off behind such origins).
  SimulationConfig far = sc.config, far_respaced = sc.config;
  far.seabed.grid.origin = Eigen::Vector2d(-123456.78901234567, 9876543.2109876543);
  far_respaced.seabed.grid.origin = far.seabed.grid.origin;
  far_respaced.seabed.grid.spacing.y() = far.seabed.grid.spacing.y() * (1.0 + 1e-12);
  EXPECT_NE(configurationKeys(far_respaced).at("seabed.grid"), configurationKeys(far).at("seabed.grid"));
}

}  // namespace
}  // namespace tow_sim
