#include "tow_sim/core/chain_model.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace tow_sim
{
ChainModel::ChainModel(const CableParams& cable, std::shared_ptr<const EndBody> end_body, const Environment& env,
                       const NumericsParams& numerics, std::shared_ptr<const Seabed> seabed)
    : cable_(cable), end_body_(std::move(end_body)), env_(env), numerics_(numerics), seabed_(std::move(seabed))
{
  validate(cable_);
  prepareWaves(env_);  // validates it
  validate(numerics_);
  if (!end_body_)
    throw std::invalid_argument("end_element: no end body given (element nu+1 is required)");
  segment_ = CableSegmentModel::fromParams(cable_, env_, numerics_);
}

ChainGeometry ChainModel::initialGeometry() const
{
  ChainGeometry g;
  g.segments = cable_.segments;
  g.nominal_length = segment_.length;
  g.first_length = segment_.length;
  g.end_length = end_body_->length();
  return g;
}

ChainData ChainModel::initialData(double t) const
{
  ChainData data;
  data.geometry = initialGeometry();
  data.environment = env_;
  data.actuators = end_body_->restingActuators(t);
  return data;
}

CableSegmentModel ChainModel::firstSegment(const ChainGeometry& geometry) const
{
  if (geometry.first_length == segment_.length)
    return segment_;
  const double scale = geometry.first_length / segment_.length;
  CableSegmentModel first = segment_;
  first.length = geometry.first_length;
  first.mass *= scale;
  first.net_weight *= scale;
  first.added_mass *= scale;
  first.displaced_mass *= scale;
  return first;
}

void ChainModel::elementDynamics(int e, double t, const ElementKinematics& k, const ChainGeometry& geometry,
                                 const ChainData& data, BodyDynamics& out, bool with_contact) const
{
  if (e == 0 && geometry.segments > 0)
  {
    // While the winch runs, the cable of the first segment moves along it with its aft joint (it leaves
    // the ship at L' along s): through the water it moves L'/2 faster along s than the segment's
    // geometric midpoint. That changes only the tangential drag; the normal flow and the rotation are
    // the same.
    const CableSegmentModel first = firstSegment(geometry);
    if (geometry.first_rate != 0.0)
      cableSegmentDynamics(first, t,
                           ElementKinematics::fromJoints(k.x_f, k.x_a, k.v_f + geometry.first_rate * k.s, k.v_a),
                           data.environment, out);
    else
      cableSegmentDynamics(first, t, k, data.environment, out);
  }
  else if (e < geometry.segments)
    cableSegmentDynamics(segment_, t, k, data.environment, out);
  else
    end_body_->dynamics(t, k, data.environment, data.actuators, out);
  if (with_contact && seabed())
    addContact(e, k, geometry, out);
}

void ChainModel::addContact(int e, const ElementKinematics& k, const ChainGeometry& geometry, BodyDynamics& out) const
{
  // Contact forces at the element's contact points, moved to its CG.
  const Seabed& bottom = *seabed();
  const Eigen::Vector3d x_G = k.pointAt(out.cg_fraction);
  forEachContact(e, geometry,
                 [&](double eta, double stiffness, double damping)
                 {
                   const Eigen::Vector3d p = k.pointAt(eta);
                   const Eigen::Vector3d f = bottom.contactForce(p, k.velocityAt(eta), stiffness, damping);
                   out.wrench.head<3>() += f;
                   out.wrench.tail<3>() += (p - x_G).cross(f);
                 });
}

Eigen::Vector3d ChainModel::segmentContactForce(int e, const ElementKinematics& k, const ChainGeometry& geometry) const
{
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  if (seabed() && e < geometry.segments)
    forEachContact(e, geometry,
                   [&](double eta, double stiffness, double damping)
                   { f += seabed()->contactForce(k.pointAt(eta), k.velocityAt(eta), stiffness, damping); });
  return f;
}

void setCurrent(ChainData& data, const Eigen::Vector3d& current_W)
{
  Environment candidate = data.environment;
  candidate.current_W = current_W;
  validate(candidate);
  data.environment = candidate;
}

void setWaveTime(ChainData& data, double wave_time)
{
  if (!std::isfinite(wave_time))
    throw std::invalid_argument("wave time origin = " + std::to_string(wave_time) + " must be finite [s]");
  data.environment.wave_time = wave_time;
}

void setCurrentProfile(ChainData& data, const std::vector<CurrentSample>& profile)
{
  Environment candidate = data.environment;
  candidate.current_profile = profile;
  validate(candidate);
  data.environment = candidate;
}

}  // namespace tow_sim
