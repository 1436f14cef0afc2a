// The Simulator's saved state: taken and given back whole, so that a restored run steps on bit-identically.
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
}  // namespace

SimulatorState Simulator::saveState() const
{
  if (free_)
    throw std::logic_error("saved state: a parted cable's state cannot be saved (not supported yet)");
  SimulatorState s;
  s.t = t_;
  s.dt = dt_;
  s.segments = data_.geometry.segments;
  s.y = y_;
  s.rudder = data_.actuators.rudder.state();
  s.elevator = data_.actuators.elevator.state();
  s.thrust = data_.actuators.thrust;
  s.winch_command = data_.winch_command;
  s.slack = slack_;
  return s;
}

void Simulator::restoreState(const SimulatorState& s)
{
  // Everything is checked before anything changes (restoreLayout checks first, too).
  requireFinite("t", s.t);
  if (!(s.dt > 0.0) || !std::isfinite(s.dt))
    throw std::invalid_argument("saved state: dt must be a finite step > 0 s, got " + std::to_string(s.dt));
  if (s.segments < 1 || s.segments > 100000)
    throw std::invalid_argument("saved state: segments must be in [1, 100000], got " + std::to_string(s.segments));
  const StateLayout L{ s.segments + 1 };
  if (s.y.size() != L.size())
    throw std::invalid_argument("saved state: y has " + std::to_string(s.y.size()) + " values; " +
                                std::to_string(s.segments) + " segments need " + std::to_string(L.size()));
  for (std::size_t i = 0; i < s.y.size(); ++i)
    requireFinite("y[" + std::to_string(i) + "]", s.y[i]);
  requireFinite("rudder", s.rudder);
  requireFinite("elevator", s.elevator);
  requireFinite("thrust", s.thrust);
  requireFinite("winch_command", s.winch_command);
  if (!winch_.enabled && (s.winch_command != 0.0 || L.payoutRate(s.y) != 0.0))
    throw std::invalid_argument(
        "saved state: the winch runs (a payout command or rate) but this run has no winch "
        "(winch.enabled)");
  if (!s.slack.empty() && s.slack.size() != static_cast<std::size_t>(s.segments))
    throw std::invalid_argument("saved state: slack has " + std::to_string(s.slack.size()) + " flags for " +
                                std::to_string(s.segments) + " segments");
  const bool was_parted = free_;
  free_ = false;  // a saved state is of a whole cable
  try
  {
    restoreLayout(s.segments, L.cableOut(s.y));
  }
  catch (const std::invalid_argument&)
  {
    free_ = was_parted;
    std::ostringstream os;
    os << "saved state: " << s.segments << " segments and " << L.cableOut(s.y)
       << " m of cable out do not fit this cable (cable.segments " << model_->segments() << ", cable.length "
       << model_->cableLength() << " m, winch " << (winch_.enabled ? "on" : "off") << ")";
    throw std::invalid_argument(os.str());
  }
  parting_event_.reset();
  clearShipSide();
  t_ = s.t;
  dt_ = s.dt;
  y_ = s.y;
  dydt_.assign(y_.size(), 0.0);
  data_.actuators.rudder.restore(s.rudder);
  data_.actuators.elevator.restore(s.elevator);
  data_.actuators.thrust = s.thrust;
  data_.winch_command = s.winch_command;
  slack_ = s.slack;
  refreshOutputs();
}

}  // namespace tow_sim
