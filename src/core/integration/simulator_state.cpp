// The Simulator's layout and restart, and its saved state: taken and given back whole, so that a restored run
// steps on bit-identically.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tow_sim/core/integration/simulator.h"

namespace tow_sim
{
namespace
{
void requireFinite(const std::string& field, double value)
{
  if (!std::isfinite(value))
    throw std::invalid_argument("saved state: " + field + " must be finite, got " + std::to_string(value));
}

void requireFinite(const std::string& field, const FinServo::State& servo)
{
  requireFinite(field + ".t0", servo.t0);
  requireFinite(field + ".angle0", servo.angle0);
  requireFinite(field + ".target", servo.target);
}

// `geometry` with nu = segments and cable_out [m] out (Simulator::restoreLayout, whose errors it throws).
ChainGeometry laidOut(const ChainModel& model, const WinchParams& winch, ChainGeometry geometry, int segments,
                      double cable_out)
{
  geometry.segments = segments;
  const double first = cable_out - geometry.lengthAftOfFirst();
  const bool fixed_length_differs =
      !winch.enabled && std::abs(cable_out - model.cableLength()) > 1e-9 * model.cableLength();
  if (segments <= geometry.aftSectionSegments() || segments > 100000 || !std::isfinite(cable_out) || !(first > 0.0) ||
      (winch.enabled && (cable_out < winch.min_length || cable_out > winch.max_length)) ||
      (!winch.enabled && (segments != model.segments() || fixed_length_differs)))
    throw std::invalid_argument("restoreLayout: " + std::to_string(segments) + " segments and " +
                                std::to_string(cable_out) + " m of cable out are not a layout of this cable");
  geometry.first_length = winch.enabled ? first : geometry.nominal_length;
  return geometry;
}

// Everything in a saved state that can be checked without the simulator's cable (std::invalid_argument
// naming the field); its layout.
StateLayout validateSavedState(const SimulatorState& s, bool winch_enabled, bool roll)
{
  requireFinite("t", s.t);
  if (!(s.dt > 0.0) || !std::isfinite(s.dt))
    throw std::invalid_argument("saved state: dt must be a finite step > 0 s, got " + std::to_string(s.dt));
  if (s.segments < 1 || s.segments > 100000)
    throw std::invalid_argument("saved state: segments must be in [1, 100000], got " + std::to_string(s.segments));
  const StateLayout L{ s.segments + 1, false, 0, true, roll };
  if (s.y.size() != L.size())
    throw std::invalid_argument("saved state: y has " + std::to_string(s.y.size()) + " values; " +
                                std::to_string(s.segments) + " segments need " + std::to_string(L.size()));
  for (std::size_t i = 0; i < s.y.size(); ++i)
    requireFinite("y[" + std::to_string(i) + "]", s.y[i]);
  requireFinite("rudder", s.rudder);
  requireFinite("elevator", s.elevator);
  requireFinite("differential", s.differential);
  requireFinite("thrust", s.thrust);
  requireFinite("winch_command", s.winch_command);
  if (!winch_enabled && (s.winch_command != 0.0 || L.payoutRate(s.y) != 0.0))
    throw std::invalid_argument(
        "saved state: the winch runs (a payout command or rate) but this run has no winch "
        "(winch.enabled)");
  if (!s.slack.empty() && s.slack.size() != static_cast<std::size_t>(s.segments))
    throw std::invalid_argument("saved state: slack has " + std::to_string(s.slack.size()) + " flags for " +
                                std::to_string(s.segments) + " segments");
  return L;
}
}  // namespace

void Simulator::restoreLayout(int segments, double cable_out)
{
  if (parted())
    throw std::logic_error("restoreLayout: the cable has parted: rejoin() it first");
  forgetLinearisation();
  vehicleSide().setGeometry(laidOut(*model_, winch_, geometry(), segments, cable_out));
  y_.assign(layout().size(), 0.0);
  layout().cableOut(y_) = cable_out;
}

void Simulator::reset(double t, const ChainState& state)
{
  if (parted())
    throw std::logic_error("reset: the cable has parted: rejoin() it first");
  const StateLayout L = layout();
  if (state.x.cols() != L.joints || state.v.cols() != L.joints)
  {
    std::ostringstream os;
    os << "initial state: expected " << L.joints << " joints (segments + 1), got " << state.x.cols()
       << " positions and " << state.v.cols() << " velocities";
    throw std::invalid_argument(os.str());
  }
  if (!std::isfinite(t) || !state.x.allFinite() || !state.v.allFinite())
    throw std::invalid_argument("initial state: time, positions and velocities must be finite");
  t_ = t;
  y_.resize(L.size());
  dydt_.resize(L.size());
  // The winch restarts from rest with its command cleared; the cable out and the layout are kept.
  L.payoutRate(y_) = 0.0;
  data_.winch_command = 0.0;
  L.positions(y_) = state.x;
  L.velocities(y_) = state.v;
  L.setRollState(y_, Eigen::Vector2d::Zero());  // a rolling vehicle starts level and not spinning
  project(t_);
  refreshOutputs();
  dt_ = std::min(model_->numerics().max_step, 0.01);
  slack_.clear();
  StepReport ignored;
  countSnaps(ignored);  // the taut segments of the restart
}

SimulatorState Simulator::saveState() const
{
  if (parted())
    throw std::logic_error("saved state: a parted cable's state cannot be saved (not supported yet)");
  SimulatorState s;
  s.t = t_;
  s.dt = dt_;
  s.segments = geometry().segments;
  s.y = y_;
  s.rudder = data_.actuators.rudder.state();
  s.elevator = data_.actuators.elevator.state();
  s.differential = data_.actuators.differential.state();
  s.thrust = data_.actuators.thrust;
  s.winch_command = data_.winch_command;
  s.slack = slack_;
  return s;
}

void Simulator::restoreState(const SimulatorState& s)
{
  // Everything is checked before anything changes (restoreLayout checks first, too); a saved state is of
  // the whole cable.
  const StateLayout L = validateSavedState(s, winch_.enabled, model_->initialGeometry().rollingEnd());
  const std::vector<Chain> before = chains_;
  chains_.assign(1, Chain(model_->initialGeometry(), StateLayout{}));
  try
  {
    restoreLayout(s.segments, L.cableOut(s.y));
  }
  catch (const std::invalid_argument&)
  {
    chains_ = before;
    std::ostringstream os;
    os << "saved state: " << s.segments << " segments and " << L.cableOut(s.y)
       << " m of cable out do not fit this cable (cable.segments " << model_->segments() << ", cable.length "
       << model_->cableLength() << " m, winch " << (winch_.enabled ? "on" : "off") << ")";
    throw std::invalid_argument(os.str());
  }
  parting_event_.reset();
  t_ = s.t;
  dt_ = s.dt;
  y_ = s.y;
  dydt_.assign(y_.size(), 0.0);
  data_.actuators.rudder.restore(s.rudder);
  data_.actuators.elevator.restore(s.elevator);
  data_.actuators.differential.restore(s.differential);
  data_.actuators.thrust = s.thrust;
  data_.winch_command = s.winch_command;
  slack_ = s.slack;
  refreshOutputs();
}

}  // namespace tow_sim
