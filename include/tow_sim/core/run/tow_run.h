// One towing run, whatever drives it: the model, the simulator (with the chain's data), the ship as it
// moves, a schedule of commands, the depth autopilot in the loop if there is one, and the one policy for
// the initial shape. It produces a TowSnapshot holding every derived output. tow_sim_node, tow_sim_batch
// and tow_sim_demo are adapters around it: they feed it ship samples and commands and convert snapshots
// into messages, CSV rows or table lines; none of them builds a model or derives an output itself.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tow_sim/core/integration/simulator.h"
#include "tow_sim/core/run/depth_autopilot.h"
#include "tow_sim/core/run/ship_track.h"
#include "tow_sim/core/run/simulation_config.h"

namespace tow_sim
{
// Fins, thrust and winch from a time on (a schedule entry).
struct CommandEvent
{
  double t = 0.0;             // [s]
  double rudder = 0.0;        // [rad]
  double elevator = 0.0;      // [rad]
  double thrust = 0.0;        // [N]
  double payout_rate = 0.0;   // [m/s] winch, positive pays out (needs winch.enabled)
  double differential = 0.0;  // [rad] the elevator's differential (physics.md §5b): starboard fin +, port fin -
};

// How the cable is laid out when a run starts (and restarts after a divergence). One fallback: when no
// steady-tow equilibrium is found, a straight line along line_direction_S.
struct InitialShape
{
  enum class Type
  {
    kEquilibrium,  // the steady tow at the ship's velocity then (default)
    kLine,         // straight from the tow point along line_direction_S
    kHanging,      // straight down
    kPoints,       // the given joints (world)
    kFile          // a saved state (saved_state.h) at `path`: TowRun::restore() it; start() cannot
  };
  Type type = Type::kEquilibrium;
  Eigen::Vector3d line_direction_S = Eigen::Vector3d(-1.0, 0.0, -0.5);  // ship frame (FLU), turned by the heading
  Eigen::Matrix3Xd points;                                              // joints x_2 .. x_{nu+2}, for kPoints
  std::string path;                                                     // the saved state, for kFile
  bool any_configuration = false;  // kFile: load a state saved under another configuration (refused otherwise)
};

// A point body on the cable (cable.bodies) in a snapshot: where it is and the cable's pull on either side.
struct BodyOutput
{
  int joint = -1;  // its column of TowSnapshot::joints; -1: not on the vehicle side (a parting forward of it)
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();            // [m]
  double depth = 0.0;                                       // [m]
  Eigen::Vector3d tension_above = Eigen::Vector3d::Zero();  // [N] the pull on the segment above it, toward the ship
  Eigen::Vector3d tension_below = Eigen::Vector3d::Zero();  // [N] T at its joint: the cable below's
};

// Every output of the run at one instant (SI units, world ENU frame unless stated).
struct TowSnapshot
{
  double t = 0.0;                    // [s]
  ShipPose ship;                     // the ship's reference point, heading and speed
  ShipEndState tow_point;            // x_1
  int segments = 0;                  // nu (the winch changes it)
  Eigen::Matrix3Xd joints;           // [m] x_1 .. x_{nu+2}, tow point first
  Eigen::Matrix3Xd tensions;         // [N] T_1 .. T_{nu+1}, the pull toward the ship on each element's forward joint
  std::vector<bool> slack;           // per element: a rigid link carries compression; an elastic segment no tension
  std::vector<int> segment_section;  // per cable segment of `joints`, tow point first: its section (0: the first)
  std::vector<BodyOutput> bodies;    // cable.bodies, in the configuration's order
  double tension_ship = 0.0, tension_vehicle = 0.0;  // [N] |T_1|, |T_{nu+1}|
  double cable_length = 0.0, payout_rate = 0.0;      // [m], [m/s]
  // [N] the smallest and largest tension at the ship and at the vehicle over the steps since the previous
  // snapshot and at this one (a peak shorter than an output interval shows here)
  ValueRange tension_ship_range, tension_vehicle_range;
  double max_length_error = 0.0;  // [-] largest relative length error a step left before projection, since
                                  // the previous snapshot (an elastic cable: its end body's)
  // Elastic cable (zero for the rigid one): segments gone from slack to taut since the run started, and the
  // largest segment strain over the steps since the previous snapshot and at this one.
  long snap_count = 0;
  double max_strain = 0.0;  // [-]
  VehicleOutputs vehicle;   // at the CG, in the dynamics' body frame (zero roll unless it rolls); fins' angles, loads
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();  // as published (AttitudeHold near the vertical)
  double pitch = 0.0, yaw = 0.0;  // [rad] REP-103 of `attitude`: pitch positive nose down, yaw from +x
  double roll = 0.0;              // [rad] REP-103, positive starboard down: 0 unless vehicle.roll is free
  double depth = 0.0;             // [m] of the CG
  double layback = 0.0;           // [m] of the CG behind the tow point, along the ship's heading
  Diversion diversion;            // of the CG from the ship's track, positive to port, and its rate
  bool seabed_present = false;
  double vehicle_altitude = 0.0;         // [m] CG above the seabed (NaN without one)
  std::vector<bool> joint_contact;       // per joint x_1 .. x_{nu+2}: below the bottom (x_1 never)
  int contacts = 0;                      // joints below the bottom
  bool vehicle_on_seabed = false;        // a hull end below the bottom
  std::optional<double> depth_setpoint;  // [m] the autopilot's (the equivalent depth in altitude mode)
  // The cable parted (cable.break_at_breaking_load) since the run started: joints then begin at the free
  // end of the vehicle side (tow_point stays the ship's) and segments are that side's; the cable left on
  // the ship hangs from the tow point (ship_side: its joints, tow point first; its tensions T_1 ..; empty
  // after a parting at the tow point), and tension_ship is its T_1 (0: none).
  std::optional<PartingEvent> parting;
  bool parted = false;  // the cable is parted now (also after a part() by hand, which has no event)
  Eigen::Matrix3Xd ship_side, ship_side_tensions;
};

// T_1 [N], world: the force on the cable hanging from the ship at its tow point (the ship feels -T_1):
// the whole cable's, or after a parting the ship side's (zero: none left on the ship).
inline Eigen::Vector3d shipPull(const TowSnapshot& s)
{
  if (!s.parted)
    return s.tensions.col(0);
  return s.ship_side_tensions.cols() > 0 ? Eigen::Vector3d(s.ship_side_tensions.col(0)) : Eigen::Vector3d::Zero();
}

// The outputs at time t between two snapshots a, b of one run (a.t <= t <= b.t, else the nearer end):
// linear in every continuous output (positions, velocities, tensions, loads, angles), the attitudes by
// slerp, the discrete ones (slack and contact flags, setpoint, layout) from the nearer snapshot; across
// a change of layout (the winch re-meshing) the nearer snapshot whole. The length-error maximum is the
// larger of the two. (The node publishes between whole steps of the implicit stepper this way.)
TowSnapshot interpolate(const TowSnapshot& a, const TowSnapshot& b, double t);

// The time a real-time driver's tick integrates to (tow_sim_node's physics tick): toward `wanted` [s], not past
// `available` [s], at most max_sim [s] of simulated time and about max_wall [s] of wall time at `cost` wall
// seconds per simulated second (0: not known yet), yet at least one step `step` [s] of a whole-step
// stepper (0: none; then at least 1 ms) and never past `wanted` by more than that step.
double tickTarget(double now, double wanted, double available, double step, double cost, double max_sim,
                  double max_wall);

// A run's saved state (saved_state.h reads and writes it as text): the simulator's, where the ship was, the
// outputs' running maxima and counters, the attitude's held heading and the autopilot's, and the configuration
// it was saved under as keys and values (to refuse a state under another one). Not in it: the model, the
// ship's motion, the environment now and the schedule (the caller's, as the scenario or the node has them).
struct RunState
{
  SimulatorState sim;
  // [s] the time the run was advanced to: the events due by it have acted (sim.t may fall short of it by
  // the steppers' rounding, 1e-12 s)
  double reached = 0.0;
  ShipEndState tow_point;                                // x_1 at sim.t (world)
  double heading = 0.0;                                  // [rad] the ship's at sim.t
  long ticks = 0;                                        // the autopilot's next tick (its index)
  long snap_count = 0;                                   // since the run started
  double max_strain = 0.0;                               // [-] since the last snapshot (-inf: none yet)
  double max_length_error = 0.0;                         // [-] likewise
  ValueRange tension_ship_range, tension_vehicle_range;  // [N] likewise
  double attitude_heading = 0.0;                         // [rad] AttitudeHold's held yaw; NaN: none held
  std::optional<DepthAutopilotState> autopilot;
  // The configuration's keys and values as text (configurationKeys, config.h; the caller fills it in before
  // writing); empty: not recorded (a state of format 1, or a caller without a configuration).
  std::map<std::string, std::string> configuration;
};

// A state carried to another time and ship pose (tow_sim_node's ~load_state): the cable's shape and
// velocities relative to the tow point turned about the vertical by the change of heading, at the tow point
// `tow_point` at time t [s], the fin servos' and the autopilot's clocks shifted by as much as the time. The
// batch restores a state as it is (bit-identical); this is for a run on another ship track.
RunState relocate(const RunState& state, double t, const ShipEndState& tow_point, double heading);

class TowRun
{
public:
  // Validates the configuration (std::invalid_argument naming the key). The ship history is shared with
  // the caller, who adds samples as they come (the node) or all in advance (the batch).
  TowRun(const SimulationConfig& config, std::shared_ptr<ShipHistory> ship,
         const InitialShape& initial = InitialShape());

