#include "tow_sim/core/analysis/strumming.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
// The mode with the longest power-in length among the segments [first, last) of one span: each segment adds
// its length to every mode from its lowest to its highest (a sweep over the band edges, O(n log n)).
void findDominantMode(const std::vector<StrummingSegment>& segments, const std::vector<double>& lengths, size_t first,
                      size_t last, StrummingSpan& span)
{
  std::map<long, double> change;  // at mode k the power-in length changes by this
  for (size_t i = first; i < last; ++i)
  {
    const StrummingSegment& s = segments[i];
    if (s.lowest_mode == 0)
      continue;
    change[s.lowest_mode] += lengths[i];
    change[s.highest_mode + 1] -= lengths[i];
    span.lowest_mode = span.lowest_mode == 0 ? s.lowest_mode : std::min(span.lowest_mode, s.lowest_mode);
    span.highest_mode = std::max(span.highest_mode, s.highest_mode);
  }
  double running = 0.0;
  for (const auto& [mode, delta] : change)
  {
    running += delta;
    if (running > span.power_in_length + 1e-9 * (span.end - span.start))
    {
      span.power_in_length = running;
      span.dominant_mode = mode;
    }
  }
  if (span.dominant_mode > 0)
    span.dominant_frequency = span.dominant_mode * span.fundamental;
}
}  // namespace

namespace
{
// Each segment's flow, shedding frequency, tension and wave speed (P54), and the span it lies in: point bodies
// split the cable into spans. Fills lengths with the segments' lengths.
void describeSegments(const ChainModel& model, const ChainGeometry& geometry, double t, const Eigen::Matrix3Xd& joints,
                      const Eigen::Matrix3Xd& velocities, const Eigen::Matrix3Xd& tensions,
                      std::vector<StrummingSegment>& segments, std::vector<double>& lengths)
{
  const Environment& env = model.environment();
  const int nu = geometry.segments;
  segments.assign(static_cast<size_t>(nu), StrummingSegment());
  lengths.assign(static_cast<size_t>(nu), 0.0);
  double along = 0.0;
  int span = 0;
  for (int e = 0; e < nu; ++e)
  {
    const CableParams& cable = model.segmentCable(e, geometry);
    StrummingSegment& seg = segments[static_cast<size_t>(e)];
    const Eigen::Vector3d x_f = joints.col(e), x_a = joints.col(e + 1);
    const double d = (x_a - x_f).norm();  // > 0 but for a fully slack elastic segment, which has no axis to shed off
    const Eigen::Vector3d s = d > 0.0 ? Eigen::Vector3d((x_a - x_f) / d) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d u = 0.5 * (velocities.col(e) + velocities.col(e + 1)) - env.flowOver(x_f, x_a, t).velocity_W;
    // A depressor is a rigid body, not a string, and heavy: a span of its own, which neither sheds nor rings.
    const bool depressor = model.depressorAt(e, geometry) != nullptr;
    if (depressor && e > 0)
      ++span;
    seg.section = geometry.sectionOf(e);
    seg.span = span;
    seg.arc_length = along + 0.5 * d;
    seg.depth = -0.5 * (x_f.z() + x_a.z());
    // A faired segment sheds no vortices (its fairing is there to stop them): it strums not, but rings.
    seg.normal_speed = d > 0.0 && !depressor && !cable.loading ? (u - u.dot(s) * s).norm() : 0.0;
    seg.shedding_frequency = cable.strouhal_number * seg.normal_speed / cable.diameter;
    // The tension at its aft end: the next element's, and a point body's load there taken by this segment (the
    // body at rest relative to the ship: T_aft = T_{e+1} - F_body).
    const JointBody* body = model.bodyAft(e, geometry);
    const Eigen::Vector3d t_aft =
        body ? Eigen::Vector3d(tensions.col(e + 1) - body->force(env, t, x_a, velocities.col(e + 1)))
             : Eigen::Vector3d(tensions.col(e + 1));
    seg.tension = 0.5 * (tensions.col(e).norm() + t_aft.norm());
    // The string's mass per length: the cable's and its added mass (the segment model's, per metre).
    const CableSegmentModel model_e = model.segmentModel(e, geometry);
    const double m_t = (model_e.mass + model_e.added_mass) / model_e.length;
    seg.wave_speed = seg.tension > 0.0 && !depressor ? std::sqrt(seg.tension / m_t) : 0.0;
    seg.drag_amplification = cable.normalDragAmplification();
    lengths[static_cast<size_t>(e)] = d;
    along += d;
    if (body || depressor)  // the next span begins
      ++span;
  }
}

// Span k of the segments [first, last): its travel time and fundamental, each segment's band of its modes
// f_s (1 - b) <= j f_1 <= f_s (1 + b), and the dominant mode.
StrummingSpan describeSpan(std::vector<StrummingSegment>& segments, const std::vector<double>& lengths, size_t first,
                           size_t last, double bandwidth)
{
  StrummingSpan sp;
  sp.start = segments[first].arc_length - 0.5 * lengths[first];
  sp.end = segments[last - 1].arc_length + 0.5 * lengths[last - 1];
  for (size_t i = first; i < last; ++i)
    if (segments[i].wave_speed > 0.0)  // a slack segment carries no transverse wave
      sp.travel_time += lengths[i] / segments[i].wave_speed;
  if (sp.travel_time <= 0.0)
    return sp;
  sp.fundamental = 0.5 / sp.travel_time;
  for (size_t i = first; i < last; ++i)
  {
    StrummingSegment& seg = segments[i];
    const double high = seg.shedding_frequency * (1.0 + bandwidth) / sp.fundamental;
    if (seg.wave_speed <= 0.0 || !(seg.shedding_frequency > 0.0) || !(high < 1e15))
      continue;
    const long lo =
        std::max(1L, static_cast<long>(std::ceil(seg.shedding_frequency * (1.0 - bandwidth) / sp.fundamental - 1e-12)));
    const long hi = static_cast<long>(std::floor(high + 1e-12));
    if (lo <= hi)
    {
      seg.lowest_mode = lo;
      seg.highest_mode = hi;
    }
  }
  findDominantMode(segments, lengths, first, last, sp);
  return sp;
}
}  // namespace

