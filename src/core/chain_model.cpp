#include "tow_sim/core/chain_model.h"

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
