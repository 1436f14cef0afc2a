// Time integration of the chain (MoorDyn's Time / MuJoCo's mj_step role): Boost.Odeint steppers,
// projection back onto the segment lengths after every step, and the outputs at the current state.
// The core never reads a clock: the caller says up to which time to integrate.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "tow_sim/core/chain_model.h"
#include "tow_sim/core/chain_solver.h"
#include "tow_sim/core/fins.h"
#include "tow_sim/core/implicit_stepper.h"
#include "tow_sim/core/rosenbrock_tableau.h"

namespace tow_sim
{
// Tow-point motion as a function of time [s] (position, velocity, acceleration, world).
using ShipMotion = std::function<ShipEndState(double t)>;

// A tow point moving with constant velocity: p(t) = p0 + v t.
ShipMotion constantVelocityShip(const Eigen::Vector3d& p0_W, const Eigen::Vector3d& v_W);

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

// The integrator's state vector: joint positions x_2 .. x_{nu+2} (3 x (nu+1)), their velocities, the cable
// out [m] and the payout rate [m/s], in that order. Named views instead of index arithmetic.
struct StateLayout
{
  int joints = 0;     // nu + 1
  bool free = false;  // a parted cable: the free first joint's position and velocity follow (6 more)
  int remnant = 0;    // and the joints of the cable left on the ship, x_2 .. x_j: positions, velocities
  std::size_t shipSideOffset() const { return 6 * static_cast<std::size_t>(joints) + 2 + (free ? 6 : 0); }
  std::size_t size() const { return shipSideOffset() + 6 * static_cast<std::size_t>(remnant); }
  Eigen::Map<Eigen::Matrix3Xd> shipSidePositions(std::vector<double>& y) const
  {
    return { y.data() + shipSideOffset(), 3, remnant };
  }
  Eigen::Map<const Eigen::Matrix3Xd> shipSidePositions(const std::vector<double>& y) const
  {
    return { y.data() + shipSideOffset(), 3, remnant };
  }
  Eigen::Map<Eigen::Matrix3Xd> shipSideVelocities(std::vector<double>& y) const
  {
    return { y.data() + shipSideOffset() + 3 * remnant, 3, remnant };
  }
  Eigen::Map<const Eigen::Matrix3Xd> shipSideVelocities(const std::vector<double>& y) const
  {
    return { y.data() + shipSideOffset() + 3 * remnant, 3, remnant };
  }
  Eigen::Map<Eigen::Matrix3Xd> positions(std::vector<double>& y) const { return { y.data(), 3, joints }; }
  Eigen::Map<const Eigen::Matrix3Xd> positions(const std::vector<double>& y) const { return { y.data(), 3, joints }; }
  Eigen::Map<Eigen::Matrix3Xd> velocities(std::vector<double>& y) const { return { y.data() + 3 * joints, 3, joints }; }
  Eigen::Map<const Eigen::Matrix3Xd> velocities(const std::vector<double>& y) const
  {
    return { y.data() + 3 * joints, 3, joints };
  }
  double& cableOut(std::vector<double>& y) const { return y[6 * static_cast<std::size_t>(joints)]; }
  double cableOut(const std::vector<double>& y) const { return y[6 * static_cast<std::size_t>(joints)]; }
  double& payoutRate(std::vector<double>& y) const { return y[6 * static_cast<std::size_t>(joints) + 1]; }
  double payoutRate(const std::vector<double>& y) const { return y[6 * static_cast<std::size_t>(joints) + 1]; }
  Eigen::Map<Eigen::Vector3d> freePosition(std::vector<double>& y) const
  {
    return Eigen::Map<Eigen::Vector3d>(y.data() + 6 * joints + 2);
  }
  Eigen::Map<const Eigen::Vector3d> freePosition(const std::vector<double>& y) const
  {
    return Eigen::Map<const Eigen::Vector3d>(y.data() + 6 * joints + 2);
  }
  Eigen::Map<Eigen::Vector3d> freeVelocity(std::vector<double>& y) const
  {
    return Eigen::Map<Eigen::Vector3d>(y.data() + 6 * joints + 5);
  }
  Eigen::Map<const Eigen::Vector3d> freeVelocity(const std::vector<double>& y) const
  {
    return Eigen::Map<const Eigen::Vector3d>(y.data() + 6 * joints + 5);
  }
};

// The cable parting (cable.break_at_breaking_load): when, where and at what tension.
struct PartingEvent
{
  double t = 0.0;        // [s]
  int joint = 0;         // 1 = the tow point .. nu + 1 = the bail: the forward joint of element joint - 1
  double tension = 0.0;  // [N] |T| there, above breaking_load
};

// Lateral diversion (the report's): horizontal offset of a point from the line through the ship along
// the unit horizontal track direction, positive to port, and its rate for a fixed track direction.
struct Diversion
{
  double offset = 0.0;  // [m]
  double rate = 0.0;    // [m/s]
};
Diversion lateralDiversion(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, const ShipEndState& ship,
                           const Eigen::Vector3d& track_direction_W);

// Slack flags of the tensions T_1 .. T_{nu+1} (3 x (nu+1)) at joints x_1 .. x_{nu+2} (3 x (nu+2)): element
// lambda is slack where its tension pushes instead of pulls, T_lambda . (x_{lambda+1} - x_lambda) > 0 (the
// rigid links carry compression; a real cable would go slack there).
std::vector<bool> slackFlags(const Eigen::Matrix3Xd& joints, const Eigen::Matrix3Xd& tensions);

// The smallest and largest of a series of values (empty: min > max).
struct ValueRange
{
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  void add(double v)
  {
    min = std::min(min, v);
    max = std::max(max, v);
  }
  void add(const ValueRange& r)
  {
    min = std::min(min, r.min);
    max = std::max(max, r.max);
  }
  bool empty() const { return min > max; }
};

struct StepReport
{
  int steps = 0;                  // accepted steps
  int rejected = 0;               // steps the error control rejected
  double max_length_error = 0.0;  // [-] largest relative length error left by a step, before projection
  ValueRange tension_ship;        // [N] |T_1| at the end of each accepted step
  ValueRange tension_vehicle;     // [N] |T_{nu+1}| likewise
  int snaps = 0;                  // elastic cable: segments that went from slack (T = 0 at or below their
                                  // rest length) to taut (T > 0)
  // [-] elastic cable: the largest segment strain at the end of a step (-inf: none)
  double max_strain = -std::numeric_limits<double>::infinity();
  std::optional<PartingEvent> parting;  // the cable parted during these steps (advanceTo goes on after it)
};

// What the simulator holds between steps (a saved state): enough to go on bit-identically. The model, the
// ship and the environment (currents, the sea's clock) are the caller's, not part of it.
struct SimulatorState
{
  double t = 0.0;         // [s]
  double dt = 0.0;        // [s] the adaptive steppers' next step
  int segments = 0;       // nu now (the winch changes it)
  std::vector<double> y;  // StateLayout for segments + 1 joints
  FinServo::State rudder, elevator;
  double thrust = 0.0;         // [N] as saturated
  double winch_command = 0.0;  // [m/s]
  std::vector<char> slack;     // elastic cable: each segment slack (empty: none counted yet)
};

class Simulator
{
public:
  using StateVector = std::vector<double>;  // laid out as StateLayout says

