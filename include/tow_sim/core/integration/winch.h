// The winch's rate law (physics.md's winch; docs/solver.md §1): how the payout rate follows the command.
#pragma once

#include "tow_sim/core/params.h"

namespace tow_sim
{
// [m/s^2] the payout acceleration of a winch with `length` [m] out, paying out at `rate` [m/s], commanded
// `command` [m/s] (positive pays out); 0 when it is disabled. The rate follows the command with the
// winch's response time, within max_rate and max_acceleration, slowing so as to stop at min_length and
// max_length.
double winchAcceleration(const WinchParams& winch, double command, double length, double rate);

}  // namespace tow_sim
