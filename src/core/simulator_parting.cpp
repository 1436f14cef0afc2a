// The cable parting (cable.break_at_breaking_load): the chain goes on as its vehicle side, from a free first
// joint (ChainSolver::solveFree, docs/solver.md §9), whose position and velocity join the state.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "tow_sim/core/simulator.h"

namespace tow_sim
{
ShipEndState Simulator::towPoint(double t, const StateVector& y) const
{
  if (!free_)
    return ship_(t);
  const StateLayout L = layout();
  ShipEndState end;
  end.p_W = L.freePosition(y);
  end.v_W = L.freeVelocity(y);
  return end;
}

void Simulator::part(int element)
{
  if (free_)
    throw std::logic_error("part: the cable has parted already");
  const StateLayout L = layout();
  if (element < 0 || element >= L.joints)
    throw std::out_of_range("part: element " + std::to_string(element) + " is not in 0 .. " +
                            std::to_string(L.joints - 1));
  // The parted joint: the tow point, or the aft joint of the element forward of it.
  ShipEndState end = ship_(t_);
  if (element == 0)  // the cable there moves with the payout: the first element keeps its length from now on
    end.v_W += data_.geometry.first_rate * (L.positions(y_).col(0) - end.p_W).normalized();
  else
  {
    end.p_W = L.positions(y_).col(element - 1);
    end.v_W = L.velocities(y_).col(element - 1);
  }
  const int segments = data_.geometry.segments - element;
  const StateLayout next{ segments + 1, true };
  StateVector y(next.size());
  next.positions(y) = L.positions(y_).rightCols(segments + 1);
  next.velocities(y) = L.velocities(y_).rightCols(segments + 1);
  next.cableOut(y) = element == 0 ? L.cableOut(y_) : segments * data_.geometry.nominal_length;
  next.payoutRate(y) = 0.0;
  next.freePosition(y) = end.p_W;
  next.freeVelocity(y) = end.v_W;
  data_.geometry.segments = segments;
  if (element > 0)
    data_.geometry.first_length = data_.geometry.nominal_length;
  data_.geometry.first_rate = data_.geometry.first_acceleration = 0.0;
  data_.winch_command = 0.0;
  if (!slack_.empty())
    slack_.erase(slack_.begin(), slack_.begin() + std::min<std::size_t>(slack_.size(), element));
  y_.swap(y);
  dydt_.assign(y_.size(), 0.0);
  free_ = true;
  refreshOutputs();
}

void Simulator::rejoin()
{
  parting_event_.reset();
  if (!free_)
    return;
  free_ = false;
  data_.geometry = model_->initialGeometry();
  y_.assign(layout().size(), 0.0);
  layout().cableOut(y_) = model_->cableLength();
  dydt_.assign(y_.size(), 0.0);
  slack_.clear();
}

void Simulator::checkBreak(StepReport& report)
{
  const CableParams& cable = model_->cable();
  if (free_ || !cable.break_at_breaking_load || !cable.breaking_load)
    return;
  Eigen::Index worst = 0;
  const double largest = tensions_.colwise().norm().maxCoeff(&worst);
  if (!(largest > *cable.breaking_load))
    return;
  PartingEvent parting;
  parting.t = t_;
  parting.joint = static_cast<int>(worst) + 1;
  parting.tension = largest;
  report.parting = parting_event_ = parting;
  part(static_cast<int>(worst));
}

}  // namespace tow_sim
