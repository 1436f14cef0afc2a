// docs/own_ship.md as a reader runs it: scripts/run_walkthrough.py runs its marked command blocks, as
// written, in a scratch HOME on a master of their own (a stand-in ship's bag recorded for 40 s, tow_sim.launch
// ship:=false use_sim_time:=true, rosbag play --clock, then the tension and the vehicle's place echoed
// while it plays); any block that fails or hangs fails the test.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace
{
TEST(OwnShip, TheWalkthroughRunsAsWritten)
{
  const std::string command = std::string("/usr/bin/python3 ") + TOW_SIM_SOURCE_DIR + "/scripts/run_walkthrough.py " +
                              TOW_SIM_SOURCE_DIR + "/docs/own_ship.md " + TOW_SIM_WS + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string said;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe))
    if (std::string(buffer).find("[RUNNING]") == std::string::npos)  // rosbag play's progress line
      said += buffer;
  const int status = pclose(pipe);
  std::printf("%s", said.c_str());
  EXPECT_EQ(status, 0) << said;
  EXPECT_NE(said.find("4 blocks, passed"), std::string::npos);  // every block the page marks ran
  EXPECT_NE(said.find("z: -"), std::string::npos) << "the vehicle is under water";
}
}  // namespace
