// tow_sim_node: the towing simulation. Topics and services: docs/nodes.md; parameters: docs/parameters.md.
#include <ros/ros.h>

#include "tow_sim/ros/tow_sim_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "tow_sim");
  ros::NodeHandle nh, pnh("~");  // outlive the node, so ROS is still up to report a failure
  try
  {
    tow_sim::TowSimNode node(nh, pnh);
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("tow_sim: bad configuration: %s", e.what());
    return 1;
  }
  return 0;
}
