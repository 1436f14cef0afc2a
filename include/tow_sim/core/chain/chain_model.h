// The model of the towed chain (pinocchio's Model): a list of elements, nu cable segments in one or more
// cable sections (each of its own segment length, weight, drag, added mass and stiffness) with point bodies
// at joints, followed by the end body (docs/solver.md §11); the environment as configured and the seabed. Constant
// after construction: what changes while running is the geometry (the layout the winch re-meshes) and ChainData
// (the currents, the actuators), and the loads are evaluated for a given ChainGeometry and ChainData.
//
// Indexing in code is 0-based: element e = 0..nu joins joint e (forward, toward the ship) and joint e+1;
// joint 0 is the tow point x_1, joint nu is the bail x_{nu+1}, joint nu+1 the tail point x_{nu+2}.
// Element e = nu is the end body.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "tow_sim/core/chain/element.h"
#include "tow_sim/core/environment/seabed.h"
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

// A run of equal cable segments: a cable section after the first (the first is the winch's).
struct SegmentRun
{
  int segments = 0;     // [-]
  double length = 0.0;  // [m] each
};

// The element lengths of the chain at one instant: nu segments, the first (at the ship) of its own length
// while the winch runs (it changes at first_rate and first_acceleration), the others their section's
// (docs/solver.md §11), the end body last.
struct ChainGeometry
{
  int segments = 1;                 // nu
  double nominal_length = 0.0;      // [m] the first section's segment length L_1 / nu_1 as configured
  double first_length = 0.0;        // [m] the first segment's length (nominal without a winch)
  double first_rate = 0.0;          // [m/s] its rate of change
  double first_acceleration = 0.0;  // [m/s^2]
  double end_length = 0.0;          // [m] d_{nu+1}
  // false: no end body, the last segment's aft joint is free (a parted cable's ship side, docs/solver.md §10)
  bool end_body = true;
  // The end body rolls (physics.md §5b): its roll angle and spin are in the chain's state (StateLayout::roll).
  bool end_roll = false;
  bool rollingEnd() const { return end_body && end_roll; }
  // The cable's sections after the first, forward to aft (null: one uniform cable). Their segments are the
  // whole cable's last ones, so the winch, paying out and hauling in the first section, never moves them.
  std::shared_ptr<const std::vector<SegmentRun>> aft_sections;
  // The whole cable's segments aft of this chain's last one: the vehicle side's for the ship side of a
  // parted cable, 0 for a chain that ends at the end body.
  int aft_segments = 0;

  int elementCount() const { return segments + (end_body ? 1 : 0); }  // nu + 1 (nu without the end body)
  int jointCount() const { return elementCount(); }                   // unknown joints x_2 .. x_{nu+2}
  // (A free end body alone, a parted cable's vehicle side, has no segment: segments = 0.)
  double elementLength(int e) const
  {
    if (e >= segments)
      return end_length;
    if (e == 0)
      return first_length;
    return aft_sections ? sectionLength(sectionOf(e)) : nominal_length;
  }
  // The section of segment e, 0 the first (always 0 for one uniform cable).
  int sectionOf(int e) const;
  // [m] the nominal segment length of section i.
  double sectionLength(int i) const
  {
    return i == 0 ? nominal_length : (*aft_sections)[static_cast<size_t>(i - 1)].length;
  }
  // [m] the cable aft of the first segment: the cable out less first_length.
  double lengthAftOfFirst() const;
  // The whole cable's segments in the sections after the first.
  int aftSectionSegments() const;
  double cableLength() const { return first_length + lengthAftOfFirst(); }  // [m] cable out
  double totalLength() const { return cableLength() + (end_body ? end_length : 0.0); }
};

// What changes while the simulation runs and all its chains share, apart from the integrator's state (joint
// positions and velocities, cable out and its rate) and each chain's geometry (Chain): the currents, the
// actuators and the winch command. The right-hand side reads it and never writes it.
struct ChainData
{
  Environment environment;     // gravity and density as the model's; the currents now
  Actuators actuators;         // the end body's fins and thrust
  double winch_command = 0.0;  // [m/s] payout rate commanded, positive pays out
};

// A length of uniform cable (docs/solver.md §11): its parameters (its own length, segments, diameter, weight,
// drag, added mass, axial stiffness) and the model of one of its segments.
struct CableSection
{
  CableParams cable;
  CableSegmentModel segment;                   // a nominal segment
  std::shared_ptr<const Depressor> depressor;  // a section that is a winged depressor (one element), else null
};

// A point body at a joint of the cable: a clump weight or a float (docs/solver.md §11). Its mass and loads
// act at the joint: weight less buoyancy, a quadratic drag against the flow there, and the waves' inertia
// force on it. Treated as submerged.
struct JointBody
{
  int joint = 0;                  // which joint: the number of segments aft of it (0: the bail x_{nu+1})
  double mass = 0.0;              // [kg] in air, >= 0
  double displaced_volume = 0.0;  // [m^3] >= 0
  double drag_area = 0.0;         // [m^2] C_D A, >= 0: force -1/2 rho C_D A |u| u, u relative to the flow
  double added_mass = 0.0;        // [kg] >= 0, isotropic
  // Its loads at x_W [m] moving at v_W [m/s] at time t [s] (world): gravity, buoyancy, drag and the waves'
  // Froude-Krylov and added-mass force [N].
  Eigen::Vector3d force(const Environment& env, double t, const Eigen::Vector3d& x_W, const Eigen::Vector3d& v_W) const;
  // d force / d v_W [N s/m] (the drag's).
  Eigen::Matrix3d forceVelocityJacobian(const Environment& env, double t, const Eigen::Vector3d& x_W,
                                        const Eigen::Vector3d& v_W) const;
  double inertia() const { return mass + added_mass; }  // [kg]
};

