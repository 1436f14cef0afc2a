// A batch run's cable shapes (shapes.csv) read back for replay (tow_sim_replay): the joints, tensions and
// slack flags at each shape time, and the shape at any time between them.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tow_sim
{
struct ShapeFrame
{
  double t = 0.0;               // [s]
  Eigen::Matrix3Xd joints;      // [m] x_1 .. x_{nu+2}, tow point first, world
  std::vector<double> tension;  // [N] at each joint (the CSV's column; the tail point's is the last element's)
  std::vector<bool> slack;      // per joint row as written
};

// Reads `path` (columns t, joint, x, y, z, tension, slack; rows grouped by time, joints 1, 2, ... in order).
// Throws std::invalid_argument naming the file and the line for anything else, or for no rows.
std::vector<ShapeFrame> readShapes(const std::string& path);

// The shape at time t: linear in the joints and tensions between the two frames around t when both have as
// many joints (the winch changes the count), else the earlier frame; the first or last frame outside them.
// Slack flags from the earlier frame.
ShapeFrame shapeAt(const std::vector<ShapeFrame>& frames, double t);

}  // namespace tow_sim
