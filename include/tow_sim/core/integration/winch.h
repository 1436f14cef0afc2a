// The winch (docs/physics.md §9; docs/solver.md §1): its rate law, how the payout rate follows the
// command, and the re-meshing of the first segment, the one whose length the winch changes.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"
#include "tow_sim/core/params.h"

namespace tow_sim
{
// [m/s^2] the payout acceleration of a winch with `length` [m] out, paying out at `rate` [m/s], commanded
// `command` [m/s] (positive pays out); 0 when it is disabled. The rate follows the command with the
// winch's response time, within max_rate and max_acceleration, slowing so as to stop at min_length and
// max_length.
double winchAcceleration(const WinchParams& winch, double command, double length, double rate);
// d winchAcceleration / d length [1/s^2] and d / d rate [1/s], by central differences (the rate law has
// corners: the implicit stepper's W-method needs no more); zero when the winch is disabled.
Eigen::Vector2d winchAccelerationDerivatives(const WinchParams& winch, double command, double length, double rate);

// The chain's element lengths with `length` [m] of cable out paying out at `rate` [m/s]: the first segment's
// length the cable out less the cable aft of it, its rate the payout rate and its acceleration the rate law's.
ChainGeometry paidOut(const WinchParams& winch, double command, ChainGeometry geometry, double length, double rate);

// The winch stops at its limits: its rate law brakes toward them, this removes the last overshoot of the
// cable out [m] and the payout rate [m/s].
void stopAtLimits(const WinchParams& winch, double& length, double& rate);

// validate(winch, cable) of the model's first section. With cable sections the winch pays out and hauls in
// the first section only (docs/solver.md §11): its limits, less the cable of the sections aft of it, are the
// first section's (std::invalid_argument saying so).
void validate(const WinchParams& winch, const ChainModel& model);
// The same for cable sections from the tow point aft, naming the winch's keys under `prefix` ("winch").
void validate(const WinchParams& winch, const std::vector<CableParams>& sections, const std::string& prefix = "winch");

// Keeps the first segment's length within [segment_min_fraction, segment_max_fraction] x the nominal d:
// above the band a new joint splits it d from its aft end, below it merges into the second segment (within
// the first section only), repeated in one direction until it is inside. `y` is the whole chain's state
// (StateLayout of `geometry`, the tow point `ship` now); both change with the layout. Returns true when
// the layout changed.
bool remeshFirstSegment(const WinchParams& winch, const ShipEndState& ship, ChainGeometry& geometry,
                        std::vector<double>& y);

}  // namespace tow_sim
