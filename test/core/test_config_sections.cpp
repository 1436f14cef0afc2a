// cable.sections and cable.bodies in the configuration (docs/physics.md §11): what each entry inherits from
// the cable level, where a body's joint is (counted by hand from the lengths), the written configuration
// read back unchanged, the towing chart paying out the first section, and every refusal naming its key.
#include <gtest/gtest.h>

#include <iterator>
#include <memory>
#include <string>
#include <utility>

#include "core/config_error.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/towing_chart.h"

namespace tow_sim
{
namespace
{
// 400 m of 17 mm armoured cable in 40 segments, a 500 kg clump, then 150 m of 12 mm tether in 30.
const char* const kTwoPart = R"(
cable:
  diameter: 0.017
  mass_per_length: 0.9
  normal_drag_coefficient: 1.5
  sections:
    - {length: 400, segments: 40}
    - {length: 150, segments: 30, diameter: 0.012, mass_per_length: 0.15}
  bodies:
    - {at: 400, mass: 500, displaced_volume: 0.06, drag_area: 0.3, added_mass: 20}
    - {at: 550, mass: 0, displaced_volume: 0.02}
)";

std::string errorOf(const std::string& yaml)
{
  return test::configError(yaml, "/tow_sim/");
}

// kTwoPart with `from` replaced by `to` (which must be there).
std::string edited(const std::string& from, const std::string& to)
{
  std::string yaml = kTwoPart;
  const size_t at = yaml.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? yaml : yaml.replace(at, from.size(), to);
}

TEST(ConfigSections, EachSectionTakesTheCableLevelsKeysItLeavesOut)
{
  const SimulationConfig c = loadConfig(YAML::Load(kTwoPart));
  ASSERT_EQ(c.sections.size(), 2u);
  EXPECT_EQ(c.cable.length, 550.0);  // the sums, since the cable level leaves them out
  EXPECT_EQ(c.cable.segments, 70);
  EXPECT_EQ(c.sections[0].diameter, 0.017);
  EXPECT_EQ(c.sections[0].normal_drag_coefficient, 1.5);
  EXPECT_EQ(c.sections[1].diameter, 0.012);
  EXPECT_EQ(c.sections[1].mass_per_length, 0.15);
  EXPECT_EQ(c.sections[1].normal_drag_coefficient, 1.5);                                  // inherited
  EXPECT_EQ(c.sections[1].added_mass_coefficient, CableParams().added_mass_coefficient);  // the default
  EXPECT_EQ(c.sections[1].segmentLength(), 5.0);
  const std::vector<CableParams> sections = cableSections(c);
  EXPECT_EQ(sections.size(), 2u);
  EXPECT_EQ(cableSections(SimulationConfig()).size(), 1u);  // no sections: the cable alone
}

TEST(ConfigSections, ABodysJointIsCountedFromTheBail)
{
  const SimulationConfig c = loadConfig(YAML::Load(kTwoPart));
  const std::vector<JointBody> bodies = jointBodies(c);
  ASSERT_EQ(bodies.size(), 2u);
  EXPECT_EQ(bodies[0].joint, 30);  // 400 m: the 30 tether segments aft of it
  EXPECT_EQ(bodies[0].mass, 500.0);
  EXPECT_EQ(bodies[0].displaced_volume, 0.06);
  EXPECT_EQ(bodies[0].drag_area, 0.3);
  EXPECT_EQ(bodies[0].added_mass, 20.0);
  EXPECT_EQ(bodies[1].joint, 0);  // 550 m: the bail
  EXPECT_EQ(jointBodies(loadConfig(YAML::Load(edited("at: 400", "at: 405")))).front().joint, 29);
  EXPECT_EQ(jointBodies(loadConfig(YAML::Load(edited("at: 400", "at: 390")))).front().joint, 31);
  // The model TowRun builds has the sections and bodies.
  auto ship = std::make_shared<ShipHistory>(1.0, 8);
  TowRun run(c, ship, InitialShape());
  EXPECT_EQ(run.model().sectionCount(), 2);
  EXPECT_EQ(run.model().segments(), 70);
  ASSERT_EQ(run.model().bodies().size(), 2u);
  EXPECT_EQ(run.model().bodies()[0].joint, 30);
}

TEST(ConfigSections, TheWrittenConfigurationReadsBackUnchanged)
{
  const SimulationConfig c = loadConfig(YAML::Load(kTwoPart));
  const SimulationConfig back = loadConfig(toYaml(c));
  ASSERT_EQ(back.sections.size(), c.sections.size());
  for (size_t i = 0; i < c.sections.size(); ++i)
  {
    EXPECT_EQ(back.sections[i].length, c.sections[i].length);
    EXPECT_EQ(back.sections[i].segments, c.sections[i].segments);
    EXPECT_EQ(back.sections[i].diameter, c.sections[i].diameter);
    EXPECT_EQ(back.sections[i].mass_per_length, c.sections[i].mass_per_length);
    EXPECT_EQ(back.sections[i].normal_drag_coefficient, c.sections[i].normal_drag_coefficient);
  }
  ASSERT_EQ(back.bodies.size(), c.bodies.size());
  for (size_t i = 0; i < c.bodies.size(); ++i)
  {
    EXPECT_EQ(back.bodies[i].at, c.bodies[i].at);
    EXPECT_EQ(back.bodies[i].body.mass, c.bodies[i].body.mass);
    EXPECT_EQ(back.bodies[i].body.displaced_volume, c.bodies[i].body.displaced_volume);
    EXPECT_EQ(back.bodies[i].body.drag_area, c.bodies[i].body.drag_area);
    EXPECT_EQ(back.bodies[i].body.added_mass, c.bodies[i].body.added_mass);
  }
  EXPECT_EQ(back.cable.length, 550.0);
  EXPECT_EQ(back.cable.segments, 70);
  // Without sections: empty lists, one cable.
  const YAML::Node plain = toYaml(SimulationConfig());
  EXPECT_EQ(plain["cable"]["sections"].size(), 0u);
  EXPECT_EQ(plain["cable"]["bodies"].size(), 0u);
  EXPECT_TRUE(loadConfig(plain).sections.empty());
}

TEST(ConfigSections, TheChartPaysOutTheFirstSectionAndTheBodiesAftOfItMoveWithTheCable)
{
  SimulationConfig c = loadConfig(YAML::Load(kTwoPart));
  payOutTo(c, 650.0);
  EXPECT_EQ(c.sections[0].length, 500.0);
  EXPECT_EQ(c.sections[0].segments, 50);
  EXPECT_EQ(c.sections[1].length, 150.0);
  EXPECT_EQ(c.cable.length, 650.0);
  EXPECT_EQ(c.cable.segments, 80);
  EXPECT_EQ(c.bodies[0].at, 500.0);
  EXPECT_EQ(c.bodies[1].at, 650.0);
  EXPECT_EQ(jointBodies(c).front().joint, 30);  // still at the top of the tether
  EXPECT_THROW(payOutTo(c, 150.0), std::invalid_argument);
  // A body inside the first section: the configured cable out is charted as it is, another is refused.
  SimulationConfig inside = loadConfig(YAML::Load(edited("at: 400", "at: 390")));
  EXPECT_NO_THROW(payOutTo(inside, 550.0));
  EXPECT_EQ(inside.bodies[0].at, 390.0);
  try
  {
    payOutTo(inside, 600.0);
    ADD_FAILURE() << "accepted a body inside the first section";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("cable.bodies[0].at = 390 m is inside the first section"), std::string::npos)
        << e.what();
  }
  SimulationConfig uniform;
  payOutTo(uniform, 250.0);
  EXPECT_EQ(uniform.cable.length, 250.0);
  EXPECT_EQ(uniform.cable.segments, 50);  // 5 m segments
  // The chart's point at the configured cable out is the configuration's own steady tow.
  const SimulationConfig two = loadConfig(YAML::Load(kTwoPart));
  const ChartPoint p = chartPoint(two, 1.5, 550.0, Eigen::Vector3d::Zero());
  ASSERT_TRUE(p.converged) << p.error;
  EXPECT_GT(p.depth, 0.0);
}

