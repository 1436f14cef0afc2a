// gnss_ship_node: a survey vessel's GNSS as ship/odom (tow_sim/ros/gnss_ship_node.h, docs/own_ship.md).
#include <ros/ros.h>

#include "tow_sim/ros/gnss_ship_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "gnss_ship");
  ros::NodeHandle nh, pnh("~");  // outlive the node, so ROS is still up to report a failure
  try
  {
    tow_sim::GnssShipNode ship(nh, pnh);
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("gnss_ship: %s", e.what());
    return 1;
  }
  return 0;
}
