// One chain of the simulation (docs/solver.md §9, §10): its element lengths, its two ends and its block of the
// simulator's state vector. Its first joint follows the ship's tow point or is free (a parted end: its position
// and velocity are in the block); its last element is the end body or its last segment ends free (a parted
// cable's ship side: geometry.end_body false). It owns the solver's workspace and the outputs at the state it
// last refreshed; the model and the data (currents, actuators) are the simulator's, shared by its chains.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/chain/chain_state.h"

namespace tow_sim
{
class Chain
{
public:
  using StateVector = std::vector<double>;

  // `layout` says where the block sits and whether the first joint is free; its joints are the geometry's.
  Chain(const ChainGeometry& geometry, const StateLayout& layout);

  const ChainGeometry& geometry() const { return geometry_; }
  // New element lengths; the block grows or shrinks with its joints (a re-mesh) where it sits.
  void setGeometry(const ChainGeometry& geometry)
  {
    geometry_ = geometry;
    layout_.joints = geometry_.jointCount();
    layout_.roll = geometry_.rollingEnd();
  }
  const StateLayout& layout() const { return layout_; }
  bool freeFirst() const { return layout_.free; }
  bool hasEndBody() const { return geometry_.end_body; }

  // Its first joint x_1 in the state y: the ship's tow point, or the free end held in y (its acceleration
  // unknown: 0 here).
  ShipEndState firstJoint(const ShipEndState& ship, const StateVector& y) const;

  // Its part of dy/dt at (t, y) for the element lengths `geometry` (the winch's rate law moves the first
  // segment's between steps): the joints' velocities and accelerations, and the free end's. The cable out
  // and the payout rate are the simulator's. Only the solver's workspace changes.
  void derivative(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                  const ShipEndState& ship, const StateVector& y, StateVector& dydt) const;
  // The same at the state y for its own geometry, keeping the tensions, accelerations and axial multipliers.
  void refresh(const ChainModel& model, const ChainData& data, double t, const ShipEndState& ship, const StateVector& y,
               StateVector& dydt);

  // Sequentially from the first joint: each element's length restored along its current direction, then
  // the relative velocity along it removed (but the first segment's rate of change). An elastic cable's
  // segments stretch: only an end body has a length to keep.
  void project(const ChainModel& model, const ShipEndState& ship, StateVector& y) const;
  // The largest relative length error of the elements it keeps the lengths of (see project()).
  double lengthError(const ChainModel& model, const ShipEndState& ship, const StateVector& y) const;
  // [m/s] its fastest joint relative to its first joint (0: no joint).
  double largestRelativeSpeed(const ShipEndState& ship, const StateVector& y) const;

  // Joints x_1 .. (3 x (joints + 1)), the first joint first.
  Eigen::Matrix3Xd jointPositions(const ShipEndState& ship, const StateVector& y) const;
  // Kinematics of element e (0 .. joints - 1), a rolling end body's with its roll; std::out_of_range for another e.
  ElementKinematics elementKinematics(int e, const ShipEndState& ship, const StateVector& y) const;

  // At the state of the last refresh(): T_1 .. (force on element lambda at its forward joint) [N], the
  // joints' accelerations [m/s^2], each element's axial multiplier [N] (compression positive), and the
  // element equations the implicit stepper linearises around.
  const Eigen::Matrix3Xd& tensions() const { return tensions_; }
  const Eigen::Matrix3Xd& accelerations() const { return accelerations_; }
  const std::vector<double>& axialMultipliers() const { return multipliers_; }
  const std::vector<ElementTerms>& terms() const { return solver_.terms(); }

  // A rolling end body's d(dp/dt)/dphi [1/s^2] and d(dp/dt)/dp [1/s] at y, its joints' accelerations dydt held
  // (the implicit stepper's roll block, docs/solver.md (S29)).
  Eigen::Vector2d spinAccelerationDerivatives(const ChainModel& model, const ChainData& data, double t,
                                              const ShipEndState& ship, const StateVector& y,
                                              const StateVector& dydt) const;

  // The derivatives of the seabed's force on a free first joint (freeEndContact) in its position [N/m] and
  // velocity [N s/m], at `end`: zero without a seabed, for the end body alone, or off the bottom.
  void freeEndContactJacobian(const ChainModel& model, const ShipEndState& end, Eigen::Matrix3d& dF_dx,
                              Eigen::Matrix3d& dF_dv) const;

private:
  // physics.md §5b: a rolling end body's roll angle and spin rates into dydt, from the joints' accelerations a.
  void rollDerivative(const ChainModel& model, const ChainData& data, double t, const ShipEndState& ship,
                      const StateVector& y, const Eigen::Ref<const Eigen::Matrix3Xd>& a, StateVector& dydt) const;
  // The end element's forward joint's acceleration: a joint's of a (the chain's own), the ship's, or a free first
  // joint's (in dydt).
  Eigen::Vector3d endForwardAcceleration(const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& a,
                                         const StateVector& dydt) const;
  // The seabed's force on a free first joint (the contact of half the first segment's length, as each
  // segment's aft joint carries: ChainModel::forEachContact); zero without a seabed or for the end body alone.
  Eigen::Vector3d freeEndContact(const ChainModel& model, const ChainGeometry& geometry, const ShipEndState& end) const;
  // The seabed and its penalty stiffness [N/m] and damping [N s/m] on a free first joint (half the first
  // segment's length in contact); null without a seabed or for the end body alone.
  const Seabed* freeEndPenalty(const ChainModel& model, const ChainGeometry& geometry, double& stiffness,
                               double& damping) const;
  // The first element whose length is kept: an elastic cable's first element after its segments.
  int firstKeptElement(const ChainModel& model) const { return model.elastic() ? geometry_.segments : 0; }

  ChainGeometry geometry_;
  StateLayout layout_;
  mutable ChainSolver solver_;  // workspace only
  Eigen::Matrix3Xd tensions_, accelerations_;
  std::vector<double> multipliers_;
};

}  // namespace tow_sim
