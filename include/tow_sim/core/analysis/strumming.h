// Strumming (issue 31, item 5; docs/physics.md §13): where along a tow its cable sheds vortices, at which
// frequency, and which of its transverse string modes that shedding can lock into. A flow U normal to a bare
// cable of diameter D sheds vortices at f_s = St |u_n| / D (St the section's strouhal_number); the cable
// between two point bodies (or a body and an end) is a string of tension T(l) and mass per length m_t
// (cable plus added mass), whose high modes are f_k = k / (2 tau), tau = integral dl / sqrt(T / m_t) (P54a). A
// mode can lock in where it lies within the band f_s (1 +- b); the mode with the most cable in its band (its
// power-in length) is the one most likely to be excited. The drag amplification of a strumming cable is the
// section's own (CableParams::normalDragAmplification, (P55)).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
struct StrummingSegment
{
  int section = 0;                  // its cable section (0: the first, at the tow point)
  int span = 0;                     // its span: the cable between point bodies, 0 from the tow point
  double arc_length = 0.0;          // [m] of its centre, along the cable from the tow point
  double depth = 0.0;               // [m] of its centre below the surface
  double normal_speed = 0.0;        // [m/s] |u_n|, the flow through the water normal to it
  double shedding_frequency = 0.0;  // [Hz] f_s = St |u_n| / D
  double tension = 0.0;             // [N] the mean of its two joints' |T|
  double wave_speed = 0.0;          // [m/s] sqrt(T / m_t) (0: slack)
  // The string modes of its span within the lock-in band, lowest_mode .. highest_mode (both 0: none, or slack).
  long lowest_mode = 0, highest_mode = 0;
  double drag_amplification = 1.0;  // [-] of its section while it strums (P55; 1 with strumming none)
};

struct StrummingSpan
{
  double start = 0.0, end = 0.0;    // [m] along the cable from the tow point
  double travel_time = 0.0;         // [s] tau, a transverse wave's time from one end to the other (slack: skipped)
  double fundamental = 0.0;         // [Hz] 1 / (2 tau) (0: no taut cable in it)
  long dominant_mode = 0;           // the mode with the longest power-in length (0: none can lock in)
  double dominant_frequency = 0.0;  // [Hz] its frequency
  double power_in_length = 0.0;     // [m] the length of cable with that mode in its lock-in band
  long lowest_mode = 0, highest_mode = 0;  // the modes any of its segments can lock into (0, 0: none)
};

struct StrummingAnalysis
{
  double bandwidth = 0.2;                  // [-] b
  std::vector<StrummingSegment> segments;  // the cable's, from the tow point
  std::vector<StrummingSpan> spans;        // from the tow point
};

// At time t [s] with the joints x_1 .. x_{nu+2} at `joints` [m] moving at `velocities` [m/s] (world, at least the
// cable's nu + 1 columns each) and the tensions T_1 .. T_{nu+1} [N] (`tensions`, columns), in the chain's
// geometry; the flow is the model's environment (current, its profile and the waves) at each segment. bandwidth
// b in [0, 1): std::invalid_argument otherwise, or for matrices too small for the geometry.
StrummingAnalysis strummingAnalysis(const ChainModel& model, const ChainGeometry& geometry, double t,
                                    const Eigen::Matrix3Xd& joints, const Eigen::Matrix3Xd& velocities,
                                    const Eigen::Matrix3Xd& tensions, double bandwidth = 0.2);

}  // namespace tow_sim
