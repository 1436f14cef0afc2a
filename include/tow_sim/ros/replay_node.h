// tow_sim_replay: a tow_sim_batch run's cable shapes (shapes.csv) replayed into rviz as cable/markers on
// the run's own /clock (set use_sim_time), to review offline studies in 3D. Parameters and topics:
// docs/tools.md ("Replay in rviz").
#pragma once

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <vector>

#include "tow_sim/config/node_params.h"
#include "tow_sim/scenario/shape_replay.h"

namespace tow_sim
{
class ReplayNode
{
public:
  // Reads and validates the parameters and the run's shapes.csv; throws std::invalid_argument naming the
  // parameter or the file and line.
  ReplayNode(ros::NodeHandle nh, ros::NodeHandle pnh);

private:
  void tick(const ros::WallTimerEvent& event);
  void publish(double t);  // /clock and cable/markers for the run's time t [s]

  ros::NodeHandle nh_, pnh_;
  ReplayParams params_;
  std::vector<ShapeFrame> frames_;
  ros::WallTime started_;  // wall time of the run's first frame (moved when looping)
  ros::Publisher clock_pub_, marker_pub_;
  ros::WallTimer timer_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  double last_tf_t_ = -1.0;  // [s] the run's time of the last tf sent
};

}  // namespace tow_sim