TEST(ConfigSections, EachBadEntryIsRefusedByItsKey)
{
  const std::pair<std::string, std::string> cases[] = {
    { edited("  diameter: 0.017", "  length: 600\n  diameter: 0.017"),
      "/tow_sim/cable.length = 600 [m] must be the sections' lengths added up, 550" },
    { edited("  diameter: 0.017", "  segments: 100\n  diameter: 0.017"),
      "/tow_sim/cable.segments = 100 must be the sections' segments added up, 70" },
    { edited("{length: 400, segments: 40}", "{length: 400}"), "/tow_sim/cable.sections[0].segments: is required" },
    { edited("{length: 400, segments: 40}", "{segments: 40}"), "/tow_sim/cable.sections[0].length: is required" },
    { edited("{length: 400, segments: 40}", "{length: 400, segments: 40, breaking_load: 9}"),
      "/tow_sim/cable.sections[0].breaking_load: is the whole cable's: set it at /tow_sim/cable.breaking_load" },
    { edited("{length: 400, segments: 40}", "{length: 400, segments: 40, bodies: []}"),
      "/tow_sim/cable.sections[0].bodies: sections do not nest" },
    { edited("{length: 400, segments: 40}", "{length: 400, segments: 40, diamter: 0.02}"),
      "/tow_sim/cable.sections[0].diamter: unknown key; did you mean 'diameter'?" },
    { edited("{length: 400, segments: 40}", "{length: 400, segments: 40, diameter: 2}"),
      "/tow_sim/cable.sections[0].diameter = 2 is out of range" },
    { edited("{length: 400, segments: 40}", "{length: 400, segments: 40, axial_stiffness: 1e7}"),
      "/tow_sim/cable.sections[1].axial_stiffness: the sections are all elastic or all rigid" },
    { edited("at: 400", "at: 401"),
      "/tow_sim/cable.bodies[0].at = 401 [m] is not on a joint: the nearest joints are at 400 and 405 m" },
    { edited("at: 400", "at: 551"), "/tow_sim/cable.bodies[0].at = 551 must be in (0, 550]" },
    { edited("at: 400,", "mass: 1,"), "/tow_sim/cable.bodies[0].at: is required" },
    { edited("drag_area: 0.3", "drag_area: -1"), "/tow_sim/cable.bodies[0].drag_area = -1 is out of range" },
    { edited("drag_area: 0.3", "drag_aera: 1"), "/tow_sim/cable.bodies[0].drag_aera: unknown key; did you mean" },
    { edited("at: 400", "at: 390") + "winch: {enabled: true, min_length: 300, max_length: 900}\n",
      "/tow_sim/cable.bodies[0].at = 390 [m] is inside the first section, which the winch pays out" },
  };
  for (size_t i = 0; i < std::size(cases); ++i)
  {
    const std::string error = errorOf(cases[i].first);
    EXPECT_NE(error.find(cases[i].second), std::string::npos) << "case " << i << ": " << error;
  }
  // A body the cable cannot carry hanging at rest: below the clump hang, in water, the clump (500 - 61.5) g =
  // 4301.7 N, the tether 150 (0.15 - 0.1159) g = 50.1 N, the float (2 - 20.5) g = -181.5 N and the example
  // vehicle (180 - 123) g = 559.2 N: 4729.5 N in all.
  const std::string heavy = errorOf(edited("  diameter: 0.017", "  breaking_load: 4700\n  diameter: 0.017"));
  EXPECT_NE(heavy.find("/tow_sim/cable.bodies[0].mass = 500 [kg]: the cable cannot carry it"), std::string::npos)
      << heavy;
  EXPECT_NE(heavy.find("more than /tow_sim/cable.breaking_load = 4700 N"), std::string::npos) << heavy;
  EXPECT_EQ(errorOf(edited("  diameter: 0.017", "  breaking_load: 4760\n  diameter: 0.017")), "(accepted)");
  // A float is never the body the cable cannot carry, however heavy the rest (a cable and vehicle too heavy on
  // their own are accepted without bodies, so with a float too).
  EXPECT_EQ(errorOf("cable: {length: 100, segments: 10, breaking_load: 10, bodies: [{at: 50, displaced_volume: 0.1}]}"),
            "(accepted)");
  // With the winch, a body at the first section's end is fine; so is a body at the bail of one cable.
  EXPECT_EQ(errorOf(kTwoPart + std::string("winch: {enabled: true, min_length: 300, max_length: 900}\n")),
            "(accepted)");
  EXPECT_EQ(errorOf("cable: {length: 100, segments: 10, bodies: [{at: 100, mass: 5}]}\n"
                    "winch: {enabled: true, min_length: 50, max_length: 200}\n"),
            "(accepted)");
}

}  // namespace
}  // namespace tow_sim