  // The winch (validated against the model's cable) is off by default: the cable length is fixed. The
  // chain starts with the model's initial data (its currents, the end body's actuators at rest at t = 0).
  Simulator(std::shared_ptr<const ChainModel> model, ShipMotion ship, const WinchParams& winch = WinchParams());
  ~Simulator();

  // Restart at time t from the given state, projected onto the segment lengths. Throws
  // std::invalid_argument for a wrong size or a non-finite value. The cable out and the layout are kept;
  // the winch restarts from rest with its command cleared; the actuators are not touched.
  void reset(double t, const ChainState& state);

  // Integrate to t_end (>= time()). Throws std::runtime_error if the state stops being finite, a joint
  // runs away (faster than 200 m/s relative to the tow point) or the step size collapses; the
  // simulator then keeps the last good state.
  StepReport advanceTo(double t_end);

  // Takes the layout of a saved state (or a test's): nu segments and the cable out [m] (the first segment
  // gets the rest). A reset() with as many joints must follow. Throws std::invalid_argument for a layout
  // the cable cannot have (no segment or more than 100000, a first segment not longer than 0, cable out
  // beyond the winch's limits while it is enabled, or other than the configured cable without the winch).
  void restoreLayout(int segments, double cable_out);

  // The state now, and back: restoreState() takes the layout (as restoreLayout, whose errors it throws), the
  // state vector, time, step and actuators as they were, without projecting, so that advancing from it is
  // bit-identical to advancing from where it was taken. Throws std::invalid_argument (naming the field) for a
  // state of the wrong size or with a non-finite value; nothing changes then.
  SimulatorState saveState() const;
  void restoreState(const SimulatorState& state);

