#include "tow_sim/core/run/tow_run.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
std::shared_ptr<const Seabed> makeSeabed(const SeabedParams& params)
{
  return params.type == SeabedParams::Type::kNone ? nullptr : std::make_shared<Seabed>(params);
}
}  // namespace

double tickTarget(double now, double wanted, double available, double step, double cost, double max_sim,
                  double max_wall)
{
  double chunk = max_sim;
  if (cost > 0.0)
    chunk = std::min(chunk, max_wall / cost);
  chunk = std::max(chunk, step > 0.0 ? step : 1e-3);
  return std::min({ std::max(wanted, now + step), available, now + chunk });
}

TowRun::TowRun(const SimulationConfig& config, std::shared_ptr<ShipHistory> ship, const InitialShape& initial)
    : config_(config),
      vehicle_(std::make_shared<Vehicle>(config.vehicle, config.numerics)),
      model_(std::make_shared<ChainModel>(cableSections(config), jointBodies(config), vehicle_, config.environment,
                                          config.numerics, makeSeabed(config.seabed))),
      ship_(std::move(ship)),
      initial_(initial),
      sim_(
          model_, [ship = ship_.get()](double t) { return ship->towPoint(t); }, config.winch)
{
  if (!ship_)
    throw std::invalid_argument("TowRun: no ship history given");
  validateSectionsAndBodies(config);
}

void TowRun::schedule(std::vector<CommandEvent> commands)
{
  std::stable_sort(commands.begin(), commands.end(),
                   [](const CommandEvent& a, const CommandEvent& b) { return a.t < b.t; });
  for (const CommandEvent& c : commands)
    if (c.payout_rate != 0.0 && !config_.winch.enabled)
      throw std::invalid_argument("commands: payout_rate needs the winch (winch.enabled is false)");
  commands_ = std::move(commands);
  next_command_ = 0;
}

void TowRun::setAutopilot(const AutopilotLoop& loop)
{
  loop.params.validate("autopilot.");
  requireInRange("autopilot.rate", loop.rate, 0.1, 1000.0, "[Hz]");
  if (loop.enabled && loop.params.actuator != DepthAutopilotParams::Actuator::kElevator && !config_.winch.enabled)
    throw std::invalid_argument("autopilot.actuator: winch and both need the winch (winch.enabled: true)");
  autopilot_loop_ = loop;
  std::stable_sort(autopilot_loop_.setpoints.begin(), autopilot_loop_.setpoints.end(),
                   [](const AutopilotSetpoint& a, const AutopilotSetpoint& b) { return a.t < b.t; });
  autopilot_ = loop.enabled ? std::make_unique<DepthAutopilot>(loop.params) : nullptr;
  next_setpoint_ = 0;
  ticks_ = started_ ? firstTickFrom(time()) : 0;
}

namespace
{
// The lengths of the first `segments` elements of joints x from the tow point.
std::vector<double> segmentLengths(const Eigen::Vector3d& tow_point_W, int segments, const Eigen::Matrix3Xd& x)
{
  std::vector<double> lengths(static_cast<size_t>(segments));
  Eigen::Vector3d x_f = tow_point_W;
  for (int e = 0; e < segments; ++e)
  {
    lengths[static_cast<size_t>(e)] = (x.col(e) - x_f).norm();
    x_f = x.col(e);
  }
  return lengths;
}

// The joints laid out again from the tow point along their directions at the given lengths.
void layOut(const Eigen::Vector3d& tow_point_W, const std::vector<double>& lengths, Eigen::Matrix3Xd& x)
{
  Eigen::Vector3d x_f = tow_point_W;
  for (size_t e = 0; e < lengths.size(); ++e)
  {
    const Eigen::Index j = static_cast<Eigen::Index>(e);
    x.col(j) = x_f + lengths[e] * (x.col(j) - x_f).normalized();
    x_f = x.col(j);
  }
}
}  // namespace

