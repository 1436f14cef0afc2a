// The URDF towfish's description read from a node configuration (tow_sim_urdf): the default sensor frames
// by hand, the configuration's own, and refusals naming the key. (The URDF itself is parsed by urdf and
// checked through tf in the rostest towfish_urdf.test.)
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "tow_sim/core/constants.h"
#include "tow_sim/scenario/towfish_urdf.h"

namespace
{
using tow_sim::readTowfishDescription;
using tow_sim::TowfishDescription;

TEST(UrdfDescription, DefaultsAreTheNodesFrameAndThreeSensorsOnTheHull)
{
  const TowfishDescription d = readTowfishDescription(YAML::Node());
  EXPECT_EQ(d.vehicle_frame, "tow_vehicle");
  EXPECT_EQ(d.hull_diameter, 0.3);
  ASSERT_EQ(d.sensors.size(), 3u);
  EXPECT_EQ(d.sensors[0].name, "sidescan_port");
  EXPECT_EQ(d.sensors[0].xyz.y(), 0.15);  // on the hull's port side
  EXPECT_NEAR(d.sensors[0].rpy.z(), tow_sim::kPi / 2, 1e-12);
  EXPECT_EQ(d.sensors[1].xyz.y(), -0.15);
  EXPECT_EQ(d.sensors[2].name, "altimeter");
  EXPECT_EQ(d.sensors[2].xyz.z(), -0.15);
  const std::string urdf = tow_sim::towfishUrdf(tow_sim::VehicleParams(), d);
  EXPECT_NE(urdf.find("<joint name=\"tow_vehicle_rudder_joint\" type=\"revolute\">"), std::string::npos);
  EXPECT_NE(urdf.find("<axis xyz=\"0 -1 0\"/>"), std::string::npos);  // the elevator's, no "-0"
}

TEST(UrdfDescription, ReadsTheConfigurationsSensorsAndFrame)
{
  const TowfishDescription d = readTowfishDescription(YAML::Load(
      "vehicle_frame: fish\nvehicle_diameter: 0.5\n"
      "sensor_frames: [{name: camera, xyz: [0.5, 0, -0.2], rpy: [0, 1.5, 0]}, {name: dvl, xyz: [-0.3, 0, -0.2]}]\n"
      "cable: {length: 10}\n"));
  EXPECT_EQ(d.vehicle_frame, "fish");
  EXPECT_EQ(d.hull_diameter, 0.5);
  ASSERT_EQ(d.sensors.size(), 2u);
  EXPECT_EQ(d.sensors[0].xyz.x(), 0.5);
  EXPECT_EQ(d.sensors[0].rpy.y(), 1.5);
  EXPECT_EQ(d.sensors[1].rpy.norm(), 0.0);
}

TEST(UrdfDescription, RefusesBadSensorFramesNamingTheKey)
{
  const std::pair<const char*, const char*> cases[] = {
    { "sensor_frames: {name: a}", "sensor_frames: must be a list" },
    { "sensor_frames: [{name: 'a b', xyz: [0, 0, 0]}]", "sensor_frames[0].name = 'a b'" },
    { "sensor_frames: [{xyz: [0, 0, 0]}]", "sensor_frames[0].name = ''" },
    { "sensor_frames: [{name: a, xyz: [0, 0]}]", "sensor_frames[0].xyz: must be a list of 3 numbers" },
    { "sensor_frames: [{name: a, xyz: [0, 0, 200]}]", "sensor_frames[0].xyz[2] = 200 is out of range" },
    { "sensor_frames: [{name: a, xyz: [0, 0, 0], rpy: [0, x, 0]}]", "sensor_frames[0].rpy[1]: must be a number" },
    { "sensor_frames: [{name: a, xyz: [0, 0, 0], size: 1}]", "sensor_frames[0].size: unknown key" },
    { "sensor_frames: [{name: a, xyz: [0, 0, 0]}, {name: a, xyz: [1, 0, 0]}]",
      "sensor_frames[1].name = 'a': used twice" },
    { "vehicle_diameter: -1", "vehicle_diameter = -1 is out of range" },
  };
  for (const auto& [yaml, expected] : cases)
  {
    try
    {
      readTowfishDescription(YAML::Load(yaml));
      ADD_FAILURE() << yaml << ": accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << yaml << ": " << e.what();
    }
  }
}

}  // namespace
