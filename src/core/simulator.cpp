#include "tow_sim/core/simulator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace tow_sim
{
namespace odeint = boost::numeric::odeint;

namespace
{
// Smallest adaptive step [s] before the integration is declared failed.
constexpr double kMinStep = 1e-10;
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

ChainState straightChain(const ChainModel& model, const Eigen::Vector3d& tow_point_W,
                         const Eigen::Vector3d& direction_W, const Eigen::Vector3d& velocity_W)
{
  const int n = model.jointCount();
  ChainState state;
  state.x.resize(3, n);
  state.v.resize(3, n);
  const Eigen::Vector3d dir = direction_W.normalized();
  Eigen::Vector3d p = tow_point_W;
  for (int e = 0; e < n; ++e)
  {
    p += model.elementLength(e) * dir;
    state.x.col(e) = p;
    state.v.col(e) = velocity_W;
  }
  return state;
}

double maxRelativeLengthError(const ChainModel& model, const Eigen::Vector3d& tow_point_W, const ChainState& state)
{
  double worst = 0.0;
  Eigen::Vector3d x_f = tow_point_W;
  for (int e = 0; e < model.elementCount(); ++e)
  {
    const double d = model.elementLength(e);
    worst = std::max(worst, std::abs((state.x.col(e) - x_f).norm() / d - 1.0));
    x_f = state.x.col(e);
  }
  return worst;
}

Diversion lateralDiversion(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, const ShipEndState& ship,
                           const Eigen::Vector3d& track_direction_W)
{
  const Eigen::Vector3d port = Eigen::Vector3d::UnitZ().cross(track_direction_W).normalized();
  Diversion d;
  d.offset = port.dot(p_W - ship.p_W);
  d.rate = port.dot(v_W - ship.v_W);
  return d;
}

std::vector<bool> slackFlags(const Eigen::Matrix3Xd& joints, const Eigen::Matrix3Xd& tensions)
{
  std::vector<bool> slack(static_cast<size_t>(tensions.cols()));
  for (Eigen::Index j = 0; j < tensions.cols(); ++j)
    slack[static_cast<size_t>(j)] = tensions.col(j).dot(joints.col(j + 1) - joints.col(j)) > 0.0;
  return slack;
}

Simulator::Simulator(std::shared_ptr<ChainModel> model, ShipMotion ship, const WinchParams& winch)
    : model_(std::move(model)), ship_(std::move(ship)), solver_(*model_), winch_(winch)
{
  if (!ship_)
    throw std::invalid_argument("Simulator: no ship motion given");
  validate(winch_, model_->cable());
  const int n = model_->jointCount();
  y_.assign(6 * n + 2, 0.0);
  dydt_.assign(6 * n + 2, 0.0);
  y_[6 * n] = model_->cableLength();
  tensions_.setZero(3, n);
  accelerations_.setZero(3, n);
  dt_ = std::min(model_->numerics().max_step, 0.01);
}

double Simulator::setWinchCommand(double payout_rate)
{
  if (!winch_.enabled)
    throw std::invalid_argument("winch command: the winch is disabled (winch.enabled: false)");
  if (!std::isfinite(payout_rate))
    throw std::invalid_argument("winch command: the payout rate must be a finite number [m/s]");
  winch_command_ = std::clamp(payout_rate, -winch_.max_rate, winch_.max_rate);
  return winch_command_;
}

double Simulator::cableLength() const
{
  return y_[6 * model_->jointCount()];
}
double Simulator::payoutRate() const
{
  return y_[6 * model_->jointCount() + 1];
}

double Simulator::winchAcceleration(double length, double rate) const
{
  if (!winch_.enabled)
    return 0.0;
  // Target rate: the command within the rate limit, slowing before each length limit so that the
  // lagged rate never carries the cable past it: no faster than a stop at half the deceleration limit
  // allows (room for the lag), and near the limit proportional to the distance left with gain
  // 1/(4 tau), which makes the last approach critically damped: the length creeps up to the limit
  // without crossing it and the acceleration stays within its limit.
  const double a = winch_.max_acceleration, tau = winch_.response_time;
  const double k = 0.25 / tau;
  const double to_max = std::max(0.0, winch_.max_length - length), to_min = std::max(0.0, length - winch_.min_length);
  double target = std::clamp(winch_command_, -winch_.max_rate, winch_.max_rate);
  target = std::min({ target, std::sqrt(a * to_max), k * to_max });
  target = std::max({ target, -std::sqrt(a * to_min), -k * to_min });
  return std::clamp((target - rate) / tau, -a, a);
}

void Simulator::syncWinch(const StateVector& y)
{
  if (!winch_.enabled)
    return;
  const int n = model_->jointCount();
  const double length = y[6 * n], rate = y[6 * n + 1];
  const double first = length - (model_->segments() - 1) * model_->nominalSegmentLength();
  model_->setFirstSegment(std::max(first, 1e-9), rate, winchAcceleration(length, rate));
}

bool Simulator::remesh(double t)
{
  if (!winch_.enabled)
    return false;
  const double d = model_->nominalSegmentLength();
  // One pass in one direction: split while the first segment is above the band, or merge while it is
  // below. The first segment's length is carried from step to step (not recomputed from the cable out,
  // whose rounding could put it on both sides of the band at once), and a call never turns back.
  // A relative margin of 1e-6 on both edges: with max >= min + 1 a split then lands strictly above the
  // merge edge and a merge strictly below the split edge, whatever the rounding.
  const double split_above = winch_.segment_max_fraction * d * (1.0 + 1e-6);
  const double merge_below = winch_.segment_min_fraction * d * (1.0 - 1e-6);
  double first = model_->firstLength();
  const bool split = first > split_above;
  const bool merge = !split && first < merge_below && model_->segments() >= 2;
  if (!split && !merge)
    return false;
  const ShipEndState ship = ship_(t);
  for (int pass = 0; pass < 100000; ++pass)
  {
    const int n = model_->jointCount();
    const int nu = model_->segments();
    const double length = y_[6 * n], rate = y_[6 * n + 1];
    Eigen::Map<Eigen::Matrix3Xd> x(y_.data(), 3, n), v(y_.data() + 3 * n, 3, n);
    StateVector next;
    if (split && first > split_above)
    {
      // A new joint on the first segment, d from its aft end. It moves as a point of the rigid segment
      // across the flow and with the aft joint along it (that part keeps its length d).
      const Eigen::Vector3d axis = x.col(0) - ship.p_W;
      const Eigen::Vector3d s = axis.normalized();
      const double eta = (first - d) / first;
      Eigen::Vector3d w = ship.v_W + eta * (v.col(0) - ship.v_W);
      w += s.dot(v.col(0) - w) * s;
      next.resize(6 * (n + 1) + 2);
      Eigen::Map<Eigen::Matrix3Xd> nx(next.data(), 3, n + 1), nv(next.data() + 3 * (n + 1), 3, n + 1);
      nx.col(0) = ship.p_W + eta * axis;
      nv.col(0) = w;
      nx.rightCols(n) = x;
      nv.rightCols(n) = v;
      first -= d;
      model_->setLayout(nu + 1, first);
    }
    else if (merge && first < merge_below && nu >= 2)
    {
      // Merge the first segment into the second: drop joint x_2. The new first segment runs straight
      // from the tow point to x_3; its length is the sum, so mass is kept; the projection then
      // restores that length (a shift of second order in the kink at x_2).
      next.resize(6 * (n - 1) + 2);
      Eigen::Map<Eigen::Matrix3Xd> nx(next.data(), 3, n - 1), nv(next.data() + 3 * (n - 1), 3, n - 1);
      nx = x.rightCols(n - 1);
      nv = v.rightCols(n - 1);
      first += d;
      model_->setLayout(nu - 1, first);
    }
    else
    {
      break;
    }
    const int m = model_->jointCount();
    next[6 * m] = length;
    next[6 * m + 1] = rate;
    y_.swap(next);
    dydt_.assign(y_.size(), 0.0);
  }
  return true;
}

void Simulator::reset(double t, const ChainState& state)
{
  const int n = model_->jointCount();
  if (state.x.cols() != n || state.v.cols() != n)
  {
    std::ostringstream os;
    os << "initial state: expected " << n << " joints (segments + 1), got " << state.x.cols() << " positions and "
       << state.v.cols() << " velocities";
    throw std::invalid_argument(os.str());
  }
  if (!std::isfinite(t) || !state.x.allFinite() || !state.v.allFinite())
    throw std::invalid_argument("initial state: time, positions and velocities must be finite");
  t_ = t;
  y_.resize(6 * n + 2);
  dydt_.resize(6 * n + 2);
  // The winch restarts from rest with its command cleared, as the vehicle's actuators do; the cable out and
  // the layout are kept.
  y_[6 * n + 1] = 0.0;
  winch_command_ = 0.0;
  std::copy(state.x.data(), state.x.data() + 3 * n, y_.begin());
  std::copy(state.v.data(), state.v.data() + 3 * n, y_.begin() + 3 * n);
  project(t_);
  refreshOutputs();
  dt_ = std::min(model_->numerics().max_step, 0.01);
}

void Simulator::rhs(const StateVector& y, StateVector& dydt, double t)
{
  const int n = model_->jointCount();
  Eigen::Map<const Eigen::Matrix3Xd> x(y.data(), 3, n);
  Eigen::Map<const Eigen::Matrix3Xd> v(y.data() + 3 * n, 3, n);
  Eigen::Map<Eigen::Matrix3Xd> x_dot(dydt.data(), 3, n);
  Eigen::Map<Eigen::Matrix3Xd> a(dydt.data() + 3 * n, 3, n);
  x_dot = v;
  syncWinch(y);
  solver_.solve(t, ship_(t), x, v, a);
  dydt[6 * n] = winch_.enabled ? y[6 * n + 1] : 0.0;
  dydt[6 * n + 1] = winch_.enabled ? model_->firstAcceleration() : 0.0;
}

void Simulator::refreshOutputs()
{
  const int n = model_->jointCount();
  syncWinch(y_);
  tensions_.resize(3, n);
  accelerations_.resize(3, n);
  dydt_.resize(6 * n + 2);
  Eigen::Map<const Eigen::Matrix3Xd> x(y_.data(), 3, n);
  Eigen::Map<const Eigen::Matrix3Xd> v(y_.data() + 3 * n, 3, n);
  solver_.solve(t_, ship_(t_), x, v, accelerations_, &tensions_);
  Eigen::Map<Eigen::Matrix3Xd>(dydt_.data(), 3, n) = v;
  Eigen::Map<Eigen::Matrix3Xd>(dydt_.data() + 3 * n, 3, n) = accelerations_;
  dydt_[6 * n] = winch_.enabled ? y_[6 * n + 1] : 0.0;
  dydt_[6 * n + 1] = winch_.enabled ? model_->firstAcceleration() : 0.0;
}

void Simulator::project(double t)
{
  // Sequentially from the ship: restore each element's length along its current direction, then
  // remove the relative velocity along the element (s.(v_a - v_f) = 0).
  const int n = model_->jointCount();
  if (winch_.enabled)
  {
    // The winch stops at its limits (its rate law brakes toward them; this removes the last overshoot).
    double& length = y_[6 * n];
    double& rate = y_[6 * n + 1];
    if (length >= winch_.max_length)
      rate = std::min(rate, 0.0);
    if (length <= winch_.min_length)
      rate = std::max(rate, 0.0);
    length = std::clamp(length, winch_.min_length, winch_.max_length);
    rate = std::clamp(rate, -winch_.max_rate, winch_.max_rate);
  }
  syncWinch(y_);
  Eigen::Map<Eigen::Matrix3Xd> x(y_.data(), 3, n);
  Eigen::Map<Eigen::Matrix3Xd> v(y_.data() + 3 * n, 3, n);
  const ShipEndState ship = ship_(t);
  Eigen::Vector3d x_f = ship.p_W;
  Eigen::Vector3d v_f = ship.v_W;
  for (int e = 0; e < n; ++e)
  {
    const Eigen::Vector3d s = (x.col(e) - x_f).normalized();
    x.col(e) = x_f + model_->elementLength(e) * s;
    // Relative velocity along the element: none, but the winch's rate on the first segment.
    const double along = e == 0 ? model_->firstRate() : 0.0;
    v.col(e) -= (s.dot(v.col(e) - v_f) - along) * s;
    x_f = x.col(e);
    v_f = v.col(e);
  }
}

double Simulator::lengthErrorOf(const StateVector& y, double t) const
{
  const int n = model_->jointCount();
  ChainState s;
  s.x = Eigen::Map<const Eigen::Matrix3Xd>(y.data(), 3, n);
  s.v.resize(3, 0);
  return maxRelativeLengthError(*model_, ship_(t).p_W, s);
}

double Simulator::lengthError() const
{
  return lengthErrorOf(y_, t_);
}

double Simulator::largestRelativeSpeed(double t) const
{
  const int n = model_->jointCount();
  Eigen::Map<const Eigen::Matrix3Xd> v(y_.data() + 3 * n, 3, n);
  return (v.colwise() - ship_(t).v_W).colwise().norm().maxCoeff();
}

StepReport Simulator::advanceTo(double t_end)
{
  if (!(t_end >= t_))
  {
    std::ostringstream os;
    os << "advanceTo: target time " << t_end << " s is before the current time " << t_ << " s";
    throw std::invalid_argument(os.str());
  }
  const NumericsParams& num = model_->numerics();
  auto system = [this](const StateVector& y, StateVector& dydt, double t) { rhs(y, dydt, t); };
  auto controlled = odeint::make_controlled(num.abs_tol, num.rel_tol, odeint::runge_kutta_dopri5<StateVector>());
  odeint::runge_kutta4<StateVector> rk4;

  // The commands, the current or the thrust may have changed since the last step: the derivative the
  // first step starts from (k1, first-same-as-last) is taken afresh.
  refreshOutputs();
  // While the winch runs, a step shortens the first segment by at most half the band's lower edge (the
  // rate stays within max_rate), so it never collapses before the merge that follows the step.
  const double winch_step = winch_.enabled
                                ? 0.5 * winch_.segment_min_fraction * model_->nominalSegmentLength() / winch_.max_rate
                                : std::numeric_limits<double>::infinity();
  StepReport report;
  StateVector y_prev;
  while (t_end - t_ > 1e-12 * std::max(1.0, std::abs(t_end)))
  {
    y_prev = y_;
    const double t_prev = t_;
    if (num.stepper == StepperType::kRk4)
    {
      const double h = std::min({ num.fixed_step, winch_step, t_end - t_ });
      rk4.do_step(system, y_, dydt_, t_, h);
      t_ = h == t_end - t_ ? t_end : t_ + h;
    }
    else
    {
      const double remaining = t_end - t_;
      const bool clamped = dt_ >= remaining;
      double h = std::min({ dt_, remaining, num.max_step, winch_step });
      // dopri5 is first-same-as-last: dydt_ holds f(y_) and is advanced with the step.
      if (controlled.try_step(system, y_, dydt_, t_, h) == odeint::fail)
      {
        ++report.rejected;
        dt_ = h;
        if (dt_ < kMinStep)
        {
          refreshOutputs();  // the rejected stages left the winch's first segment at a trial value
          throw std::runtime_error(
              "integration failed: the adaptive step fell below 1e-10 s at t = " + std::to_string(t_) + " s");
        }
        continue;
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
    ++report.steps;
    syncWinch(y_);
    report.max_length_error = std::max(report.max_length_error, lengthErrorOf(y_, t_));
    if (remesh(t_))
    {
      // New state size: fresh steppers (odeint sizes its buffers once).
      controlled = odeint::make_controlled(num.abs_tol, num.rel_tol, odeint::runge_kutta_dopri5<StateVector>());
      rk4 = odeint::runge_kutta4<StateVector>();
    }
    project(t_);
    refreshOutputs();
  }
  return report;
}

ElementKinematics Simulator::elementKinematics(int e) const
{
  const int n = model_->jointCount();
  if (e < 0 || e >= n)
    throw std::out_of_range("elementKinematics: element " + std::to_string(e) + " is not in 0 .. " +
                            std::to_string(n - 1));
  Eigen::Map<const Eigen::Matrix3Xd> x(y_.data(), 3, n);
  Eigen::Map<const Eigen::Matrix3Xd> v(y_.data() + 3 * n, 3, n);
  const ShipEndState ship = ship_(t_);
  const Eigen::Vector3d x_f = e == 0 ? ship.p_W : Eigen::Vector3d(x.col(e - 1));
  const Eigen::Vector3d v_f = e == 0 ? ship.v_W : Eigen::Vector3d(v.col(e - 1));
  return ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
}

ChainState Simulator::state() const
{
  const int n = model_->jointCount();
  ChainState s;
  s.x = Eigen::Map<const Eigen::Matrix3Xd>(y_.data(), 3, n);
  s.v = Eigen::Map<const Eigen::Matrix3Xd>(y_.data() + 3 * n, 3, n);
  return s;
}

Eigen::Matrix3Xd Simulator::jointPositions() const
{
  const int n = model_->jointCount();
  Eigen::Matrix3Xd p(3, n + 1);
  p.col(0) = ship_(t_).p_W;
  p.rightCols(n) = Eigen::Map<const Eigen::Matrix3Xd>(y_.data(), 3, n);
  return p;
}

}  // namespace tow_sim
