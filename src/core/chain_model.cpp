#include "tow_sim/core/chain_model.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace tow_sim
{
ChainModel::ChainModel(const CableParams& cable, std::shared_ptr<const EndBody> end_body, const Environment& env,
                       const NumericsParams& numerics)
    : cable_(cable), end_body_(std::move(end_body)), env_(env), numerics_(numerics)
{
  validate(cable_);
  validate(env_);
  validate(numerics_);
  if (!end_body_)
    throw std::invalid_argument("end_element: no end body given (element nu+1 is required)");
  segment_ = CableSegmentModel::fromParams(cable_, env_, numerics_);
  first_ = segment_;
  segments_ = cable_.segments;
}

void ChainModel::setFirstSegment(double length, double rate, double acceleration)
{
  if (!(length > 0.0) || !std::isfinite(length) || !std::isfinite(rate) || !std::isfinite(acceleration))
    throw std::invalid_argument("ChainModel: the first segment needs a finite length > 0, rate and acceleration");
  first_rate_ = rate;
  first_acceleration_ = acceleration;
  if (length == first_.length)
    return;
  const double scale = length / segment_.length;
  first_ = segment_;
  first_.length = length;
  first_.mass *= scale;
  first_.net_weight *= scale;
  first_.added_mass *= scale;
}

void ChainModel::elementDynamics(int e, double t, const ElementKinematics& k, BodyDynamics& out,
                                 bool with_contact) const
{
  if (e == 0 && segments_ > 0)
  {
    // While the winch runs, the cable of the first segment moves along it with its aft joint (it leaves
    // the ship at L' along s): through the water it moves L'/2 faster along s than the segment's
    // geometric midpoint. That changes only the tangential drag; the normal flow and the rotation are
    // the same.
    if (first_rate_ != 0.0)
      cableSegmentDynamics(first_, ElementKinematics::fromJoints(k.x_f, k.x_a, k.v_f + first_rate_ * k.s, k.v_a), env_,
                           out);
    else
      cableSegmentDynamics(first_, k, env_, out);
  }
  else if (e < segments_)
    cableSegmentDynamics(segment_, k, env_, out);
  else
    end_body_->dynamics(t, k, env_, out);
  const Seabed* bottom = with_contact ? seabed() : nullptr;
  if (!bottom)
    return;
  // Contact forces at points of the element, moved to its CG. A cable segment carries its aft joint
  // (so each joint x_2 .. x_{nu+1} once) with the stiffness of the cable that joint stands for: half of
  // each neighbouring segment (the bail: half the last one); the end body its own contact points.
  const Eigen::Vector3d x_G = k.pointAt(out.cg_fraction);
  auto add = [&](double eta, double stiffness, double damping)
  {
    const Eigen::Vector3d p = k.pointAt(eta);
    const Eigen::Vector3d f = bottom->contactForce(p, k.velocityAt(eta), stiffness, damping);
    out.wrench.head<3>() += f;
    out.wrench.tail<3>() += (p - x_G).cross(f);
  };
  const SeabedParams& sp = bottom->params();
  if (e < segments_)
  {
    const double carried = 0.5 * (elementLength(e) + (e + 1 < segments_ ? elementLength(e + 1) : 0.0));
    add(1.0, sp.stiffness * carried, sp.damping * carried);
    return;
  }
  for (double eta : end_body_->contactFractions())
    add(eta, sp.vehicle_stiffness, sp.vehicle_damping);
}

void ChainModel::setLayout(int segments, double first_length)
{
  if (segments < 1)
    throw std::invalid_argument("ChainModel: at least one cable segment is needed");
  segments_ = segments;
  setFirstSegment(first_length, first_rate_, first_acceleration_);
}

void ChainModel::setCurrent(const Eigen::Vector3d& current_W)
{
  Environment candidate = env_;
  candidate.current_W = current_W;
  validate(candidate);
  env_ = candidate;
}

void ChainModel::setCurrentProfile(const std::vector<CurrentSample>& profile)
{
  Environment candidate = env_;
  candidate.current_profile = profile;
  validate(candidate);
  env_ = candidate;
}

}  // namespace tow_sim
