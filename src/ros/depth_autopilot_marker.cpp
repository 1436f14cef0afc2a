// depth_autopilot_node's interactive marker (~setpoint_marker): a disc at the vehicle, dragged along z in
// rviz; where it is let go (MOUSE_UP) becomes the depth setpoint, validated like autopilot/depth_setpoint.
// It follows the vehicle horizontally and stays at the setpoint's depth.
#include <cmath>
#include <string>

#include "tow_sim/ros/depth_autopilot_node.h"

namespace tow_sim
{
namespace
{
constexpr char kMarker[] = "depth_setpoint";
}  // namespace

void DepthAutopilotNode::setUpMarker()
{
  marker_server_ =
      std::make_unique<interactive_markers::InteractiveMarkerServer>(pnh_.getNamespace() + "/setpoint_marker");
  visualization_msgs::InteractiveMarker marker;
  marker.header.frame_id = node_params_.world_frame;
  marker.name = kMarker;
  marker.description = "depth setpoint (drag up or down)";
  marker.scale = 8.0;
  marker.pose.orientation.w = 1.0;
  visualization_msgs::InteractiveMarkerControl move;
  move.name = "move_z";
  move.interaction_mode = visualization_msgs::InteractiveMarkerControl::MOVE_AXIS;
  // The control moves along its own x axis: turned onto the world's z.
  move.orientation.w = std::sqrt(0.5);
  move.orientation.y = std::sqrt(0.5);
  move.always_visible = true;
  visualization_msgs::Marker disc;
  disc.type = visualization_msgs::Marker::CYLINDER;
  disc.scale.x = disc.scale.y = 6.0;
  disc.scale.z = 0.3;
  disc.color.r = 0.2;
  disc.color.g = 0.9;
  disc.color.b = 0.4;
  disc.color.a = 0.6;
  disc.pose.orientation.w = 1.0;
  move.markers.push_back(disc);
  marker.controls.push_back(move);
  marker_server_->insert(marker, [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback)
                         { onMarkerFeedback(feedback); });
  marker_server_->applyChanges();
}

void DepthAutopilotNode::onMarkerFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback)
{
  if (feedback->event_type != visualization_msgs::InteractiveMarkerFeedback::MOUSE_UP)
    return;
  if (feedback->header.frame_id != node_params_.world_frame)
  {
    ROS_WARN_THROTTLE(2.0, "depth_autopilot: rejected setpoint marker feedback: header.frame_id = '%s', expected '%s'",
                      feedback->header.frame_id.c_str(), node_params_.world_frame.c_str());
    moveMarker();
    return;
  }
  applyDepthSetpoint(-feedback->pose.position.z, "setpoint marker: -pose.position.z");
}

void DepthAutopilotNode::followWithMarker()
{
  if (!marker_server_ || !autopilot_.hasVehicle())
    return;
  const Eigen::Vector3d& p = autopilot_.vehiclePosition();
  const double z = autopilot_.hasSetpoint() ? -autopilot_.setpoint() : 0.0;
  if (std::hypot(p.x() - marker_x_, p.y() - marker_y_) > 2.0 || z != marker_z_)
    moveMarker();
}

void DepthAutopilotNode::moveMarker()
{
  if (!marker_server_)
    return;
  if (autopilot_.hasVehicle())
  {
    marker_x_ = autopilot_.vehiclePosition().x();
    marker_y_ = autopilot_.vehiclePosition().y();
  }
  geometry_msgs::Pose pose;
  pose.position.x = marker_x_;
  pose.position.y = marker_y_;
  pose.position.z = marker_z_ = autopilot_.hasSetpoint() ? -autopilot_.setpoint() : 0.0;
  pose.orientation.w = 1.0;
  marker_server_->setPose(kMarker, pose);
  marker_server_->applyChanges();
}

}  // namespace tow_sim
