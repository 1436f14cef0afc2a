// rostest of the URDF towfish (towfish_urdf.test): robot_description (tow_sim_urdf from
// test/ros/urdf_config.yaml) parses as URDF with the joints where the configuration puts them, tf holds
// the fin and sensor frames (robot_state_publisher), and the elevator joint follows a commanded elevator in
// the simulation's sense (a positive elevator lifts the leading edge). Expected numbers are written out
// here from the configuration file, not taken from the generator.
#include <gtest/gtest.h>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/transform_listener.h>
#include <urdf/model.h>

#include <cmath>
#include <cstdio>
#include <mutex>
#include <string>

#include "tow_sim/FinCommand.h"

namespace
{
// test/ros/urdf_config.yaml: vehicle_frame fish; cg_from_bail 0.2, vertical fin 1.1, horizontal fin 0.9 aft
// of the bail; the default nose 0.8 and tail 1.2 from the bail; hull diameter 0.4.
constexpr double kRudderX = 0.2 - 1.1, kElevatorX = 0.2 - 0.9, kHullX = 0.2 - 0.5 * (1.2 - 0.8);

class Ship
{
public:
  Ship()
  {
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/ship/odom", 20);
    fin_pub_ = nh_.advertise<tow_sim::FinCommand>("/fins/command", 5);
    joint_sub_ = nh_.subscribe<sensor_msgs::JointState>("/joint_states", 10,
                                                        [this](const sensor_msgs::JointState::ConstPtr& m)
                                                        {
                                                          std::lock_guard<std::mutex> lock(mutex_);
                                                          joints_ = *m;
                                                        });
    spinner_.start();
  }
  // `seconds` of a ship at 2 m/s along +x, odometry at 20 Hz, the elevator command repeated each time.
  void run(double seconds, double elevator)
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
      tow_sim::FinCommand c;
      c.header.stamp = o.header.stamp;
      c.elevator = elevator;
      fin_pub_.publish(c);
      ros::WallDuration(0.05).sleep();
    }
  }
  sensor_msgs::JointState joints()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return joints_;
  }

private:
  ros::NodeHandle nh_;
  ros::Time start_ = ros::Time::now();
  ros::Publisher odom_pub_, fin_pub_;
  ros::Subscriber joint_sub_;
  std::mutex mutex_;
  sensor_msgs::JointState joints_;
  ros::AsyncSpinner spinner_{ 1 };
};

TEST(TowfishUrdf, DescriptionParsesWithTheConfiguredJointsAndFrames)
{
  std::string xml;
  ASSERT_TRUE(ros::param::get("/robot_description", xml));
  urdf::Model model;
  ASSERT_TRUE(model.initString(xml)) << xml;
  EXPECT_EQ(model.getRoot()->name, "fish");
  const auto rudder = model.getJoint("fish_rudder_joint"), elevator = model.getJoint("fish_elevator_joint");
  ASSERT_TRUE(rudder && elevator);
  EXPECT_EQ(rudder->type, urdf::Joint::REVOLUTE);
  EXPECT_EQ(elevator->type, urdf::Joint::REVOLUTE);
  EXPECT_NEAR(rudder->parent_to_joint_origin_transform.position.x, kRudderX, 1e-9);
  EXPECT_NEAR(elevator->parent_to_joint_origin_transform.position.x, kElevatorX, 1e-9);
  EXPECT_EQ(rudder->axis.z, 1.0);  // positive rudder: leading edge to port
  EXPECT_EQ(elevator->axis.y, -1.0);
  // The elevator's differential: the starboard fin's joint, the port fin's its mimic with the opposite sense.
  const auto differential = model.getJoint("fish_elevator_differential_joint"),
             port = model.getJoint("fish_elevator_port_joint");
  ASSERT_TRUE(differential && port && port->mimic);
  EXPECT_EQ(differential->child_link_name, "fish_elevator_starboard");
  EXPECT_EQ(port->mimic->joint_name, "fish_elevator_differential_joint");
  EXPECT_EQ(port->mimic->multiplier, -1.0);
  EXPECT_NEAR(rudder->limits->upper, 0.436, 1e-12);  // the default max_deflection
  EXPECT_NEAR(model.getJoint("fish_hull_joint")->parent_to_joint_origin_transform.position.x, kHullX, 1e-9);
  EXPECT_NEAR(model.getJoint("fish_bail_joint")->parent_to_joint_origin_transform.position.x, 0.2, 1e-9);
  const auto camera = model.getJoint("fish_camera_joint");
  ASSERT_TRUE(camera && model.getLink("fish_dvl"));
  EXPECT_NEAR(camera->parent_to_joint_origin_transform.position.x, 0.5, 1e-9);
  EXPECT_NEAR(camera->parent_to_joint_origin_transform.position.z, -0.2, 1e-9);
  EXPECT_FALSE(model.getLink("fish_altimeter"));  // the configuration's sensors replace the defaults
}

