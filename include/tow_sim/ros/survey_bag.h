// A recorded survey's sensor messages read back as tow_nav's rows (tow_sim_nav --bag, docs/survey.md): the
// topics tow_nav_node subscribes, under a prefix, turned into rows by SurveyRows (survey_rows.h) as the node
// takes them live, each message at the time it was recorded.
#pragma once

#include <string>
#include <vector>

#include "tow_sim/ros/survey_rows.h"

namespace tow_sim
{
struct SurveyBag
{
  std::vector<SurveyMeasurement> rows;  // t: seconds after `epoch`
  ros::Time epoch;                      // the first message's stamp, whole seconds
  long messages = 0;                    // survey messages read
  long refused = 0;                     // of them refused (a bad field or type; SurveyRows says which)
  long late = 0;                        // of them recorded after their row had gone (more than hold after)
  std::string first_refusal;            // the first refusal's reason, with its topic
};

// The survey topics under `prefix` ("/" or "/ns/"): survey/ship/fix, survey/ship/heading, survey/cable_out,
// survey/tension, survey/fish/depth, survey/fish/pressure, survey/fish/imu, survey/usbl.
std::vector<std::string> surveyTopics(const std::string& prefix);

// Throws std::runtime_error naming the file if it cannot be read as a bag, or if it holds none of the survey
// topics (the message lists the topics it has).
SurveyBag readSurveyBag(const std::string& path, const std::string& prefix, const SurveyRowSettings& settings);

}  // namespace tow_sim
