// The cable's load limits (cable.safe_working_load, cable.breaking_load): which one the largest tension
// exceeds, and where.
#pragma once

#include <Eigen/Core>

#include "tow_sim/core/params.h"

namespace tow_sim
{
struct TensionLimitCheck
{
  enum class Level
  {
    kWithin,             // at or below the safe working load (or no limits set)
    kAboveWorkingLoad,   // above the safe working load, at or below the breaking load
    kAboveBreakingLoad,  // above the breaking load
  };
  Level level = Level::kWithin;
  double largest = 0.0;  // [N] the largest |T_lambda|
  int joint = 0;         // where: 0 the tow point (T_1) .. nu the bail (T_{nu+1})
  // The worse of two checks (the larger tension when equal in level).
  static const TensionLimitCheck& worse(const TensionLimitCheck& a, const TensionLimitCheck& b);
};

// The limits against tensions T_1 .. T_{nu+1} (3 x (nu+1), as TowSnapshot::tensions).
TensionLimitCheck checkTensionLimits(const CableParams& cable, const Eigen::Ref<const Eigen::Matrix3Xd>& tensions);

}  // namespace tow_sim