TEST(TowfishUrdf, TfHasTheFinAndSensorFramesAndTheElevatorFollowsItsCommand)
{
  Ship ship;
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ship.run(3.0, 0.0);
  ship.run(4.0, 0.3);  // 0.3 rad reached after 0.86 s at the default 0.35 rad/s
  const sensor_msgs::JointState joints = ship.joints();
  ASSERT_EQ(joints.name.size(), 3u);
  EXPECT_EQ(joints.name[1], "fish_elevator_joint");
  EXPECT_EQ(joints.name[2], "fish_elevator_differential_joint");
  EXPECT_NEAR(joints.position[1], 0.3, 1e-6);
  EXPECT_NEAR(joints.position[0], 0.0, 1e-6);
  EXPECT_EQ(joints.position[2], 0.0);  // no differential commanded

  geometry_msgs::TransformStamped fin, camera, dvl, world;
  ASSERT_NO_THROW(fin = buffer.lookupTransform("fish", "fish_elevator", ros::Time(0), ros::Duration(2.0)));
  ASSERT_NO_THROW(camera = buffer.lookupTransform("fish", "fish_camera", ros::Time(0), ros::Duration(2.0)));
  ASSERT_NO_THROW(dvl = buffer.lookupTransform("fish", "fish_dvl", ros::Time(0), ros::Duration(2.0)));
  ASSERT_NO_THROW(world = buffer.lookupTransform("odom", "fish_elevator", ros::Time(0), ros::Duration(2.0)));
  // robot_state_publisher turns the differential's mimic joint into the port fin's frame too.
  EXPECT_NO_THROW(buffer.lookupTransform("fish_elevator", "fish_elevator_port", ros::Time(0), ros::Duration(2.0)));
  EXPECT_NO_THROW(buffer.lookupTransform("fish_elevator", "fish_elevator_starboard", ros::Time(0), ros::Duration(2.0)));
  const auto& q = fin.transform.rotation;
  const tf2::Matrix3x3 R(tf2::Quaternion(q.x, q.y, q.z, q.w));
  const tf2::Vector3 leading_edge = R * tf2::Vector3(1, 0, 0);
  std::printf("elevator link: x %.4f m, leading edge (%.4f, %.4f, %.4f); dvl at (%.2f, %.2f, %.2f) m\n",
              fin.transform.translation.x, leading_edge.x(), leading_edge.y(), leading_edge.z(),
              dvl.transform.translation.x, dvl.transform.translation.y, dvl.transform.translation.z);
  EXPECT_NEAR(fin.transform.translation.x, kElevatorX, 1e-9);
  EXPECT_NEAR(leading_edge.x(), std::cos(0.3), 1e-6);
  EXPECT_NEAR(leading_edge.z(), std::sin(0.3), 1e-6);  // lifted: the simulation's positive elevator
  EXPECT_NEAR(dvl.transform.translation.x, -0.3, 1e-9);
  EXPECT_NEAR(dvl.transform.translation.z, -0.2, 1e-9);
  const auto& c = camera.transform.rotation;
  const tf2::Vector3 look = tf2::Matrix3x3(tf2::Quaternion(c.x, c.y, c.z, c.w)) * tf2::Vector3(1, 0, 0);
  EXPECT_NEAR(look.z(), -1.0, 1e-6);               // pitched 90 degrees: looking down
  EXPECT_LT(world.transform.translation.z, -1.0);  // the whole tree hangs under odom, in the water
}

}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_towfish_urdf");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
