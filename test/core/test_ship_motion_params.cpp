// ship_motion_node's parameters without roscore: read from its private namespace as YAML through the
// table (a value of the wrong type is an error naming it, not a silent default), checked with messages that
// name each parameter, and its presets as the scripted ship's manoeuvres.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "tow_sim/config/node_params.h"
#include "tow_sim/scenario/scripted_ship.h"

namespace tow_sim
{
namespace
{
ShipMotionParams read(const std::string& yaml)
{
  return readShipMotionParams(YAML::Load(yaml), "/ship_motion");
}

// The message of the error reading `yaml` ("" when there is none).
std::string refusal(const std::string& yaml)
{
  try
  {
    read(yaml);
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  return "";
}

TEST(ShipMotionParams, ReadsEveryKeyAndLeavesOtherReadersKeysAlone)
{
  const ShipMotionParams p = read(
      "{manoeuvre: waypoints, speed: 3.5, heading: 0.5, rate: 50, world_frame: map, ship_frame: boat, "
      "waypoints: [100, 0, 100, 200], waypoint_radius: 20, wave_response: false, rao_file: r.csv, "
      "environment: {waves: {type: regular}}, cable: {length: 500}}");
  EXPECT_EQ(p.manoeuvre, "waypoints");
  EXPECT_EQ(p.speed, 3.5);
  EXPECT_EQ(p.heading, 0.5);
  EXPECT_EQ(p.rate, 50.0);
  EXPECT_EQ(p.world_frame, "map");
  EXPECT_EQ(p.ship_frame, "boat");
  ASSERT_EQ(p.waypoints.size(), 2u);
  EXPECT_EQ(p.waypoints[1], Eigen::Vector2d(100.0, 200.0));
  EXPECT_EQ(p.waypoint_radius, 20.0);
  EXPECT_FALSE(p.wave_response);
  EXPECT_EQ(p.rao_file, "r.csv");
  const ShipMotionParams defaults = read("{}");
  EXPECT_EQ(defaults.manoeuvre, "straight");
  EXPECT_EQ(defaults.rate, 20.0);
}

// Each of these fell back to its default or was named wrongly before (issue 26): now refused, by name.
TEST(ShipMotionParams, WrongTypesAndRangesAreRefusedNamingTheParameter)
{
  const std::pair<const char*, const char*> cases[] = {
    { "{rate: fast}", "/ship_motion.rate" },
    { "{heading: north}", "/ship_motion.heading" },
    { "{world_frame: [1, 2]}", "/ship_motion.world_frame" },
    { "{ship_frame: odom}", "/ship_motion.ship_frame" },
    { "{rate: 0.5}", "/ship_motion.rate" },
    { "{zigzag_period: 0}", "/ship_motion.zigzag_period" },
    { "{change_duration: -1}", "/ship_motion.change_duration" },
    { "{turn_start: -5}", "/ship_motion.turn_start" },
    { "{change_time: -5}", "/ship_motion.change_time" },
    { "{speed: 20}", "/ship_motion.speed" },
    { "{turn_radius: 5}", "/ship_motion.turn_radius" },
    { "{turn_radius: -5}", "/ship_motion.turn_radius" },
    { "{manoeuvre: circle}", "/ship_motion.manoeuvre" },
    { "{manoeuvre: waypoints}", "/ship_motion.waypoints" },
    { "{waypoints: [1, 2, 3]}", "/ship_motion.waypoints" },
    { "{wave_response: maybe}", "/ship_motion.wave_response" },
  };
  for (const auto& [yaml, name] : cases)
  {
    const std::string why = refusal(yaml);
    EXPECT_EQ(why.rfind(name, 0), 0u) << yaml << ": " << why;
  }
  EXPECT_NE(refusal("{rate: 0.5}").find("[1, 1000]"), std::string::npos) << refusal("{rate: 0.5}");
}

// The presets as manoeuvres: their parameters where the documentation puts them, and a turn that turns
// to the side turn_radius's sign says at the steady rate speed / |turn_radius|.
TEST(ShipMotionParams, PresetsBecomeTheDocumentedManoeuvres)
{
  ShipMotionParams p;
  p.manoeuvre = "zigzag";
  p.speed = 3.0;
  p.turn_radius = -300.0;
  p.zigzag_period = 200.0;
  p.turn_start = 50.0;
  std::vector<Manoeuvre> list = presetManoeuvres(p);
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].type, Manoeuvre::Type::kStraight);
  EXPECT_EQ(list[0].duration, 50.0);
  EXPECT_EQ(list[1].type, Manoeuvre::Type::kZigzag);
  EXPECT_DOUBLE_EQ(list[1].angle, 3.0 / 300.0 * 200.0 / 4.0);
  EXPECT_EQ(list[1].direction, -1);
  EXPECT_EQ(list[1].radius, 300.0);

  p.manoeuvre = "speed_change";
  p.speed_2 = 1.5;
  list = presetManoeuvres(p);
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].duration, p.change_time);
  EXPECT_EQ(list[1].type, Manoeuvre::Type::kSpeedChange);
  EXPECT_EQ(list[1].to_speed, 1.5);
  EXPECT_EQ(list[1].duration, p.change_duration);
  EXPECT_EQ(list[2].speed, 1.5);  // and on at the new speed

  p.manoeuvre = "turn";
  p.turn_start = 10.0;
  ScriptedShip ship(presetManoeuvres(p), 0.0, 0.0, 0.0);
  for (int i = 0; i < 4000; ++i)  // 200 s: long past the yaw lag
    ship.step(0.05);
  EXPECT_NEAR(ship.yawRate(), -3.0 / 300.0, 1e-6);  // to starboard for a negative radius
  EXPECT_LT(ship.heading(), -1.0);
}

}  // namespace
}  // namespace tow_sim
