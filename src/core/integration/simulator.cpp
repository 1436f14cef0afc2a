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
  validate(winch_, *model_);
  data_ = model_->initialData(0.0);
  wholeCable();
  dt_ = std::min(model_->numerics().max_step, 0.01);
  tableau_ = model_->numerics().implicit_method == ImplicitMethod::kRos2 ? &ros2Tableau() : &ros34pw2Tableau();
  implicit_.setMethod(tableau_->gamma, model_->numerics().implicit_frame == ImplicitFrame::kTowPoint);
}

Simulator::~Simulator() = default;

void Simulator::wholeCable()
{
  forgetLinearisation();
  chains_.assign(1, Chain(model_->initialGeometry(), StateLayout{}));
  y_.assign(layout().size(), 0.0);
  dydt_.assign(y_.size(), 0.0);
  layout().cableOut(y_) = model_->cableLength();
}

double Simulator::setWinchCommand(double payout_rate)
{
  if (!winch_.enabled)
    throw std::invalid_argument("winch command: the winch is disabled (winch.enabled: false)");
  if (parted())
    throw std::invalid_argument("winch command: the cable has parted");
  if (!std::isfinite(payout_rate))
    throw std::invalid_argument("winch command: the payout rate must be a finite number [m/s]");
  forgetLinearisation();
  data_.winch_command = std::clamp(payout_rate, -winch_.max_rate, winch_.max_rate);
  return data_.winch_command;
}

ChainGeometry Simulator::geometryOf(const StateVector& y) const
{
  if (!winch_.enabled || parted())  // parted: the winch has nothing to pay out
    return vehicleSide().geometry();
  return paidOut(winch_, data_.winch_command, vehicleSide().geometry(), layout().cableOut(y), layout().payoutRate(y));
}

bool Simulator::remesh(double t)
{
  if (!winch_.enabled || parted())
    return false;
  ChainGeometry geometry = vehicleSide().geometry();
  if (!remeshFirstSegment(winch_, ship_(t), geometry, y_))
    return false;
  vehicleSide().setGeometry(geometry);
  dydt_.assign(y_.size(), 0.0);
  return true;
}

void Simulator::derivative(double t, const StateVector& y, StateVector& dydt) const
{
  const ShipEndState ship = ship_(t);
  const ChainGeometry geometry = geometryOf(y);
  vehicleSide().derivative(*model_, geometry, data_, t, ship, y, dydt);
  for (std::size_t i = 1; i < chains_.size(); ++i)
    chains_[i].derivative(*model_, chains_[i].geometry(), data_, t, ship, y, dydt);
  const StateLayout& L = layout();
  L.cableOut(dydt) = winch_.enabled ? L.payoutRate(y) : 0.0;
  L.payoutRate(dydt) = winch_.enabled ? geometry.first_acceleration : 0.0;
}

void Simulator::refreshOutputs(bool keep_linearisation)
{
  vehicleSide().setGeometry(geometryOf(y_));
  dydt_.resize(chains_.back().layout().end());
  const ShipEndState ship = ship_(t_);
  for (Chain& chain : chains_)
    chain.refresh(*model_, data_, t_, ship, y_, dydt_);
  const StateLayout& L = layout();
  L.cableOut(dydt_) = winch_.enabled ? L.payoutRate(y_) : 0.0;
  L.payoutRate(dydt_) = winch_.enabled ? geometry().first_acceleration : 0.0;
  if (implicit() && !(keep_linearisation && linearised_t_ == t_ && linearised_size_ == y_.size()))
  {
    linearise();
    linearised_t_ = t_;
    linearised_size_ = y_.size();
  }
}

void Simulator::project(double t)
{
  if (winch_.enabled && !parted())  // parted: the vehicle side's length is no winch's
    stopAtLimits(winch_, layout().cableOut(y_), layout().payoutRate(y_));
  vehicleSide().setGeometry(geometryOf(y_));
  const ShipEndState ship = ship_(t);
  for (const Chain& chain : chains_)
    chain.project(*model_, ship, y_);
}

double Simulator::lengthError() const
{
  double error = 0.0;
  for (const Chain& chain : chains_)
    error = std::max(error, chain.lengthError(*model_, ship_(t_), y_));
  return error;
}

double Simulator::largestRelativeSpeed(double t) const
{
  double speed = 0.0;
  for (const Chain& chain : chains_)
    speed = std::max(speed, chain.largestRelativeSpeed(ship_(t), y_));
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
  refreshOutputs(true);
  // While the winch runs, a step shortens the first segment by at most half the band's lower edge (the
  // rate stays within max_rate), so it never collapses before the merge that follows the step.
  const double winch_step = winch_.enabled
                                ? 0.5 * winch_.segment_min_fraction * geometry().nominal_length / winch_.max_rate
                                : std::numeric_limits<double>::infinity();
  StepReport report;
  while (t_end - t_ > 1e-12 * std::max(1.0, std::abs(t_end)))
    stepOnce(t_end, parted() ? std::numeric_limits<double>::infinity() : winch_step, report);  // parted: stopped
  return report;
}

void Simulator::stepOnce(double t_end, double winch_step, StepReport& report)
{
  const StateVector y_prev = y_;
  const double t_prev = t_;
  if (implicit())
  {
    if (!stepImplicit(t_end, winch_step, report))
      return;
  }
  else if (!explicit_->step(
               stepper(), [this](const StateVector& y, StateVector& dydt, double t) { derivative(t, y, dydt); }, y_,
               dydt_, t_, dt_, t_end, winch_step))
  {
    ++report.rejected;
    if (dt_ < kMinStep)
      throw std::runtime_error("integration failed: the adaptive step fell below 1e-10 s at t = " + std::to_string(t_) +
                               " s");
    return;
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
  vehicleSide().setGeometry(geometryOf(y_));
  report.max_length_error = std::max(report.max_length_error, lengthError());
  const std::size_t size = y_.size();
  remesh(t_);
  project(t_);
  refreshOutputs();
  report.tension_ship.add(shipTension());
  report.tension_vehicle.add(tensions().col(tensions().cols() - 1).norm());
  countSnaps(report);
  checkBreak(report);
  if (y_.size() != size)  // re-meshed or parted: odeint sizes its buffers once
    explicit_ = std::make_unique<ExplicitStepper>(model_->numerics());
}

ElementKinematics Simulator::elementKinematics(int e) const
{
  return vehicleSide().elementKinematics(e, ship_(t_), y_);
}

ChainState Simulator::state() const
{
  ChainState s;
  s.x = layout().positions(y_);
  s.v = layout().velocities(y_);
  return s;
}

Eigen::Matrix3Xd Simulator::jointPositions() const
{
  return vehicleSide().jointPositions(ship_(t_), y_);
}

}  // namespace tow_sim
