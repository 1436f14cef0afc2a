// The rviz picture of the tow: one batched MarkerArray per update.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include "tow_sim/core/simulator.h"
#include "tow_sim/core/vehicle.h"
#include "tow_sim/ros/tow_sim_node.h"

namespace tow_sim
{
// Cable line strip coloured by tension (ns "cable"), hull and four fins at their actual angles
// ("vehicle"), the tow force on the ship ("tow_force") and tension labels ("labels").
visualization_msgs::MarkerArray makeMarkers(const Simulator& sim, const Vehicle& vehicle, const VehicleOutputs& out,
                                            const Eigen::Quaterniond& q_published, const NodeParams& params,
                                            const std_msgs::Header& header);

}  // namespace tow_sim
