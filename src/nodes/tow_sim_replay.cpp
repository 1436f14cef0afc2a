// tow_sim_replay: a tow_sim_batch run's cable shapes replayed into rviz on the run's own /clock.
// Topics: docs/tools.md ("Replay in rviz"); parameters: docs/parameters.md.
#include <ros/ros.h>

#include "tow_sim/ros/replay_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "tow_sim_replay");
  ros::NodeHandle nh, pnh("~");  // outlive the node, so ROS is still up to report a failure
  try
  {
    tow_sim::ReplayNode node(nh, pnh);
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("tow_sim_replay: %s", e.what());
    return 1;
  }
  return 0;
}
