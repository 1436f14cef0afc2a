// tow_sim_nav --bag (tow_sim/ros/survey_bag.h, docs/survey.md), without roscore: a run's measurements written as
// the survey/ messages tow_sim_node publishes, into a bag under a namespace, come back as the same rows; and
// tow_sim_nav gives the same estimate from the bag as from the CSV. (The USBL's ship-frame conversion is
// checked by hand in test_survey_rows; this survey has none.)
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <rosbag/bag.h>
#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>

#include <unistd.h>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "tow_sim/core/io/measurement_csv.h"
#include "tow_sim/core/survey/survey_sensors.h"
#include "tow_sim/ros/survey_bag.h"
#include "tow_sim/scenario/batch_run.h"

namespace
{
using namespace tow_sim;
constexpr double kEpoch = 5000.0;  // [s] the bag's stamps are this plus the rows' t

const char* kSurvey = R"(
cable: {length: 200.0, segments: 10}
environment: {current: [0.0, 0.15, 0.0]}
ship:
  manoeuvres:
    - {type: straight, speed: 2.0, duration: 100.0}
    - {type: turn, speed: 2.0, radius: 150.0, angle: 1.6, direction: port}
simulation: {duration: 220.0, output_interval: 0.5, shape_interval: 220.0}
sensors: {usbl: {enabled: false}}
)";

std::vector<SurveyMeasurement> measure()
{
  const Scenario sc = loadScenario(YAML::Load(kSurvey));
  SurveySensors sensors(sc.sensors);
  std::vector<SurveyMeasurement> rows;
  std::ostringstream series, shapes;
  BatchResult result;
  runScenario(sc, series, shapes, result, {}, {}, 10,
              [&](const TowSnapshot& s)
              {
                sensors.observe(s);
                for (const SurveyMeasurement& row : sensors.take(s.t))
                  rows.push_back(row);
              });
  return rows;
}

template <class M>
void put(rosbag::Bag& bag, const std::string& topic, double t, M msg)
{
  msg.header.stamp = ros::Time(kEpoch + t);
  bag.write("/survey_ship/" + topic, msg.header.stamp, msg);
}

tow_sim::SensorValue value(double v)
{
  tow_sim::SensorValue m;
  m.value = v;
  return m;
}

