// The cable parting (cable.break_at_breaking_load): the chain goes on as its vehicle side, from a free first
// joint (ChainSolver::solveFree, docs/solver.md §9), whose position and velocity join the state.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "tow_sim/core/integration/simulator.h"

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
  // The cable forward of the joint stays on the ship: `element` segments, the first as it was.
  ship_side_ = data_.geometry;
  ship_side_.segments = element;
  ship_side_.end_body = false;
  ship_side_.aft_segments = segments;  // the whole cable's segments aft of it: the vehicle side's
  ship_side_.first_rate = ship_side_.first_acceleration = 0.0;
  const StateLayout next{ segments + 1, true, element };
  StateVector y(next.size());
  next.positions(y) = L.positions(y_).rightCols(segments + 1);
  next.velocities(y) = L.velocities(y_).rightCols(segments + 1);
  // The vehicle side's first segment keeps its section's length (the winch's first segment stays on the ship).
  const double first_length = element == 0 ? data_.geometry.first_length
                                           : (element < data_.geometry.segments ? data_.geometry.elementLength(element)
                                                                                : data_.geometry.nominal_length);
  next.payoutRate(y) = 0.0;
  next.freePosition(y) = end.p_W;
  next.freeVelocity(y) = end.v_W;
  next.shipSidePositions(y) = L.positions(y_).leftCols(element);
  next.shipSideVelocities(y) = L.velocities(y_).leftCols(element);
  data_.geometry.segments = segments;
  data_.geometry.first_length = first_length;
  next.cableOut(y) = element == 0 ? L.cableOut(y_) : data_.geometry.cableLength();
  data_.geometry.first_rate = data_.geometry.first_acceleration = 0.0;
  data_.winch_command = 0.0;
  if (!slack_.empty())
    slack_.erase(slack_.begin(), slack_.begin() + std::min<std::size_t>(slack_.size(), element));
  y_.swap(y);
  dydt_.assign(y_.size(), 0.0);
  free_ = true;
  projectShipSide(t_);  // its first joint no longer moves away from the tow point with the payout
  refreshOutputs();
}

void Simulator::rejoin()
{
  parting_event_.reset();
  if (!free_)
    return;
  free_ = false;
  clearShipSide();
  data_.geometry = model_->initialGeometry();
  y_.assign(layout().size(), 0.0);
  layout().cableOut(y_) = model_->cableLength();
  dydt_.assign(y_.size(), 0.0);
  slack_.clear();
}

void Simulator::checkBreak(StepReport& report)
{
  const CableParams& cable = model_->cable();  // breaking_load: the first section's
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

// The cable left on the ship (docs/solver.md §10): the prescribed sweep over its segments, from the ship's
// tow point, its last joint free.
ChainGeometry Simulator::noShipSide()
{
  ChainGeometry g;
  g.segments = 0;
  g.end_body = false;
  return g;
}

Eigen::Vector3d Simulator::freeEndContact(const ChainGeometry& geometry, const ShipEndState& end) const
{
  const Seabed* bottom = model_->seabed();
  if (!bottom || geometry.segments == 0)
    return Eigen::Vector3d::Zero();
  const double carried = 0.5 * geometry.elementLength(0);  // as each segment's aft joint (ChainModel::forEachContact)
  return bottom->contactForce(end.p_W, end.v_W, bottom->params().stiffness * carried,
                              bottom->params().damping * carried);
}

void Simulator::clearShipSide()
{
  ship_side_ = noShipSide();
  ship_side_tensions_.resize(3, 0);
}

void Simulator::shipSideDerivative(double t, const StateVector& y, StateVector& dydt) const
{
  const StateLayout L = layout();
  if (L.ship_side == 0)
    return;
  L.shipSidePositions(dydt) = L.shipSideVelocities(y);
  ship_side_solver_.solve(*model_, ship_side_, data_, t, ship_(t), L.shipSidePositions(y), L.shipSideVelocities(y),
                          L.shipSideVelocities(dydt));
}

void Simulator::shipSideOutputs()
{
  const StateLayout L = layout();
  ship_side_tensions_.resize(3, L.ship_side);
  if (L.ship_side == 0)
    return;
  L.shipSidePositions(dydt_) = L.shipSideVelocities(y_);
  ship_side_solver_.solve(*model_, ship_side_, data_, t_, ship_(t_), L.shipSidePositions(y_), L.shipSideVelocities(y_),
                          L.shipSideVelocities(dydt_), &ship_side_tensions_);
}

void Simulator::projectShipSide(double t)
{
  const StateLayout L = layout();
  if (L.ship_side == 0 || model_->elastic())  // an elastic cable's segments stretch: no length to keep
    return;
  auto x = L.shipSidePositions(y_);
  auto v = L.shipSideVelocities(y_);
  const ShipEndState ship = ship_(t);
  Eigen::Vector3d x_f = ship.p_W, v_f = ship.v_W;
  for (int e = 0; e < L.ship_side; ++e)
  {
    const Eigen::Vector3d s = (x.col(e) - x_f).normalized();
    x.col(e) = x_f + ship_side_.elementLength(e) * s;
    v.col(e) -= s.dot(v.col(e) - v_f) * s;
    x_f = x.col(e);
    v_f = v.col(e);
  }
}

double Simulator::shipSideLengthError() const
{
  const StateLayout L = layout();
  if (L.ship_side == 0 || model_->elastic())
    return 0.0;
  return maxRelativeLengthError(ship_side_, ship_(t_).p_W, L.shipSidePositions(y_));
}

Eigen::Matrix3Xd Simulator::shipSideJoints() const
{
  const StateLayout L = layout();
  if (L.ship_side == 0)
    return Eigen::Matrix3Xd(3, 0);
  Eigen::Matrix3Xd p(3, L.ship_side + 1);
  p.col(0) = ship_(t_).p_W;
  p.rightCols(L.ship_side) = L.shipSidePositions(y_);
  return p;
}

double Simulator::shipTension() const
{
  if (!free_)
    return tensions_.col(0).norm();
  return ship_side_tensions_.cols() > 0 ? ship_side_tensions_.col(0).norm() : 0.0;
}

}  // namespace tow_sim