  // The cable parted (cable.break_at_breaking_load, or part()): the chain is the vehicle side, from a free
  // first joint; the winch is stopped, and the steppers are explicit (dopri5; rk4 if configured).
  bool parted() const { return free_; }
  // Where and when it parted at its breaking load (checkBreak; kept until rejoin() or restoreState(), so an
  // advance that throws after it does not lose it). Empty after a part() by hand.
  const std::optional<PartingEvent>& partingEvent() const { return parting_event_; }
  // The cable left on the ship after a parting at joint j > 1 (j - 1 segments, its last joint free, no end
  // body: docs/solver.md §10): its joints from the tow point (empty: none) and the force on each segment at
  // its forward joint [N]. shipTension() is |T_1| of whichever chain hangs from the ship (0: none).
  Eigen::Matrix3Xd shipSideJoints() const;
  const Eigen::Matrix3Xd& shipSideTensions() const { return ship_side_tensions_; }
  double shipTension() const;
  // Parts the cable now at element e's forward joint (0: the tow point .. nu: the bail): the elements
  // forward of it leave the simulation, the joint's position and velocity become the free end's. Throws
  // std::logic_error if already parted, std::out_of_range for another e.
  void part(int element);
  // The whole cable again, laid out as configured (the winch's cable out as configured too): a reset() must
  // follow. Nothing happens to a cable that has not parted.
  void rejoin();

  // The right-hand side dy/dt at (t, y) for the current data: no side effect (only the solver's
  // workspace changes), so equal arguments give bit-identical results whatever was evaluated before.
  void derivative(double t, const StateVector& y, StateVector& dydt) const;

  // The data that changes while running. Commands act from time(); the currents are validated first
  // (std::invalid_argument naming the field).
  const ChainData& data() const { return data_; }
  bool command(double rudder, double elevator, double thrust);              // true if something saturated
  bool commandAt(double t, double rudder, double elevator, double thrust);  // from time t [s] (a restart)
  void resetActuators(double t);                                            // fins centred, no thrust, from time t [s]
  void setCurrent(const Eigen::Vector3d& current_W);
  void setCurrentProfile(const std::vector<CurrentSample>& profile);
  void setWaveTime(double wave_time) { tow_sim::setWaveTime(data_, wave_time); }

  // Winch: the commanded payout rate [m/s] (positive pays out), saturated at +-max_rate (returned).
  // Throws std::invalid_argument if it is not finite or the winch is disabled. The rate follows the
  // command with the winch's response time, within max_acceleration, and slows down so as to stop at
  // min_length and max_length.
  double setWinchCommand(double payout_rate);
  double winchCommand() const { return data_.winch_command; }
  double cableLength() const;  // [m] cable out
  double payoutRate() const;   // [m/s] its rate of change now
  const WinchParams& winch() const { return winch_; }

  double time() const { return t_; }
  // [s] the step the stepper takes next if nothing cuts it short: the fixed step, or the adaptive
  // steppers' proposal (at most max_step).
  double nextStep() const;
  ChainState state() const;
  const StateVector& stateVector() const { return y_; }         // the integrator's state, StateLayout
  ShipEndState shipEnd() const { return ship_(t_); }            // the ship's tow point, parted or not
  ShipEndState firstJoint() const { return towPoint(t_, y_); }  // x_1: the tow point, or the free end once parted
  // The element lengths now (the winch changes the layout): geometry().segments is nu now.
  const ChainGeometry& geometry() const { return data_.geometry; }
  // Joints x_1 .. x_{nu+2} (3 x (nu+2)) with the tow point first.
  Eigen::Matrix3Xd jointPositions() const;
  // T_1 .. T_{nu+1} at the current state (force on element lambda at its forward joint) [N].
  const Eigen::Matrix3Xd& tensions() const { return tensions_; }
  // Joint accelerations x_2 .. x_{nu+2} at the current state [m/s^2].
  const Eigen::Matrix3Xd& accelerations() const { return accelerations_; }
  // Current relative length error (after projection): the end body's alone for an elastic cable.
  double lengthError() const;
  // Each element's axial multiplier mu at the current state [N], compression positive: an elastic
  // segment's is minus its tension (0 when slack).
  const std::vector<double>& axialMultipliers() const { return multipliers_; }
  // Kinematics of element e (0 .. nu) at the current state; e = nu is the vehicle.
  ElementKinematics elementKinematics(int e) const;

