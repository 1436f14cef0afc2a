// Small motions of a chain about an equilibrium (issue 31, items 2 and 3; docs/physics.md §12): each element's
// direction turned by two small angles normal to its axis (about the horizontal normal to it: in the vertical
// plane through it, "in-plane"; and about the third axis: "out-of-plane"), so every rigid length is kept exactly,
// and each elastic segment's stretch as a third coordinate; the coordinates' accelerations from the full solve
// (ChainSolver), differenced centrally in the coordinates (stiffness) and in their rates (damping). The eigenvalues of
// the first-order system [[0, I], [K, D]] give the natural modes; the same system forced by the tow point's harmonic
// motion gives the response to ship motion. The tow point holds its motion (or moves as the input). Dense:
// O(elements^3).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
struct Mode
{
  double period = 0.0;         // [s] 2 pi / the damped angular frequency; infinity for a mode that does not oscillate
  double frequency = 0.0;      // [rad/s] the undamped natural angular frequency |lambda|
  double damping_ratio = 0.0;  // [-] -Re(lambda) / |lambda|
  // The part that moves most: "in-plane", "out-of-plane" or "axial" (the cable; axial: its stretch), "vehicle
  // pitch" or "vehicle yaw" (the end body turning more than the cable's joints move).
  std::string dominant;
  Eigen::Matrix3Xd shape;  // [m] the joints' displacements x_2 .. x_{nu+2} (the largest 1), at the phase of its peak
};

// The modes at the state (x, v) with the tow point `ship` (an equilibrium: the accelerations about zero; in a
// steady tow v is the ship's velocity everywhere), longest period first, one per pair of conjugate
// eigenvalues. `step` [rad, m] is the differencing step of the angles and stretches (and [rad/s, m/s] of their rates).
std::vector<Mode> naturalModes(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                               const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                               double step = 1e-6);

// The `count` lowest natural modes (ascending natural frequency) of naturalModes, by shift-invert Arnoldi about zero
// frequency on the joints' amplitudes of motionResponses: O(nu) per iteration (docs/physics.md §12, (P52b)). An
// elastic or bending cable takes naturalModes (dense) and its first `count`. Throws std::runtime_error where the
// linearised chain has a mode of zero frequency.
std::vector<Mode> lowestModes(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                              const ShipEndState& ship, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                              std::size_t count, double step = 1e-6);

// The steady response to a harmonic motion of the tow point along `input` (a translation per unit input: (0, 0, 1)
// for heave, or the tow point's displacement per radian of the ship's pitch), per unit input amplitude, as complex
// amplitudes (magnitude and phase relative to the input's displacement): the same linearisation as the modes,
// forced by the tow point's displacement, velocity and acceleration (docs/physics.md §12, (P53)). The vehicle's
// point is its CG, cg_fraction of the way from the bail to the tail point.
struct MotionResponse
{
  double period = 0.0;                                 // [s] of the input
  std::complex<double> surge, sway, heave;             // [m/unit] of the vehicle's CG, world x, y, z
  std::complex<double> pitch;                          // [rad/unit] REP-103, positive nose down
  std::complex<double> tension_ship, tension_vehicle;  // [N/unit] |T_1| and |T_{nu+1}|
};
std::vector<MotionResponse> motionResponse(const ChainModel& model, const ChainGeometry& geometry,
                                           const ChainData& data, double t, const ShipEndState& ship,
                                           const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                           const Eigen::Vector3d& input, const std::vector<double>& periods,
                                           double cg_fraction, double step = 1e-6);

// The same for several inputs at once; [input][period]. In the joints' own displacements, each element linearised
// alone (central differences of its loads in its two joints) and one sparse factorisation per period: O(nu) per
// period and in the linearisation (docs/physics.md §12, (P53b)). An elastic or a bending cable, whose loads reach
// past the element, takes motionResponsesDense.
std::vector<std::vector<MotionResponse>> motionResponses(const ChainModel& model, const ChainGeometry& geometry,
                                                         const ChainData& data, double t, const ShipEndState& ship,
                                                         const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                                         const std::vector<Eigen::Vector3d>& inputs,
                                                         const std::vector<double>& periods, double cg_fraction,
                                                         double step = 1e-6);

// The same in the angle coordinates of naturalModes, every coordinate differenced through the whole solve and a
// dense factorisation per period: O(nu^2) and O(nu^3). The reference for motionResponses.
std::vector<std::vector<MotionResponse>> motionResponsesDense(const ChainModel& model, const ChainGeometry& geometry,
                                                              const ChainData& data, double t, const ShipEndState& ship,
                                                              const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                                              const std::vector<Eigen::Vector3d>& inputs,
                                                              const std::vector<double>& periods, double cg_fraction,
                                                              double step = 1e-6);

}  // namespace tow_sim
