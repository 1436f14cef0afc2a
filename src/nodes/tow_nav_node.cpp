// tow_nav_node: the towfish's position from a survey's sensor topics (tow_sim/ros/tow_nav_node.h, docs/survey.md).
#include <ros/ros.h>

#include "tow_sim/ros/tow_nav_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "tow_nav");
  ros::NodeHandle nh, pnh("~");  // outlive the node, so ROS is still up to report a failure
  try
  {
    tow_sim::TowNavNode nav(nh, pnh);
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("tow_nav: %s", e.what());
    return 1;
  }
  return 0;
}