StrummingAnalysis strummingAnalysis(const ChainModel& model, const ChainGeometry& geometry, double t,
                                    const Eigen::Matrix3Xd& joints, const Eigen::Matrix3Xd& velocities,
                                    const Eigen::Matrix3Xd& tensions, double bandwidth)
{
  if (!(bandwidth >= 0.0 && bandwidth < 1.0))
    throw std::invalid_argument("strumming: the lock-in bandwidth " + std::to_string(bandwidth) +
                                " is out of range: must be in [0, 1)");
  const int nu = geometry.segments;
  if (nu < 1 || joints.cols() < nu + 1 || velocities.cols() < nu + 1 || tensions.cols() < nu + 1)
    throw std::invalid_argument("strumming: fewer joints, velocities or tensions than the chain's " +
                                std::to_string(nu) + " segments need");
  if (!joints.allFinite() || !velocities.allFinite() || !tensions.allFinite())
    throw std::invalid_argument("strumming: the joints, velocities and tensions must be finite");
  StrummingAnalysis out;
  out.bandwidth = bandwidth;
  std::vector<double> lengths;
  describeSegments(model, geometry, t, joints, velocities, tensions, out.segments, lengths);
  for (size_t first = 0; first < out.segments.size();)
  {
    size_t last = first;
    while (last < out.segments.size() && out.segments[last].span == out.segments[first].span)
      ++last;
    out.spans.push_back(describeSpan(out.segments, lengths, first, last, bandwidth));
    first = last;
  }
  return out;
}

}  // namespace tow_sim
