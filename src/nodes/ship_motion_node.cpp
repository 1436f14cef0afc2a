// ship_motion_node: a scripted ship for demos and tests (tow_sim/ros/ship_motion_node.h). Topics and
// presets: docs/nodes.md; parameters: docs/parameters.md.
#include <ros/ros.h>

#include "tow_sim/ros/ship_motion_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "ship_motion");
  ros::NodeHandle nh, pnh("~");  // outlive the node, so ROS is still up to report a failure
  try
  {
    tow_sim::ShipMotionNode ship(nh, pnh);
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("ship_motion: %s", e.what());
    return 1;
  }
  return 0;
}
