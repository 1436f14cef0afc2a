// A survey vessel's sensors, simulated from a run's outputs (docs/survey.md): ship GNSS and heading, the
// winch's cable counter, the tow point's load cell, the fish's pressure depth, AHRS and altimeter, and USBL fixes
// of the fish. Each channel samples the truth at its own rate (at the times k / rate), adds a constant bias and
// white Gaussian noise from its own seeded stream, loses a sample with its dropout probability, and reports it
// `latency` seconds later. The rows are measurements.csv's (survey_measurement.h); tow_sim_batch writes them for
// a scenario with `sensors.enabled`.
//
// The truth between two snapshots is linear in time (the heading unwrapped): output intervals of 1 s or less
// keep that well inside the sensors' noise except in the sharpest manoeuvres.
#pragma once

#include <Eigen/Core>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "tow_sim/core/param_table.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/core/survey/survey_measurement.h"

namespace tow_sim
{
// One sensor's timing and errors. The noise and bias are in the sensor's unit (GNSS and USBL: per axis).
struct SensorChannel
{
  bool enabled = true;
  double rate = 1.0;     // [Hz] samples at t = k / rate
  double noise = 0.0;    // [unit] standard deviation of the white noise
  double bias = 0.0;     // [unit] constant offset (GNSS, USBL: on each axis)
  double latency = 0.0;  // [s] a sample reaches the row this long after the instant it measures
  double dropout = 0.0;  // [-] probability that a sample is lost
  int seed = 1;          // the channel's random stream
};

// Defaults typical of survey equipment (docs/survey.md says where each comes from).
struct SurveySensorParams
{
  bool enabled = false;                                             // tow_sim_batch writes measurements.csv
  SensorChannel gnss{ true, 1.0, 0.5, 0.0, 0.0, 0.0, 1 };           // [m] DGNSS, per horizontal axis
  double gnss_speed_noise = 0.05;                                   // [m/s] its speed over ground
  SensorChannel heading{ true, 10.0, 0.0017, 0.0, 0.0, 0.0, 2 };    // [rad] gyro compass, 0.1 deg
  SensorChannel cable_counter{ true, 1.0, 0.5, 0.0, 0.0, 0.0, 3 };  // [m]
  SensorChannel load_cell{ true, 10.0, 200.0, 0.0, 0.0, 0.0, 4 };   // [N]
  SensorChannel depth{ true, 1.0, 0.1, 0.0, 0.0, 0.0, 5 };          // [m] pressure depth
  SensorChannel ahrs{ true, 10.0, 0.017, 0.0, 0.0, 0.0, 6 };        // [rad] the fish's heading, 1 deg
  double ahrs_pitch_noise = 0.0035;                                 // [rad] its pitch, 0.2 deg
  double ahrs_roll_noise = 0.0035;                                  // [rad] its roll, 0.2 deg
  SensorChannel altimeter{ true, 1.0, 0.1, 0.0, 0.0, 0.0, 7 };      // [m] (only with a seabed)
  SensorChannel usbl{ true, 0.2, 0.5, 0.0, 1.0, 0.1, 8 };           // [m] floor of the noise per axis
  double usbl_range_noise = 0.005;  // [-] the noise's part proportional to the slant range, per axis
  // tow_sim_node only: the geodetic origin of the world frame (the GNSS fixes' latitude and longitude) and the
  // frame of the USBL fixes.
  double origin_latitude = 0.0;   // [deg] WGS84, north positive
  double origin_longitude = 0.0;  // [deg] WGS84, east positive
  double origin_altitude = 0.0;   // [m] above the WGS84 ellipsoid
  std::string ship_frame = "ship";
};

const ParamTable<SensorChannel>& sensorChannelParams();
const ParamTable<SurveySensorParams>& surveySensorParams();  // nests sensorChannelParams() per channel
// Throws std::invalid_argument naming PREFIX.<key> and its range.
void validate(const SurveySensorParams& params, const std::string& prefix);

enum class SensorKind
{
  kGnss,
  kHeading,
  kCableCounter,
  kLoadCell,
  kDepth,
  kAhrs,
  kAltimeter,
  kUsbl
};

// One sensor's sample, as a node publishes it: stamped with the instant it measures, sent when it arrives.
struct SensorSample
{
  SensorKind kind = SensorKind::kGnss;
  double measured = 0.0;                             // [s] the instant it measures
  double arrives = 0.0;                              // [s] measured + the channel's latency
  SurveyMeasurement values;                          // this sensor's fields only (values.t = arrives)
  Eigen::Vector3d usbl_S = Eigen::Vector3d::Zero();  // kUsbl: the fix in the ship frame (FLU) then [m]
};

class SurveySensors
{
public:
  enum class Output
  {
    kRows,    // take(): the rows of measurements.csv
    kSamples  // takeSamples(): each sensor's samples (tow_sim_node publishes them)
  };
  // Validates (prefix "sensors").
  explicit SurveySensors(const SurveySensorParams& params, Output output = Output::kRows);
  SurveySensors(const SurveySensors&) = delete;  // its streams point into its own parameters
  SurveySensors& operator=(const SurveySensors&) = delete;

  // A snapshot of the run, in time order (an earlier one is ignored): samples every channel due since the
  // previous one.
  void observe(const TowSnapshot& s);
  // The rows that have arrived by `up_to` [s] and were not taken yet, in time order; samples due at one instant
  // share a row.
  std::vector<SurveyMeasurement> take(double up_to);
  // The samples that have arrived by `up_to` [s] and were not taken yet, by arrival time (Output::kSamples).
  std::vector<SensorSample> takeSamples(double up_to);

  // What the sensors see at one instant (world ENU, SI), from a snapshot.
  struct Truth
  {
    double t = 0.0;
    double ship_x = 0.0, ship_y = 0.0, ship_heading = 0.0, ship_speed = 0.0;
    double cable_out = 0.0, tension = 0.0;
    double fish_x = 0.0, fish_y = 0.0, fish_z = 0.0, fish_heading = 0.0, fish_pitch = 0.0;
    double fish_roll = 0.0;  // [rad] REP-103, 0 unless the vehicle rolls (vehicle.roll: free)
    double altitude = 0.0;   // NaN without a seabed
  };
  static Truth truthOf(const TowSnapshot& s);
  // Linear between a and b at t (headings through the shorter way round).
  static Truth between(const Truth& a, const Truth& b, double t);

private:
  struct Stream
  {
    const SensorChannel* channel = nullptr;
    std::mt19937_64 random;
    long next = 0;  // the next sample's index k (t = k / rate)
  };
  void sampleDue(const Truth& a, const Truth& b);
  void sample(int channel, const Truth& truth);
  void keep(const SensorSample& sample);
  double normal(Stream& s, double sigma);

  SurveySensorParams params_;
  std::vector<Stream> streams_;
  bool started_ = false;
  Truth last_;
  Output output_;
  std::map<double, SurveyMeasurement> pending_;  // rows by arrival time
  std::multimap<double, SensorSample> samples_;  // samples by arrival time
};

}  // namespace tow_sim