  // Lays the cable out at time t at the ship's pose then, by the initial-shape policy, whatever ran before
  // (a restart is a start): the last scheduled command due by t applied from t (fins from centre, thrust,
  // the winch from rest), the autopilot afresh with its setpoints due by t and its ticks from t on.
  // Returns a warning when it had to fall back (no equilibrium: a straight line), else "".
  std::string start(double t);
  bool started() const { return started_; }

  // The state now (std::logic_error before start()), and a start from a saved one instead of start(): the
  // simulator as it was, the schedule's commands and setpoints due by its time taken as done (the actuators
  // and the autopilot are the state's), the autopilot (if this run has one; its state's if saved with one,
  // else afresh with the setpoints due) ticking on. Advancing then is bit-identical to advancing the run the
  // state was saved from. Throws std::invalid_argument (naming the field) for a state that does not fit this
  // run; nothing changes then.
  RunState saveState() const;
  void restore(const RunState& state);

  // Commands due later, applied in time order as the run passes them (sorted here); after start(), those
  // before the run's time act at once.
  void schedule(std::vector<CommandEvent> commands);
  // The depth autopilot in the loop: it commands the fins at its rate from vehicle outputs and the ship's
  // track, with its setpoints at their times. Validates its parameters.
  void setAutopilot(const AutopilotLoop& loop);

