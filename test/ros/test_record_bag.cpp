// The demo with record:=true writes a bag with the node's outputs: 20 s of wall time recorded, its topics
// counted by `rosbag info`.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>

namespace
{
// "topics:" lines of `rosbag info`: name -> message count.
std::map<std::string, int> topicCounts(const std::string& info)
{
  std::map<std::string, int> counts;
  std::istringstream in(info);
  std::string line;
  bool topics = false;
  while (std::getline(in, line))
  {
    if (line.rfind("topics:", 0) == 0)
    {
      topics = true;
      line = line.substr(7);
    }
    if (!topics)
      continue;
    std::istringstream fields(line);
    std::string name, msgs;
    int count = 0;
    if (fields >> name >> count >> msgs && msgs == "msgs")
      counts[name] = count;
  }
  return counts;
}

TEST(RecordBag, TheDemoRecordsItsOutputs)
{
  const std::string command = std::string("WS=") + TOW_SIM_WS + " " + TOW_SIM_SOURCE_DIR +
                              "/scripts/record_demo.sh /tmp/tow_sim_test_record 20 straight";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string info;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe))
    info += buffer;
  ASSERT_EQ(pclose(pipe), 0) << info;
  const std::map<std::string, int> n = topicCounts(info);
  for (const auto& kv : n)
    std::printf("%s: %d messages\n", kv.first.c_str(), kv.second);
  // publish_rate 10 Hz for ~20 s less the start; the forces with every state; the ship at 20 Hz.
  ASSERT_TRUE(n.count("cable/state")) << info;
  EXPECT_GT(n.at("cable/state"), 120);
  EXPECT_LT(n.at("cable/state"), 260);
  for (const char* topic : { "vehicle/odom", "vehicle/fin_loads", "ship/tow_force", "vehicle/tow_force" })
  {
    ASSERT_TRUE(n.count(topic)) << topic;
    EXPECT_NEAR(n.at(topic), n.at("cable/state"), 3) << topic;
  }
  ASSERT_TRUE(n.count("ship/odom"));
  EXPECT_GT(n.at("ship/odom"), n.at("cable/state"));
  EXPECT_TRUE(n.count("/tf") && n.count("/diagnostics"));
}

}  // namespace
