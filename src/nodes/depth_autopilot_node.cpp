// depth_autopilot_node: holds the towed vehicle's depth with the elevator and keeps it on the ship's
// track with the rudder. Topics and signs: docs/nodes.md; parameters: docs/parameters.md.
#include <ros/ros.h>

#include "tow_sim/ros/depth_autopilot_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "depth_autopilot");
  ros::NodeHandle nh, pnh("~");  // outlive the node, so ROS is still up to report a failure
  try
  {
    tow_sim::DepthAutopilotNode node(nh, pnh);
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("depth_autopilot: bad configuration: %s", e.what());
    return 1;
  }
  return 0;
}
