#include "tow_sim/core/chain/chain_model.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tow_sim
{
int ChainGeometry::sectionOf(int e) const
{
  if (!aft_sections)
    return 0;
  int aft = segments - 1 - e + aft_segments;  // the whole cable's segments aft of segment e
  for (size_t i = aft_sections->size(); i-- > 0;)
  {
    const int n = (*aft_sections)[i].segments;
    if (aft < n)
      return static_cast<int>(i) + 1;
    aft -= n;
  }
  return 0;
}

int ChainGeometry::aftSectionSegments() const
{
  int n = 0;
  if (aft_sections)
    for (const SegmentRun& run : *aft_sections)
      n += run.segments;
  return n;
}

double ChainGeometry::lengthAftOfFirst() const
{
  if (!aft_sections)
    return (segments - 1) * nominal_length;
  // Segments 1 .. nu-1 are the whole cable's aft_segments .. aft_segments + nu - 2 counted from its end.
  const int lo = aft_segments, hi = aft_segments + segments - 1;  // [lo, hi)
  double length = 0.0;
  int counted = 0, run_lo = 0;
  for (size_t i = aft_sections->size(); i-- > 0;)
  {
    const SegmentRun& run = (*aft_sections)[i];
    const int n = std::max(0, std::min(hi, run_lo + run.segments) - std::max(lo, run_lo));
    length += n * run.length;
    counted += n;
    run_lo += run.segments;
  }
  return length + (segments - 1 - counted) * nominal_length;
}

ChainModel::ChainModel(const CableParams& cable, std::shared_ptr<const EndBody> end_body, const Environment& env,
                       const NumericsParams& numerics, std::shared_ptr<const Seabed> seabed)
    : ChainModel(std::vector<CableParams>{ cable }, {}, std::move(end_body), env, numerics, std::move(seabed))
{
}

ChainModel::ChainModel(const std::vector<CableParams>& sections, const std::vector<JointBody>& bodies,
                       std::shared_ptr<const EndBody> end_body, const Environment& env, const NumericsParams& numerics,
                       std::shared_ptr<const Seabed> seabed)
    : bodies_(bodies), end_body_(std::move(end_body)), env_(env), numerics_(numerics), seabed_(std::move(seabed))
{
  if (sections.empty())
    throw std::invalid_argument("cable.sections: at least one section is required");
  for (size_t i = 0; i < sections.size(); ++i)
    validate(sections[i], sections.size() == 1 ? "cable" : "cable.sections[" + std::to_string(i) + "]");
  prepareWaves(env_);  // validates it
  validate(numerics_);
  if (!end_body_)
    throw std::invalid_argument("end_element: no end body given (element nu+1 is required)");
  auto runs = std::make_shared<std::vector<SegmentRun>>();
  for (size_t i = 0; i < sections.size(); ++i)
  {
    if (sections[i].elastic() != sections[0].elastic())
      throw std::invalid_argument("cable.sections[" + std::to_string(i) +
                                  "].axial_stiffness: every section must be elastic or every one rigid");
    if (sections[i].depressor && i == 0)
      throw std::invalid_argument(
          "cable.sections[0].depressor: the first section is the cable the tow point pulls "
          "and the winch pays out; a depressor follows a section of cable");
    sections_.push_back(
        { sections[i], CableSegmentModel::fromParams(sections[i], env_, numerics_),
          sections[i].depressor ? std::make_shared<const Depressor>(*sections[i].depressor, numerics_) : nullptr });
    segments_ += sections[i].segments;
    bends_ = bends_ || sections[i].bending_stiffness > 0.0;
    if (i > 0)
      runs->push_back({ sections[i].segments, sections_.back().segment.length });
  }
  if (!runs->empty())
    aft_sections_ = runs;
  for (size_t i = 0; i < bodies_.size(); ++i)
    validate(bodies_[i], i, segments_);
}

ChainGeometry ChainModel::initialGeometry() const
{
  ChainGeometry g;
  g.segments = segments_;
  g.nominal_length = segment().length;
  g.first_length = segment().length;
  g.end_length = end_body_->length();
  g.end_roll = end_body_->rolls();
  g.aft_sections = aft_sections_;
  return g;
}

ChainData ChainModel::initialData(double t) const
{
  ChainData data;
  data.environment = env_;
  data.actuators = end_body_->restingActuators(t);
  return data;
}

CableSegmentModel ChainModel::segmentModel(int e, const ChainGeometry& geometry) const
{
  return e == 0 ? firstSegment(geometry) : sections_[static_cast<size_t>(geometry.sectionOf(e))].segment;
}

CableSegmentModel ChainModel::firstSegment(const ChainGeometry& geometry) const
{
  const CableSegmentModel& nominal = sections_[static_cast<size_t>(geometry.sectionOf(0))].segment;
  if (geometry.first_length == nominal.length)
    return nominal;
  const double scale = geometry.first_length / nominal.length;
  CableSegmentModel first = nominal;
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
  {
    const CableSection& section = sections_[static_cast<size_t>(geometry.sectionOf(e))];
    if (section.depressor)
      section.depressor->dynamics(t, k, data.environment, out);
    else
      cableSegmentDynamics(section.segment, t, k, data.environment, out);
  }
  else
    end_body_->dynamics(t, k, data.environment, data.actuators, out);
  if (with_contact && seabed())
    addContact(e, k, geometry, out);
}

double ChainModel::jointBendingStiffness(int e, const ChainGeometry& geometry) const
{
  const double ei_f = segmentCable(e - 1, geometry).bending_stiffness,
               ei_a = segmentCable(e, geometry).bending_stiffness;
  if (ei_f <= 0.0 || ei_a <= 0.0)
    return 0.0;
  return 1.0 / (0.5 * geometry.elementLength(e - 1) / ei_f + 0.5 * geometry.elementLength(e) / ei_a);
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

void validate(const JointBody& body, size_t index, int segments)
{
  const std::string name = "cable.bodies[" + std::to_string(index) + "].";
  if (body.joint < 0 || body.joint >= segments)
    throw std::invalid_argument(name + "joint = " + std::to_string(body.joint) + " must be in 0 .. " +
                                std::to_string(segments - 1) + " (segments aft of it; 0: the bail)");
  const std::pair<const char*, double> values[] = { { "mass", body.mass },
                                                    { "displaced_volume", body.displaced_volume },
                                                    { "drag_area", body.drag_area },
                                                    { "added_mass", body.added_mass } };
  for (const auto& [key, value] : values)
    if (!(value >= 0.0 && value <= 1e9))
      throw std::invalid_argument(name + key + " = " + std::to_string(value) + " must be in 0 .. 1e9");
}

Eigen::Vector3d JointBody::force(const Environment& env, double t, const Eigen::Vector3d& x_W,
                                 const Eigen::Vector3d& v_W) const
{
  const WaveKinematics flow = env.flowAt(x_W, t);
  const Eigen::Vector3d u = v_W - flow.velocity_W;
  const double rho = env.water_density, displaced = rho * displaced_volume;
  return Eigen::Vector3d(0.0, 0.0, (displaced - mass) * env.gravity) - 0.5 * rho * drag_area * u.norm() * u +
         (displaced + added_mass) * flow.acceleration_W;
}

Eigen::Matrix3d JointBody::forceVelocityJacobian(const Environment& env, double t, const Eigen::Vector3d& x_W,
                                                 const Eigen::Vector3d& v_W) const
{
  const Eigen::Vector3d u = v_W - env.flowAt(x_W, t).velocity_W;
  const double speed = u.norm();
  Eigen::Matrix3d d = speed * Eigen::Matrix3d::Identity();
  if (speed > 0.0)
    d += u * u.transpose() / speed;
  return -0.5 * env.water_density * drag_area * d;
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
