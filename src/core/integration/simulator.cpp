#include "tow_sim/core/integration/simulator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/integration/winch.h"

namespace tow_sim
{
namespace
{
// A joint moving faster than this relative to the tow point [m/s] means the integration ran away.
constexpr double kMaxRelativeSpeed = 200.0;

bool allFinite(const std::vector<double>& y)
{
  return std::all_of(y.begin(), y.end(), [](double value) { return std::isfinite(value); });
}
}  // namespace

ShipMotion constantVelocityShip(const Eigen::Vector3d& p0_W, const Eigen::Vector3d& v_W)
{
  return [p0_W, v_W](double t)
  {
    ShipEndState s;
    s.p_W = p0_W + t * v_W;
    s.v_W = v_W;
    return s;
  };
}

Simulator::Simulator(std::shared_ptr<const ChainModel> model, ShipMotion ship, const WinchParams& winch)
    : model_(std::move(model)), ship_(std::move(ship)), winch_(winch)
{
  if (!ship_)
    throw std::invalid_argument("Simulator: no ship motion given");
  validateWinch();
  data_ = model_->initialData(0.0);
  const StateLayout L = layout();
  y_.assign(L.size(), 0.0);
  dydt_.assign(L.size(), 0.0);
  L.cableOut(y_) = model_->cableLength();
  tensions_.setZero(3, L.joints);
  accelerations_.setZero(3, L.joints);
  dt_ = std::min(model_->numerics().max_step, 0.01);
  tableau_ = model_->numerics().implicit_method == ImplicitMethod::kRos2 ? &ros2Tableau() : &ros34pw2Tableau();
  implicit_.setGamma(tableau_->gamma);
}

Simulator::~Simulator() = default;

bool Simulator::command(double rudder, double elevator, double thrust)
{
  return commandAt(t_, rudder, elevator, thrust);
}

bool Simulator::commandAt(double t, double rudder, double elevator, double thrust)
{
  return model_->endBody().command(data_.actuators, t, rudder, elevator, thrust);
}

void Simulator::resetActuators(double t)
{
  data_.actuators = model_->endBody().restingActuators(t);
}

void Simulator::setCurrent(const Eigen::Vector3d& current_W)
{
  tow_sim::setCurrent(data_, current_W);
}

void Simulator::setCurrentProfile(const std::vector<CurrentSample>& profile)
{
  tow_sim::setCurrentProfile(data_, profile);
}

double Simulator::setWinchCommand(double payout_rate)
{
  if (!winch_.enabled)
    throw std::invalid_argument("winch command: the winch is disabled (winch.enabled: false)");
  if (free_)
    throw std::invalid_argument("winch command: the cable has parted");
  if (!std::isfinite(payout_rate))
    throw std::invalid_argument("winch command: the payout rate must be a finite number [m/s]");
  data_.winch_command = std::clamp(payout_rate, -winch_.max_rate, winch_.max_rate);
  return data_.winch_command;
}

double Simulator::cableLength() const
{
  return layout().cableOut(y_);
}
double Simulator::payoutRate() const
{
  return layout().payoutRate(y_);
}

ChainGeometry Simulator::geometryOf(const StateVector& y) const
{
  ChainGeometry g = data_.geometry;
  if (!winch_.enabled || free_)  // parted: the winch has nothing to pay out
    return g;
  const StateLayout L{ g.jointCount() };
  const double length = L.cableOut(y), rate = L.payoutRate(y);
  g.first_length = std::max(length - g.lengthAftOfFirst(), 1e-9);
  g.first_rate = rate;
  g.first_acceleration = winchAcceleration(winch_, data_.winch_command, length, rate);
  return g;
}

void Simulator::validateWinch() const
{
  if (model_->sectionCount() == 1)
  {
    validate(winch_, model_->cable());
    return;
  }
  // With cable sections the winch pays out and hauls in the first section only (docs/solver.md §11): its
  // limits, less the cable of the sections aft of it, are the first section's.
  double aft = 0.0;
  for (int i = 1; i < model_->sectionCount(); ++i)
    aft += model_->section(i).cable.length;
  WinchParams first = winch_;
  first.min_length -= aft;
  first.max_length -= aft;
  try
  {
    validate(first, model_->cable());
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(
        std::string(e.what()) + " (with cable sections: the winch's min_length and max_length less the " +
        std::to_string(aft) + " m of the sections aft of the first, which the winch never moves)");
  }
}

bool Simulator::remesh(double t)
{
  if (!winch_.enabled || free_)
    return false;
  if (!remeshFirstSegment(winch_, ship_(t), data_.geometry, y_))
    return false;
  dydt_.assign(y_.size(), 0.0);
  return true;
}

void Simulator::restoreLayout(int segments, double cable_out)
{
  ChainGeometry candidate = data_.geometry;
  candidate.segments = segments;
  const double first = cable_out - candidate.lengthAftOfFirst();
  const bool fixed_length_differs =
      !winch_.enabled && std::abs(cable_out - model_->cableLength()) > 1e-9 * model_->cableLength();
  if (segments <= candidate.aftSectionSegments() || segments > 100000 || !std::isfinite(cable_out) || !(first > 0.0) ||
      (winch_.enabled && (cable_out < winch_.min_length || cable_out > winch_.max_length)) ||
      (!winch_.enabled && (segments != model_->segments() || fixed_length_differs)))
    throw std::invalid_argument("restoreLayout: " + std::to_string(segments) + " segments and " +
                                std::to_string(cable_out) + " m of cable out are not a layout of this cable");
  data_.geometry.segments = segments;
  y_.assign(layout().size(), 0.0);
  layout().cableOut(y_) = cable_out;
  data_.geometry.first_length = winch_.enabled ? first : data_.geometry.nominal_length;
}

void Simulator::reset(double t, const ChainState& state)
{
  if (free_)
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
  project(t_);
  refreshOutputs();
  dt_ = std::min(model_->numerics().max_step, 0.01);
  slack_.clear();
  StepReport ignored;
  countSnaps(ignored);  // the taut segments of the restart
}

void Simulator::derivative(double t, const StateVector& y, StateVector& dydt) const
{
  const ChainGeometry geometry = geometryOf(y);
  const StateLayout L{ geometry.jointCount(), free_, free_ ? ship_side_.segments : 0 };
  L.positions(dydt) = L.velocities(y);
  Eigen::Map<Eigen::Matrix3Xd> a = L.velocities(dydt);
  if (free_)
  {
    const ShipEndState end = towPoint(t, y);
    L.freePosition(dydt) = L.freeVelocity(y);
    L.freeVelocity(dydt) = solver_.solveFree(*model_, geometry, data_, t, end, L.positions(y), L.velocities(y), a,
                                             nullptr, nullptr, freeEndContact(geometry, end));
    shipSideDerivative(t, y, dydt);
  }
  else
    solver_.solve(*model_, geometry, data_, t, ship_(t), L.positions(y), L.velocities(y), a);
  L.cableOut(dydt) = winch_.enabled ? L.payoutRate(y) : 0.0;
  L.payoutRate(dydt) = winch_.enabled ? geometry.first_acceleration : 0.0;
}

void Simulator::refreshOutputs()
{
  const StateLayout L = layout();
  data_.geometry = geometryOf(y_);
  tensions_.resize(3, L.joints);
  accelerations_.resize(3, L.joints);
  dydt_.resize(L.size());
  if (free_)
  {
    L.freePosition(dydt_) = L.freeVelocity(y_);
    const ShipEndState end = towPoint(t_, y_);
    L.freeVelocity(dydt_) =
        solver_.solveFree(*model_, data_.geometry, data_, t_, end, L.positions(y_), L.velocities(y_), accelerations_,
                          &tensions_, &multipliers_, freeEndContact(data_.geometry, end));
    shipSideOutputs();
  }
  else
    solver_.solve(*model_, data_.geometry, data_, t_, ship_(t_), L.positions(y_), L.velocities(y_), accelerations_,
                  &tensions_, &multipliers_);
  L.positions(dydt_) = L.velocities(y_);
  L.velocities(dydt_) = accelerations_;
  L.cableOut(dydt_) = winch_.enabled ? L.payoutRate(y_) : 0.0;
  L.payoutRate(dydt_) = winch_.enabled ? data_.geometry.first_acceleration : 0.0;
  if (implicit())
    linearise();
}

void Simulator::project(double t)
{
  // Sequentially from the ship: restore each element's length along its current direction, then
  // remove the relative velocity along the element (s.(v_a - v_f) = 0).
  const StateLayout L = layout();
  if (winch_.enabled && !free_)  // parted: the vehicle side's length is no winch's
  {
    // The winch stops at its limits (its rate law brakes toward them; this removes the last overshoot).
    double& length = L.cableOut(y_);
    double& rate = L.payoutRate(y_);
    if (length >= winch_.max_length)
      rate = std::min(rate, 0.0);
    if (length <= winch_.min_length)
      rate = std::max(rate, 0.0);
    length = std::clamp(length, winch_.min_length, winch_.max_length);
    rate = std::clamp(rate, -winch_.max_rate, winch_.max_rate);
  }
  data_.geometry = geometryOf(y_);
  auto x = L.positions(y_);
  auto v = L.velocities(y_);
  const ShipEndState ship = towPoint(t, y_);
  Eigen::Vector3d x_f = ship.p_W;
  Eigen::Vector3d v_f = ship.v_W;
  // An elastic cable's segments stretch: only its end body has a length to keep.
  const int first = model_->elastic() ? data_.geometry.segments : 0;
  for (int e = 0; e < L.joints; ++e)
  {
    if (e < first)
    {
      x_f = x.col(e);
      v_f = v.col(e);
      continue;
    }
    const Eigen::Vector3d s = (x.col(e) - x_f).normalized();
    x.col(e) = x_f + data_.geometry.elementLength(e) * s;
    // Relative velocity along the element: none, but the winch's rate on the first segment.
    const double along = e == 0 ? data_.geometry.first_rate : 0.0;
    v.col(e) -= (s.dot(v.col(e) - v_f) - along) * s;
    x_f = x.col(e);
    v_f = v.col(e);
  }
  if (free_)
    projectShipSide(t);
}

double Simulator::lengthError() const
{
  const int first = model_->elastic() ? data_.geometry.segments : 0;
  return std::max(maxRelativeLengthError(data_.geometry, towPoint(t_, y_).p_W, layout().positions(y_), first),
                  shipSideLengthError());
}

void Simulator::countSnaps(StepReport& report)
{
  if (!model_->elastic())
    return;
  // A segment goes slack when it carries no tension at or below its rest length (not when its damping
  // alone zeroes the tension of a still stretched segment) and snaps when it carries tension again. A
  // restart at the rest lengths (a straight line) is not slack.
  const size_t n = static_cast<size_t>(data_.geometry.segments);
  const bool first = slack_.size() != n;  // after a reset: no step to compare with
  slack_.resize(n);
  const std::vector<double> strain = segmentStrains(data_.geometry, jointPositions());
  for (size_t e = 0; e < n; ++e)
  {
    const bool taut = multipliers_[e] < 0.0;
    if (first)
      slack_[e] = !taut && strain[e] < 0.0;
    else if (slack_[e] && taut)
    {
      ++report.snaps;
      slack_[e] = false;
    }
    else if (!taut && strain[e] <= 0.0)
      slack_[e] = true;
    report.max_strain = std::max(report.max_strain, strain[e]);
  }
}

double Simulator::largestRelativeSpeed(double t) const
{
  const StateLayout L = layout();
  double speed = (L.velocities(y_).colwise() - towPoint(t, y_).v_W).colwise().norm().maxCoeff();
  if (L.ship_side > 0)  // the cable left on the ship, relative to the ship
    speed = std::max(speed, (L.shipSideVelocities(y_).colwise() - ship_(t).v_W).colwise().norm().maxCoeff());
  return speed;
}

StepReport Simulator::advanceTo(double t_end)
{
  if (!(t_end >= t_))
  {
    std::ostringstream os;
    os << "advanceTo: target time " << t_end << " s is before the current time " << t_ << " s";
    throw std::invalid_argument(os.str());
  }
  explicit_ = std::make_unique<ExplicitStepper>(model_->numerics());
  // The commands, the current or the thrust may have changed since the last step: the derivative the
  // first step starts from (k1, first-same-as-last) is taken afresh.
  refreshOutputs();
  // While the winch runs, a step shortens the first segment by at most half the band's lower edge (the
  // rate stays within max_rate), so it never collapses before the merge that follows the step.
  const double winch_step = winch_.enabled
                                ? 0.5 * winch_.segment_min_fraction * data_.geometry.nominal_length / winch_.max_rate
                                : std::numeric_limits<double>::infinity();
  StepReport report;
  while (t_end - t_ > 1e-12 * std::max(1.0, std::abs(t_end)))
    stepOnce(t_end, winch_step, report);
  return report;
}

void Simulator::stepOnce(double t_end, double winch_step, StepReport& report)
{
  const NumericsParams& num = model_->numerics();
  const ExplicitStepper::System system = [this](const StateVector& y, StateVector& dydt, double t)
  { derivative(t, y, dydt); };
  const StateVector y_prev = y_;
  const double t_prev = t_;
  if (implicit())
  {
    if (!stepImplicit(t_end, winch_step, report))
      return;
  }
  else if (stepper() == StepperType::kRk4)
  {
    const double h = std::min({ num.fixed_step, winch_step, t_end - t_ });
    explicit_->rk4(system, y_, dydt_, t_, h);
    t_ = h == t_end - t_ ? t_end : t_ + h;
  }
  else
  {
    const double remaining = t_end - t_;
    const bool clamped = dt_ >= remaining;
    double h = std::min({ dt_, remaining, num.max_step, winch_step });
    // dopri5 is first-same-as-last: dydt_ holds f(y_) and is advanced with the step.
    if (!explicit_->dopri5(system, y_, dydt_, t_, h))
    {
      ++report.rejected;
      dt_ = h;
      if (dt_ < kMinStep)
        throw std::runtime_error(
            "integration failed: the adaptive step fell below 1e-10 s at t = " + std::to_string(t_) + " s");
      return;
    }
    if (!clamped || h > dt_)
      dt_ = std::min(h, num.max_step);
    if (clamped && remaining - (t_ - t_prev) < 1e-12)
      t_ = t_end;
  }
  const bool finite = allFinite(y_);
  const double speed = finite ? largestRelativeSpeed(t_) : 0.0;
  if (!finite || speed > kMaxRelativeSpeed)
  {
    y_ = y_prev;
    t_ = t_prev;
    refreshOutputs();
    throw std::runtime_error(finite ? "integration ran away: a joint moves at " + std::to_string(speed) +
                                          " m/s relative to the tow point at t = " + std::to_string(t_) + " s"
                                    : "integration diverged: non-finite state at t = " + std::to_string(t_) + " s");
  }
  acceptStep(report);
}

void Simulator::acceptStep(StepReport& report)
{
  ++report.steps;
  data_.geometry = geometryOf(y_);
  report.max_length_error = std::max(report.max_length_error, lengthError());
  const std::size_t size = y_.size();
  remesh(t_);
  project(t_);
  refreshOutputs();
  report.tension_ship.add(shipTension());
  report.tension_vehicle.add(tensions_.col(tensions_.cols() - 1).norm());
  countSnaps(report);
  checkBreak(report);
  if (y_.size() != size)  // re-meshed or parted: odeint sizes its buffers once
    explicit_ = std::make_unique<ExplicitStepper>(model_->numerics());
}

ElementKinematics Simulator::elementKinematics(int e) const
{
  const StateLayout L = layout();
  if (e < 0 || e >= L.joints)
    throw std::out_of_range("elementKinematics: element " + std::to_string(e) + " is not in 0 .. " +
                            std::to_string(L.joints - 1));
  const auto x = L.positions(y_);
  const auto v = L.velocities(y_);
  const ShipEndState ship = towPoint(t_, y_);
  const Eigen::Vector3d x_f = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
  const Eigen::Vector3d v_f = e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1));
  return ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
}

ChainState Simulator::state() const
{
  const StateLayout L = layout();
  ChainState s;
  s.x = L.positions(y_);
  s.v = L.velocities(y_);
  return s;
}

Eigen::Matrix3Xd Simulator::jointPositions() const
{
  const StateLayout L = layout();
  Eigen::Matrix3Xd p(3, L.joints + 1);
  p.col(0) = towPoint(t_, y_).p_W;
  p.rightCols(L.joints) = L.positions(y_);
  return p;
}

}  // namespace tow_sim
