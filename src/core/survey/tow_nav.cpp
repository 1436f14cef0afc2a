#include "tow_sim/core/survey/tow_nav.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

namespace tow_sim
{
namespace
{
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
    if (c.loading)
      c.loading = std::make_shared<const CableLoading>(c.loading->scaled(k, "the loading table times the drag scale"));
  };
  scale(config.cable);
  for (CableParams& s : config.sections)
    scale(s);
  return config;
}

// The largest ln k that keeps every drag coefficient within its range (C_dn <= 10, C_dt <= 1), at most 1.5.
double largestLnK(const SimulationConfig& config)
{
  double largest = 1.5;
  for (const CableParams& c : cableSections(config))
  {
    if (c.normal_drag_coefficient > 0.0)
      largest = std::min(largest, std::log(10.0 / c.normal_drag_coefficient));
    if (c.tangential_drag_coefficient > 0.0)
      largest = std::min(largest, std::log(1.0 / c.tangential_drag_coefficient));
    if (c.loading)  // a faired section's coefficients stay within CableLoading's 100
      for (const std::vector<double>* v : { &c.loading->normal(), &c.loading->tangential(), &c.loading->lift() })
        for (double x : *v)
          if (x != 0.0)
            largest = std::min(largest, std::log(100.0 / std::abs(x)));
  }
  return largest;
}

}  // namespace

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
      max_ln_k_(largestLnK(config)),
      ship_(std::make_shared<ShipHistory>(params.ship_interval + 1.0, 100000)),
      gnss_(GnssTrackParams{ Eigen::Vector3d::Zero(), params.gnss_smoothing, false }),
      rules_(params.tow_point_S, params.catenary_factor),
      random_(static_cast<std::uint64_t>(params.seed))
{
  validate(params_, "nav");
  TowRun check(config_, ship_);  // the configuration's own checks, before any row
  if (check.seabed())
    seabed_ = std::make_unique<Seabed>(check.seabed()->params());
}

TowNav::~TowNav() = default;

