// Survey rows from sensors that report on their own (docs/survey.md, "tow_nav_node"): each sample is a field of
// SurveyMeasurement at the instant it measures; samples of the same instant make one row, and a row is released
// once `hold` has passed since its time, so that a sensor whose messages come late still finds its place in the
// order tow_nav needs. A sample earlier than a row already released is refused and counted.
#pragma once

#include <functional>
#include <map>
#include <vector>

#include "tow_sim/core/survey/survey_measurement.h"

namespace tow_sim
{
class SurveyRowQueue
{
public:
  // hold [s] >= 0: how long a row waits for the samples of its instant.
  explicit SurveyRowQueue(double hold);

  // A sample at t [s] (finite): `set` writes its fields into the row of t. Returns false, and counts it in
  // late(), if a row at or after t has been released already; a non-finite t is refused the same way.
  bool add(double t, const std::function<void(SurveyMeasurement&)>& set);
  // The rows with t <= now - hold, in time order (released: they leave the queue).
  std::vector<SurveyMeasurement> release(double now);
  // Every row still held, in time order (the end of a recording).
  std::vector<SurveyMeasurement> releaseAll();

  long late() const { return late_; }
  size_t held() const { return rows_.size(); }

private:
  double hold_;
  double released_;  // the time of the last row released
  std::map<double, SurveyMeasurement> rows_;
  long late_ = 0;
};

}  // namespace tow_sim
