// The cable parting (cable.break_at_breaking_load, or part()): the whole cable's chain is replaced by its
// vehicle side, from a free first joint (ChainSolver::solveFree, docs/solver.md §9), and the cable left on the
// ship, its last joint free (§10).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "tow_sim/core/integration/simulator.h"

namespace tow_sim
{
namespace
{
struct Parted
{
  std::vector<Chain> chains;  // the vehicle side, and the cable left on the ship (if any)
  std::vector<double> y;      // their state
};

// The chains after a parting at element e's forward joint, from the whole cable's geometry, layout L and
// state y, the parted joint moving as `end` (docs/solver.md §9, §10).
Parted partedChains(const ChainGeometry& whole, const StateLayout& L, const std::vector<double>& y_whole, int element,
                    const ShipEndState& end)
{
  const int segments = whole.segments - element;
  // The vehicle side: the segments aft of the joint, its first keeping its section's length (the winch's
  // first segment stays on the ship); the cable forward of it stays on the ship: `element` segments, the
  // first as it was, the vehicle side's segments aft of it.
  ChainGeometry vehicle = whole, ship_side = whole;
  vehicle.segments = segments;
  vehicle.first_length = element == 0
                             ? whole.first_length
                             : (element < whole.segments ? whole.elementLength(element) : whole.nominal_length);
  vehicle.first_rate = vehicle.first_acceleration = 0.0;
  ship_side.segments = element;
  ship_side.end_body = false;
  ship_side.aft_segments = segments;
  ship_side.first_rate = ship_side.first_acceleration = 0.0;
  std::vector<Chain> chains{ Chain(vehicle, StateLayout{ 0, true }) };
  if (element > 0)
    chains.emplace_back(ship_side, StateLayout{ 0, false, chains.front().layout().end(), false });
  const StateLayout& V = chains.front().layout();
  std::vector<double> y(chains.back().layout().end());  // zeros: the payout rate, and all that is not set below
  V.positions(y) = L.positions(y_whole).rightCols(segments + 1);
  V.velocities(y) = L.velocities(y_whole).rightCols(segments + 1);
  V.cableOut(y) = element == 0 ? L.cableOut(y_whole) : vehicle.cableLength();
  V.freePosition(y) = end.p_W;
  V.freeVelocity(y) = end.v_W;
  V.setRollState(y, L.rollState(y_whole));
  if (element > 0)
  {
    chains.back().layout().positions(y) = L.positions(y_whole).leftCols(element);
    chains.back().layout().velocities(y) = L.velocities(y_whole).leftCols(element);
  }
  return { std::move(chains), std::move(y) };
}
}  // namespace

void Simulator::part(int element)
{
  if (parted())
    throw std::logic_error("part: the cable has parted already");
  const StateLayout L = layout();
  if (element < 0 || element >= L.joints)
    throw std::out_of_range("part: element " + std::to_string(element) + " is not in 0 .. " +
                            std::to_string(L.joints - 1));
  const ChainGeometry& whole = geometry();
  // The parted joint: the tow point, or the aft joint of the element forward of it.
  ShipEndState end = ship_(t_);
  if (element == 0)  // the cable there moves with the payout: the first element keeps its length from now on
    end.v_W += whole.first_rate * (L.positions(y_).col(0) - end.p_W).normalized();
  else
  {
    end.p_W = L.positions(y_).col(element - 1);
    end.v_W = L.velocities(y_).col(element - 1);
  }
  Parted parted = partedChains(whole, L, y_, element, end);
  data_.winch_command = 0.0;
  if (!slack_.empty())
    slack_.erase(slack_.begin(), slack_.begin() + std::min<std::size_t>(slack_.size(), element));
  y_.swap(parted.y);
  dydt_.assign(y_.size(), 0.0);
  chains_ = std::move(parted.chains);
  // The ship side's first joint no longer moves away from the tow point with the payout.
  if (chains_.size() > 1)
    chains_.back().project(*model_, ship_(t_), y_);
  refreshOutputs();
}

void Simulator::rejoin()
{
  parting_event_.reset();
  if (!parted())
    return;
  wholeCable();
  slack_.clear();
}

void Simulator::checkBreak(StepReport& report)
{
  const CableParams& cable = model_->cable();  // breaking_load: the first section's
  if (parted() || !cable.break_at_breaking_load || !cable.breaking_load)
    return;
  Eigen::Index worst = 0;
  const double largest = tensions().colwise().norm().maxCoeff(&worst);
  if (!(largest > *cable.breaking_load))
    return;
  PartingEvent parting;
  parting.t = t_;
  parting.joint = static_cast<int>(worst) + 1;
  parting.tension = largest;
  report.parting = parting_event_ = parting;
  part(static_cast<int>(worst));
}

Eigen::Matrix3Xd Simulator::shipSideJoints() const
{
  if (chains_.size() < 2)
    return Eigen::Matrix3Xd(3, 0);
  return chains_.back().jointPositions(ship_(t_), y_);
}

const Eigen::Matrix3Xd& Simulator::shipSideTensions() const
{
  static const Eigen::Matrix3Xd kNone(3, 0);
  return chains_.size() < 2 ? kNone : chains_.back().tensions();
}

double Simulator::shipTension() const
{
  for (const Chain& chain : chains_)
    if (!chain.freeFirst())  // the one that hangs from the ship
      return chain.tensions().cols() > 0 ? chain.tensions().col(0).norm() : 0.0;
  return 0.0;
}

}  // namespace tow_sim
