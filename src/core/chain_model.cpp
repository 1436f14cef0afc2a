#include "tow_sim/core/chain_model.h"

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