// Each row's measurements as the messages tow_sim_node's SurveyPublisher sends, in a bag under /survey_ship/.
void writeBag(const std::string& path, const std::vector<SurveyMeasurement>& rows)
{
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  const GeographicLib::LocalCartesian origin(43.1, 5.9, 0.0);
  for (const SurveyMeasurement& r : rows)
  {
    if (std::isfinite(r.ship_x))
    {
      sensor_msgs::NavSatFix f;
      f.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
      origin.Reverse(r.ship_x, r.ship_y, 0.0, f.latitude, f.longitude, f.altitude);
      put(bag, "survey/ship/fix", r.t, f);
    }
    if (std::isfinite(r.ship_heading))
    {
      geometry_msgs::QuaternionStamped h;
      h.quaternion.z = std::sin(r.ship_heading / 2.0);
      h.quaternion.w = std::cos(r.ship_heading / 2.0);
      put(bag, "survey/ship/heading", r.t, h);
    }
    if (std::isfinite(r.cable_out))
      put(bag, "survey/cable_out", r.t, value(r.cable_out));
    if (std::isfinite(r.tension))
      put(bag, "survey/tension", r.t, value(r.tension));
    if (std::isfinite(r.fish_depth))
      put(bag, "survey/fish/depth", r.t, value(r.fish_depth));
    if (std::isfinite(r.fish_heading))
    {
      const Eigen::Quaterniond q(Eigen::AngleAxisd(r.fish_heading, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(r.fish_pitch, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(r.fish_roll, Eigen::Vector3d::UnitX()));
      sensor_msgs::Imu imu;
      imu.orientation.x = q.x(), imu.orientation.y = q.y(), imu.orientation.z = q.z(), imu.orientation.w = q.w();
      put(bag, "survey/fish/imu", r.t, imu);
    }
  }
}

std::string scratch(const std::string& name)
{
  const std::string dir = std::filesystem::temp_directory_path() / ("tow_sim_bag_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

SurveyRowSettings settings()
{
  SurveyRowSettings s;
  s.origin_from_first_fix = false;
  s.origin_latitude = 43.1;
  s.origin_longitude = 5.9;
  return s;
}

struct Recorded
{
  std::vector<SurveyMeasurement> rows;
  std::string bag;
};

const Recorded& recorded()
{
  static Recorded r;
  if (r.rows.empty())
  {
    r.rows = measure();
    r.bag = scratch("survey.bag");
    writeBag(r.bag, r.rows);
  }
  return r;
}

TEST(SurveyBag, TheMessagesComeBackAsTheRows)
{
  const Recorded& r = recorded();
  ASSERT_GT(r.rows.size(), 400u);
  const SurveyBag bag = readSurveyBag(r.bag, "/survey_ship", settings());
  EXPECT_EQ(bag.refused, 0);
  EXPECT_DOUBLE_EQ(bag.epoch.toSec(), kEpoch);
  ASSERT_EQ(bag.rows.size(), r.rows.size());
  for (size_t i = 0; i < r.rows.size(); ++i)
  {
    SurveyMeasurement want = r.rows[i];
    want.ship_speed = SurveyMeasurement::kNone;  // NavSatFix has no speed (tow_nav does not use it)
    const auto a = want.values(), b = bag.rows[i].values();
    for (int c = 0; c < SurveyMeasurement::kColumns; ++c)
    {
      ASSERT_EQ(std::isnan(a[c]), std::isnan(b[c])) << "row " << i << " column " << c;
      if (!std::isnan(a[c]))
      {
        ASSERT_NEAR(b[c], a[c], c == 1 || c == 2 ? 1e-6 : 1e-9) << "row " << i << " column " << c;
      }
    }
  }
}

int runTool(const std::string& args)
{
  const std::string command = std::string(TOW_SIM_NAV_BINARY) + " " + args + " > " + scratch("tool.log") + " 2>&1";
  return WEXITSTATUS(std::system(command.c_str()));
}

std::vector<std::string> lines(const std::string& path)
{
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);)
    out.push_back(line);
  return out;
}

TEST(SurveyBag, TowSimNavGivesTheSameEstimateFromTheBagAsFromTheCsv)
{
  const Recorded& r = recorded();
  std::ofstream(scratch("nav.yaml")) << "cable: {length: 200.0, segments: 10}\nnav: {members: 8, start_after: 20.0}\n";
  std::ofstream(scratch("node.yaml")) << "origin_from_first_fix: false\norigin_latitude: 43.1\norigin_longitude: 5.9\n";
  {
    std::ofstream csv(scratch("measurements.csv"));
    csv << surveyMeasurementHeader() << '\n';
    for (const SurveyMeasurement& row : r.rows)
      csv << surveyMeasurementRow(row, 17) << '\n';
  }
  const std::string config = " --config " + scratch("nav.yaml");
  ASSERT_EQ(runTool(config + " --measurements " + scratch("measurements.csv") + " --out " + scratch("from_csv")), 0);
  ASSERT_EQ(runTool(config + " --bag " + r.bag + " --topics /survey_ship/ --nav-config " + scratch("node.yaml") +
                    " --out " + scratch("from_bag")),
            0);
  const std::vector<std::string> csv = lines(scratch("from_csv/estimate.csv")),
                                 bag = lines(scratch("from_bag/estimate.csv"));
  ASSERT_EQ(csv.size(), r.rows.size() + 1);
  ASSERT_EQ(bag.size(), csv.size());
  int compared = 0;
  for (size_t i = 1; i < csv.size(); ++i)
  {
    std::vector<double> a, b;
    for (auto [line, into] : { std::pair{ &csv[i], &a }, std::pair{ &bag[i], &b } })
    {
      std::stringstream cells(*line);
      for (std::string cell; std::getline(cells, cell, ',');)
        into->push_back(cell.empty() ? NAN : std::stod(cell));
    }
    ASSERT_EQ(a.size(), b.size()) << "row " << i;
    for (size_t c = 1; c < a.size(); ++c)
    {
      if (std::isnan(a[c]) && std::isnan(b[c]))
        continue;
      ASSERT_NEAR(b[c], a[c], 1e-3) << "row " << i << " column " << c;
      ++compared;
    }
  }
  EXPECT_GT(compared, 1000);  // the model started: positions were compared, not just times
}

TEST(SurveyBag, ABagWithoutTheSurveyTopicsIsRefusedNamingThoseItHas)
{
  const Recorded& r = recorded();
  try
  {
    readSurveyBag(r.bag, "/", settings());
    FAIL() << "a bag with none of /survey/... was read";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("/survey_ship/survey/ship/fix"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readSurveyBag(scratch("missing.bag"), "/", settings()), std::runtime_error);
  std::ofstream(scratch("nav_only.yaml")) << "cable: {length: 200.0, segments: 10}\n";
  EXPECT_EQ(runTool("--config " + scratch("nav_only.yaml") + " --bag " + scratch("missing.bag") + " --out " +
                    scratch("none")),
            2);
  std::ifstream log(scratch("tool.log"));
  const std::string said((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(said.find("cannot read the bag " + scratch("missing.bag")), std::string::npos) << said;
}
}  // namespace
