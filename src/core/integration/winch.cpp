#include "tow_sim/core/integration/winch.h"

#include <algorithm>
#include <cmath>

namespace tow_sim
{
double winchAcceleration(const WinchParams& winch, double command, double length, double rate)
{
  if (!winch.enabled)
    return 0.0;
  // Target rate: the command within the rate limit, slowing before each length limit so that the
  // lagged rate never carries the cable past it: no faster than a stop at half the deceleration limit
  // allows (room for the lag), and near the limit proportional to the distance left with gain
  // 1/(4 tau), which makes the last approach critically damped: the length creeps up to the limit
  // without crossing it and the acceleration stays within its limit.
  const double a = winch.max_acceleration, tau = winch.response_time;
  const double k = 0.25 / tau;
  const double to_max = std::max(0.0, winch.max_length - length), to_min = std::max(0.0, length - winch.min_length);
  double target = std::clamp(command, -winch.max_rate, winch.max_rate);
  target = std::min({ target, std::sqrt(a * to_max), k * to_max });
  target = std::max({ target, -std::sqrt(a * to_min), -k * to_min });
  return std::clamp((target - rate) / tau, -a, a);
}

}  // namespace tow_sim
