// What a run reports of its steps: value ranges, step reports, a cable parting, the lateral diversion.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
// The cable parting (cable.break_at_breaking_load): when, where and at what tension.
struct PartingEvent
{
  double t = 0.0;        // [s]
  int joint = 0;         // 1 = the tow point .. nu + 1 = the bail: the forward joint of element joint - 1
  double tension = 0.0;  // [N] |T| there, above breaking_load
};

// Lateral diversion (the report's): horizontal offset of a point from the line through the ship along
// the unit horizontal track direction, positive to port, and its rate for a fixed track direction.
struct Diversion
{
  double offset = 0.0;  // [m]
  double rate = 0.0;    // [m/s]
};
Diversion lateralDiversion(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, const ShipEndState& ship,
                           const Eigen::Vector3d& track_direction_W);

// The smallest and largest of a series of values (empty: min > max).
struct ValueRange
{
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  void add(double v)
  {
    min = std::min(min, v);
    max = std::max(max, v);
  }
  void add(const ValueRange& r)
  {
    min = std::min(min, r.min);
    max = std::max(max, r.max);
  }
  bool empty() const { return min > max; }
};

struct StepReport
{
  int steps = 0;                  // accepted steps
  int rejected = 0;               // steps the error control rejected
  double max_length_error = 0.0;  // [-] largest relative length error left by a step, before projection
  ValueRange tension_ship;        // [N] |T_1| at the end of each accepted step
  ValueRange tension_vehicle;     // [N] |T_{nu+1}| likewise
  int snaps = 0;                  // elastic cable: segments that went from slack (T = 0 at or below their
                                  // rest length) to taut (T > 0)
  // [-] elastic cable: the largest segment strain at the end of a step (-inf: none)
  double max_strain = -std::numeric_limits<double>::infinity();
  std::optional<PartingEvent> parting;  // the cable parted during these steps (advanceTo goes on after it)
};

// An elastic cable's slack segments after a step (joints x_1 .. x_{nu+2}, each element's axial multiplier
// [N]): a segment goes slack when it carries no tension at or below its rest length (not when its damping
// alone zeroes the tension of a still stretched segment) and snaps when it carries tension again; the snaps
// and the largest strain go into the report. `slack` holds each segment's flag between steps; of another
// size (after a restart) it is set afresh, a restart at the rest lengths (a straight line) not slack.
void countSnaps(const ChainGeometry& geometry, const Eigen::Matrix3Xd& joints, const std::vector<double>& multipliers,
                std::vector<char>& slack, StepReport& report);

}  // namespace tow_sim
