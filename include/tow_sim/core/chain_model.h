// The constant model of the towed chain (pinocchio's Model): nu identical cable segments followed by
// the end body. Indexing in code is 0-based: element e = 0..nu joins joint e (forward, toward the
// ship) and joint e+1; joint 0 is the tow point x_1, joint nu is the bail x_{nu+1}, joint nu+1 the
// tail point x_{nu+2}. Element e = nu is the end body.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "tow_sim/core/element.h"
#include "tow_sim/core/params.h"

namespace tow_sim
{
// Prescribed motion of the tow point x_1 (physics.md §7), world.
struct ShipEndState
{
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();  // [m/s]
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();  // [m/s^2]
};

class ChainModel
{
public:
  // Validates every parameter (std::invalid_argument on a bad one).
  ChainModel(const CableParams& cable, std::shared_ptr<const EndBody> end_body, const Environment& env,
             const NumericsParams& numerics);

  int segments() const { return cable_.segments; }           // nu
  int elementCount() const { return cable_.segments + 1; }   // nu + 1
  int jointCount() const { return cable_.segments + 1; }     // unknown joints x_2 .. x_{nu+2}
  double elementLength(int e) const { return e < segments() ? segment_.length : end_body_->length(); }
  double totalLength() const { return cable_.length + end_body_->length(); }

  const CableParams& cable() const { return cable_; }
  const CableSegmentModel& segment() const { return segment_; }
  const EndBody& endBody() const { return *end_body_; }
  const Environment& environment() const { return env_; }
  const NumericsParams& numerics() const { return numerics_; }

  // The uniform current may change while running (validated like the rest).
  void setCurrent(const Eigen::Vector3d& current_W);
  // So may the current profile (depth -> current, added to the uniform current; empty: none).
  void setCurrentProfile(const std::vector<CurrentSample>& profile);

  // Newton-Euler description of element e at time t [s] and the given kinematics.
  void elementDynamics(int e, double t, const ElementKinematics& k, BodyDynamics& out) const
  {
    if (e < segments())
      cableSegmentDynamics(segment_, k, env_, out);
    else
      end_body_->dynamics(t, k, env_, out);
  }

private:
  CableParams cable_;
  CableSegmentModel segment_;
  std::shared_ptr<const EndBody> end_body_;
  Environment env_;
  NumericsParams numerics_;
};

}  // namespace tow_sim
