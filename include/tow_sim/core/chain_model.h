// The model of the towed chain (pinocchio's Model): nu cable segments followed by the end body, with
// their coefficients, the environment as configured and the seabed. Constant after construction:
// everything that changes while running (the layout the winch re-meshes, the currents, the actuators) is
// ChainData, and the loads are evaluated for a given ChainGeometry and ChainData.
//
// Indexing in code is 0-based: element e = 0..nu joins joint e (forward, toward the ship) and joint e+1;
// joint 0 is the tow point x_1, joint nu is the bail x_{nu+1}, joint nu+1 the tail point x_{nu+2}.
// Element e = nu is the end body.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

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

// The element lengths of the chain at one instant: nu segments, the first (at the ship) of its own length
// while the winch runs (it changes at first_rate and first_acceleration), the others nominal, the end body
// last.
struct ChainGeometry
{
  int segments = 1;                 // nu
  double nominal_length = 0.0;      // [m] L / nu of the configuration
  double first_length = 0.0;        // [m] the first segment's length (nominal without a winch)
  double first_rate = 0.0;          // [m/s] its rate of change
  double first_acceleration = 0.0;  // [m/s^2]
  double end_length = 0.0;          // [m] d_{nu+1}
  // false: no end body, the last segment's aft joint is free (a parted cable's ship side, docs/solver.md §10)
  bool end_body = true;

  int elementCount() const { return segments + (end_body ? 1 : 0); }  // nu + 1 (nu without the end body)
  int jointCount() const { return elementCount(); }                   // unknown joints x_2 .. x_{nu+2}
  // (A free end body alone, a parted cable's vehicle side, has no segment: segments = 0.)
  double elementLength(int e) const { return e < segments ? (e == 0 ? first_length : nominal_length) : end_length; }
  double cableLength() const { return first_length + (segments - 1) * nominal_length; }  // [m] cable out
  double totalLength() const { return cableLength() + (end_body ? end_length : 0.0); }
};

// Everything about the chain that changes while it runs, apart from the integrator's state (joint positions
// and velocities, cable out and its rate): the geometry after the last step, the currents, the actuators
// and the winch command. The right-hand side reads it and never writes it.
struct ChainData
{
  ChainGeometry geometry;      // after the last accepted step (the winch re-meshes between steps)
  Environment environment;     // gravity and density as the model's; the currents now
  Actuators actuators;         // the end body's fins and thrust
  double winch_command = 0.0;  // [m/s] payout rate commanded, positive pays out
};

class ChainModel
{
public:
  // Validates every parameter (std::invalid_argument on a bad one). No seabed by default.
  ChainModel(const CableParams& cable, std::shared_ptr<const EndBody> end_body, const Environment& env,
             const NumericsParams& numerics, std::shared_ptr<const Seabed> seabed = nullptr);

  // As configured (the winch changes the running chain's: see ChainData::geometry).
  ChainGeometry initialGeometry() const;
  int segments() const { return cable_.segments; }          // nu
  int elementCount() const { return cable_.segments + 1; }  // nu + 1
  int jointCount() const { return cable_.segments + 1; }    // unknown joints x_2 .. x_{nu+2}
  double elementLength(int e) const { return initialGeometry().elementLength(e); }
  double nominalSegmentLength() const { return segment_.length; }
  double cableLength() const { return initialGeometry().cableLength(); }  // [m] as configured
  double totalLength() const { return initialGeometry().totalLength(); }

  // The data at rest at time t [s]: the configured geometry and environment, the actuators at rest.
  ChainData initialData(double t = 0.0) const;

  const CableParams& cable() const { return cable_; }
  const CableSegmentModel& segment() const { return segment_; }
  const EndBody& endBody() const { return *end_body_; }
  const Environment& environment() const { return env_; }  // as configured
  const NumericsParams& numerics() const { return numerics_; }
  const Seabed* seabed() const { return seabed_ && seabed_->present() ? seabed_.get() : nullptr; }

  // The first segment's model for a geometry (scaled to its length while the winch runs).
  CableSegmentModel firstSegment(const ChainGeometry& geometry) const;

  // Newton-Euler description of element e at time t [s] and the given kinematics, for the chain's geometry
  // and data at that instant; with_contact false leaves out the seabed.
  void elementDynamics(int e, double t, const ElementKinematics& k, const ChainGeometry& geometry,
                       const ChainData& data, BodyDynamics& out, bool with_contact = true) const;

  // Calls visit(eta, stiffness [N/m], damping [N s/m]) for each point of element e that meets the seabed
  // (eta: the fraction of the way from its forward to its aft joint). A cable segment carries its aft
  // joint (so each joint x_2 .. x_{nu+1} once) with the stiffness of the cable that joint stands for: half
  // of each neighbouring segment (the bail: half the last one); the end body its own contact points.
  template <class Visit>
  void forEachContact(int e, const ChainGeometry& geometry, Visit&& visit) const
  {
    if (!seabed())
      return;
    const SeabedParams& sp = seabed()->params();
    if (e < geometry.segments)
    {
      const double carried =
          0.5 * (geometry.elementLength(e) + (e + 1 < geometry.segments ? geometry.elementLength(e + 1) : 0.0));
      visit(1.0, sp.stiffness * carried, sp.damping * carried);
      return;
    }
    for (double eta : end_body_->contactFractions())
      visit(eta, sp.vehicle_stiffness, sp.vehicle_damping);
  }

  // The seabed's force on cable segment e at its aft joint, the joint's own (zero without a seabed): an
  // elastic segment takes it on that joint directly (its stretch would feel the rigid projection's moment arm).
  Eigen::Vector3d segmentContactForce(int e, const ElementKinematics& k, const ChainGeometry& geometry) const;

private:
  void addContact(int e, const ElementKinematics& k, const ChainGeometry& geometry, BodyDynamics& out) const;

  CableParams cable_;
  CableSegmentModel segment_;  // nominal segment
  std::shared_ptr<const EndBody> end_body_;
  Environment env_;
  NumericsParams numerics_;
  std::shared_ptr<const Seabed> seabed_;
};

// Validates a change of the currents before it enters ChainData (std::invalid_argument naming the field).
void setCurrent(ChainData& data, const Eigen::Vector3d& current_W);
void setCurrentProfile(ChainData& data, const std::vector<CurrentSample>& profile);
// The sea's clock at t = 0 [s] (Environment::wave_time); finite, else std::invalid_argument.
void setWaveTime(ChainData& data, double wave_time);

}  // namespace tow_sim
