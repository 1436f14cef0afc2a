// rostest of tow_sim_replay (replay.test): the shipped turn_180 run's shapes.csv replayed at 100 times real
// time. Every published cable marker equals the shape the test interpolates itself from the file at the
// marker's stamp, the stamps follow the replay's own /clock, and tf has the vehicle frame for rviz's view.
#include <gtest/gtest.h>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Joints = std::vector<std::array<double, 3>>;

// shapes.csv: time -> joints in order (the file's rows are grouped by time, joints ascending).
std::map<double, Joints> readShapesHere(const std::string& path)
{
  std::map<double, Joints> shapes;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line))
  {
    std::istringstream cells(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(cells, cell, ','))
      v.push_back(std::stod(cell));
    shapes[v[0]].push_back({ v[2], v[3], v[4] });
  }
  return shapes;
}

TEST(Replay, MarkersFollowTheRecordedShapesOnTheRunsClock)
{
  ros::NodeHandle nh;
  const std::map<double, Joints> shapes =
      readShapesHere(std::string(TOW_SIM_SOURCE_DIR) + "/test/golden/turn_180/shapes.csv");
  ASSERT_GE(shapes.size(), 5u);
  std::mutex mutex;
  std::vector<visualization_msgs::Marker> cables;
  double clock = 0.0;
  ros::Subscriber markers =
      nh.subscribe<visualization_msgs::MarkerArray>("/cable/markers", 50,
                                                    [&](const visualization_msgs::MarkerArray::ConstPtr& m)
                                                    {
                                                      std::lock_guard<std::mutex> lock(mutex);
                                                      for (const auto& marker : m->markers)
                                                        if (marker.ns == "cable")
                                                          cables.push_back(marker);
                                                    });
  ros::Subscriber clocks = nh.subscribe<rosgraph_msgs::Clock>("/clock", 50,
                                                              [&](const rosgraph_msgs::Clock::ConstPtr& c)
                                                              {
                                                                std::lock_guard<std::mutex> lock(mutex);
                                                                clock = c->clock.toSec();
                                                              });
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const ros::WallTime start = ros::WallTime::now();
  while (ros::WallTime::now() - start < ros::WallDuration(20.0))
  {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (clock > 250.0)
        break;
    }
    ros::WallDuration(0.02).sleep();
  }
  EXPECT_TRUE(buffer.canTransform("odom", "tow_vehicle", ros::Time(0), ros::Duration(2.0)));
  std::lock_guard<std::mutex> lock(mutex);
  const double wall = (ros::WallTime::now() - start).toSec();
  ASSERT_GT(clock, 250.0) << "the replay's clock after " << wall << " s of wall time";
  ASSERT_GE(cables.size(), 20u);
  double worst = 0.0, previous = -1.0;
  for (const auto& cable : cables)
  {
    const double t = cable.header.stamp.toSec();
    EXPECT_GT(t, previous);
    previous = t;
    auto after = shapes.upper_bound(t);
    if (after == shapes.end())
      continue;
    auto before = after == shapes.begin() ? after : std::prev(after);
    const double w = after == before ? 0.0 : (t - before->first) / (after->first - before->first);
    ASSERT_EQ(cable.points.size(), before->second.size());
    for (size_t j = 0; j < cable.points.size(); ++j)
    {
      const auto& a = before->second[j];
      const auto& b = after->second[j];
      const double ex = (1 - w) * a[0] + w * b[0], ey = (1 - w) * a[1] + w * b[1], ez = (1 - w) * a[2] + w * b[2];
      worst = std::max(worst, std::hypot(cable.points[j].x - ex, cable.points[j].y - ey, cable.points[j].z - ez));
    }
  }
  std::printf("%zu cable markers from %.1f s to %.1f s of the run in %.1f s of wall time; worst joint %.2e m\n",
              cables.size(), cables.front().header.stamp.toSec(), previous, wall, worst);
  EXPECT_LT(worst, 1e-6);
}

}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_replay");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