void TowNav::takeShip(const SurveyMeasurement& row)
{
  if (std::isfinite(row.ship_heading))
    heading_ = row.ship_heading, heading_t_ = row.t;
  if (!std::isfinite(row.ship_x) || !std::isfinite(row.ship_y) || !std::isfinite(heading_))
    return;
  if (!std::isnan(last_fix_) && row.t <= last_fix_)
  {
    ++fixes_rejected_;
    return;
  }
  GnssFix fix;
  fix.t = row.t;
  fix.antenna_W = Eigen::Vector3d(row.ship_x, row.ship_y, 0.0);
  fix.yaw = heading_;
  const ShipEstimate e = gnss_.update(fix);
  ship_now_ = e;
  last_fix_ = row.t;
  if (std::isnan(first_fix_))
    first_fix_ = row.t;
  rules_.addShip(e.p_W.x(), e.p_W.y(), e.yaw);
  if (row.t - last_knot_ < params_.ship_interval - 1e-9)
    return;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(e.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d arm_W = R * params_.tow_point_S;
  const Eigen::Vector3d v_W = R * e.v_S;
  ShipPose pose;
  pose.x = e.p_W.x();
  pose.y = e.p_W.y();
  pose.heading = e.yaw;
  pose.speed = v_W.head<2>().norm();
  ship_->add(row.t, e.p_W + arm_W, v_W + Eigen::Vector3d(0.0, 0.0, e.yaw_rate).cross(arm_W), pose);
  last_knot_ = row.t;
}

void TowNav::shipAt(double t, Eigen::Vector3d& p_W, double& yaw, Eigen::Vector3d& tow_W) const
{
  const double dt = t - ship_now_.t;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(ship_now_.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  p_W = ship_now_.p_W + dt * (R * ship_now_.v_S);
  yaw = ship_now_.yaw + dt * ship_now_.yaw_rate;
  tow_W = p_W + Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * params_.tow_point_S;
}

// A depth more than 3 depth_sigma below the seabed under the estimate (or under the ship before the runs start).
bool TowNav::belowSeabed(double depth) const
{
  if (!seabed_)
    return false;
  const Eigen::Vector3d at = started() ? estimateAt(t_).p_W : ship_now_.p_W;
  return -depth < seabed_->bottomZ(at.x(), at.y()) - 3.0 * params_.depth_sigma;
}

void TowNav::holdMeasurements(SurveyMeasurement row)
{
  if (std::isfinite(row.fish_depth) && belowSeabed(row.fish_depth))
  {
    ++depths_rejected_;
    row.fish_depth = SurveyMeasurement::kNone;
  }
  if (std::isfinite(row.cable_out))
    cable_out_ = row.cable_out;
  if (std::isfinite(row.fish_depth))
    depth_ = row.fish_depth, depth_t_ = row.t;
  if (!started())
    return;
  if (std::isfinite(row.fish_depth) || std::isfinite(row.tension) || std::isfinite(row.fish_heading))
    window_.push_back(row);
  if (std::isfinite(row.usbl_x) && std::isfinite(row.usbl_y) && std::isfinite(row.usbl_z))
    fixes_.push_back(PendingFix{ row, Eigen::Matrix3Xd(3, members_.size()), false });
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

// The members from the steady tow at t, each with its draw of the parameters (the draws centred: their mean is the
// prior's).
void TowNav::startMembers(double t)
{
  std::normal_distribution<double> normal(0.0, 1.0);
  members_.resize(params_.members);
  Eigen::MatrixXd draws(3, members_.size());
  for (Eigen::Index i = 0; i < draws.cols(); ++i)
    draws.col(i) << params_.current_sigma * normal(random_), params_.current_sigma * normal(random_),
        params_.drag_sigma * normal(random_);
  draws.colwise() -= draws.rowwise().mean();
  for (size_t i = 0; i < members_.size(); ++i)
  {
    Member& m = members_[i];
    m.x << draws(0, i), draws(1, i), std::clamp(draws(2, i), -1.5, max_ln_k_), 0.0, 0.0;
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
  std::vector<TowSnapshot> before;
  for (Member& m : members_)
  {
    before.push_back(m.last);
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
    integrate(m, before.back());
  }
  placeFixes(t, before);
  ship_->dropBefore(t - 10.0);  // the runs look no further back
}

// The trapezoidal time integrals of the member's depth, tension and heading (as a unit vector) since `before`.
void TowNav::integrate(Member& m, const TowSnapshot& before)
{
  const double dt = m.last.t - before.t;
  m.duration += dt;
  m.depth += 0.5 * dt * (before.depth + m.last.depth);
  m.tension += 0.5 * dt * (before.tension_ship + m.last.tension_ship);
  m.heading_cos += 0.5 * dt * (std::cos(before.yaw) + std::cos(m.last.yaw));
  m.heading_sin += 0.5 * dt * (std::sin(before.yaw) + std::sin(m.last.yaw));
}

// Each member's fish at the instant of every USBL fix the runs have now passed (linear between the two
// snapshots; a fix of an instant before `before`, carried back by the velocity then).
void TowNav::placeFixes(double t, const std::vector<TowSnapshot>& before)
{
  for (PendingFix& f : fixes_)
  {
    const double instant = f.fix.t - params_.usbl_latency;
    if (f.placed || instant > t)
      continue;
    for (size_t i = 0; i < members_.size(); ++i)
    {
      const TowSnapshot& a = before[i];
      const TowSnapshot& b = members_[i].last;
      if (instant >= a.t && b.t > a.t)
        f.members.col(i) = a.vehicle.p_cg_W + (instant - a.t) / (b.t - a.t) * (b.vehicle.p_cg_W - a.vehicle.p_cg_W);
      else
        f.members.col(i) = a.vehicle.p_cg_W - (a.t - instant) * a.vehicle.v_cg_W;
    }
    f.placed = true;
  }
}

// A member's run built again for its drag scale and current, its state carried over. A run that cannot be (a
// parted cable, a state that does not fit) keeps its drag.
void TowNav::rebuild(Member& m)
{
  SimulationConfig c = withDragScale(config_, std::exp(m.x[2]));
  c.environment.current_W = Eigen::Vector3d(m.x[0], m.x[1], 0.0);
  try
  {
    auto run = std::make_unique<TowRun>(c, ship_);
    if (m.run && m.run->started())
      run->restore(m.run->saveState());
    m.run = std::move(run);
    m.built_ln_k = m.x[2];
  }
  catch (const std::exception&)
  {
    if (!m.run)
      throw;
    m.x[2] = m.built_ln_k;
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
  e.rows_rejected = rows_rejected_;
  e.fixes_rejected = fixes_rejected_;
  e.usbl_rejected = usbl_rejected_;
  e.depths_rejected = depths_rejected_;
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
  // The depth is measured (to a decimetre, where the model is metres off in a turn): while the latest is fresh,
  // it is the estimate's z, with depth_sigma.
  if (std::isfinite(depth_) && t - depth_t_ <= kFreshDepth)
  {
    e.p_W.z() = -depth_;
    e.covariance.row(2).setZero();
    e.covariance.col(2).setZero();
    e.covariance(2, 2) = params_.depth_sigma * params_.depth_sigma;
  }
  // Layback and cross-track along the latest measured heading while it is fresh (a gyro's is far better than
  // the smoothed track's, which lags by metres at the start of a turn), from the tow point on the smoothed track.
  Eigen::Vector3d ship, tow;
  double yaw = 0.0;
  shipAt(t, ship, yaw, tow);
  if (std::isfinite(heading_) && t - heading_t_ <= kFreshHeading)
  {
    yaw = heading_;
    tow = ship + Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * params_.tow_point_S;
  }
  const Eigen::Vector3d d = e.p_W - tow;
  e.layback = -(d.x() * std::cos(yaw) + d.y() * std::sin(yaw));
  e.cross_track = -d.x() * std::sin(yaw) + d.y() * std::cos(yaw);
  e.heading = yaw;
  return e;
}

}  // namespace tow_sim
