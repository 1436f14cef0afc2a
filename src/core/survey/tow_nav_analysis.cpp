// tow_nav's analysis (tow_nav.h): the measurements' means against the members' over the same time, the USBL fixes
// against each member's fish at their instants, and the ensemble Kalman filter's update of the parameters.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "tow_sim/core/survey/tow_nav.h"

namespace tow_sim
{
// The measurements of one analysis and each member's prediction of them.
struct TowNav::Observations
{
  std::vector<double> y, sigma;
  std::vector<bool> usbl;                  // a USBL axis (the only rows that move the offsets)
  std::vector<Eigen::VectorXd> predicted;  // per row, a value per member
  void add(double value, double s, const Eigen::VectorXd& members, bool is_usbl = false)
  {
    y.push_back(value);
    sigma.push_back(s);
    usbl.push_back(is_usbl);
    predicted.push_back(members);
  }
};

void TowNav::analyse(double t)
{
  const int n = static_cast<int>(members_.size());
  const double walk_time = std::sqrt(std::max(0.0, t - last_analysis_));
  last_analysis_ = t;
  // The random walk, its increments centred over the members (it spreads them, it does not move their mean); the
  // offsets walk only once a USBL fix has passed the gate (without USBL nothing would ever bring them back).
  std::normal_distribution<double> normal(0.0, 1.0);
  const double offset_walk = usbl_seen_ ? params_.offset_walk : 0.0;
  const Eigen::Matrix<double, 5, 1> walk(params_.current_walk, params_.current_walk, params_.drag_walk, offset_walk,
                                         offset_walk);
  Eigen::MatrixXd step(5, n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 5; ++k)
      step(k, i) = walk[k] * walk_time * normal(random_);
  step.colwise() -= step.rowwise().mean();
  for (int i = 0; i < n; ++i)
    members_[i].x += step.col(i);

  Observations obs;
  addWindowMeans(t, obs);
  std::vector<PendingFix> later;
  for (const PendingFix& f : fixes_)
    if (f.placed)
      addUsbl(f, obs);
    else
      later.push_back(f);
  fixes_.swap(later);
  if (!obs.y.empty())
    ensembleUpdate(obs);
  applyParameters();
  next_analysis_ = t + params_.analysis_interval;
}

// The rows' mean depth, tension and fish heading up to t against each member's time means over the same stretch
// (integrate()); the rows after t wait for the next analysis.
void TowNav::addWindowMeans(double t, Observations& obs)
{
  const int n = static_cast<int>(members_.size());
  double depth = 0.0, tension = 0.0, c = 0.0, s = 0.0;
  int depths = 0, tensions = 0, headings = 0;
  auto later = std::find_if(window_.begin(), window_.end(), [t](const SurveyMeasurement& r) { return r.t > t; });
  for (auto r = window_.begin(); r != later; ++r)
  {
    if (std::isfinite(r->fish_depth))
      depth += r->fish_depth, ++depths;
    if (std::isfinite(r->tension))
      tension += r->tension, ++tensions;
    if (std::isfinite(r->fish_heading))
      c += std::cos(r->fish_heading), s += std::sin(r->fish_heading), ++headings;
  }
  window_.erase(window_.begin(), later);
  const bool integrated = members_.front().duration > 0.0;
  Eigen::VectorXd pd(n), pt(n), ph(n);
  const double heading = std::atan2(s, c);
  for (int i = 0; i < n; ++i)
  {
    Member& m = members_[i];
    const double w = integrated ? 1.0 / m.duration : 0.0;
    pd[i] = integrated ? m.depth * w : m.last.depth;
    pt[i] = integrated ? m.tension * w : m.last.tension_ship;
    const double yaw = integrated ? std::atan2(m.heading_sin, m.heading_cos) : m.last.yaw;
    ph[i] = heading + wrapAngle(yaw - heading);  // on the measurement's side of the circle
    m.duration = m.depth = m.tension = m.heading_cos = m.heading_sin = 0.0;
  }
  if (depths > 0)
    obs.add(depth / depths, params_.depth_sigma, pd);
  if (tensions > 0)
    obs.add(tension / tensions, params_.tension_sigma * std::max(1.0, std::abs(tension / tensions)), pt);
  if (headings > 0)
    obs.add(heading, params_.heading_sigma, ph);
}

// A USBL fix's three axes against each member's fish at its instant plus its offset; a fix further than usbl_gate
// sigma from the ensemble on any axis is rejected (and does not start the offsets' walk).
void TowNav::addUsbl(const PendingFix& pending, Observations& obs)
{
  const int n = static_cast<int>(members_.size());
  const SurveyMeasurement& fix = pending.fix;
  const Eigen::Vector3d z(fix.usbl_x, fix.usbl_y, fix.usbl_z);
  Eigen::Matrix3Xd p = pending.members;
  for (int i = 0; i < n; ++i)
    p.col(i).head<2>() += members_[i].x.segment<2>(3);
  const Eigen::Vector3d mean = p.rowwise().mean();
  Eigen::Vector3d ship, tow;
  double yaw = 0.0;
  shipAt(fix.t - params_.usbl_latency, ship, yaw, tow);
  const double range = (mean - Eigen::Vector3d(ship.x(), ship.y(), 0.0)).norm();
  const double sigma = params_.usbl_sigma + params_.usbl_range_sigma * range;
  for (int a = 0; a < 3; ++a)
  {
    const double spread = (p.row(a).array() - mean[a]).square().sum() / std::max(1, n - 1);
    if (std::abs(z[a] - mean[a]) > params_.usbl_gate * std::sqrt(spread + sigma * sigma))
    {
      ++usbl_rejected_;
      return;
    }
  }
  usbl_seen_ = true;
  for (int a = 0; a < 3; ++a)
    obs.add(z[a], sigma, p.row(a).transpose(), true);
}

// The ensemble Kalman filter's analysis with perturbed observations; the offsets take only USBL rows.
void TowNav::ensembleUpdate(const Observations& obs)
{
  const int n = static_cast<int>(members_.size()), rows = static_cast<int>(obs.y.size());
  Eigen::MatrixXd X(5, n), Y(rows, n);
  for (int i = 0; i < n; ++i)
    X.col(i) = members_[i].x;
  for (int r = 0; r < rows; ++r)
    Y.row(r) = obs.predicted[r].transpose();
  const Eigen::MatrixXd A = X.colwise() - X.rowwise().mean();
  const Eigen::MatrixXd HA = Y.colwise() - Y.rowwise().mean();
  Eigen::MatrixXd Cyy = HA * HA.transpose() / (n - 1);
  for (int r = 0; r < rows; ++r)
    Cyy(r, r) += obs.sigma[r] * obs.sigma[r];
  const Eigen::MatrixXd Cxy = A * HA.transpose() / (n - 1);
  Eigen::MatrixXd K = Cyy.ldlt().solve(Cxy.transpose()).transpose();
  for (int r = 0; r < rows; ++r)
    if (!obs.usbl[r])
      K.block(3, r, 2, 1).setZero();
  // Perturbed observations (Burgers, van Leeuwen and Evensen, 1998). The deterministic form (Sakov and Oke, 2008)
  // was tried: steadier in a straight tow, but its ensemble collapsed in the lawn-mower survey (USBL fixes then
  // failed the gate and the error grew to 200 m).
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int i = 0; i < n; ++i)
  {
    Eigen::VectorXd d(rows);
    for (int r = 0; r < rows; ++r)
      d[r] = obs.y[r] + obs.sigma[r] * normal(random_) - Y(r, i);
    members_[i].x += K * d;
  }
}

// The parameters into the runs: currents within +-5 m/s, ln k within what the configuration's ranges allow (a run
// rebuilt when its drag moved by more than 2 %).
void TowNav::applyParameters()
{
  for (Member& m : members_)
  {
    m.x[0] = std::clamp(m.x[0], -5.0, 5.0);
    m.x[1] = std::clamp(m.x[1], -5.0, 5.0);
    m.x[2] = std::clamp(m.x[2], -1.5, max_ln_k_);
    if (std::abs(m.x[2] - m.built_ln_k) > 0.02)
      rebuild(m);
    m.run->setCurrent(Eigen::Vector3d(m.x[0], m.x[1], 0.0));
  }
}

}  // namespace tow_sim