ChainState TowRun::initialState(double t, std::string* warning) const
{
  const ShipEndState tow = ship_->towPoint(t);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(ship_->pose(t).heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const ChainGeometry& geometry = sim_.geometry();
  ChainState state;
  switch (initial_.type)
  {
    case InitialShape::Type::kEquilibrium:
      try
      {
        // The steady tow in calm water at the tow point's horizontal velocity: a ship heaving or pitching in
        // waves does not tow upward or downward on average, and the sea is no steady load.
        ChainData calm = sim_.data();
        calm.environment.wave_field.reset();
        state =
            steadyTowEquilibrium(*model_, geometry, calm, t, tow.p_W, Eigen::Vector3d(tow.v_W.x(), tow.v_W.y(), 0.0))
                .state;
        break;
      }
      catch (const std::runtime_error& e)
      {
        *warning = std::string(e.what()) + "; starting from a straight line instead";
      }
      state = straightChain(geometry, tow.p_W, R * initial_.line_direction_S, tow.v_W);
      break;
    case InitialShape::Type::kLine:
      state = straightChain(geometry, tow.p_W, R * initial_.line_direction_S, tow.v_W);
      break;
    case InitialShape::Type::kHanging:
      state = straightChain(geometry, tow.p_W, -Eigen::Vector3d::UnitZ(), tow.v_W);
      break;
    case InitialShape::Type::kPoints:
      state.x = initial_.points;
      state.v = initial_.points;
      state.v.colwise() = tow.v_W;
      break;
    case InitialShape::Type::kFile:
      throw std::logic_error("TowRun::start: a saved state (" + initial_.path + ") is restore()d, not started");
  }
  // The initial shapes know nothing of the seabed: joints below it are raised onto it (and an elastic
  // cable's segments laid out again at their lengths along their new directions, as the projection does
  // for rigid links).
  if (model_->seabed())
  {
    const std::vector<double> lengths = segmentLengths(tow.p_W, geometry.segments, state.x);
    liftAboveSeabed(*model_->seabed(), state);
    if (model_->elastic())
      layOut(tow.p_W, lengths, state.x);
  }
  // An elastic cable starts with no segment stretching (else a heaving tow point would start it with a jerk
  // of its axial damping); the projection does this for rigid links.
  if (model_->elastic())
    removeStretchRates(tow, geometry.segments, state);
  return state;
}

std::string TowRun::start(double t)
{
  if (ship_->empty())
    throw std::invalid_argument("TowRun::start: no ship sample yet");
  if (!std::isfinite(t))
    throw std::invalid_argument("TowRun::start: the start time must be finite");
  // The schedule as it stands at t, whatever ran before (a restart replays it): the last command due by t
  // sets the fins and thrust (from t, the servos from centre) and the winch; later ones stay scheduled.
  next_command_ = 0;
  while (next_command_ < commands_.size() && commands_[next_command_].t <= t)
    ++next_command_;
  const CommandEvent* due = next_command_ > 0 ? &commands_[next_command_ - 1] : nullptr;
  sim_.rejoin();  // a parted cable is whole again: a restart lays the configured cable out
  sim_.resetActuators(t);
  if (due && !autopilot_)  // the thrust shapes the equilibrium
    sim_.commandAt(t, due->rudder, due->elevator, due->thrust, due->differential);
  // The autopilot starts afresh: its setpoints due by t given, its ticks from t on.
  if (autopilot_loop_.enabled)
  {
    autopilot_ = std::make_unique<DepthAutopilot>(autopilot_loop_.params);
    const std::vector<AutopilotSetpoint>& setpoints = autopilot_loop_.setpoints;
    for (next_setpoint_ = 0; next_setpoint_ < setpoints.size() && setpoints[next_setpoint_].t <= t; ++next_setpoint_)
      applySetpoint(setpoints[next_setpoint_]);
    ticks_ = firstTickFrom(t);
  }
  std::string warning;
  const ChainState state = initialState(t, &warning);
  sim_.reset(t, state);  // the winch from rest, its command cleared
  if (due && config_.winch.enabled &&
      !(autopilot_ && autopilot_loop_.params.actuator != DepthAutopilotParams::Actuator::kElevator))
    sim_.setWinchCommand(due->payout_rate);
  attitude_.reset();
  max_length_error_ = 0.0;
  snap_count_ = 0;
  max_strain_ = -std::numeric_limits<double>::infinity();
  tension_ship_range_ = tension_vehicle_range_ = ValueRange();
  started_ = true;
  reached_ = t;
  return warning;
}

VehicleOutputs TowRun::vehicleOutputs() const
{
  return vehicle_->outputs(sim_.time(), sim_.elementKinematics(sim_.geometry().segments), sim_.data().environment,
                           sim_.data().actuators);
}

void TowRun::autopilotTick(double t)
{
  ++ticks_;
  const VehicleOutputs o = vehicleOutputs();
  VehicleMeasurement m;
  m.t = t;
  m.p_W = o.p_cg_W;
  m.v_W = o.v_cg_W;
  m.roll = o.roll;  // 0 unless the vehicle rolls
  m.roll_rate = o.omega_B.x();
  if (model_->seabed())
    m.altitude = model_->seabed()->altitude(o.p_cg_W);
  if (config_.winch.enabled)
    m.cable_out = sim_.cableLength();
  autopilot_->addVehicle(m);
  const ShipPose pose = ship_->pose(t);
  autopilot_->addShip(Eigen::Vector2d(pose.x, pose.y));
  const AutopilotCommand c = autopilot_->update(t);
  sim_.command(c.rudder, c.elevator, c.thrust, c.differential);
  if (c.winch && !sim_.parted())
    sim_.setWinchCommand(c.payout_rate);
}

StepReport TowRun::advanceTo(double t)
{
  if (!started_)
    throw std::logic_error("TowRun::advanceTo before start()");
  if (!std::isfinite(t) || t < time())
    throw std::invalid_argument("TowRun::advanceTo: the target time " + std::to_string(t) +
                                " s must be finite and not before the run's time " + std::to_string(time()) + " s");
  // Everything due up to t in time order (at equal times: commands, then setpoints, then autopilot ticks),
  // each after the simulation has reached its time; then the simulation to t.
  const double never = std::numeric_limits<double>::infinity();
  StepReport total;
  auto integrate = [&](double to)
  {
    const StepReport r = sim_.advanceTo(to);
    total.steps += r.steps;
    total.rejected += r.rejected;
    total.max_length_error = std::max(total.max_length_error, r.max_length_error);
    max_length_error_ = std::max(max_length_error_, r.max_length_error);
    total.snaps += r.snaps;
    total.max_strain = std::max(total.max_strain, r.max_strain);
    snap_count_ += r.snaps;
    if (r.parting)
      total.parting = r.parting;
    max_strain_ = std::max(max_strain_, r.max_strain);
    tension_ship_range_.add(r.tension_ship);
    tension_vehicle_range_.add(r.tension_vehicle);
  };
  for (;;)
  {
    const double t_command = next_command_ < commands_.size() ? commands_[next_command_].t : never;
    const std::vector<AutopilotSetpoint>& setpoints = autopilot_loop_.setpoints;
    const double t_setpoint = autopilot_ && next_setpoint_ < setpoints.size() ? setpoints[next_setpoint_].t : never;
    const double t_tick = autopilot_ ? ticks_ / autopilot_loop_.rate : never;
    const double t_next = std::min({ t_command, t_setpoint, t_tick });
    if (t_next > t)
      break;
    integrate(std::max(t_next, time()));  // an event scheduled in the past acts now
    if (t_next == t_command)
    {
      const CommandEvent& c = commands_[next_command_++];
      if (!autopilot_)
        sim_.command(c.rudder, c.elevator, c.thrust, c.differential);
      const bool autopilot_winch =
          autopilot_ && autopilot_loop_.params.actuator != DepthAutopilotParams::Actuator::kElevator;
      if (config_.winch.enabled && !autopilot_winch && !sim_.parted())  // else the autopilot drives the winch
        sim_.setWinchCommand(c.payout_rate);
    }
    else if (t_next == t_setpoint)
      applySetpoint(setpoints[next_setpoint_++]);
    else
      autopilotTick(t_next);
  }
  integrate(t);
  reached_ = t;
  return total;
}

long TowRun::firstTickFrom(double t) const
{
  return static_cast<long>(std::ceil(t * autopilot_loop_.rate - 1e-9));
}

void TowRun::applySetpoint(const AutopilotSetpoint& sp)
{
  if (sp.altitude)
    autopilot_->setAltitudeSetpoint(sp.value);
  else
    autopilot_->setSetpoint(sp.value);
  // The winch's feed-forward: the planner's steady cable out for a depth at the ship's speed now (none in
  // altitude mode, whose depth changes with the bottom, or where no cable out reaches the depth).
  if (autopilot_loop_.cable_out_plan && autopilot_loop_.params.actuator != DepthAutopilotParams::Actuator::kElevator)
  {
    const double plan = sp.altitude
                            ? std::numeric_limits<double>::quiet_NaN()
                            : autopilot_loop_.cable_out_plan(sp.value, ship_->pose(std::max(sp.t, time())).speed);
    autopilot_->setCableOutFeedForward(std::isfinite(plan) && plan > 0.0 ? plan
                                                                         : std::numeric_limits<double>::quiet_NaN());
  }
}

void TowRun::elasticOutputs(TowSnapshot& s)
{
  if (model_->elastic())
  {
    // A segment is slack when it carries no tension (the end body keeps the rigid rule).
    const std::vector<double>& mu = sim_.axialMultipliers();
    for (int e = 0; e < s.segments; ++e)
      s.slack[static_cast<size_t>(e)] = !(mu[static_cast<size_t>(e)] < 0.0);
    for (double eps : segmentStrains(sim_.geometry(), s.joints))
      max_strain_ = std::max(max_strain_, eps);
  }
  s.snap_count = snap_count_;
  s.max_strain = model_->elastic() ? max_strain_ : 0.0;
  max_strain_ = -std::numeric_limits<double>::infinity();
}

// The published attitude (AttitudeHold near the vertical), its pitch and yaw, then a rolling vehicle's roll
// about x_b (REP-103: yaw, pitch, roll).
void TowRun::attitudeOutputs(TowSnapshot& s)
{
  const VehicleOutputs& o = s.vehicle;
  const Eigen::Quaterniond level = attitude_.update(o.q_WB * Eigen::Vector3d::UnitX());
  s.pitch = pitchOf(level * Eigen::Vector3d::UnitX());
  s.yaw = yawOf(level * Eigen::Vector3d::UnitY());
  s.roll = o.roll;
  s.attitude = o.roll != 0.0 ? Eigen::Quaterniond(level * Eigen::AngleAxisd(o.roll, Eigen::Vector3d::UnitX())) : level;
}

TowSnapshot TowRun::snapshot()
{
  if (!started_)
    throw std::logic_error("TowRun::snapshot before start()");
  TowSnapshot s;
  s.t = sim_.time();
  s.ship = ship_->pose(s.t);
  s.tow_point = sim_.shipEnd();
  s.segments = sim_.geometry().segments;
  s.joints = sim_.jointPositions();
  s.tensions = sim_.tensions();
  if (!s.joints.allFinite() || !s.tensions.allFinite())
    throw std::runtime_error("non-finite state at t = " + std::to_string(s.t) + " s");
  s.slack = slackFlags(s.joints, s.tensions);
  sectionAndBodyOutputs(s);
  elasticOutputs(s);
  s.tension_ship = sim_.shipTension();  // parted: of the cable left on the ship (0: none)
  s.parted = sim_.parted();
  s.ship_side = sim_.shipSideJoints();
  s.ship_side_tensions = sim_.shipSideTensions();
  s.tension_vehicle = s.tensions.col(s.segments).norm();
  s.cable_length = sim_.cableLength();
  s.payout_rate = sim_.payoutRate();
  s.max_length_error = max_length_error_;
  max_length_error_ = 0.0;
  tension_ship_range_.add(s.tension_ship);
  tension_vehicle_range_.add(s.tension_vehicle);
  s.tension_ship_range = tension_ship_range_;
  s.tension_vehicle_range = tension_vehicle_range_;
  tension_ship_range_ = tension_vehicle_range_ = ValueRange();

  const VehicleOutputs& o = s.vehicle = vehicleOutputs();
  attitudeOutputs(s);
  s.depth = o.depth;
  const Eigen::Vector3d heading(std::cos(s.ship.heading), std::sin(s.ship.heading), 0.0);
  s.layback = (s.tow_point.p_W - o.p_cg_W).dot(heading);
  s.diversion = lateralDiversion(o.p_cg_W, o.v_cg_W, s.tow_point, heading);

  const Seabed* bottom = model_->seabed();
  s.seabed_present = bottom != nullptr;
  s.vehicle_altitude = bottom ? bottom->altitude(o.p_cg_W) : std::numeric_limits<double>::quiet_NaN();
  s.joint_contact.assign(static_cast<size_t>(s.joints.cols()), false);
  if (bottom)
  {
    for (Eigen::Index j = 1; j < s.joints.cols(); ++j)
      s.joint_contact[static_cast<size_t>(j)] = bottom->altitude(s.joints.col(j)) < 0.0;
    s.contacts = static_cast<int>(std::count(s.joint_contact.begin(), s.joint_contact.end(), true));
    const ElementKinematics k = sim_.elementKinematics(s.segments);
    for (double eta : vehicle_->contactFractions())
      s.vehicle_on_seabed = s.vehicle_on_seabed || bottom->altitude(k.pointAt(eta)) < 0.0;
  }
  if (autopilot_ && autopilot_->hasSetpoint())
    s.depth_setpoint = autopilot_->setpoint();
  s.parting = sim_.partingEvent();
  return s;
}

void TowRun::sectionAndBodyOutputs(TowSnapshot& s) const
{
  const ChainGeometry& geometry = sim_.geometry();
  s.segment_section.resize(static_cast<size_t>(geometry.segments));
  for (int e = 0; e < geometry.segments; ++e)
    s.segment_section[static_cast<size_t>(e)] = geometry.sectionOf(e);
  if (model_->bodies().empty())
    return;
  const ChainState state = sim_.state();  // x_2 .., like the accelerations
  for (const JointBody& body : model_->bodies())
  {
    BodyOutput& out = s.bodies.emplace_back();
    const int c = geometry.segments - body.joint;  // its column of the joints: x_1 is column 0
    if (body.joint >= geometry.segments)
    {
      out.joint = -1;
      out.p_W = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
      out.depth = out.p_W.z();
      out.tension_above = out.tension_below = out.p_W;
      continue;
    }
    out.joint = c;
    out.p_W = s.joints.col(c);
    out.depth = -out.p_W.z();
    out.tension_below = s.tensions.col(c);
    // The body's balance (docs/physics.md §11, (P47)): (m_p + m_a) a = T_above - T_below + f_p.
    const Eigen::Vector3d f = body.force(sim_.data().environment, s.t, out.p_W, state.v.col(c - 1));
    out.tension_above = out.tension_below - f + body.inertia() * sim_.accelerations().col(c - 1);
  }
}

RunState TowRun::saveState() const
{
  if (!started_)
    throw std::logic_error("TowRun::saveState before start()");
  RunState s;
  s.sim = sim_.saveState();
  s.reached = reached_;
  s.tow_point = sim_.shipEnd();
  s.heading = ship_->pose(time()).heading;
  s.ticks = ticks_;
  s.snap_count = snap_count_;
  s.max_strain = max_strain_;
  s.max_length_error = max_length_error_;
  s.tension_ship_range = tension_ship_range_;
  s.tension_vehicle_range = tension_vehicle_range_;
  s.attitude_heading = attitude_.heldHeading();
  if (autopilot_)
    s.autopilot = autopilot_->state();
  return s;
}

namespace
{
void requireFinite(const std::string& field, double value)
{
  if (!std::isfinite(value))
    throw std::invalid_argument("saved state: " + field + " must be finite, got " + std::to_string(value));
}

void requireNotAfter(const std::string& field, double value, double reached)
{
  requireFinite(field, value);
  if (value > reached + 1e-9 * std::max(1.0, std::abs(reached)))
    throw std::invalid_argument("saved state: " + field + " = " + std::to_string(value) +
                                " s is after the state's time " + std::to_string(reached) + " s");
}

void requireNotInfinite(const std::string& field, double value)
{
  if (std::isinf(value))
    throw std::invalid_argument("saved state: " + field + " must be finite or NaN (unknown)");
}

void validate(const DepthAutopilotState& a, double max_depth, double reached)
{
  if (!(a.setpoint >= 0.0 && a.setpoint <= max_depth) ||
      !(a.altitude_setpoint >= 0.0 && a.altitude_setpoint <= max_depth))
    throw std::invalid_argument("saved state: autopilot.setpoint and altitude_setpoint must be in [0, max_depth = " +
                                std::to_string(max_depth) + "] [m]");
  requireNotAfter("autopilot.vehicle.t", a.vehicle.t, reached);
  requireNotAfter("autopilot.integrated_until", a.integrated_until, reached);
  if (!a.vehicle.p_W.allFinite() || !a.vehicle.v_W.allFinite())
    throw std::invalid_argument("saved state: autopilot.vehicle position and velocity must be finite");
  requireNotInfinite("autopilot.vehicle altitude", a.vehicle.altitude);
  requireNotInfinite("autopilot.vehicle cable out", a.vehicle.cable_out);
  requireNotInfinite("autopilot.vehicle received", a.vehicle.received);
  if (!std::isnan(a.cable_out_base) && !(a.cable_out_base > 0.0 && std::isfinite(a.cable_out_base)))
    throw std::invalid_argument("saved state: the autopilot's cable out base must be > 0 m or NaN (none)");
  requireFinite("autopilot.integral", a.integral);
  requireFinite("autopilot.winch_integral", a.winch_integral);
}

void validateOutputs(const RunState& s)
{
  requireFinite("reached", s.reached);
  if (std::abs(s.reached - s.sim.t) > 1e-6 * std::max(1.0, std::abs(s.reached)))
    throw std::invalid_argument("saved state: reached = " + std::to_string(s.reached) +
                                " s is not the state's t = " + std::to_string(s.sim.t) + " s");
  if (!(s.max_length_error >= 0.0) || std::isnan(s.max_strain) || std::isnan(s.tension_ship_range.min) ||
      std::isnan(s.tension_ship_range.max) || std::isnan(s.tension_vehicle_range.min) ||
      std::isnan(s.tension_vehicle_range.max))
    throw std::invalid_argument(
        "saved state: max_length_error must be >= 0, max_strain and the tension ranges "
        "not NaN");
}
}  // namespace

void TowRun::restore(const RunState& s)
{
  if (ship_->empty())
    throw std::invalid_argument("TowRun::restore: no ship sample yet");
  validateOutputs(s);
  if (s.autopilot)
    validate(*s.autopilot, autopilot_loop_.params.max_depth, s.reached);
  if (s.snap_count < 0 || s.ticks < 0)
    throw std::invalid_argument("saved state: ticks and snap_count must not be negative");
  sim_.restoreState(s.sim);  // checks everything before it changes anything
  const double t = s.reached;
  // The schedule as it stands after t: what was due by then has acted (the state holds its effect).
  next_command_ = 0;
  while (next_command_ < commands_.size() && commands_[next_command_].t <= t)
    ++next_command_;
  if (autopilot_loop_.enabled)
  {
    autopilot_ = std::make_unique<DepthAutopilot>(autopilot_loop_.params);
    const std::vector<AutopilotSetpoint>& setpoints = autopilot_loop_.setpoints;
    for (next_setpoint_ = 0; next_setpoint_ < setpoints.size() && setpoints[next_setpoint_].t <= t; ++next_setpoint_)
      if (!s.autopilot)
        applySetpoint(setpoints[next_setpoint_]);
    if (s.autopilot)
      autopilot_->restore(*s.autopilot);
    // The saved tick goes on where it was (a tick at exactly t has run or not); any other rate's from t on.
    const long first = firstTickFrom(t);
    ticks_ = s.autopilot && (s.ticks == first || s.ticks == first + 1) ? s.ticks : first;
  }
  snap_count_ = s.snap_count;
  max_strain_ = s.max_strain;
  max_length_error_ = s.max_length_error;
  tension_ship_range_ = s.tension_ship_range;
  tension_vehicle_range_ = s.tension_vehicle_range;
  attitude_.restoreHeading(s.attitude_heading);
  started_ = true;
  reached_ = s.reached;
}

RunState relocate(const RunState& state, double t, const ShipEndState& tow_point, double heading)
{
  RunState s = state;
  const double dt = t - state.sim.t;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(heading - state.heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d p0 = state.tow_point.p_W, v0 = state.tow_point.v_W;
  auto place = [&](Eigen::Vector3d& p, Eigen::Vector3d& v)
  {
    p = tow_point.p_W + R * (p - p0);
    v = tow_point.v_W + R * (v - v0);
  };
  // A rolling vehicle's two roll states (physics.md §5b) follow the rest; its roll angle is from its zero-roll
  // frame, which turns with the joints.
  const StateLayout plain{ state.sim.segments + 1 };
  const StateLayout L{ plain.joints, false, 0, true, state.sim.y.size() == plain.size() + 2 };
  if (state.sim.y.size() != L.size())
    throw std::invalid_argument("saved state: y does not have the size of its segments");
  auto x = L.positions(s.sim.y);
  auto v = L.velocities(s.sim.y);
  for (int j = 0; j < L.joints; ++j)
  {
    Eigen::Vector3d p = x.col(j), w = v.col(j);
    place(p, w);
    x.col(j) = p;
    v.col(j) = w;
  }
  s.sim.t = t;
  s.reached += dt;
  s.sim.rudder.t0 += dt;
  s.sim.elevator.t0 += dt;
  s.sim.differential.t0 += dt;
  s.tow_point = tow_point;
  s.heading = heading;
  if (std::isfinite(s.attitude_heading))  // a held heading turns with the ship
    s.attitude_heading += heading - state.heading;
  if (s.autopilot)
  {
    DepthAutopilotState& a = *s.autopilot;
    a.vehicle.t += dt;
    a.vehicle.received += dt;  // NaN stays NaN
    a.integrated_until += dt;
    place(a.vehicle.p_W, a.vehicle.v_W);
    for (Eigen::Vector2d& q : a.track)
      q = tow_point.p_W.head<2>() + R.topLeftCorner<2, 2>() * (q - p0.head<2>());
  }
  return s;
}

}  // namespace tow_sim
