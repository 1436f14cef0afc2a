#include "tow_sim/core/run/tension_limits.h"

namespace tow_sim
{
const TensionLimitCheck& TensionLimitCheck::worse(const TensionLimitCheck& a, const TensionLimitCheck& b)
{
  if (a.level != b.level)
    return static_cast<int>(a.level) > static_cast<int>(b.level) ? a : b;
  return a.largest >= b.largest ? a : b;
}

TensionLimitCheck checkTensionLimits(const CableParams& cable, const Eigen::Ref<const Eigen::Matrix3Xd>& tensions)
{
  TensionLimitCheck check;
  for (Eigen::Index j = 0; j < tensions.cols(); ++j)
  {
    const double t = tensions.col(j).norm();
    if (t > check.largest)
    {
      check.largest = t;
      check.joint = static_cast<int>(j);
    }
  }
  if (cable.breaking_load && check.largest > *cable.breaking_load)
    check.level = TensionLimitCheck::Level::kAboveBreakingLoad;
  else if (cable.safe_working_load && check.largest > *cable.safe_working_load)
    check.level = TensionLimitCheck::Level::kAboveWorkingLoad;
  return check;
}

}  // namespace tow_sim
