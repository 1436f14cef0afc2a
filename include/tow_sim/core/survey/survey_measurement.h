// One row of a survey's measurements (docs/survey.md): what a survey vessel's sensors report at time t, each
// field NaN when that sensor gave nothing at t. The columns of measurements.csv (tow_sim_batch) and of the
// input of tow_sim_nav, in this order.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace tow_sim
{
struct SurveyMeasurement
{
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double t = 0.0;                // [s] when the row arrived (a sensor's latency: its value is older)
  double ship_x = kNone;         // [m] the ship's reference point from GNSS, world ENU
  double ship_y = kNone;         // [m]
  double ship_heading = kNone;   // [rad] ENU: 0 east, counter-clockwise, in (-pi, pi]
  double ship_speed = kNone;     // [m/s] over ground
  double cable_out = kNone;      // [m] the winch's cable counter
  double fish_depth = kNone;     // [m] positive down, from the fish's pressure sensor
  double fish_heading = kNone;   // [rad] the fish's AHRS heading, same convention as ship_heading
  double fish_pitch = kNone;     // [rad] REP-103: nose down positive
  double tension = kNone;        // [N] the tow point's load cell
  double usbl_x = kNone;         // [m] a USBL fix of the fish, world ENU
  double usbl_y = kNone;         // [m]
  double usbl_z = kNone;         // [m] (z up: minus the depth)
  double fish_altitude = kNone;  // [m] the fish's altimeter (above the seabed)
  double fish_roll = kNone;      // [rad] the fish's AHRS roll, REP-103: starboard down positive

  static constexpr int kColumns = 15;
  // The fields in column order (t first), for reading and writing rows.
  std::array<double*, kColumns> fields();
  std::array<double, kColumns> values() const;
  // True when no sensor reported anything in this row.
  bool empty() const;
};

// "t,ship_x,ship_y,ship_heading,ship_speed,cable_out,fish_depth,fish_heading,fish_pitch,tension,usbl_x,usbl_y,
// usbl_z,fish_altitude,fish_roll"
const std::string& surveyMeasurementHeader();
// The row (no line break): numbers to `precision` significant digits, an empty cell for NaN.
std::string surveyMeasurementRow(const SurveyMeasurement& m, int precision = 10);

// An angle wrapped into (-pi, pi].
inline double wrapAngle(double a)
{
  const double w = std::remainder(a, 2.0 * M_PI);
  return w <= -M_PI ? w + 2.0 * M_PI : w;
}

}  // namespace tow_sim