class ChainModel
{
public:
  // One uniform cable. Validates every parameter (std::invalid_argument on a bad one). No seabed by default.
  ChainModel(const CableParams& cable, std::shared_ptr<const EndBody> end_body, const Environment& env,
             const NumericsParams& numerics, std::shared_ptr<const Seabed> seabed = nullptr);
  // Cable sections from the tow point aft (each validated as a cable; all elastic or all rigid) and point
  // bodies at joints (std::invalid_argument naming the section or body, the value and the rule).
  ChainModel(const std::vector<CableParams>& sections, const std::vector<JointBody>& bodies,
             std::shared_ptr<const EndBody> end_body, const Environment& env, const NumericsParams& numerics,
             std::shared_ptr<const Seabed> seabed = nullptr);

  // As configured (the winch changes the running chain's: Chain::geometry).
  ChainGeometry initialGeometry() const;
  int segments() const { return segments_; }          // nu, all sections
  int elementCount() const { return segments_ + 1; }  // nu + 1
  int jointCount() const { return segments_ + 1; }    // unknown joints x_2 .. x_{nu+2}
  double elementLength(int e) const { return initialGeometry().elementLength(e); }
  double nominalSegmentLength() const { return segment().length; }        // [m] the first section's
  double cableLength() const { return initialGeometry().cableLength(); }  // [m] as configured
  double totalLength() const { return initialGeometry().totalLength(); }

  // The data at rest at time t [s]: the configured environment, the actuators at rest.
  ChainData initialData(double t = 0.0) const;

  int sectionCount() const { return static_cast<int>(sections_.size()); }
  const CableSection& section(int i) const { return sections_[static_cast<size_t>(i)]; }
  // The first section's parameters (the whole cable's when it is uniform) and nominal segment.
  const CableParams& cable() const { return sections_.front().cable; }
  const CableSegmentModel& segment() const { return sections_.front().segment; }
  // Cable segment e's section parameters and model in a geometry; the first segment's model is scaled to
  // its length (the winch's).
  const CableParams& segmentCable(int e, const ChainGeometry& geometry) const
  {
    return sections_[static_cast<size_t>(geometry.sectionOf(e))].cable;
  }
  // The depressor that element e is in a geometry (null: a cable segment or the end body).
  const Depressor* depressorAt(int e, const ChainGeometry& geometry) const
  {
    return e < geometry.segments ? sections_[static_cast<size_t>(geometry.sectionOf(e))].depressor.get() : nullptr;
  }
  CableSegmentModel segmentModel(int e, const ChainGeometry& geometry) const;
  bool elastic() const { return cable().elastic(); }  // every section alike
  bool bends() const { return bends_; }               // some section has a bending stiffness
  // [N m/rad] the rotational stiffness of the joint between cable segments e - 1 and e (1 <= e < segments)
  // in a geometry (physics.md §11): EI / ((l_1 + l_2)/2) within a section; between two sections their
  // halves in series, 1 / (l_1 / (2 EI_1) + l_2 / (2 EI_2)) (0 when either EI is).
  double jointBendingStiffness(int e, const ChainGeometry& geometry) const;
  const std::vector<JointBody>& bodies() const { return bodies_; }
  // The point body at cable segment e's aft joint in a geometry (null: none).
  const JointBody* bodyAft(int e, const ChainGeometry& geometry) const
  {
    if (bodies_.empty() || e >= geometry.segments)
      return nullptr;
    const int joint = geometry.segments - 1 - e + geometry.aft_segments;
    for (const JointBody& b : bodies_)
      if (b.joint == joint)
        return &b;
    return nullptr;
  }
  const EndBody& endBody() const { return *end_body_; }
  const Environment& environment() const { return env_; }  // as configured
  const NumericsParams& numerics() const { return numerics_; }
  const Seabed* seabed() const { return seabed_ && seabed_->present() ? seabed_.get() : nullptr; }

  // The first segment's model for a geometry (scaled to its length while the winch runs).
  CableSegmentModel firstSegment(const ChainGeometry& geometry) const;

  // Newton-Euler description of element e at time t [s] and the given kinematics, for the chain's geometry
  // and data at that instant; with_contact false leaves out the seabed. (A point body at its aft joint is
  // the solver's: ChainSolver adds it on that joint.)
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

  std::vector<CableSection> sections_;                           // from the tow point aft, at least one
  std::shared_ptr<const std::vector<SegmentRun>> aft_sections_;  // sections_[1..] as runs (null: one section)
  int segments_ = 0;                                             // nu, all sections
  std::vector<JointBody> bodies_;
  bool bends_ = false;
  std::shared_ptr<const EndBody> end_body_;
  Environment env_;
  NumericsParams numerics_;
  std::shared_ptr<const Seabed> seabed_;
};

// A point body's values (std::invalid_argument naming cable.bodies[index] and the key): joint in
// 0 .. segments - 1, the rest finite and >= 0.
void validate(const JointBody& body, size_t index, int segments);

// Validates a change of the currents before it enters ChainData (std::invalid_argument naming the field).
void setCurrent(ChainData& data, const Eigen::Vector3d& current_W);
void setCurrentProfile(ChainData& data, const std::vector<CurrentSample>& profile);
// The sea's clock at t = 0 [s] (Environment::wave_time); finite, else std::invalid_argument.
void setWaveTime(ChainData& data, double wave_time);

}  // namespace tow_sim
