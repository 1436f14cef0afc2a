// rostest of the cable parting in tow_sim_node (cable_parting.test, parting_config.yaml): the breaking load
// is far below the tow's tension at the tow point, so the cable parts there at once. cable/parting
// (latched) says joint 1 and a tension above the load; afterwards cable/state carries no tension at the
// ship and the vehicle sinks; /diagnostics report the parting as an ERROR; ~reset lays the cable out again.
#include <gtest/gtest.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include <cstdio>
#include <mutex>
#include <optional>
#include <string>

#include "tow_sim/CableParting.h"
#include "tow_sim/CableState.h"
#include "tow_sim/config/node_params.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/ros/conversions.h"
#include "tow_sim/ros/markers.h"

namespace
{
class Ship
{
public:
  Ship()
  {
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/ship/odom", 20);
    parting_sub_ = nh_.subscribe<tow_sim::CableParting>("/cable/parting", 1,
                                                        [this](const tow_sim::CableParting::ConstPtr& m)
                                                        {
                                                          std::lock_guard<std::mutex> lock(mutex_);
                                                          parting_ = *m;
                                                        });
    state_sub_ = nh_.subscribe<tow_sim::CableState>("/cable/state", 5,
                                                    [this](const tow_sim::CableState::ConstPtr& m)
                                                    {
                                                      std::lock_guard<std::mutex> lock(mutex_);
                                                      state_ = *m;
                                                    });
    diag_sub_ =
        nh_.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 5,
                                                        [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m)
                                                        {
                                                          std::lock_guard<std::mutex> lock(mutex_);
                                                          for (const auto& status : m->status)
                                                            if (status.name.find("simulation") != std::string::npos)
                                                            {
                                                              level_ = status.level;
                                                              summary_ = status.message;
                                                            }
                                                        });
    spinner_.start();
  }
  // `seconds` of a ship at 2 m/s along +x, odometry at 20 Hz.
  void run(double seconds)
  {
    for (int i = 0; i < static_cast<int>(seconds * 20.0); ++i)
    {
      nav_msgs::Odometry o;
      o.header.stamp = ros::Time::now();
      o.header.frame_id = "odom";
      o.pose.pose.position.x = 2.0 * (o.header.stamp - start_).toSec();
      o.pose.pose.orientation.w = 1.0;
      o.twist.twist.linear.x = 2.0;
      odom_pub_.publish(o);
      ros::WallDuration(0.05).sleep();
    }
  }
  std::optional<tow_sim::CableParting> parting()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return parting_;
  }
  tow_sim::CableState state()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_;
  }
  std::pair<int, std::string> diagnostics()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return { level_, summary_ };
  }
  void forgetParting()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    parting_.reset();
  }

private:
  ros::NodeHandle nh_;
  ros::Time start_ = ros::Time::now();
  ros::Publisher odom_pub_;
  ros::Subscriber parting_sub_, state_sub_, diag_sub_;
  std::mutex mutex_;
  std::optional<tow_sim::CableParting> parting_;
  tow_sim::CableState state_;
  int level_ = -1;
  std::string summary_;
  ros::AsyncSpinner spinner_{ 1 };
};

