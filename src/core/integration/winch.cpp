#include "tow_sim/core/integration/winch.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tow_sim/core/chain/chain_state.h"

namespace tow_sim
{
double winchAcceleration(const WinchParams& winch, double command, double length, double rate)
{
  if (!winch.enabled)
    return 0.0;
  // Target rate: the command within the rate limit, slowing before each length limit so that the
  // lagged rate never carries the cable past it: no faster than a stop at half the deceleration limit
  // allows (room for the lag), and near the limit proportional to the distance left with gain
  // 1/(4 tau), which makes the last approach critically damped: the length creeps up to the limit
  // without crossing it and the acceleration stays within its limit.
  const double a = winch.max_acceleration, tau = winch.response_time;
  const double k = 0.25 / tau;
  const double to_max = std::max(0.0, winch.max_length - length), to_min = std::max(0.0, length - winch.min_length);
  double target = std::clamp(command, -winch.max_rate, winch.max_rate);
  target = std::min({ target, std::sqrt(a * to_max), k * to_max });
  target = std::max({ target, -std::sqrt(a * to_min), -k * to_min });
  return std::clamp((target - rate) / tau, -a, a);
}

Eigen::Vector2d winchAccelerationDerivatives(const WinchParams& winch, double command, double length, double rate)
{
  if (!winch.enabled)
    return Eigen::Vector2d::Zero();
  const double dl = 1e-6 * std::max(1.0, length), dr = 1e-6;
  return {
    (winchAcceleration(winch, command, length + dl, rate) - winchAcceleration(winch, command, length - dl, rate)) /
        (2.0 * dl),
    (winchAcceleration(winch, command, length, rate + dr) - winchAcceleration(winch, command, length, rate - dr)) /
        (2.0 * dr)
  };
}

ChainGeometry paidOut(const WinchParams& winch, double command, ChainGeometry geometry, double length, double rate)
{
  geometry.first_length = std::max(length - geometry.lengthAftOfFirst(), 1e-9);
  geometry.first_rate = rate;
  geometry.first_acceleration = winchAcceleration(winch, command, length, rate);
  return geometry;
}

void stopAtLimits(const WinchParams& winch, double& length, double& rate)
{
  if (length >= winch.max_length)
    rate = std::min(rate, 0.0);
  if (length <= winch.min_length)
    rate = std::max(rate, 0.0);
  length = std::clamp(length, winch.min_length, winch.max_length);
  rate = std::clamp(rate, -winch.max_rate, winch.max_rate);
}

void validate(const WinchParams& winch, const ChainModel& model)
{
  std::vector<CableParams> sections;
  for (int i = 0; i < model.sectionCount(); ++i)
    sections.push_back(model.section(i).cable);
  validate(winch, sections);
}

void validate(const WinchParams& winch, const std::vector<CableParams>& sections, const std::string& prefix)
{
  if (sections.size() == 1 || !winch.enabled)  // a winch that does not run: its table's ranges
  {
    validate(winch, sections.front(), prefix);
    return;
  }
  double aft = 0.0;
  for (size_t i = 1; i < sections.size(); ++i)
    aft += sections[i].length;
  WinchParams first = winch;
  first.min_length -= aft;
  first.max_length -= aft;
  try
  {
    validate(first, sections.front(), prefix);
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(
        std::string(e.what()) + " (with cable sections: the winch's min_length and max_length less the " +
        std::to_string(aft) + " m of the sections aft of the first, which the winch never moves)");
  }
}

namespace
{
// A new joint on the first segment, d from its aft end. It moves as a point of the rigid segment across the
// flow and with the aft joint along it (that part keeps its length d).
void splitFirstSegment(const ShipEndState& ship, ChainGeometry& geometry, std::vector<double>& y)
{
  const bool roll = geometry.rollingEnd();
  const StateLayout L{ geometry.jointCount(), false, 0, true, roll }, next_layout{ L.joints + 1, false, 0, true, roll };
  const double d = geometry.nominal_length, first = geometry.first_length;
  const auto x = L.positions(y);
  const auto v = L.velocities(y);
  const Eigen::Vector3d axis = x.col(0) - ship.p_W;
  const Eigen::Vector3d s = axis.normalized();
  const double eta = (first - d) / first;
  Eigen::Vector3d w = ship.v_W + eta * (v.col(0) - ship.v_W);
  w += s.dot(v.col(0) - w) * s;
  std::vector<double> next(next_layout.size());
  auto nx = next_layout.positions(next);
  auto nv = next_layout.velocities(next);
  nx.col(0) = ship.p_W + eta * axis;
  nv.col(0) = w;
  nx.rightCols(L.joints) = x;
  nv.rightCols(L.joints) = v;
  next_layout.cableOut(next) = L.cableOut(y);
  next_layout.payoutRate(next) = L.payoutRate(y);
  next_layout.setRollState(next, L.rollState(y));
  geometry.segments += 1;
  geometry.first_length = first - d;
  y.swap(next);
}

// The first segment merged into the second: joint x_2 dropped. The new first segment runs straight from the
// tow point to x_3; its length is the sum, so mass is kept; the projection then restores that length (a
// shift of second order in the kink at x_2).
void mergeFirstSegment(ChainGeometry& geometry, std::vector<double>& y)
{
  const bool roll = geometry.rollingEnd();
  const StateLayout L{ geometry.jointCount(), false, 0, true, roll }, next_layout{ L.joints - 1, false, 0, true, roll };
  std::vector<double> next(next_layout.size());
  next_layout.positions(next) = L.positions(y).rightCols(L.joints - 1);
  next_layout.velocities(next) = L.velocities(y).rightCols(L.joints - 1);
  next_layout.cableOut(next) = L.cableOut(y);
  next_layout.payoutRate(next) = L.payoutRate(y);
  next_layout.setRollState(next, L.rollState(y));
  geometry.segments -= 1;
  geometry.first_length += geometry.nominal_length;
  y.swap(next);
}
}  // namespace

bool remeshFirstSegment(const WinchParams& winch, const ShipEndState& ship, ChainGeometry& geometry,
                        std::vector<double>& y)
{
  // One pass in one direction: split while the first segment is above the band, or merge while it is
  // below. The first segment's length is carried from split to split (not recomputed from the cable out,
  // whose rounding could put it on both sides of the band at once), and a call never turns back.
  // A relative margin of 1e-6 on both edges: with max >= min + 1 a split then lands strictly above the
  // merge edge and a merge strictly below the split edge, whatever the rounding.
  auto firstSectionSegments = [&] { return geometry.segments - geometry.aftSectionSegments(); };
  const double d = geometry.nominal_length;
  const double split_above = winch.segment_max_fraction * d * (1.0 + 1e-6);
  const double merge_below = winch.segment_min_fraction * d * (1.0 - 1e-6);
  const bool split = geometry.first_length > split_above;
  const bool merge = !split && geometry.first_length < merge_below && firstSectionSegments() >= 2;
  if (!split && !merge)
    return false;
  for (int pass = 0; pass < 100000; ++pass)
  {
    if (split && geometry.first_length > split_above)
      splitFirstSegment(ship, geometry, y);
    else if (merge && geometry.first_length < merge_below && firstSectionSegments() >= 2)
      mergeFirstSegment(geometry, y);
    else
      break;
  }
  return true;
}

}  // namespace tow_sim
