// Reading a survey's measurements (survey_measurement.h) from CSV: tow_sim_nav's input and tow_sim_batch's
// measurements.csv (docs/survey.md, "Measurements").
#pragma once

#include <string>
#include <vector>

#include "tow_sim/core/survey/survey_measurement.h"

namespace tow_sim
{
// The header names columns of surveyMeasurementHeader() in any order; `t` is required, every other column
// optional (absent: that sensor never reports). Each further line holds a number or an empty cell (no
// measurement) per column; blank lines and lines starting with # are skipped. Throws std::invalid_argument
// naming the file, the line and the column (an unknown column with the list of known ones).
std::vector<SurveyMeasurement> readSurveyMeasurements(const std::string& path);

}  // namespace tow_sim
