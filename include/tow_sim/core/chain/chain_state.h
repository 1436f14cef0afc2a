// The chain's state as the integrator holds it: joint positions and velocities, the state vector's layout,
// and what follows from a state alone (straight chains, length errors, strains, slack flags).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
// Joint positions and velocities x_2 .. x_{nu+2} (3 x (nu+1)), world.
struct ChainState
{
  Eigen::Matrix3Xd x;  // [m]
  Eigen::Matrix3Xd v;  // [m/s]
};

// A straight chain of the given geometry (the model's as configured) from the tow point along `direction`,
// every joint moving with `velocity`.
ChainState straightChain(const ChainGeometry& geometry, const Eigen::Vector3d& tow_point_W,
                         const Eigen::Vector3d& direction_W, const Eigen::Vector3d& velocity_W);
ChainState straightChain(const ChainModel& model, const Eigen::Vector3d& tow_point_W,
                         const Eigen::Vector3d& direction_W, const Eigen::Vector3d& velocity_W);

// Largest |(|x_{l+1} - x_l|) / d_l - 1| over the elements from first_element on: the relative length error
// (an elastic cable's segments stretch: only its end body has a length to keep).
double maxRelativeLengthError(const ChainGeometry& geometry, const Eigen::Vector3d& tow_point_W,
                              const Eigen::Ref<const Eigen::Matrix3Xd>& x, int first_element = 0);

// Removes from the first `segments` joints' velocities, from the tow point aft, each segment's stretch rate
// (the relative velocity along it), as the projection does for rigid links.
void removeStretchRates(const ShipEndState& tow_point, int segments, ChainState& state);

// The strain eps = |x_{l+1} - x_l| / d_l - 1 of each cable segment (nu values), joints x_1 .. x_{nu+2}.
std::vector<double> segmentStrains(const ChainGeometry& geometry, const Eigen::Matrix3Xd& joints);

// Slack flags of the tensions T_1 .. T_{nu+1} (3 x (nu+1)) at joints x_1 .. x_{nu+2} (3 x (nu+2)): element
// lambda is slack where its tension pushes instead of pulls, T_lambda . (x_{lambda+1} - x_lambda) > 0 (the
// rigid links carry compression; a real cable would go slack there).
std::vector<bool> slackFlags(const Eigen::Matrix3Xd& joints, const Eigen::Matrix3Xd& tensions);

// A chain's block of the integrator's state vector: joint positions x_2 .. x_{nu+2} (3 x (nu+1); 3 x nu
// without an end body), their velocities, then the cable out [m] and the payout rate [m/s] (the chain the
// winch pays out: the simulator's first), then a free first joint's position and velocity, then a rolling end
// body's roll angle [rad] and spin [rad/s] (physics.md §5b), in that order. Named views instead of index arithmetic.
struct StateLayout
{
  int joints = 0;          // nu + 1 (nu without an end body)
  bool free = false;       // the first joint is free (a parted end): its position and velocity follow (6 more)
  std::size_t offset = 0;  // where the block starts in the state vector
  bool winch = true;       // the cable out and the payout rate follow the velocities (2 more)
  bool roll = false;       // the end body rolls: its roll angle and spin come last (2 more)
  std::size_t size() const { return rollOffset() + (roll ? 2 : 0) - offset; }
  std::size_t end() const { return offset + size(); }  // where the next block starts
  Eigen::Map<Eigen::Matrix3Xd> positions(std::vector<double>& y) const { return { y.data() + offset, 3, joints }; }
  Eigen::Map<const Eigen::Matrix3Xd> positions(const std::vector<double>& y) const
  {
    return { y.data() + offset, 3, joints };
  }
  Eigen::Map<Eigen::Matrix3Xd> velocities(std::vector<double>& y) const
  {
    return { y.data() + offset + 3 * joints, 3, joints };
  }
  Eigen::Map<const Eigen::Matrix3Xd> velocities(const std::vector<double>& y) const
  {
    return { y.data() + offset + 3 * joints, 3, joints };
  }
  double& cableOut(std::vector<double>& y) const { return y[winchOffset()]; }
  double cableOut(const std::vector<double>& y) const { return y[winchOffset()]; }
  double& payoutRate(std::vector<double>& y) const { return y[winchOffset() + 1]; }
  double payoutRate(const std::vector<double>& y) const { return y[winchOffset() + 1]; }
  Eigen::Map<Eigen::Vector3d> freePosition(std::vector<double>& y) const
  {
    return Eigen::Map<Eigen::Vector3d>(y.data() + freeOffset());
  }
  Eigen::Map<const Eigen::Vector3d> freePosition(const std::vector<double>& y) const
  {
    return Eigen::Map<const Eigen::Vector3d>(y.data() + freeOffset());
  }
  Eigen::Map<Eigen::Vector3d> freeVelocity(std::vector<double>& y) const
  {
    return Eigen::Map<Eigen::Vector3d>(y.data() + freeOffset() + 3);
  }
  Eigen::Map<const Eigen::Vector3d> freeVelocity(const std::vector<double>& y) const
  {
    return Eigen::Map<const Eigen::Vector3d>(y.data() + freeOffset() + 3);
  }

  double& rollAngle(std::vector<double>& y) const { return y[rollOffset()]; }
  double rollAngle(const std::vector<double>& y) const { return y[rollOffset()]; }
  double& rollRate(std::vector<double>& y) const { return y[rollOffset() + 1]; }
  double rollRate(const std::vector<double>& y) const { return y[rollOffset() + 1]; }
  // The roll angle and spin of y (zero without roll), and setting them (nothing without roll).
  Eigen::Vector2d rollState(const std::vector<double>& y) const
  {
    return roll ? Eigen::Vector2d(y[rollOffset()], y[rollOffset() + 1]) : Eigen::Vector2d::Zero();
  }
  void setRollState(std::vector<double>& y, const Eigen::Vector2d& state) const
  {
    if (roll)
      Eigen::Map<Eigen::Vector2d>(y.data() + rollOffset()) = state;
  }

private:
  std::size_t winchOffset() const { return offset + 6 * static_cast<std::size_t>(joints); }
  std::size_t freeOffset() const { return winchOffset() + (winch ? 2 : 0); }
  std::size_t rollOffset() const { return freeOffset() + (free ? 6 : 0); }
};

// Raises every joint of `state` that lies below the bottom onto it (a start from a shape computed
// without the seabed; the simulator's reset then restores the segment lengths).
void liftAboveSeabed(const Seabed& seabed, ChainState& state);

}  // namespace tow_sim