  // Immediate commands from now on (as Simulator's).
  bool command(double rudder, double elevator, double thrust, double differential = 0.0)
  {
    return sim_.command(rudder, elevator, thrust, differential);
  }
  double setWinchCommand(double payout_rate) { return sim_.setWinchCommand(payout_rate); }
  void setCurrent(const Eigen::Vector3d& current_W) { sim_.setCurrent(current_W); }
  void setCurrentProfile(const std::vector<CurrentSample>& profile) { sim_.setCurrentProfile(profile); }
  // The sea's clock at t = 0 [s] (Environment::wave_time).
  void setWaveTime(double wave_time) { sim_.setWaveTime(wave_time); }

  // Integrates to t (finite, >= time(); else std::invalid_argument), applying the scheduled commands, setpoints and
  // autopilot ticks due on the way in time order. Throws std::runtime_error on divergence (the last good state stays).
  StepReport advanceTo(double t);
  // Every output now; the length-error maximum starts again. Both throw std::logic_error before start().
  TowSnapshot snapshot();

  double time() const { return sim_.time(); }
  double nextStep() const { return sim_.nextStep(); }  // [s] Simulator::nextStep
  const Simulator& simulator() const { return sim_; }
  const ChainModel& model() const { return *model_; }
  const Vehicle& vehicle() const { return *vehicle_; }
  const SimulationConfig& config() const { return config_; }
  const Seabed* seabed() const { return model_->seabed(); }

private:
  ChainState initialState(double t, std::string* warning) const;
  void autopilotTick(double t);
  void applySetpoint(const AutopilotSetpoint& setpoint);
  long firstTickFrom(double t) const;  // the autopilot's first tick at or after t [s]
  VehicleOutputs vehicleOutputs() const;
  void elasticOutputs(TowSnapshot& s);               // slack flags, snap count and strain of an elastic cable
  void sectionAndBodyOutputs(TowSnapshot& s) const;  // each segment's section, each point body's place and pulls
  void attitudeOutputs(TowSnapshot& s);              // attitude, pitch, yaw, roll from s.vehicle

  SimulationConfig config_;
  std::shared_ptr<const Vehicle> vehicle_;
  std::shared_ptr<const ChainModel> model_;
  std::shared_ptr<ShipHistory> ship_;
  InitialShape initial_;
  Simulator sim_;
  bool started_ = false;
  std::vector<CommandEvent> commands_;
  size_t next_command_ = 0;
  AutopilotLoop autopilot_loop_;
  std::unique_ptr<DepthAutopilot> autopilot_;
  size_t next_setpoint_ = 0;
  long ticks_ = 0;
  double max_length_error_ = 0.0;
  long snap_count_ = 0;                                    // since start()
  double max_strain_ = 0.0;                                // since the last snapshot (-inf: none yet)
  ValueRange tension_ship_range_, tension_vehicle_range_;  // since the last snapshot
  AttitudeHold attitude_;
  double reached_ = 0.0;  // [s] the time of the last start() or advanceTo()
};

}  // namespace tow_sim