TEST(CableParting, TheNodeSaysWhereTheCablePartedAndTheVehicleSideSinks)
{
  Ship ship;
  ship.run(4.0);
  const std::optional<tow_sim::CableParting> p = ship.parting();
  ASSERT_TRUE(p) << "no cable/parting message";
  EXPECT_EQ(p->joint, 1u);  // the tow point carries the most
  EXPECT_GT(p->tension, 300.0);
  EXPECT_EQ(p->breaking_load, 300.0);
  const double depth_then = ship.state().vehicle_depth;
  ship.run(3.0);
  const tow_sim::CableState s = ship.state();
  std::printf("parted at joint %u under %.0f N; vehicle depth %.2f m, then %.2f m\n", p->joint, p->tension, depth_then,
              s.vehicle_depth);
  EXPECT_GT(s.vehicle_depth, depth_then + 1.0);  // sinking, free
  EXPECT_EQ(s.tension_ship, 0.0);                // nothing pulls on the ship
  const auto [level, summary] = ship.diagnostics();
  EXPECT_EQ(level, diagnostic_msgs::DiagnosticStatus::ERROR);
  EXPECT_NE(summary.find("parted at joint 1"), std::string::npos) << summary;

  // ~reset joins the cable again (and it parts again at once: the tension is still above the load).
  ship.forgetParting();
  ros::ServiceClient reset = ros::NodeHandle().serviceClient<std_srvs::Trigger>("/tow_sim/reset");
  ASSERT_TRUE(reset.waitForExistence(ros::Duration(5.0)));
  std_srvs::Trigger r;
  ASSERT_TRUE(reset.call(r));
  ship.run(2.0);
  ASSERT_TRUE(ship.parting()) << "no second parting after ~reset";
  EXPECT_GT(ship.parting()->header.stamp, p->header.stamp);
}

// The node's outputs after a parting aft of the tow point (no node here: the conversions it publishes
// with): a floating cable on a sinking body parts at the bail, and the whole cable stays on the ship,
// hanging straight down and pushing up with its net buoyancy (b - w) L. ship/tow_force is that force,
// the tow_force arrow points along it and the marker "cable_ship_side" draws the cable from the tow point.
TEST(CableParting, AfterAPartingAtTheBailTheShipFeelsTheCableLeftOnIt)
{
  tow_sim::SimulationConfig c;
  c.cable.length = 50.0;
  c.cable.segments = 10;
  c.cable.mass_per_length = 0.1;  // lighter than the water it displaces
  c.cable.breaking_load = 100.0;  // the bail carries the vehicle's net weight, about 800 N
  c.cable.break_at_breaking_load = true;
  c.numerics.stepper = tow_sim::StepperType::kDopri5;
  auto ship = std::make_shared<tow_sim::ShipHistory>(1.0, 100);
  for (int i = 0; i <= 20; ++i)
    ship->add(i, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), tow_sim::ShipPose());
  tow_sim::InitialShape hanging;
  hanging.type = tow_sim::InitialShape::Type::kHanging;
  tow_sim::TowRun run(c, ship, hanging);
  run.start(0.0);
  run.advanceTo(1.0);
  const tow_sim::TowSnapshot s = run.snapshot();
  ASSERT_TRUE(s.parting);
  ASSERT_EQ(s.parting->joint, 11);
  const double area = 0.25 * tow_sim::kPi * c.cable.diameter * c.cable.diameter;
  const double lift = (c.environment.water_density * area - c.cable.mass_per_length) * c.environment.gravity * 50.0;

  std_msgs::Header header;
  header.frame_id = "odom";
  const geometry_msgs::WrenchStamped force = tow_sim::ros_conv::toShipTowForce(s, header);
  std::printf("after a parting at the bail: ship/tow_force (%.4f, %.4f, %.4f) N, closed form (0, 0, %.4f) N\n",
              force.wrench.force.x, force.wrench.force.y, force.wrench.force.z, lift);
  EXPECT_NEAR(force.wrench.force.z, lift, 1e-6 * lift);
  EXPECT_NEAR(std::hypot(force.wrench.force.x, force.wrench.force.y), 0.0, 1e-6 * lift);

  const tow_sim::NodeParams params;
  const visualization_msgs::MarkerArray markers = tow_sim::makeMarkers(s, c.vehicle, nullptr, params, header);
  int ship_side_points = -1;
  double arrow_dz = 0.0;
  for (const auto& m : markers.markers)
  {
    if (m.ns == "cable_ship_side" && m.action == visualization_msgs::Marker::ADD)
      ship_side_points = static_cast<int>(m.points.size());
    if (m.ns == "tow_force" && m.points.size() == 2)
      arrow_dz = m.points[1].z - m.points[0].z;
  }
  EXPECT_EQ(ship_side_points, 11);  // the tow point and the ten joints aft of it
  EXPECT_GT(arrow_dz, 0.0);         // the arrow shows the push up on the ship
}

}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_cable_parting");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
