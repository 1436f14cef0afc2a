// The rviz picture of the tow: one batched MarkerArray per update.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/core/run/track_trail.h"
#include "tow_sim/ros/tow_sim_node.h"

namespace tow_sim
{
// A marker of `type` in namespace `ns`: the header, identity pose, opaque, action ADD.
visualization_msgs::Marker baseMarker(const std_msgs::Header& header, const std::string& ns, int id, int type);
// The cable as a line strip through `points` (ns "cable", id 0), each point coloured by its tension [N] on
// the scale up to `color_max` (magenta where `slack`): the node's cable and tow_sim_replay's.
visualization_msgs::Marker tensionLine(const std_msgs::Header& header, const Eigen::Matrix3Xd& points,
                                       const std::vector<double>& tensions, const std::vector<bool>& slack,
                                       double width, double color_max);

struct MarkerTrails
{
  const TrackTrail* ship = nullptr;     // of the ship's reference point
  const TrackTrail* vehicle = nullptr;  // of the vehicle's CG
};

// How cable sections and point bodies are drawn (from the configuration: cableLook).
struct CableLook
{
  std::vector<double> section_widths;  // [m] each section's line width; empty or one: a single line
  std::vector<double> body_diameters;  // [m] each point body's sphere (cable.bodies' order)
  std::vector<bool> body_floats;       // buoyant (yellow) or not (dark grey)
};
// Each section's width: `width` [m] times its diameter over the first section's (0.25 .. 4 times); each
// body's sphere of its displaced volume, at least 3 `width` across.
CableLook cableLook(const SimulationConfig& config, double width);

// Cable line strip coloured by tension (ns "cable"; with sections one strip each, ids 0 ..., of its own width),
// point bodies as spheres ("cable_bodies", id i the i-th body), hull and four fins at their actual angles
// ("vehicle", at the snapshot's published attitude), the tow force on the ship ("tow_force"), tension
// labels ("labels"), the ship's hull outline and tow point ("ship"), the trails when given ("trails": 0
// the ship, 1 the vehicle) and the seabed around the vehicle ("seabed", when there is one).
visualization_msgs::MarkerArray makeMarkers(const TowSnapshot& s, const VehicleParams& vehicle, const Seabed* seabed,
                                            const NodeParams& params, const std_msgs::Header& header,
                                            const MarkerTrails& trails = MarkerTrails(),
                                            const CableLook& look = CableLook());

}  // namespace tow_sim
