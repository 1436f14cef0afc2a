// A scenario written out with every default filled in (toYaml: tow_sim_batch's scenario.yaml, the Python
// module's Scenario.to_yaml) reads back as the same scenario: every manoeuvre and command with its values,
// and the run it gives is the same run. (They once came back as default manoeuvres without their fields.)
#include <gtest/gtest.h>

#include <dirent.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
namespace
{
std::vector<std::string> shippedScenarios()
{
  std::vector<std::string> paths;
  const std::string dir = std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/";
  if (DIR* d = opendir(dir.c_str()))
  {
    while (const dirent* e = readdir(d))
    {
      const std::string name = e->d_name;
      if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml" && name.rfind("bathymetry_", 0) != 0)
        paths.push_back(dir + name);
    }
    closedir(d);
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

std::string text(const YAML::Node& node)
{
  std::ostringstream os;
  os << node;
  return os.str();
}

void expectSameManoeuvres(const Scenario& a, const Scenario& b, const std::string& name)
{
  ASSERT_EQ(a.manoeuvres.size(), b.manoeuvres.size()) << name;
  for (size_t i = 0; i < a.manoeuvres.size(); ++i)
  {
    const Manoeuvre &x = a.manoeuvres[i], &y = b.manoeuvres[i];
    EXPECT_EQ(x.type, y.type) << name << " manoeuvre " << i;
    EXPECT_EQ(x.direction, y.direction) << name << " manoeuvre " << i;
    EXPECT_EQ(x.legs, y.legs) << name << " manoeuvre " << i;
    EXPECT_EQ(x.points, y.points) << name << " manoeuvre " << i;
    for (auto field : { &Manoeuvre::speed, &Manoeuvre::duration, &Manoeuvre::to_speed, &Manoeuvre::radius,
                        &Manoeuvre::angle, &Manoeuvre::acceptance })
      EXPECT_EQ(x.*field, y.*field) << name << " manoeuvre " << i;
  }
}

void expectSameCommands(const Scenario& a, const Scenario& b, const std::string& name)
{
  ASSERT_EQ(a.commands.size(), b.commands.size()) << name;
  for (size_t i = 0; i < a.commands.size(); ++i)
    for (auto field : { &CommandEvent::t, &CommandEvent::rudder, &CommandEvent::elevator, &CommandEvent::thrust,
                        &CommandEvent::payout_rate })
      EXPECT_EQ(a.commands[i].*field, b.commands[i].*field) << name << " command " << i;
}
}  // namespace

TEST(ScenarioYaml, EveryShippedScenarioReadsBackAsItself)
{
  const std::vector<std::string> paths = shippedScenarios();
  ASSERT_GE(paths.size(), 13u);
  size_t manoeuvres = 0, commands = 0;
  for (const std::string& path : paths)
  {
    const Scenario sc = loadScenarioFile(path);
    const Scenario back = loadScenario(toYaml(sc));
    expectSameManoeuvres(sc, back, path);
    expectSameCommands(sc, back, path);
    EXPECT_EQ(sc.autopilot.setpoints.size(), back.autopilot.setpoints.size()) << path;
    EXPECT_EQ(text(toYaml(sc)), text(toYaml(back))) << path;
    manoeuvres += sc.manoeuvres.size();
    commands += sc.commands.size();
  }
  EXPECT_GT(manoeuvres, paths.size());  // the check saw lists of manoeuvres and commands, not just defaults
  EXPECT_GT(commands, 1u);
}

TEST(ScenarioYaml, TheWrittenScenarioRunsTheSameRun)
{
  for (const char* name : { "report_elevator_step", "zigzag" })  // commands; a manoeuvre list
  {
    Scenario sc = loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/" + name + ".yaml");
    sc.duration = 90.0;
    const Scenario back = loadScenario(toYaml(sc));
    std::ostringstream series_a, shapes_a, series_b, shapes_b;
    BatchResult result;
    runScenario(sc, series_a, shapes_a, result);
    runScenario(back, series_b, shapes_b, result);
    EXPECT_EQ(series_a.str(), series_b.str()) << name;
    EXPECT_EQ(shapes_a.str(), shapes_b.str()) << name;
  }
}

}  // namespace tow_sim
