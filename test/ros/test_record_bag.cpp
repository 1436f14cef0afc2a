// The demo with record:=true writes a bag with the node's outputs: 20 s of wall time recorded, its topics
// counted by `rosbag info`; tow_sim_plot turns the bag into the batch runner's CSV files and plots.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

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

  // tow_sim_plot BAG --out DIR: one timeseries row per cable/state message, increasing times, tensions
  // positive; the four plots of a run.
  const std::string out = "/tmp/tow_sim_test_record/plots";
  const std::string plot = "rm -rf " + out + " && /usr/bin/python3 " + TOW_SIM_SOURCE_DIR +
                           "/scripts/tow_sim_plot /tmp/tow_sim_test_record/tow_sim_*.bag --out " + out + " 2>&1";
  FILE* plotter = popen(plot.c_str(), "r");
  ASSERT_NE(plotter, nullptr);
  std::string said;
  while (fgets(buffer, sizeof(buffer), plotter))
    said += buffer;
  ASSERT_EQ(pclose(plotter), 0) << said;
  std::printf("%s", said.c_str());
  std::ifstream csv(out + "/timeseries.csv");
  std::string header, line;
  ASSERT_TRUE(std::getline(csv, header));
  ASSERT_EQ(header.rfind("t,", 0), 0u) << header;
  int column = 0, rows = 0;
  for (size_t at = 0; header.substr(at, 13) != "tension_ship,"; at = header.find(',', at) + 1, ++column)
    ASSERT_NE(header.find(',', at), std::string::npos) << "no tension_ship column: " << header;
  double previous_t = -1.0;
  while (std::getline(csv, line))
  {
    std::istringstream cells(line);
    std::string cell;
    std::vector<std::string> row;
    while (std::getline(cells, cell, ','))
      row.push_back(cell);
    ASSERT_GT(row.size(), static_cast<size_t>(column));
    EXPECT_GT(std::stod(row[0]), previous_t);
    EXPECT_GT(std::stod(row[column]), 0.0);
    previous_t = std::stod(row[0]);
    ++rows;
  }
  // A row per cable/state message, less those repeating a held state's stamp (the plot says how many).
  const size_t skipped_at = said.find("messages (");
  ASSERT_NE(skipped_at, std::string::npos) << said;
  const int repeats = std::atoi(said.c_str() + skipped_at + 10);
  EXPECT_EQ(rows, n.at("cable/state") - repeats);
  EXPECT_LT(repeats, n.at("cable/state") / 10);
  for (const char* png : { "depth_diversion.png", "tensions.png", "plan_view.png", "side_view.png" })
    EXPECT_TRUE(std::ifstream(out + "/" + png).good()) << png;
}

}  // namespace
