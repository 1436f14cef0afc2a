#include "tow_sim/ros/survey_bag.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <set>
#include <stdexcept>

namespace tow_sim
{
namespace
{
const char* const kTopics[] = { "survey/ship/fix",   "survey/ship/heading",  "survey/cable_out", "survey/tension",
                                "survey/fish/depth", "survey/fish/pressure", "survey/fish/imu",  "survey/usbl" };

// One message into rows by its type; "" or why it was refused.
std::string take(SurveyRows& rows, const rosbag::MessageInstance& m)
{
  if (auto fix = m.instantiate<sensor_msgs::NavSatFix>())
    return rows.fix(*fix);
  if (auto heading = m.instantiate<geometry_msgs::QuaternionStamped>())
    return rows.heading(*heading);
  if (auto pressure = m.instantiate<sensor_msgs::FluidPressure>())
    return rows.pressure(*pressure);
  if (auto imu = m.instantiate<sensor_msgs::Imu>())
    return rows.imu(*imu);
  if (auto usbl = m.instantiate<geometry_msgs::PointStamped>())
    return rows.usbl(*usbl);
  if (auto value = m.instantiate<tow_sim::SensorValue>())
  {
    const std::string& topic = m.getTopic();
    auto endsWith = [&topic](const std::string& s)
    { return topic.size() >= s.size() && topic.compare(topic.size() - s.size(), s.size(), s) == 0; };
    if (endsWith("survey/cable_out"))
      return rows.cableOut(*value);
    if (endsWith("survey/tension"))
      return rows.tension(*value);
    return rows.depth(*value);
  }
  return "its type " + m.getDataType() + " is not the topic's";
}
}  // namespace

std::vector<std::string> surveyTopics(const std::string& prefix)
{
  std::string p = prefix.empty() ? "/" : prefix;
  if (p.front() != '/')
    p = "/" + p;
  if (p.back() != '/')
    p += "/";
  std::vector<std::string> topics;
  for (const char* t : kTopics)
    topics.push_back(p + t);
  return topics;
}

SurveyBag readSurveyBag(const std::string& path, const std::string& prefix, const SurveyRowSettings& settings)
{
  rosbag::Bag bag;
  try
  {
    bag.open(path, rosbag::bagmode::Read);
  }
  catch (const rosbag::BagException& e)
  {
    throw std::runtime_error("cannot read the bag " + path + ": " + e.what());
  }
  const std::vector<std::string> topics = surveyTopics(prefix);
  rosbag::View view(bag, rosbag::TopicQuery(topics));
  if (view.size() == 0)
  {
    std::set<std::string> has;
    for (const rosbag::ConnectionInfo* c : rosbag::View(bag).getConnections())
      has.insert(c->topic);
    std::string list;
    for (const std::string& t : has)
      list += (list.empty() ? "" : ", ") + t;
    throw std::runtime_error("the bag " + path + " has none of the survey topics (" + topics.front() +
                             ", ...); it has: " + (list.empty() ? "no topics" : list) +
                             " (--topics sets their prefix)");
  }
  // As tow_nav_node takes them live: each message when it was recorded, and the rows held `hold` by then.
  SurveyRows rows(settings);
  SurveyBag out;
  long wrong_type = 0;
  for (const rosbag::MessageInstance& m : view)
  {
    ++out.messages;
    const long before = rows.refused();
    const std::string why = take(rows, m);
    if (!why.empty() && rows.refused() == before)
      ++wrong_type;  // refused here, not by SurveyRows
    if (!why.empty() && out.first_refusal.empty())
      out.first_refusal = m.getTopic() + ": " + why;
    for (const SurveyMeasurement& row : rows.release(m.getTime()))
      out.rows.push_back(row);
  }
  for (const SurveyMeasurement& row : rows.releaseAll())
    out.rows.push_back(row);
  out.refused = rows.refused() + wrong_type;
  out.late = rows.late();
  out.epoch = rows.stampOf(0.0);
  return out;
}

}  // namespace tow_sim
