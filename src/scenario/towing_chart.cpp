#include "tow_sim/scenario/towing_chart.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/analysis/modes.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/io/numeric_csv.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/ship_path.h"

namespace tow_sim
{
void payOutTo(SimulationConfig& config, double cable_out)
{
  if (cable_out == config.cable.length)
    return;  // as configured
  CableParams& first = config.sections.empty() ? config.cable : config.sections.front();
  const double aft = config.cable.length - first.length, length = cable_out - aft;
  if (!(length > 0.0))
  {
    std::ostringstream os;
    os << "cable out " << cable_out << " m: not more than the " << aft
       << " m of the sections aft of the first, which stay as they are";
    throw std::invalid_argument(os.str());
  }
  for (size_t i = 0; i < config.bodies.size(); ++i)
  {
    CableBodyParams& b = config.bodies[i];
    if (b.at < first.length - 1e-6)
    {
      std::ostringstream os;
      os << "cable.bodies[" << i << "].at = " << b.at << " m is inside the first section (" << first.length
         << " m), whose length changes with the cable out: a chart at another cable out needs it aft of it";
      throw std::invalid_argument(os.str());
    }
    b.at += length - first.length;
  }
  const int first_segments = std::max(1, static_cast<int>(std::lround(length / first.segmentLength())));
  config.cable.segments += first_segments - first.segments;
  first.segments = first_segments;
  first.length = length;
  config.cable.length = cable_out;
}

std::unique_ptr<TowRun> steadyTowRun(const SimulationConfig& config, double speed, double cable_out,
                                     const Eigen::Vector3d& current_W)
{
  if (!std::isfinite(speed) || !(cable_out > 0.0 && cable_out <= 1e5) || !current_W.allFinite())
  {
    std::ostringstream os;
    os << "steady tow at speed " << speed << " m/s, cable out " << cable_out << " m, current (" << current_W.transpose()
       << ") m/s: the speed and current must be finite, the cable out in (0, 100000] m";
    throw std::invalid_argument(os.str());
  }
  SimulationConfig c = config;
  payOutTo(c, cable_out);
  c.environment.current_W = current_W;
  c.environment.waves = WaveParams();         // the steady tow is a calm-water one
  c.winch.enabled = false;                    // the chart's lengths are the cable out, whatever the winch's limits
  c.seabed.type = SeabedParams::Type::kNone;  // the steady tow ignores the bottom
  // Never stepped: an explicit stepper spares the implicit one's linearisation at the start (most of a chart
  // point's memory and a tenth of its time); the state, the outputs and the analyses do not depend on it.
  c.numerics.stepper = StepperType::kDopri5;
  auto run = std::make_unique<TowRun>(c, straightShip(speed, -2.0, 2.0), InitialShape());
  const std::string warning = run->start(0.0);
  if (!warning.empty())
    throw std::runtime_error(warning);
  return run;
}

TowSnapshot steadyTow(const SimulationConfig& config, double speed, double cable_out, const Eigen::Vector3d& current_W)
{
  return steadyTowRun(config, speed, cable_out, current_W)->snapshot();
}

std::vector<Mode> steadyTowModes(const SimulationConfig& config, double speed, double cable_out,
                                 const Eigen::Vector3d& current_W, std::size_t count)
{
  const std::unique_ptr<TowRun> run = steadyTowRun(config, speed, cable_out, current_W);
  const Simulator& sim = run->simulator();
  const ChainState state = sim.state();
  if (count > 0)
    return lowestModes(run->model(), sim.geometry(), sim.data(), sim.time(), sim.firstJoint(), state.x, state.v, count);
  return naturalModes(run->model(), sim.geometry(), sim.data(), sim.time(), sim.firstJoint(), state.x, state.v);
}

StrummingAnalysis steadyTowStrumming(const SimulationConfig& config, double speed, double cable_out,
                                     const Eigen::Vector3d& current_W, double bandwidth)
{
  const std::unique_ptr<TowRun> run = steadyTowRun(config, speed, cable_out, current_W);
  const TowSnapshot snap = run->snapshot();
  const Simulator& sim = run->simulator();
  // In the steady tow every point moves with the ship, along +x.
  const Eigen::Matrix3Xd velocities = Eigen::Vector3d(speed, 0.0, 0.0).replicate(1, snap.joints.cols());
  return strummingAnalysis(run->model(), sim.geometry(), sim.time(), snap.joints, velocities, snap.tensions, bandwidth);
}

Eigen::Vector3d towPointMotion(const std::string& input, const Eigen::Vector3d& tow_point_S)
{
  if (input == "heave")
    return Eigen::Vector3d::UnitZ();
  if (input == "surge")
    return Eigen::Vector3d::UnitX();
  if (input == "sway")
    return Eigen::Vector3d::UnitY();
  if (input == "pitch")  // about +y, bow down: the tow point moves by y x r
    return Eigen::Vector3d::UnitY().cross(tow_point_S);
  throw std::invalid_argument("input '" + input + "': one of heave, surge, sway, pitch");
}

std::vector<std::vector<MotionResponse>> steadyTowResponses(const SimulationConfig& config, double speed,
                                                            double cable_out, const Eigen::Vector3d& current_W,
                                                            const std::vector<Eigen::Vector3d>& inputs,
                                                            const std::vector<double>& periods)
{
  for (double period : periods)
    if (!(period > 0.0 && period <= 1e5))
      throw std::invalid_argument("response: the period " + std::to_string(period) + " s is not in (0, 1e5]");
  for (const Eigen::Vector3d& input : inputs)
    if (!input.allFinite() || input.norm() == 0.0)
      throw std::invalid_argument("response: the input's tow-point motion must be finite and not zero");
  const std::unique_ptr<TowRun> run = steadyTowRun(config, speed, cable_out, current_W);
  const Simulator& sim = run->simulator();
  const ChainState state = sim.state();
  const double cg_fraction = config.vehicle.cg_from_bail / config.vehicle.tail_from_bail;
  return motionResponses(run->model(), sim.geometry(), sim.data(), sim.time(), sim.firstJoint(), state.x, state.v,
                         inputs, periods, cg_fraction);
}

std::vector<MotionResponse> steadyTowResponse(const SimulationConfig& config, double speed, double cable_out,
                                              const Eigen::Vector3d& current_W, const Eigen::Vector3d& input,
                                              const std::vector<double>& periods)
{
  return steadyTowResponses(config, speed, cable_out, current_W, { input }, periods).front();
}

ChartPoint chartPoint(const SimulationConfig& config, double speed, double cable_out, const Eigen::Vector3d& current_W)
{
  ChartPoint p;
  p.speed = speed;
  p.cable_out = cable_out;
  p.current = current_W.norm();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  p.depth = p.layback = p.tension_ship = p.tension_vehicle = p.ship_angle = p.max_tension = nan;
  try
  {
    const TowSnapshot s = steadyTow(config, speed, cable_out, current_W);
    p.converged = true;
    p.depth = s.depth;
    p.layback = s.layback;
    p.tension_ship = s.tension_ship;
    p.tension_vehicle = s.tension_vehicle;
    const Eigen::Vector3d first = s.joints.col(1) - s.joints.col(0);
    p.ship_angle = std::atan2(-first.z(), first.head<2>().norm()) * 180.0 / kPi;
    p.max_tension = s.tensions.colwise().norm().maxCoeff();
  }
  catch (const std::exception& e)
  {
    p.converged = false;
    p.error = e.what();
  }
  return p;
}

std::vector<ChartPoint> towingChart(const SimulationConfig& config, const std::vector<double>& speeds,
                                    const std::vector<double>& cable_outs, const Eigen::Vector3d& current_W)
{
  std::vector<ChartPoint> points;
  for (double cable_out : cable_outs)
    for (double speed : speeds)
      points.push_back(chartPoint(config, speed, cable_out, current_W));
  return points;
}

CableOutPlan planCableOut(const SimulationConfig& config, double target_depth, double speed,
                          const Eigen::Vector3d& current_W, double min_length, double max_length, double tolerance)
{
  CableOutPlan plan;
  auto at = [&](double length) { return chartPoint(config, speed, length, current_W); };
  ChartPoint lo = at(min_length), hi = at(max_length);
  if (!lo.converged || !hi.converged)
  {
    plan.reason = "no steady tow at " + std::string(lo.converged ? "the longest" : "the shortest") +
                  " cable out: " + (lo.converged ? hi.error : lo.error);
    return plan;
  }
  if (target_depth < lo.depth || target_depth > hi.depth)
  {
    std::ostringstream why;
    why << "at " << speed << " m/s the vehicle runs between " << lo.depth << " m (" << min_length << " m out) and "
        << hi.depth << " m (" << max_length << " m out): " << target_depth << " m is out of reach";
    plan.reason = why.str();
    return plan;
  }
  double a = min_length, b = max_length;
  ChartPoint mid = lo;
  for (int i = 0; i < 200 && b - a > 1e-6; ++i)
  {
    const double m = 0.5 * (a + b);
    mid = at(m);
    if (!mid.converged)
    {
      plan.reason = "no steady tow at " + std::to_string(m) + " m out: " + mid.error;
      return plan;
    }
    if (std::abs(mid.depth - target_depth) <= tolerance)
      break;
    (mid.depth < target_depth ? a : b) = m;
  }
  plan.cable_out = mid.cable_out;
  plan.point = mid;
  // The depth jumps a little where the segment count changes (10 m segments: centimetres); a target in
  // such a jump is missed by more than the tolerance.
  plan.reachable = std::abs(mid.depth - target_depth) <= std::max(tolerance, 0.1);
  if (!plan.reachable)
    plan.reason = "the steady depth jumps across " + std::to_string(target_depth) + " m near " +
                  std::to_string(mid.cable_out) + " m out (the segment count changes there): closest " +
                  std::to_string(mid.depth) + " m";
  return plan;
}

SpeedWindow speedWindow(const SimulationConfig& config, double cable_out, double depth_min, double depth_max,
                        const Eigen::Vector3d& current_W, double slowest_allowed, double fastest_allowed)
{
  SpeedWindow w;
  auto depth = [&](double speed)
  {
    const ChartPoint p = chartPoint(config, speed, cable_out, current_W);
    return p.converged ? p.depth : std::numeric_limits<double>::quiet_NaN();
  };
  // The speed in [lo, hi] where the depth (falling with speed) crosses `level`.
  auto crossing = [&](double level, double lo, double hi)
  {
    for (int i = 0; i < 100 && hi - lo > 1e-4; ++i)
    {
      const double m = 0.5 * (lo + hi);
      (depth(m) > level ? lo : hi) = m;
    }
    return 0.5 * (lo + hi);
  };
  const double d_slow = depth(slowest_allowed), d_fast = depth(fastest_allowed);
  if (!std::isfinite(d_slow) || !std::isfinite(d_fast))
  {
    w.reason = "no steady tow at one end of the speeds searched";
    return w;
  }
  if (d_slow < depth_min || d_fast > depth_max)
  {
    std::ostringstream why;
    why << "with " << cable_out << " m out the vehicle runs between " << d_fast << " m (" << fastest_allowed
        << " m/s) and " << d_slow << " m (" << slowest_allowed << " m/s): the band " << depth_min << " .. " << depth_max
        << " m is out of reach";
    w.reason = why.str();
    return w;
  }
  w.slowest = d_slow <= depth_max ? slowest_allowed : crossing(depth_max, slowest_allowed, fastest_allowed);
  w.fastest = d_fast >= depth_min ? fastest_allowed : crossing(depth_min, slowest_allowed, fastest_allowed);
  w.found = w.slowest <= w.fastest;
  if (!w.found)
    w.reason = "the depth does not fall monotonically with speed here";
  return w;
}

std::vector<double> parseRange(const std::string& text, const std::string& option)
{
  std::vector<double> parts;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ':'))
  {
    double v = NAN;
    if (!parseFiniteNumber(part, v))
      throw std::invalid_argument(option + " '" + text + "': '" + part + "' is not a number (FROM:TO:STEP)");
    parts.push_back(v);
  }
  if (parts.size() == 1)
    return parts;
  if (parts.size() != 3)
    throw std::invalid_argument(option + " '" + text + "' must be FROM:TO:STEP (or one value)");
  const double from = parts[0], to = parts[1], step = parts[2];
  if (!(step > 0.0) || from > to || (to - from) / step > 10000.0)
    throw std::invalid_argument(option + " '" + text + "': needs STEP > 0, FROM <= TO and at most 10000 values");
  std::vector<double> out;
  for (int i = 0; from + i * step <= to + 1e-3 * step; ++i)
    out.push_back(from + i * step);
  return out;
}

double parseSingle(const std::string& text, const std::string& option)
{
  if (text.find(':') != std::string::npos)
    throw std::invalid_argument(option + " '" + text + "' must be one number, not a range");
  return parseRange(text, option).front();
}

const char* chartHeader()
{
  return "speed,cable_out,current,depth,layback,tension_ship,tension_vehicle,ship_angle,max_tension,converged";
}

void writeChartRow(std::ostream& out, const ChartPoint& p)
{
  auto value = [&](double v)
  {
    if (std::isfinite(v))
      out << v;
  };
  out.precision(10);
  out << p.speed << ',' << p.cable_out << ',' << p.current << ',';
  for (double v : { p.depth, p.layback, p.tension_ship, p.tension_vehicle, p.ship_angle, p.max_tension })
  {
    value(v);
    out << ',';
  }
  out << (p.converged ? 1 : 0) << '\n';
}

}  // namespace tow_sim
