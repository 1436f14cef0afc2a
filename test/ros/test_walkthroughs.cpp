// The documents' commands as a reader runs them: scripts/run_walkthrough.py runs their marked command blocks,
// as written, in a scratch HOME on a master of their own; any block that fails or hangs fails the test.
// docs/own_ship.md: a stand-in ship's bag recorded for 40 s, tow_sim.launch ship:=false use_sim_time:=true,
// rosbag play --clock, then the tension and the vehicle's place echoed while it plays. The README's first
// hour: the depth autopilot given a setpoint, the towing chart, the cable-out planner, a batch run plotted
// and replayed (in the repository, as the README is read; outputs in out/, which git ignores).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace
{
// The runner's output (rosbag play's progress lines left out) and its exit status.
std::string runWalkthrough(const std::string& arguments, int* status)
{
  const std::string command =
      std::string("/usr/bin/python3 ") + TOW_SIM_SOURCE_DIR + "/scripts/run_walkthrough.py " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string said;
  if (!pipe)
  {
    *status = -1;
    return said;
  }
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe))
    if (std::string(buffer).find("[RUNNING]") == std::string::npos)
      said += buffer;
  *status = pclose(pipe);
  std::printf("%s", said.c_str());
  return said;
}

TEST(FirstHour, TheReadmesPathsRunAsWritten)
{
  int status = 0;
  const std::string said = runWalkthrough(
      std::string(TOW_SIM_SOURCE_DIR) + "/README.md " + TOW_SIM_WS + " --cwd " + TOW_SIM_SOURCE_DIR, &status);
  EXPECT_EQ(status, 0) << said;
  EXPECT_NE(said.find("7 blocks, passed"), std::string::npos);                // every block the README marks ran
  EXPECT_NE(said.find("depth 187.8 m, layback 461.0 m"), std::string::npos);  // the Python block's steady tow
  EXPECT_NE(said.find("190 points (0 without an equilibrium)"), std::string::npos);
  EXPECT_NE(said.find("with 500 m out the vehicle stays between 100 and 200 m"), std::string::npos);
}

TEST(OwnShip, TheWalkthroughRunsAsWritten)
{
  int status = 0;
  const std::string said = runWalkthrough(std::string(TOW_SIM_SOURCE_DIR) + "/docs/own_ship.md " + TOW_SIM_WS, &status);
  EXPECT_EQ(status, 0) << said;
  EXPECT_NE(said.find("4 blocks, passed"), std::string::npos);  // every block the page marks ran
  EXPECT_NE(said.find("z: -"), std::string::npos) << "the vehicle is under water";
}
}  // namespace
