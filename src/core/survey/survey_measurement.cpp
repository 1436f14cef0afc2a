#include "tow_sim/core/survey/survey_measurement.h"

#include <cstdio>

namespace tow_sim
{
std::array<double*, SurveyMeasurement::kColumns> SurveyMeasurement::fields()
{
  return { &t,          &ship_x,  &ship_y, &ship_heading, &ship_speed, &cable_out,     &fish_depth, &fish_heading,
           &fish_pitch, &tension, &usbl_x, &usbl_y,       &usbl_z,     &fish_altitude, &fish_roll };
}

std::array<double, SurveyMeasurement::kColumns> SurveyMeasurement::values() const
{
  return { t,          ship_x,  ship_y, ship_heading, ship_speed, cable_out,     fish_depth, fish_heading,
           fish_pitch, tension, usbl_x, usbl_y,       usbl_z,     fish_altitude, fish_roll };
}

bool SurveyMeasurement::empty() const
{
  const std::array<double, kColumns> v = values();
  for (int i = 1; i < kColumns; ++i)
    if (!std::isnan(v[i]))
      return false;
  return true;
}

const std::string& surveyMeasurementHeader()
{
  static const std::string header =
      "t,ship_x,ship_y,ship_heading,ship_speed,cable_out,fish_depth,fish_heading,"
      "fish_pitch,tension,usbl_x,usbl_y,usbl_z,fish_altitude,fish_roll";
  return header;
}

std::string surveyMeasurementRow(const SurveyMeasurement& m, int precision)
{
  std::string row;
  char buffer[64];
  const std::array<double, SurveyMeasurement::kColumns> v = m.values();
  for (int i = 0; i < SurveyMeasurement::kColumns; ++i)
  {
    if (i > 0)
      row += ',';
    if (std::isnan(v[i]))
      continue;
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, v[i]);
    row += buffer;
  }
  return row;
}

}  // namespace tow_sim
