#include "tow_sim/core/survey/tow_nav.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tow_sim
{
namespace
{
constexpr int kParams = 5;  // c_x, c_y, ln k, b_x, b_y
using ParamVector = Eigen::Matrix<double, kParams, 1>;

// The configuration with every cable drag coefficient (and C1, C2 where given) times k.
SimulationConfig withDragScale(SimulationConfig config, double k)
{
  auto scale = [k](CableParams& c)
  {
    c.normal_drag_coefficient *= k;
    c.tangential_drag_coefficient *= k;
    if (c.c1)
      *c.c1 *= k;
    if (c.c2)
      *c.c2 *= k;
  };
  scale(config.cable);
  for (CableParams& s : config.sections)
    scale(s);
  return config;
}

}  // namespace

struct TowNav::Member
{
  std::unique_ptr<TowRun> run;
  ParamVector x = ParamVector::Zero();
  double built_ln_k = 0.0;                          // the ln k its run was built with
  TowSnapshot last;                                 // at the last advance
  Eigen::Vector2d shown = Eigen::Vector2d::Zero();  // the offset in the estimate: follows x[3], x[4] smoothly
};

const ParamTable<TowNavParams>& towNavParams()
{
  using P = TowNavParams;
  static const ParamTable<P> table =
      ParamTable<P>()
          .integer("members", &P::members, "-", 4, 500, "tow runs in the ensemble")
          .integer("seed", &P::seed, "-", 0, 2147483647, "the ensemble's random draws")
          .number("start_after", &P::start_after, "s", 0.0, 600.0, kClosed, "ship fixes before the runs start")
          .number("gnss_smoothing", &P::gnss_smoothing, "s", 0.0, 60.0, kClosed, "the ship track's smoothing time")
          .number("ship_interval", &P::ship_interval, "s", 0.0, 60.0, kClosed, "the runs' ship track: a fix this often")
          .number("analysis_interval", &P::analysis_interval, "s", 0.0, 600.0, kOpen, "between analyses")
          .number("current_sigma", &P::current_sigma, "m/s", 0.0, 5.0, kClosed, "the current's prior spread per axis")
          .number("current_walk", &P::current_walk, "m/s/sqrt(s)", 0.0, 1.0, kClosed, "its random walk")
          .number("drag_sigma", &P::drag_sigma, "-", 0.0, 2.0, kClosed, "the prior spread of ln(drag scale)")
          .number("drag_walk", &P::drag_walk, "1/sqrt(s)", 0.0, 1.0, kClosed, "its random walk")
          .number("offset_walk", &P::offset_walk, "m/sqrt(s)", 0.0, 100.0, kClosed, "the USBL offset's random walk")
          .number("offset_blend", &P::offset_blend, "s", 0.0, 600.0, kClosed, "the estimate follows the offset so")
          .number("depth_sigma", &P::depth_sigma, "m", 0.0, 1000.0, kOpen, "fish depth against the model")
          .number("tension_sigma", &P::tension_sigma, "-", 0.0, 10.0, kOpen, "tow tension against the model, relative")
          .number("heading_sigma", &P::heading_sigma, "rad", 0.0, 3.2, kOpen, "fish heading against the model")
          .number("usbl_sigma", &P::usbl_sigma, "m", 0.0, 1000.0, kOpen, "a USBL fix per axis, plus the range part")
          .number("usbl_range_sigma", &P::usbl_range_sigma, "-", 0.0, 1.0, kClosed, "per metre of slant range")
          .number("usbl_latency", &P::usbl_latency, "s", 0.0, 60.0, kClosed, "a fix is this old when its row comes")
          .number("usbl_gate", &P::usbl_gate, "-", 0.0, 1000.0, kOpen, "fixes further off (in sigma) are rejected")
          .number("model_sigma", &P::model_sigma, "m", 0.0, 1000.0, kClosed, "added to the spread per axis")
          .number("catenary_factor", &P::catenary_factor, "-", 0.0, 1.0, kOpen, "the catenary baseline's k")
          .number("winch_time", &P::winch_time, "s", 0.0, 600.0, kOpen, "the members' winches follow the counter");
  return table;
}

void validate(const TowNavParams& params, const std::string& prefix)
{
  validateParams(towNavParams(), params, prefix);
  if (!params.tow_point_S.allFinite())
    throw std::invalid_argument("tow_point: must be finite [x, y, z] in the ship frame");
}

TowNav::TowNav(const SimulationConfig& config, const TowNavParams& params)
    : config_(config),
      params_(params),
      ship_(std::make_shared<ShipHistory>(1.0, 100000)),
      gnss_(GnssTrackParams{ Eigen::Vector3d::Zero(), params.gnss_smoothing, false }),
      rules_(params.tow_point_S, params.catenary_factor),
      random_(static_cast<std::uint64_t>(params.seed))
{
  validate(params_, "nav");
  TowRun check(config_, ship_);  // the configuration's own checks, before any row
}

TowNav::~TowNav() = default;

void TowNav::takeShip(const SurveyMeasurement& row)
{
  if (std::isfinite(row.ship_heading))
    heading_ = row.ship_heading;
  if (!std::isfinite(row.ship_x) || !std::isfinite(row.ship_y) || !std::isfinite(heading_))
    return;
  GnssFix fix;
  fix.t = row.t;
  fix.antenna_W = Eigen::Vector3d(row.ship_x, row.ship_y, 0.0);
  fix.yaw = heading_;
  const ShipEstimate e = gnss_.update(fix);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(e.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d arm_W = R * params_.tow_point_S;
  const Eigen::Vector3d v_W = R * e.v_S;
  ShipPose pose;
  pose.x = e.p_W.x();
  pose.y = e.p_W.y();
  pose.heading = e.yaw;
  pose.speed = v_W.head<2>().norm();
  if (row.t - last_knot_ >= params_.ship_interval - 1e-9)
  {
    ship_->add(row.t, e.p_W + arm_W, v_W + Eigen::Vector3d(0.0, 0.0, e.yaw_rate).cross(arm_W), pose);
    last_knot_ = row.t;
  }
  rules_.addShip(row.ship_x, row.ship_y, heading_);
  if (std::isnan(first_fix_))
    first_fix_ = row.t;
}

void TowNav::holdMeasurements(const SurveyMeasurement& row)
{
  if (std::isfinite(row.cable_out))
    cable_out_ = row.cable_out;
  if (std::isfinite(row.fish_depth))
  {
    depth_ = row.fish_depth;
    depth_sum_ += row.fish_depth;
    ++depth_count_;
  }
  if (std::isfinite(row.tension))
  {
    tension_sum_ += row.tension;
    ++tension_count_;
  }
  if (std::isfinite(row.fish_heading))
  {
    heading_cos_ += std::cos(row.fish_heading);
    heading_sin_ += std::sin(row.fish_heading);
    ++heading_count_;
  }
  if (std::isfinite(row.usbl_x) && std::isfinite(row.usbl_y) && std::isfinite(row.usbl_z))
  {
    usbl_.push_back(row);
    usbl_seen_ = true;
  }
}

TowNavEstimate TowNav::update(const SurveyMeasurement& row)
{
  if (!std::isfinite(row.t) || row.t < t_)
  {
    ++rows_rejected_;
    return estimateAt(t_);
  }
  t_ = row.t;
  takeShip(row);
  holdMeasurements(row);
  // The runs go as far as the ship's track (its newest fix): never past it on an extrapolation.
  if (!started() && !std::isnan(first_fix_) && ship_->newestTime() - first_fix_ >= params_.start_after)
    startMembers(ship_->newestTime());
  else if (started() && ship_->newestTime() > members_.front().last.t)
  {
    advanceMembers(ship_->newestTime());
    if (row.t >= next_analysis_)
      analyse(ship_->newestTime());
  }
  blendOffsets(row.t);
  return estimateAt(row.t);
}

std::optional<LaybackFixes> TowNav::baselines() const
{
  if (!rules_.hasShip() || std::isnan(cable_out_) || std::isnan(depth_))
    return std::nullopt;
  return rules_.at(cable_out_, depth_);
}

void TowNav::startMembers(double t)
{
  std::normal_distribution<double> normal(0.0, 1.0);
  members_.resize(params_.members);
  for (Member& m : members_)
  {
    m.x << params_.current_sigma * normal(random_), params_.current_sigma * normal(random_),
        params_.drag_sigma * normal(random_), 0.0, 0.0;
    SimulationConfig c = withDragScale(config_, std::exp(m.x[2]));
    c.environment.current_W = Eigen::Vector3d(m.x[0], m.x[1], 0.0);
    m.run = std::make_unique<TowRun>(c, ship_);
    m.built_ln_k = m.x[2];
    m.run->start(t);
    m.last = m.run->snapshot();
  }
  next_analysis_ = t + params_.analysis_interval;
  last_analysis_ = t;
  offsets_at_ = t;
}

void TowNav::advanceMembers(double t)
{
  for (Member& m : members_)
  {
    if (config_.winch.enabled && std::isfinite(cable_out_))
      m.run->setWinchCommand((cable_out_ - m.last.cable_length) / params_.winch_time);
    try
    {
      m.run->advanceTo(t);
    }
    catch (const std::runtime_error&)  // a diverged member starts again from the steady tow
    {
      m.run.reset();
      rebuild(m);
      m.run->start(t);
    }
    m.last = m.run->snapshot();
  }
  ship_->dropBefore(t - 10.0);  // the runs and the estimate look no further back
}

// A member's run built again for its drag scale and current, its state carried over.
void TowNav::rebuild(Member& m)
{
  SimulationConfig c = withDragScale(config_, std::exp(m.x[2]));
  c.environment.current_W = Eigen::Vector3d(m.x[0], m.x[1], 0.0);
  auto run = std::make_unique<TowRun>(c, ship_);
  if (m.run && m.run->started())
    run->restore(m.run->saveState());
  m.run = std::move(run);
  m.built_ln_k = m.x[2];
}

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
  // offsets walk only once a USBL fix has come (without USBL nothing would ever bring them back).
  std::normal_distribution<double> normal(0.0, 1.0);
  const double offset_walk = usbl_seen_ ? params_.offset_walk : 0.0;
  const ParamVector walk(params_.current_walk, params_.current_walk, params_.drag_walk, offset_walk, offset_walk);
  Eigen::MatrixXd step(kParams, n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < kParams; ++k)
      step(k, i) = walk[k] * walk_time * normal(random_);
  step.colwise() -= step.rowwise().mean();
  for (int i = 0; i < n; ++i)
    members_[i].x += step.col(i);
  Observations obs;
  Eigen::VectorXd pred(n);
  if (depth_count_ > 0)
  {
    for (int i = 0; i < n; ++i)
      pred[i] = members_[i].last.depth;
    obs.add(depth_sum_ / depth_count_, params_.depth_sigma, pred);
  }
  if (tension_count_ > 0)
  {
    const double tension = tension_sum_ / tension_count_;
    for (int i = 0; i < n; ++i)
      pred[i] = members_[i].last.tension_ship;
    obs.add(tension, params_.tension_sigma * std::max(1.0, std::abs(tension)), pred);
  }
  if (heading_count_ > 0)
  {
    const double heading = std::atan2(heading_sin_, heading_cos_);
    for (int i = 0; i < n; ++i)  // each member's heading on the measurement's side of the circle
      pred[i] = heading + wrapAngle(members_[i].last.yaw - heading);
    obs.add(heading, params_.heading_sigma, pred);
  }
  depth_sum_ = tension_sum_ = heading_cos_ = heading_sin_ = 0.0;
  depth_count_ = tension_count_ = heading_count_ = 0;
  for (const SurveyMeasurement& fix : usbl_)
    addUsbl(fix, obs);
  usbl_.clear();
  if (!obs.y.empty())
    ensembleUpdate(obs);
  for (Member& m : members_)
  {
    m.x[0] = std::clamp(m.x[0], -5.0, 5.0);
    m.x[1] = std::clamp(m.x[1], -5.0, 5.0);
    m.x[2] = std::clamp(m.x[2], -1.5, 1.5);
    if (std::abs(m.x[2] - m.built_ln_k) > 0.02)
      rebuild(m);
    m.run->setCurrent(Eigen::Vector3d(m.x[0], m.x[1], 0.0));
  }
  next_analysis_ = t + params_.analysis_interval;
}

// A USBL fix's three axes, each member's fish carried back to the fix's instant by its velocity, plus its
// offset; a fix further than usbl_gate sigma from the ensemble on any axis is rejected.
void TowNav::addUsbl(const SurveyMeasurement& fix, Observations& obs)
{
  const int n = static_cast<int>(members_.size());
  const Eigen::Vector3d z(fix.usbl_x, fix.usbl_y, fix.usbl_z);
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i)
  {
    const Member& m = members_[i];
    const double back = m.last.t - (fix.t - params_.usbl_latency);
    p.col(i) = m.last.vehicle.p_cg_W - back * m.last.vehicle.v_cg_W + Eigen::Vector3d(m.x[3], m.x[4], 0.0);
  }
  const Eigen::Vector3d mean = p.rowwise().mean();
  const Eigen::Vector2d ship(ship_->pose(fix.t).x, ship_->pose(fix.t).y);
  const double range = std::hypot((mean.head<2>() - ship).norm(), mean.z());
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
  for (int a = 0; a < 3; ++a)
    obs.add(z[a], sigma, p.row(a).transpose(), true);
}

