// The parameter tables drive the documentation: docs/parameters.md's key tables and config/tow_sim.yaml are
// what the tables say now (else: make docs), and every documented key reads back into the struct it describes.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tow_sim/config/config.h"
#include "tow_sim/core/param_tables.h"
#include "tow_sim/scenario/param_docs.h"

namespace tow_sim
{
namespace
{
std::string readFile(const std::string& path)
{
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Docs, ParameterTablesAndTheConfigFileAreCurrent)
{
  const std::string docs = readFile(std::string(TOW_SIM_SOURCE_DIR) + "/docs/parameters.md");
  ASSERT_FALSE(docs.empty());
  for (const std::string& name : documentedTables())
    EXPECT_NE(docs.find("<!-- params:" + name + " -->"), std::string::npos) << name << " is not in docs/parameters.md";
  EXPECT_TRUE(docs == withCurrentTables(docs))
      << "docs/parameters.md's parameter tables are out of date: run make docs";
  EXPECT_TRUE(readFile(std::string(TOW_SIM_SOURCE_DIR) + "/config/tow_sim.yaml") == configFile())
      << "config/tow_sim.yaml is out of date: run make docs";
}

TEST(Docs, EveryTableKeyOfTheConfigurationIsReadBack)
{
  // Each number key of the cable table, given a value inside its range, reaches the struct through the
  // YAML loader (the table drives reading as well as the documentation).
  for (const ParamSpec<CableParams>& p : cableParams().specs())
  {
    if (p.kind != ParamKind::kNumber && p.kind != ParamKind::kInteger)
      continue;
    const double value = p.kind == ParamKind::kInteger ? 7.0 : 0.5 * (p.lo + p.hi);
    YAML::Node root;
    root["cable"][p.key] = value;
    if (p.key == "axial_damping")  // only with axial_stiffness
      root["cable"]["axial_stiffness"] = 1.0e8;
    const SimulationConfig c = loadConfig(root);
    ASSERT_TRUE(p.get_number(c.cable).has_value()) << p.key;
    EXPECT_EQ(*p.get_number(c.cable), value) << p.key;
  }
  // And a key no table knows is refused, naming the known ones.
  YAML::Node root;
  root["vehicle"]["rudder"]["lift_constnt"] = 1.0;
  try
  {
    loadConfig(root);
    ADD_FAILURE() << "an unknown key was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("vehicle.rudder.lift_constnt: unknown key"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tow_sim
