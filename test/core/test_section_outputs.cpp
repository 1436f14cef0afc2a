// What a run with cable sections and point bodies reports (docs/physics.md §11): each segment's section, each
// body's joint, place and the cable's pull above and below it, in the snapshot and in the batch's CSV. In the
// steady tow the pull above a body is the pull below plus its weight in water and its drag, worked by hand
// from its parameters: ((m - rho V) g up, 1/2 rho C_D A U^2 forward).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/temp_file.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/shape_replay.h"
#include "tow_sim/scenario/ship_path.h"

namespace tow_sim
{
namespace
{
constexpr double kSpeed = 1.5;  // [m/s] along +x

// 400 m in 40 segments, a 500 kg clump, 150 m of tether in 30 segments, a float at the bail.
const char* const kTwoPart = R"(
cable:
  diameter: 0.017
  mass_per_length: 0.9
  sections:
    - {length: 400, segments: 40}
    - {length: 150, segments: 30, diameter: 0.012, mass_per_length: 0.15}
  bodies:
    - {at: 400, mass: 500, displaced_volume: 0.06, drag_area: 0.3, added_mass: 20}
    - {at: 550, mass: 2, displaced_volume: 0.02}
)";

// The steady tow of kTwoPart at kSpeed, started from its equilibrium.
TowSnapshot steadyTow(const SimulationConfig& c)
{
  TowRun run(c, straightShip(kSpeed, -2.0, 2.0), InitialShape());
  EXPECT_EQ(run.start(0.0), "");
  return run.snapshot();
}

TEST(SectionOutputs, EachSegmentsSectionAndEachBodysJoint)
{
  const TowSnapshot s = steadyTow(loadConfig(YAML::Load(kTwoPart)));
  ASSERT_EQ(s.segment_section.size(), 70u);
  for (int e = 0; e < 70; ++e)
    EXPECT_EQ(s.segment_section[static_cast<size_t>(e)], e < 40 ? 0 : 1) << e;
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].joint, 40);  // x_41, 400 m from the tow point
  EXPECT_EQ(s.bodies[1].joint, 70);  // the bail
  EXPECT_EQ(s.bodies[0].p_W, Eigen::Vector3d(s.joints.col(40)));
  EXPECT_EQ(s.bodies[0].depth, -s.joints(2, 40));
  EXPECT_EQ(s.bodies[0].tension_below, Eigen::Vector3d(s.tensions.col(40)));
  EXPECT_EQ(s.bodies[1].tension_below, Eigen::Vector3d(s.tensions.col(70)));
  // Without sections: every segment in section 0, no bodies.
  const TowSnapshot plain = steadyTow(SimulationConfig());
  EXPECT_EQ(plain.segment_section, std::vector<int>(100, 0));
  EXPECT_TRUE(plain.bodies.empty());
}

TEST(SectionOutputs, InTheSteadyTowThePullAboveABodyCarriesItsWeightInWaterAndDrag)
{
  const SimulationConfig c = loadConfig(YAML::Load(kTwoPart));
  const TowSnapshot s = steadyTow(c);
  const double rho = c.environment.water_density, g = c.environment.gravity;
  for (size_t i = 0; i < 2; ++i)
  {
    const JointBody& b = c.bodies[i].body;
    const Eigen::Vector3d by_hand(0.5 * rho * b.drag_area * kSpeed * kSpeed, 0.0,
                                  (b.mass - rho * b.displaced_volume) * g);
    const Eigen::Vector3d jump = s.bodies[i].tension_above - s.bodies[i].tension_below;
    std::printf("body %zu: pull above - below (%.4f, %.4f, %.4f) N, by hand (%.4f, %.4f, %.4f) N\n", i, jump.x(),
                jump.y(), jump.z(), by_hand.x(), by_hand.y(), by_hand.z());
    EXPECT_LT((jump - by_hand).norm(), 1e-6 * (1.0 + s.bodies[i].tension_above.norm())) << i;
  }
}

TEST(SectionOutputs, TheCsvHasASectionColumnAndFiveColumnsABody)
{
  const SimulationConfig c = loadConfig(YAML::Load(kTwoPart));
  const TowSnapshot s = steadyTow(c);
  const std::string header = timeseriesHeader(2), row = timeseriesRow(s);
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), std::count(row.begin(), row.end(), ','));
  EXPECT_NE(header.find(",body1_x,body1_y,body1_depth,body1_tension_above,body1_tension_below,body2_x"),
            std::string::npos);
  EXPECT_EQ(std::string(timeseriesHeader()), timeseriesHeader(0));
  std::ostringstream expected_end;
  expected_end.precision(10);
  expected_end << ',' << s.bodies[1].p_W.x() << ',' << s.bodies[1].p_W.y() << ',' << s.bodies[1].depth << ','
               << s.bodies[1].tension_above.norm() << ',' << s.bodies[1].tension_below.norm();
  EXPECT_EQ(row.substr(row.size() - expected_end.str().size()), expected_end.str());
  EXPECT_EQ(shapesHeader(true), "t,joint,x,y,z,tension,slack,section");
  std::istringstream rows(shapesRows(s, true));
  std::string line;
  int joint = 0;
  for (; std::getline(rows, line); ++joint)
  {
    const std::string section = line.substr(line.rfind(',') + 1);
    EXPECT_EQ(section, joint < 40 ? "0" : joint < 70 ? "1" : "-1") << line;  // -1 at the bail and the tail
  }
  EXPECT_EQ(joint, 72);
  // tow_sim_replay reads the file with its section column as without it.
  const std::vector<ShapeFrame> frames =
      readShapes(test::writeTempFile("shapes_with_sections.csv", shapesHeader(true) + "\n" + shapesRows(s, true)));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].joints.cols(), 72);
  EXPECT_NEAR((frames[0].joints - s.joints).cwiseAbs().maxCoeff(), 0.0, 1e-6);
}

}  // namespace
}  // namespace tow_sim