// The ensemble Kalman filter's analysis with perturbed observations; the offsets take only USBL rows.
void TowNav::ensembleUpdate(const Observations& obs)
{
  const int n = static_cast<int>(members_.size()), rows = static_cast<int>(obs.y.size());
  Eigen::MatrixXd X(kParams, n), Y(rows, n);
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
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int i = 0; i < n; ++i)
  {
    Eigen::VectorXd d(rows);
    for (int r = 0; r < rows; ++r)
      d[r] = obs.y[r] + obs.sigma[r] * normal(random_) - Y(r, i);
    members_[i].x += K * d;
  }
}

// The offsets the estimate shows move toward the members' over offset_blend seconds, so that a USBL fix after an
// outage turns the estimate over rather than making it jump.
void TowNav::blendOffsets(double t)
{
  if (!started() || t <= offsets_at_)
    return;
  const double w = params_.offset_blend > 0.0 ? 1.0 - std::exp(-(t - offsets_at_) / params_.offset_blend) : 1.0;
  for (Member& m : members_)
    m.shown += w * (m.x.segment<2>(3) - m.shown);
  offsets_at_ = t;
}

TowNavEstimate TowNav::estimateAt(double t) const
{
  TowNavEstimate e;
  e.t = t;
  e.usbl_rejected = usbl_rejected_;
  e.rows_rejected = rows_rejected_;
  if (!started())
    return e;
  const int n = static_cast<int>(members_.size());
  Eigen::Matrix3Xd p(3, n);
  double ln_k = 0.0;
  for (int i = 0; i < n; ++i)
  {
    const Member& m = members_[i];
    p.col(i) =
        m.last.vehicle.p_cg_W + (t - m.last.t) * m.last.vehicle.v_cg_W + Eigen::Vector3d(m.shown.x(), m.shown.y(), 0.0);
    e.current += m.x.head<2>() / n;
    ln_k += m.x[2] / n;
  }
  e.valid = true;
  e.drag_scale = std::exp(ln_k);
  e.p_W = p.rowwise().mean();
  const Eigen::Matrix3Xd a = p.colwise() - e.p_W;
  e.covariance =
      a * a.transpose() / std::max(1, n - 1) + params_.model_sigma * params_.model_sigma * Eigen::Matrix3d::Identity();
  const ShipPose pose = ship_->pose(t);
  const Eigen::Vector3d d = e.p_W - ship_->towPoint(t).p_W;
  e.layback = -(d.x() * std::cos(pose.heading) + d.y() * std::sin(pose.heading));
  e.cross_track = -d.x() * std::sin(pose.heading) + d.y() * std::cos(pose.heading);
  return e;
}

}  // namespace tow_sim
