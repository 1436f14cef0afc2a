// The rviz picture of the tow: one batched MarkerArray per update.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include "tow_sim/core/tow_run.h"
#include "tow_sim/ros/tow_sim_node.h"

namespace tow_sim
{
// Cable line strip coloured by tension (ns "cable"), hull and four fins at their actual angles
// ("vehicle", at the snapshot's published attitude), the tow force on the ship ("tow_force"), tension
// labels ("labels") and the seabed around the vehicle ("seabed", when there is one).
visualization_msgs::MarkerArray makeMarkers(const TowSnapshot& s, const VehicleParams& vehicle, const Seabed* seabed,
                                            const NodeParams& params, const std_msgs::Header& header);

}  // namespace tow_sim
