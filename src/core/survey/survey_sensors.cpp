#include "tow_sim/core/survey/survey_sensors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tow_sim
{
namespace
{
enum Channel
{
  kGnss,
  kHeading,
  kCableCounter,
  kLoadCell,
  kDepth,
  kAhrs,
  kAltimeter,
  kUsbl,
  kChannels
};

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
          .nest("altimeter", &P::altimeter, channelTable("m"))
          .nest("usbl", &P::usbl, channelTable("m"))
          .number("usbl_range_noise", &P::usbl_range_noise, "-", 0.0, 1.0, kClosed,
                  "USBL noise per axis per metre of slant range (added to usbl.noise)");
  return table;
}

void validate(const SurveySensorParams& params, const std::string& prefix)
{
  validateParams(surveySensorParams(), params, prefix);
}

SurveySensors::SurveySensors(const SurveySensorParams& params) : params_(params)
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

SurveyMeasurement& SurveySensors::rowAt(double t)
{
  SurveyMeasurement& row = pending_[t];
  row.t = t;
  return row;
}

void SurveySensors::sample(int c, const Truth& truth)
{
  Stream& s = streams_[c];
  const SensorChannel& ch = *s.channel;
  // The same draws whether the sample is lost or not, so a dropout changes no other sample.
  const bool lost = std::uniform_real_distribution<double>(0.0, 1.0)(s.random) < ch.dropout;
  const double e1 = normal(s, 1.0), e2 = normal(s, 1.0), e3 = normal(s, 1.0);
  if (lost || (c == kAltimeter && !std::isfinite(truth.altitude)))
    return;
  SurveyMeasurement& row = rowAt(truth.t + ch.latency);
  switch (c)
  {
    case kGnss:
      row.ship_x = truth.ship_x + ch.bias + ch.noise * e1;
      row.ship_y = truth.ship_y + ch.bias + ch.noise * e2;
      row.ship_speed = std::max(0.0, truth.ship_speed + params_.gnss_speed_noise * e3);
      break;
    case kHeading:
      row.ship_heading = wrapAngle(truth.ship_heading + ch.bias + ch.noise * e1);
      break;
    case kCableCounter:
      row.cable_out = truth.cable_out + ch.bias + ch.noise * e1;
      break;
    case kLoadCell:
      row.tension = truth.tension + ch.bias + ch.noise * e1;
      break;
    case kDepth:
      row.fish_depth = -truth.fish_z + ch.bias + ch.noise * e1;
      break;
    case kAhrs:
      row.fish_heading = wrapAngle(truth.fish_heading + ch.bias + ch.noise * e1);
      row.fish_pitch = truth.fish_pitch + params_.ahrs_pitch_noise * e2;
      break;
    case kAltimeter:
      row.fish_altitude = truth.altitude + ch.bias + ch.noise * e1;
      break;
    default:  // kUsbl: the transducer at the ship's reference point, the noise growing with the slant range
    {
      const double range = std::hypot(truth.fish_x - truth.ship_x, truth.fish_y - truth.ship_y, truth.fish_z);
      const double sigma = ch.noise + params_.usbl_range_noise * range;
      row.usbl_x = truth.fish_x + ch.bias + sigma * e1;
      row.usbl_y = truth.fish_y + ch.bias + sigma * e2;
      row.usbl_z = truth.fish_z + ch.bias + sigma * e3;
    }
  }
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
