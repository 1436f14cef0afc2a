#include "tow_sim/core/survey/survey_sensors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tow_sim
{
namespace
{
constexpr int kChannels = 8;  // SensorKind's, in its order (the streams are indexed by it)

// The channel table with the noise and bias in `unit`: one table per unit, built once.
const ParamTable<SensorChannel>& channelTable(const std::string& unit)
{
  static std::map<std::string, ParamTable<SensorChannel>> tables;
  auto found = tables.find(unit);
  if (found != tables.end())
    return found->second;
  using C = SensorChannel;
  ParamTable<C> table;
  table.boolean("enabled", &C::enabled, "the sensor reports")
      .number("rate", &C::rate, "Hz", 0.0, 100.0, kOpen, "samples at t = k / rate")
      .number("noise", &C::noise, unit, 0.0, 1e6, kClosed, "standard deviation of the white Gaussian noise")
      .number("bias", &C::bias, unit, -1e6, 1e6, kClosed, "constant offset")
      .number("latency", &C::latency, "s", 0.0, 60.0, kClosed, "a sample reaches its row this much later")
      .number("dropout", &C::dropout, "-", 0.0, 0.99, kClosed, "probability that a sample is lost")
      .integer("seed", &C::seed, "-", 0, 2147483647, "the channel's random stream");
  return tables.emplace(unit, std::move(table)).first->second;
}

}  // namespace

const ParamTable<SensorChannel>& sensorChannelParams()
{
  return channelTable("unit");
}

const ParamTable<SurveySensorParams>& surveySensorParams()
{
  using P = SurveySensorParams;
  static const ParamTable<P> table =
      ParamTable<P>()
          .boolean("enabled", &P::enabled,
                   "tow_sim_batch writes measurements.csv (true once a sensors: section is given)")
          .nest("gnss", &P::gnss, channelTable("m"))
          .number("gnss_speed_noise", &P::gnss_speed_noise, "m/s", 0.0, 100.0, kClosed,
                  "the GNSS speed over ground's noise")
          .nest("heading", &P::heading, channelTable("rad"))
          .nest("cable_counter", &P::cable_counter, channelTable("m"))
          .nest("load_cell", &P::load_cell, channelTable("N"))
          .nest("depth", &P::depth, channelTable("m"))
          .nest("ahrs", &P::ahrs, channelTable("rad"))
          .number("ahrs_pitch_noise", &P::ahrs_pitch_noise, "rad", 0.0, 1.0, kClosed, "the AHRS pitch's noise")
          .number("ahrs_roll_noise", &P::ahrs_roll_noise, "rad", 0.0, 1.0, kClosed, "the AHRS roll's noise")
          .nest("altimeter", &P::altimeter, channelTable("m"))
          .nest("usbl", &P::usbl, channelTable("m"))
          .number("usbl_range_noise", &P::usbl_range_noise, "-", 0.0, 1.0, kClosed,
                  "USBL noise per axis per metre of slant range (added to usbl.noise)")
          .number("origin_latitude", &P::origin_latitude, "deg", -90.0, 90.0, kClosed,
                  "tow_sim_node: the world frame's geodetic origin (WGS84) for survey/ship/fix")
          .number("origin_longitude", &P::origin_longitude, "deg", -180.0, 180.0, kClosed, "tow_sim_node: likewise")
          .number("origin_altitude", &P::origin_altitude, "m", -1000.0, 10000.0, kClosed,
                  "tow_sim_node: likewise, above the ellipsoid")
          .text("ship_frame", &P::ship_frame, "a frame name", "tow_sim_node: the frame of survey/usbl's fixes (FLU)");
  return table;
}

void validate(const SurveySensorParams& params, const std::string& prefix)
{
  validateParams(surveySensorParams(), params, prefix);
  if (params.ship_frame.empty())
    throw std::invalid_argument(paramName(prefix, "ship_frame") + ": must name a frame");
}

SurveySensors::SurveySensors(const SurveySensorParams& params, Output output) : params_(params), output_(output)
{
  validate(params_, "sensors");
  const SensorChannel* channels[kChannels] = { &params_.gnss,      &params_.heading, &params_.cable_counter,
                                               &params_.load_cell, &params_.depth,   &params_.ahrs,
                                               &params_.altimeter, &params_.usbl };
  for (const SensorChannel* c : channels)
  {
    Stream s;
    s.channel = c;
    s.random.seed(static_cast<std::uint64_t>(c->seed));
    streams_.push_back(s);
  }
}

SurveySensors::Truth SurveySensors::truthOf(const TowSnapshot& s)
{
  Truth r;
  r.t = s.t;
  r.ship_x = s.ship.x;
  r.ship_y = s.ship.y;
  r.ship_heading = s.ship.heading;
  r.ship_speed = s.ship.speed;
  r.cable_out = s.cable_length;
  r.tension = s.tension_ship;
  r.fish_x = s.vehicle.p_cg_W.x();
  r.fish_y = s.vehicle.p_cg_W.y();
  r.fish_z = s.vehicle.p_cg_W.z();
  r.fish_heading = s.yaw;
  r.fish_pitch = s.pitch;
  r.fish_roll = s.roll;
  r.altitude = s.seabed_present ? s.vehicle_altitude : std::numeric_limits<double>::quiet_NaN();
  return r;
}

SurveySensors::Truth SurveySensors::between(const Truth& a, const Truth& b, double t)
{
  const double span = b.t - a.t;
  const double w = span > 0.0 ? std::clamp((t - a.t) / span, 0.0, 1.0) : 1.0;
  auto lerp = [w](double x, double y) { return x + w * (y - x); };
  auto angle = [w](double x, double y) { return wrapAngle(x + w * wrapAngle(y - x)); };
  Truth r;
  r.t = t;
  r.ship_x = lerp(a.ship_x, b.ship_x);
  r.ship_y = lerp(a.ship_y, b.ship_y);
  r.ship_heading = angle(a.ship_heading, b.ship_heading);
  r.ship_speed = lerp(a.ship_speed, b.ship_speed);
  r.cable_out = lerp(a.cable_out, b.cable_out);
  r.tension = lerp(a.tension, b.tension);
  r.fish_x = lerp(a.fish_x, b.fish_x);
  r.fish_y = lerp(a.fish_y, b.fish_y);
  r.fish_z = lerp(a.fish_z, b.fish_z);
  r.fish_heading = angle(a.fish_heading, b.fish_heading);
  r.fish_pitch = lerp(a.fish_pitch, b.fish_pitch);
  r.fish_roll = lerp(a.fish_roll, b.fish_roll);
  r.altitude = lerp(a.altitude, b.altitude);
  return r;
}

void SurveySensors::observe(const TowSnapshot& s)
{
  const Truth now = truthOf(s);
  if (!started_)
  {
    started_ = true;
    for (Stream& stream : streams_)
      stream.next = static_cast<long>(std::ceil(now.t * stream.channel->rate - 1e-9));
    sampleDue(now, now);
  }
  else if (now.t > last_.t)
    sampleDue(last_, now);
  else
    return;
  last_ = now;
}

void SurveySensors::sampleDue(const Truth& a, const Truth& b)
{
  for (int c = 0; c < kChannels; ++c)
  {
    Stream& stream = streams_[c];
    for (;; ++stream.next)
    {
      const double t = stream.next / stream.channel->rate;
      if (t > b.t + 1e-9)
        break;
      if (stream.channel->enabled)
        sample(c, between(a, b, t));
    }
  }
}

double SurveySensors::normal(Stream& s, double sigma)
{
  return sigma * std::normal_distribution<double>(0.0, 1.0)(s.random);
}

void SurveySensors::sample(int c, const Truth& truth)
{
  Stream& s = streams_[c];
  const SensorChannel& ch = *s.channel;
  // The same draws whether the sample is lost or not, so a dropout changes no other sample.
  const bool lost = std::uniform_real_distribution<double>(0.0, 1.0)(s.random) < ch.dropout;
  const double e1 = normal(s, 1.0), e2 = normal(s, 1.0), e3 = normal(s, 1.0);
  const SensorKind kind = static_cast<SensorKind>(c);
  if (lost || (kind == SensorKind::kAltimeter && !std::isfinite(truth.altitude)))
    return;
  SensorSample out;
  out.kind = kind;
  out.measured = truth.t;
  out.arrives = truth.t + ch.latency;
  SurveyMeasurement& m = out.values;
  m.t = out.arrives;
  switch (kind)
  {
    case SensorKind::kGnss:
      m.ship_x = truth.ship_x + ch.bias + ch.noise * e1;
      m.ship_y = truth.ship_y + ch.bias + ch.noise * e2;
      m.ship_speed = std::max(0.0, truth.ship_speed + params_.gnss_speed_noise * e3);
      break;
    case SensorKind::kHeading:
      m.ship_heading = wrapAngle(truth.ship_heading + ch.bias + ch.noise * e1);
      break;
    case SensorKind::kCableCounter:
      m.cable_out = truth.cable_out + ch.bias + ch.noise * e1;
      break;
    case SensorKind::kLoadCell:
      m.tension = truth.tension + ch.bias + ch.noise * e1;
      break;
    case SensorKind::kDepth:
      m.fish_depth = -truth.fish_z + ch.bias + ch.noise * e1;
      break;
    case SensorKind::kAhrs:
      m.fish_heading = wrapAngle(truth.fish_heading + ch.bias + ch.noise * e1);
      m.fish_pitch = truth.fish_pitch + params_.ahrs_pitch_noise * e2;
      m.fish_roll = wrapAngle(truth.fish_roll + params_.ahrs_roll_noise * e3);  // e3: drawn before, unused then
      break;
    case SensorKind::kAltimeter:
      m.fish_altitude = truth.altitude + ch.bias + ch.noise * e1;
      break;
    case SensorKind::kUsbl:  // the transducer at the ship's reference point, the noise growing with the slant range
    {
      const Eigen::Vector3d d(truth.fish_x - truth.ship_x, truth.fish_y - truth.ship_y, truth.fish_z);
      const double sigma = ch.noise + params_.usbl_range_noise * d.norm();
      m.usbl_x = truth.fish_x + ch.bias + sigma * e1;
      m.usbl_y = truth.fish_y + ch.bias + sigma * e2;
      m.usbl_z = truth.fish_z + ch.bias + sigma * e3;
      const double cos_h = std::cos(truth.ship_heading), sin_h = std::sin(truth.ship_heading);
      const double dx = m.usbl_x - truth.ship_x, dy = m.usbl_y - truth.ship_y;
      out.usbl_S = Eigen::Vector3d(cos_h * dx + sin_h * dy, -sin_h * dx + cos_h * dy, m.usbl_z);
    }
  }
  keep(out);
}

// A sample into its row (fields already there from another sensor stay) or the samples' queue.
void SurveySensors::keep(const SensorSample& out)
{
  if (output_ == Output::kSamples)
  {
    samples_.emplace(out.arrives, out);
    return;
  }
  SurveyMeasurement& row = pending_[out.arrives];
  row.t = out.arrives;
  const std::array<double, SurveyMeasurement::kColumns> v = out.values.values();
  const std::array<double*, SurveyMeasurement::kColumns> f = row.fields();
  for (int i = 1; i < SurveyMeasurement::kColumns; ++i)
    if (!std::isnan(v[i]))
      *f[i] = v[i];
}

std::vector<SensorSample> SurveySensors::takeSamples(double up_to)
{
  std::vector<SensorSample> out;
  auto end = samples_.upper_bound(up_to + 1e-9);
  for (auto it = samples_.begin(); it != end; ++it)
    out.push_back(it->second);
  samples_.erase(samples_.begin(), end);
  return out;
}

std::vector<SurveyMeasurement> SurveySensors::take(double up_to)
{
  std::vector<SurveyMeasurement> rows;
  auto end = pending_.upper_bound(up_to + 1e-9);
  for (auto it = pending_.begin(); it != end; ++it)
    rows.push_back(it->second);
  pending_.erase(pending_.begin(), end);
  return rows;
}

}  // namespace tow_sim
