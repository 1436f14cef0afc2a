// The constant model of the towed chain (pinocchio's Model): nu identical cable segments followed by
// the end body. Indexing in code is 0-based: element e = 0..nu joins joint e (forward, toward the
// ship) and joint e+1; joint 0 is the tow point x_1, joint nu is the bail x_{nu+1}, joint nu+1 the
// tail point x_{nu+2}. Element e = nu is the end body.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "tow_sim/core/element.h"
#include "tow_sim/core/params.h"
#include "tow_sim/core/seabed.h"

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

  // The layout may change while running (winch): nu segments, the first (at the ship) of length
  // firstLength(), the others of the nominal length cable.length / cable.segments.
  int segments() const { return segments_; }          // nu
  int elementCount() const { return segments_ + 1; }  // nu + 1
  int jointCount() const { return segments_ + 1; }    // unknown joints x_2 .. x_{nu+2}
  double elementLength(int e) const
  {
    return e == 0 ? first_.length : (e < segments_ ? segment_.length : end_body_->length());
  }
  double nominalSegmentLength() const { return segment_.length; }
  double cableLength() const { return first_.length + (segments_ - 1) * segment_.length; }  // [m] cable out
  double totalLength() const { return cableLength() + end_body_->length(); }
  double firstLength() const { return first_.length; }
  double firstRate() const { return first_rate_; }                  // [m/s] d/dt of the first segment's length
  double firstAcceleration() const { return first_acceleration_; }  // [m/s^2]

  // Winch: the first segment's length [m] (> 0), its rate [m/s] and acceleration [m/s^2] now; and
  // re-meshing to nu segments with the given first length. Mass per length stays the cable's.
  void setFirstSegment(double length, double rate, double acceleration);
  void setLayout(int segments, double first_length);

  const CableParams& cable() const { return cable_; }
  const CableSegmentModel& segment() const { return segment_; }
  const EndBody& endBody() const { return *end_body_; }
  const Environment& environment() const { return env_; }
  const NumericsParams& numerics() const { return numerics_; }

  // The uniform current may change while running (validated like the rest).
  void setCurrent(const Eigen::Vector3d& current_W);
  // So may the current profile (depth -> current, added to the uniform current; empty: none).
  void setCurrentProfile(const std::vector<CurrentSample>& profile);

  // The seabed (none by default); contact loads join the elements' wrenches.
  void setSeabed(std::shared_ptr<const Seabed> seabed) { seabed_ = std::move(seabed); }
  const Seabed* seabed() const { return seabed_ && seabed_->present() ? seabed_.get() : nullptr; }

  // Newton-Euler description of element e at time t [s] and the given kinematics; with_contact false
  // leaves out the seabed.
  void elementDynamics(int e, double t, const ElementKinematics& k, BodyDynamics& out, bool with_contact = true) const;

private:
  CableParams cable_;
  CableSegmentModel segment_;  // nominal segment
  CableSegmentModel first_;    // the first segment, scaled to its length
  int segments_ = 0;
  double first_rate_ = 0.0, first_acceleration_ = 0.0;
  std::shared_ptr<const EndBody> end_body_;
  Environment env_;
  NumericsParams numerics_;
  std::shared_ptr<const Seabed> seabed_;
};

}  // namespace tow_sim
