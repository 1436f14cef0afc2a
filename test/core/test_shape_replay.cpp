// shapes.csv read back for tow_sim_replay: frames by time, the shape between them by hand, a change of
// joint count (the winch) held, and refusals naming the file and line.
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/temp_file.h"
#include "tow_sim/scenario/shape_replay.h"

namespace
{
std::string writeFile(const std::string& name, const std::string& text)
{
  return test::writeTempFile("tow_sim_test_" + name + ".csv", text);
}

TEST(ShapeReplay, InterpolatesBetweenFramesAndHoldsAcrossALayoutChange)
{
  const std::string path = writeFile("shapes_ok",
                                     "t,joint,x,y,z,tension,slack\n"
                                     "0,1,0,0,0,100,0\n0,2,-10,0,-1,90,0\n"
                                     "10,1,20,0,0,200,0\n10,2,10,0,-3,180,1\n"
                                     "20,1,40,0,0,300,0\n20,2,30,0,-5,270,0\n20,3,25,0,-6,260,0\n");
  const auto frames = tow_sim::readShapes(path);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[1].joints.cols(), 2);
  EXPECT_EQ(frames[2].joints.cols(), 3);
  EXPECT_TRUE(frames[1].slack[1]);
  const tow_sim::ShapeFrame mid = tow_sim::shapeAt(frames, 2.5);  // a quarter of the way
  EXPECT_DOUBLE_EQ(mid.joints(0, 1), -10.0 + 0.25 * 20.0);
  EXPECT_DOUBLE_EQ(mid.joints(2, 1), -1.0 + 0.25 * -2.0);
  EXPECT_DOUBLE_EQ(mid.tension[0], 125.0);
  const tow_sim::ShapeFrame held = tow_sim::shapeAt(frames, 15.0);  // 2 joints, then 3: the earlier frame
  EXPECT_EQ(held.joints.cols(), 2);
  EXPECT_EQ(held.joints(0, 0), 20.0);
  EXPECT_EQ(tow_sim::shapeAt(frames, -5.0).joints(0, 0), 0.0);
  EXPECT_EQ(tow_sim::shapeAt(frames, 99.0).joints.cols(), 3);
  std::remove(path.c_str());
}

TEST(ShapeReplay, RefusesFilesItCannotReplayNamingTheLine)
{
  const std::pair<const char*, const char*> cases[] = {
    { "t,joint,x,y,z,tension,slack\n0,1,0,0,0,1,0\n0,3,0,0,0,1,0\n", "line 3: joint 3 out of order (expected 2)" },
    { "t,joint,x,y,z,tension,slack\n5,1,0,0,0,1,0\n1,1,0,0,0,1,0\n", "line 3: t goes back in time" },
    { "t,joint,x,y,z,tension,slack\n", "no rows" },
    { "t,joint,x,y,z,tension,slack\n0,1,0,0,0,1\n", "line 2" },
  };
  int i = 0;
  for (const auto& [text, expected] : cases)
  {
    const std::string path = writeFile("shapes_bad" + std::to_string(i++), text);
    try
    {
      tow_sim::readShapes(path);
      ADD_FAILURE() << text << ": accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    std::remove(path.c_str());
  }
}

}  // namespace
