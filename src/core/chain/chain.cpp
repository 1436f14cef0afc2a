#include "tow_sim/core/chain/chain.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tow_sim
{
Chain::Chain(const ChainGeometry& geometry, const StateLayout& layout) : geometry_(geometry), layout_(layout)
{
  layout_.joints = geometry_.jointCount();
  layout_.roll = geometry_.rollingEnd();
  tensions_.setZero(3, layout_.joints);
  accelerations_.setZero(3, layout_.joints);
}

ShipEndState Chain::firstJoint(const ShipEndState& ship, const StateVector& y) const
{
  if (!layout_.free)
    return ship;
  ShipEndState end;
  end.p_W = layout_.freePosition(y);
  end.v_W = layout_.freeVelocity(y);
  return end;
}

void Chain::derivative(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                       const ShipEndState& ship, const StateVector& y, StateVector& dydt) const
{
  const StateLayout& L = layout_;
  L.positions(dydt) = L.velocities(y);
  Eigen::Map<Eigen::Matrix3Xd> a = L.velocities(dydt);
  solver_.setEndRoll(L.rollState(y));
  if (!L.free)
    solver_.solve(model, geometry, data, t, ship, L.positions(y), L.velocities(y), a);
  else
  {
    const ShipEndState end = firstJoint(ship, y);
    L.freePosition(dydt) = L.freeVelocity(y);
    L.freeVelocity(dydt) = solver_.solveFree(model, geometry, data, t, end, L.positions(y), L.velocities(y), a, nullptr,
                                             nullptr, freeEndContact(model, geometry, end));
  }
  if (L.roll)
    rollDerivative(model, data, t, ship, y, a, dydt);
}

void Chain::refresh(const ChainModel& model, const ChainData& data, double t, const ShipEndState& ship,
                    const StateVector& y, StateVector& dydt)
{
  const StateLayout& L = layout_;
  tensions_.resize(3, L.joints);
  accelerations_.resize(3, L.joints);
  solver_.setEndRoll(L.rollState(y));
  if (L.free)
  {
    const ShipEndState end = firstJoint(ship, y);
    L.freePosition(dydt) = L.freeVelocity(y);
    L.freeVelocity(dydt) =
        solver_.solveFree(model, geometry_, data, t, end, L.positions(y), L.velocities(y), accelerations_, &tensions_,
                          &multipliers_, freeEndContact(model, geometry_, end));
  }
  else
    solver_.solve(model, geometry_, data, t, ship, L.positions(y), L.velocities(y), accelerations_, &tensions_,
                  &multipliers_);
  L.positions(dydt) = L.velocities(y);
  L.velocities(dydt) = accelerations_;
  if (L.roll)
    rollDerivative(model, data, t, ship, y, accelerations_, dydt);
}

// physics.md (P57)-(P58): the end body's roll angle and spin rates, from its joints' accelerations a (and the
// first joint's: the ship's, or a free one's in dydt).
void Chain::rollDerivative(const ChainModel& model, const ChainData& data, double t, const ShipEndState& ship,
                           const StateVector& y, const Eigen::Ref<const Eigen::Matrix3Xd>& a, StateVector& dydt) const
{
  const StateLayout& L = layout_;
  const int e = L.joints - 1;
  const Eigen::Vector2d rates =
      model.endBody().rollRates(t, elementKinematics(e, ship, y), data.environment, data.actuators,
                                endForwardAcceleration(ship, a, dydt), a.col(e));
  L.rollAngle(dydt) = rates.x();
  L.rollRate(dydt) = rates.y();
}

Eigen::Vector3d Chain::endForwardAcceleration(const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& a,
                                              const StateVector& dydt) const
{
  const StateLayout& L = layout_;
  const int e = L.joints - 1;
  return e > 0 ? Eigen::Vector3d(a.col(e - 1)) : (L.free ? Eigen::Vector3d(L.freeVelocity(dydt)) : ship.a_W);
}

// docs/solver.md (S29): d(dp/dt)/dphi and d(dp/dt)/dp by central differences, the joints' accelerations held.
Eigen::Vector2d Chain::spinAccelerationDerivatives(const ChainModel& model, const ChainData& data, double t,
                                                   const ShipEndState& ship, const StateVector& y,
                                                   const StateVector& dydt) const
{
  const StateLayout& L = layout_;
  const int e = L.joints - 1;
  const auto a = L.velocities(dydt);
  const Eigen::Vector3d a_f = endForwardAcceleration(ship, a, dydt);
  const ElementKinematics k = elementKinematics(e, ship, y);
  auto spin = [&](double droll, double drate)
  {
    ElementKinematics kk = k;
    kk.roll += droll;
    kk.roll_rate += drate;
    return model.endBody().rollRates(t, kk, data.environment, data.actuators, a_f, a.col(e)).y();
  };
  const double h_angle = 1e-5, h_rate = 1e-5 * std::max(1.0, std::abs(k.roll_rate));
  return { (spin(h_angle, 0.0) - spin(-h_angle, 0.0)) / (2.0 * h_angle),
           (spin(0.0, h_rate) - spin(0.0, -h_rate)) / (2.0 * h_rate) };
}

// (S26): joint by joint from the first, along each element's axis only.
void Chain::project(const ChainModel& model, const ShipEndState& ship, StateVector& y) const
{
  const StateLayout& L = layout_;
  auto x = L.positions(y);
  auto v = L.velocities(y);
  const ShipEndState first_joint = firstJoint(ship, y);
  Eigen::Vector3d x_f = first_joint.p_W;
  Eigen::Vector3d v_f = first_joint.v_W;
  const int first = firstKeptElement(model);
  for (int e = 0; e < L.joints; ++e)
  {
    if (e < first)
    {
      x_f = x.col(e);
      v_f = v.col(e);
      continue;
    }
    const Eigen::Vector3d s = (x.col(e) - x_f).normalized();
    x.col(e) = x_f + geometry_.elementLength(e) * s;
    // Relative velocity along the element: none, but the winch's rate on the first segment.
    const double along = e == 0 ? geometry_.first_rate : 0.0;
    v.col(e) -= (s.dot(v.col(e) - v_f) - along) * s;
    x_f = x.col(e);
    v_f = v.col(e);
  }
}

double Chain::lengthError(const ChainModel& model, const ShipEndState& ship, const StateVector& y) const
{
  return maxRelativeLengthError(geometry_, firstJoint(ship, y).p_W, layout_.positions(y), firstKeptElement(model));
}

double Chain::largestRelativeSpeed(const ShipEndState& ship, const StateVector& y) const
{
  if (layout_.joints == 0)
    return 0.0;
  return (layout_.velocities(y).colwise() - firstJoint(ship, y).v_W).colwise().norm().maxCoeff();
}

Eigen::Matrix3Xd Chain::jointPositions(const ShipEndState& ship, const StateVector& y) const
{
  Eigen::Matrix3Xd p(3, layout_.joints + 1);
  p.col(0) = firstJoint(ship, y).p_W;
  p.rightCols(layout_.joints) = layout_.positions(y);
  return p;
}

ElementKinematics Chain::elementKinematics(int e, const ShipEndState& ship, const StateVector& y) const
{
  if (e < 0 || e >= layout_.joints)
    throw std::out_of_range("elementKinematics: element " + std::to_string(e) + " is not in 0 .. " +
                            std::to_string(layout_.joints - 1));
  const auto x = layout_.positions(y);
  const auto v = layout_.velocities(y);
  const ShipEndState first = firstJoint(ship, y);
  const Eigen::Vector3d x_f = e == 0 ? first.p_W : Eigen::Vector3d(x.col(e - 1));
  const Eigen::Vector3d v_f = e == 0 ? first.v_W : Eigen::Vector3d(v.col(e - 1));
  ElementKinematics k = ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
  if (layout_.roll && e == layout_.joints - 1)
  {
    k.roll = layout_.rollAngle(y);
    k.roll_rate = layout_.rollRate(y);
  }
  return k;
}

const Seabed* Chain::freeEndPenalty(const ChainModel& model, const ChainGeometry& geometry, double& stiffness,
                                    double& damping) const
{
  const Seabed* bottom = model.seabed();
  if (!bottom || geometry.segments == 0)
    return nullptr;
  const double carried = 0.5 * geometry.elementLength(0);  // as each segment's aft joint (ChainModel::forEachContact)
  stiffness = bottom->params().stiffness * carried;
  damping = bottom->params().damping * carried;
  return bottom;
}

Eigen::Vector3d Chain::freeEndContact(const ChainModel& model, const ChainGeometry& geometry,
                                      const ShipEndState& end) const
{
  double stiffness = 0.0, damping = 0.0;
  const Seabed* bottom = freeEndPenalty(model, geometry, stiffness, damping);
  return bottom ? bottom->contactForce(end.p_W, end.v_W, stiffness, damping) : Eigen::Vector3d::Zero();
}

void Chain::freeEndContactJacobian(const ChainModel& model, const ShipEndState& end, Eigen::Matrix3d& dF_dx,
                                   Eigen::Matrix3d& dF_dv) const
{
  dF_dx.setZero();
  dF_dv.setZero();
  double stiffness = 0.0, damping = 0.0;
  if (const Seabed* bottom = freeEndPenalty(model, geometry_, stiffness, damping))
    bottom->contactJacobian(end.p_W, end.v_W, stiffness, damping, dF_dx, dF_dv);
}

}  // namespace tow_sim