  const ChainModel& model() const { return *model_; }

private:
  StateLayout layout() const
  {
    return StateLayout{ data_.geometry.jointCount(), free_, free_ ? ship_side_.segments : 0 };
  }
  // The chain's first joint at (t, y): the ship's tow point, or the free end of a parted cable (its
  // acceleration unknown: 0 here).
  ShipEndState towPoint(double t, const StateVector& y) const;
  StepperType stepper() const;          // the configured one, explicit once parted
  void checkBreak(StepReport& report);  // parts the cable where a tension exceeds breaking_load
  // The element lengths for the state y at time t: the first segment from the cable out, its rates from
  // the winch law (the model's as configured while the winch is off).
  ChainGeometry geometryOf(const StateVector& y) const;
  bool remesh(double t);                                       // split or merge the first segment
  // Segments of the first section now (the winch's: the sections aft of it keep theirs).
  int firstSectionSegments() const { return data_.geometry.segments - data_.geometry.aftSectionSegments(); }
  void splitFirstSegment(double t);
  void mergeFirstSegment();
  void project(double t);
  void refreshOutputs();
  void stepOnce(double t_end, double winch_step, StepReport& report);  // one accepted or rejected step
  void acceptStep(StepReport& report);  // after an accepted step: re-mesh, project, outputs, snaps, parting
  // The implicit stepper's step: false when rejected (dt_ then holds the step to try next).
  bool stepImplicit(double t_end, double winch_step, StepReport& report);
  void implicitStages(double h);  // y_next_ and error_ of the step h (factored)
  bool implicit() const;          // numerics.stepper is implicit or implicit_fixed
  double errorNorm(const StateVector& error, const StateVector& y_next, double t_next) const;  // weighted RMS
  void linearise();                             // the implicit stepper's J at the current state (after refreshOutputs)
  double largestRelativeSpeed(double t) const;  // [m/s] fastest joint relative to the tow point

  static constexpr double kMinStep = 1e-10;  // [s] smallest adaptive step before the integration fails

  struct Steppers;  // Boost.Odeint's, sized for the state (re-made when the winch re-meshes)
  std::shared_ptr<const ChainModel> model_;
  ShipMotion ship_;
  std::unique_ptr<Steppers> steppers_;
  mutable ChainSolver solver_;  // workspace only
  WinchParams winch_;
  ChainData data_;
  double t_ = 0.0;
  double dt_ = 0.0;  // next adaptive step
  StateVector y_;    // StateLayout
  StateVector dydt_;
  Eigen::Matrix3Xd tensions_, accelerations_;
  std::vector<double> multipliers_;  // each element's axial multiplier at the current state [N]
  std::vector<char> slack_;          // elastic cable: each segment slack (for counting snaps)
  std::optional<PartingEvent> parting_event_;
  ChainGeometry ship_side_ = noShipSide();  // parted: the cable left on the ship (segments 0: none)
  mutable ChainSolver ship_side_solver_;    // workspace only
  Eigen::Matrix3Xd ship_side_tensions_;
  static ChainGeometry noShipSide();
  void clearShipSide();  // none (rejoin, restoreState)
  // The seabed's force on the free end of the vehicle side (at its first joint, the contact of half the
  // first segment's length; zero without a seabed or for the end body alone).
  Eigen::Vector3d freeEndContact(const ChainGeometry& geometry, const ShipEndState& end) const;
  void shipSideDerivative(double t, const StateVector& y, StateVector& dydt) const;
  void shipSideOutputs();
  void projectShipSide(double t);
  double shipSideLengthError() const;
  bool free_ = false;  // parted: the first joint is free (its state after the payout rate)
  void countSnaps(StepReport& report);
  ImplicitStepper implicit_;
  const RosenbrockTableau* tableau_ = nullptr;  // the implicit steppers' method
  std::vector<StateVector> stage_k_;            // the implicit step's workspace
  StateVector stage_y_, stage_f_, y_next_, error_;
};

}  // namespace tow_sim
