#include "tow_sim/core/survey/survey_row_queue.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tow_sim
{
SurveyRowQueue::SurveyRowQueue(double hold) : hold_(hold), released_(-std::numeric_limits<double>::infinity())
{
  if (!(hold >= 0.0 && std::isfinite(hold)))
    throw std::invalid_argument("SurveyRowQueue: hold = " + std::to_string(hold) + " must be finite, >= 0 [s]");
}

bool SurveyRowQueue::add(double t, const std::function<void(SurveyMeasurement&)>& set)
{
  if (!std::isfinite(t) || t <= released_)
  {
    ++late_;
    return false;
  }
  auto row = rows_.find(t);
  if (row == rows_.end())
  {
    row = rows_.emplace(t, SurveyMeasurement()).first;
    row->second.t = t;
  }
  set(row->second);
  return true;
}

std::vector<SurveyMeasurement> SurveyRowQueue::release(double now)
{
  std::vector<SurveyMeasurement> out;
  auto end = rows_.upper_bound(now - hold_);
  for (auto row = rows_.begin(); row != end; ++row)
    out.push_back(row->second);
  rows_.erase(rows_.begin(), end);
  if (!out.empty())
    released_ = out.back().t;
  return out;
}

std::vector<SurveyMeasurement> SurveyRowQueue::releaseAll()
{
  return release(std::numeric_limits<double>::infinity());
}

}  // namespace tow_sim
