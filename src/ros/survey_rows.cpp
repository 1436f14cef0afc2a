#include "tow_sim/ros/survey_rows.h"

#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/attitude.h"
#include "tow_sim/ros/gnss_ship_node.h"

namespace tow_sim
{
namespace
{
constexpr double kKeep = 60.0;  // [s] of ship fixes and headings kept for the USBL fixes

// a + w (b - a) for angles, the short way round.
double lerpAngle(double a, double b, double w)
{
  return wrapAngle(a + w * std::remainder(b - a, 2.0 * M_PI));
}

// The value at t from a time-ordered history, linear between the samples around it; false unless there is a
// sample at or after t and one at or before it, at most 2 gap apart (no extrapolation: a USBL fix waits for the
// ship fix after it).
bool interpolate(const std::deque<Eigen::Vector3d>& h, double t, double gap, bool angle, Eigen::Vector2d& out)
{
  auto after = std::lower_bound(h.begin(), h.end(), t, [](const Eigen::Vector3d& s, double v) { return s[0] < v; });
  if (after == h.end())
    return false;
  if ((*after)[0] == t)
  {
    out = after->tail<2>();
    return true;
  }
  if (after == h.begin())
    return false;
  const Eigen::Vector3d& a = *std::prev(after);
  const Eigen::Vector3d& b = *after;
  if (b[0] - a[0] > 2.0 * gap)
    return false;
  const double w = (t - a[0]) / (b[0] - a[0]);
  out = angle ? Eigen::Vector2d(lerpAngle(a[1], b[1], w), 0.0) : Eigen::Vector2d(a.tail<2>() + w * (b - a).tail<2>());
  return true;
}

std::string outOfRange(const char* field, double value, double low, double high, const char* unit)
{
  std::ostringstream why;
  why << field << " = " << value << " must be finite, in [" << low << ", " << high << "] [" << unit << "]";
  return why.str();
}

bool within(double v, double low, double high)
{
  return std::isfinite(v) && v >= low && v <= high;
}
}  // namespace

SurveyRowSettings surveyRowSettings(const TowNavNodeParams& p, const TowNavParams& nav, const SimulationConfig& config)
{
  SurveyRowSettings s;
  s.origin_from_first_fix = p.origin_from_first_fix;
  s.origin_latitude = p.origin_latitude;
  s.origin_longitude = p.origin_longitude;
  s.origin_altitude = p.origin_altitude;
  s.heading_convention = p.heading_convention;
  s.ship_frame = p.ship_frame;
  s.depth_source = p.depth_source;
  s.atmospheric_pressure = p.atmospheric_pressure;
  s.rho_g = config.environment.water_density * config.environment.gravity;
  if (p.depth_source == "pressure" && !(s.rho_g > 0.0))
    throw std::invalid_argument(
        "depth_source = pressure needs environment.water_density and environment.gravity "
        "above 0 (a depth is (p - atmospheric_pressure) / (rho g))");
  s.hold = p.hold;
  s.usbl_latency = nav.usbl_latency;
  s.max_ship_gap = p.max_ship_gap;
  return s;
}

SurveyRows::SurveyRows(const SurveyRowSettings& settings) : settings_(settings), queue_(settings.hold)
{
  if (!settings_.origin_from_first_fix)
    origin_ = std::make_unique<GeographicLib::LocalCartesian>(settings_.origin_latitude, settings_.origin_longitude,
                                                              settings_.origin_altitude);
}

SurveyRows::~SurveyRows() = default;

double SurveyRows::timeOf(const ros::Time& stamp)
{
  if (!has_epoch_)
    epoch_ = ros::Time(std::floor(stamp.toSec())), has_epoch_ = true;
  const double t = (stamp - epoch_).toSec();
  newest_ = std::max(newest_, t);
  return t;
}

std::string SurveyRows::refuse(const std::string& why)
{
  ++refused_;
  return why;
}

std::string SurveyRows::sample(const ros::Time& stamp, double value, const char* field, double low, double high,
                               const char* unit, double SurveyMeasurement::*member)
{
  if (stamp.isZero())
    return refuse("header.stamp is zero: a measurement needs the instant it measures");
  if (!within(value, low, high))
    return refuse(outOfRange(field, value, low, high, unit));
  queue_.add(timeOf(stamp), [&](SurveyMeasurement& m) { m.*member = value; });
  return "";
}

std::string SurveyRows::fix(const sensor_msgs::NavSatFix& msg)
{
  const std::string problem = ros_conv::fixProblem(msg);
  if (!problem.empty())
    return refuse(problem);
  if (msg.header.stamp.isZero())
    return refuse("header.stamp is zero: a fix needs the instant it measures");
  if (!origin_)
    origin_ = std::make_unique<GeographicLib::LocalCartesian>(msg.latitude, msg.longitude, msg.altitude);
  double x = 0.0, y = 0.0, z = 0.0;
  origin_->Forward(msg.latitude, msg.longitude, msg.altitude, x, y, z);
  const double t = timeOf(msg.header.stamp);
  if (!queue_.add(t, [&](SurveyMeasurement& m) { m.ship_x = x, m.ship_y = y; }))
    return "";  // late: counted there
  remember(fixes_, Eigen::Vector3d(t, x, y));
  return "";
}

void SurveyRows::remember(std::deque<Eigen::Vector3d>& history, const Eigen::Vector3d& entry)
{
  auto at = std::upper_bound(history.begin(), history.end(), entry[0],
                             [](double t, const Eigen::Vector3d& s) { return t < s[0]; });
  history.insert(at, entry);
  while (history.size() > 2 && history.front()[0] < history.back()[0] - kKeep)
    history.pop_front();
}

std::string SurveyRows::heading(const geometry_msgs::QuaternionStamped& msg)
{
  double yaw = 0.0;
  try
  {
    yaw = ros_conv::headingYaw(msg, settings_.heading_convention);
  }
  catch (const std::invalid_argument& e)
  {
    return refuse(e.what());
  }
  if (msg.header.stamp.isZero())
    return refuse("header.stamp is zero: a heading needs the instant it measures");
  const double t = timeOf(msg.header.stamp);
  if (queue_.add(t, [&](SurveyMeasurement& m) { m.ship_heading = yaw; }))
    remember(headings_, Eigen::Vector3d(t, yaw, 0.0));
  return "";
}

std::string SurveyRows::cableOut(const tow_sim::SensorValue& msg)
{
  return sample(msg.header.stamp, msg.value, "value", 0.0, 1e5, "m", &SurveyMeasurement::cable_out);
}

std::string SurveyRows::tension(const tow_sim::SensorValue& msg)
{
  return sample(msg.header.stamp, msg.value, "value", -1e8, 1e8, "N", &SurveyMeasurement::tension);
}

std::string SurveyRows::depth(const tow_sim::SensorValue& msg)
{
  if (settings_.depth_source != "depth")
    return "";
  return sample(msg.header.stamp, msg.value, "value", -100.0, 12000.0, "m", &SurveyMeasurement::fish_depth);
}

std::string SurveyRows::pressure(const sensor_msgs::FluidPressure& msg)
{
  if (settings_.depth_source != "pressure")
    return "";
  if (!within(msg.fluid_pressure, 0.0, 2e8))
    return refuse(outOfRange("fluid_pressure", msg.fluid_pressure, 0.0, 2e8, "Pa"));
  const double depth = (msg.fluid_pressure - settings_.atmospheric_pressure) / settings_.rho_g;
  return sample(msg.header.stamp, depth, "fluid_pressure as a depth", -100.0, 12000.0, "m",
                &SurveyMeasurement::fish_depth);
}

// REP-103: yaw about z, then pitch about the body's y (nose down positive), then roll about its x (starboard
// down positive).
std::string SurveyRows::imu(const sensor_msgs::Imu& msg)
{
  const auto& q = msg.orientation;
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!(std::isfinite(n) && std::abs(n - 1.0) < 0.01))
    return refuse(outOfRange("orientation: |q|", n, 0.99, 1.01, "-"));
  const Eigen::Matrix3d R = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
  const EulerAngles a = eulerOf(R);
  if (msg.header.stamp.isZero())
    return refuse("header.stamp is zero: an attitude needs the instant it measures");
  queue_.add(timeOf(msg.header.stamp),
             [&](SurveyMeasurement& m) { m.fish_heading = a.yaw, m.fish_pitch = a.pitch, m.fish_roll = a.roll; });
  // Its variances, where it gives them (sensor_msgs/Imu: zeros are "unknown").
  for (int axis = 0; axis < 3; ++axis)
  {
    const double variance = msg.orientation_covariance[4 * axis];
    attitude_variance_[axis] = std::isfinite(variance) && variance > 0.0 ? variance : NAN;
  }
  return "";
}

bool SurveyRows::shipAt(double t, Eigen::Vector2d& p, double& yaw) const
{
  Eigen::Vector2d h;
  if (!interpolate(fixes_, t, settings_.max_ship_gap, false, p) ||
      !interpolate(headings_, t, settings_.max_ship_gap, true, h))
    return false;
  yaw = h[0];
  return true;
}

// A USBL fix waits until its row is due (then the ship's fixes and headings on both sides of its stamp have
// come) and is put into the world frame there: placeUsbl.
std::string SurveyRows::usbl(const geometry_msgs::PointStamped& msg)
{
  const double xyz[3] = { msg.point.x, msg.point.y, msg.point.z };
  for (int a = 0; a < 3; ++a)
    if (!within(xyz[a], -1e5, 1e5))
      return refuse(outOfRange(a == 0 ? "point.x" : a == 1 ? "point.y" : "point.z", xyz[a], -1e5, 1e5, "m"));
  if (msg.header.frame_id != settings_.ship_frame)
    return refuse("header.frame_id = '" + msg.header.frame_id + "': a USBL fix must be in the ship frame '" +
                  settings_.ship_frame + "'");
  if (msg.header.stamp.isZero())
    return refuse("header.stamp is zero: a USBL fix needs the instant it measures");
  usbl_.push_back(PendingUsbl{ timeOf(msg.header.stamp), Eigen::Vector3d(xyz[0], xyz[1], xyz[2]) });
  return "";
}

// The fixes whose rows are due by `cutoff` (a row time) into the world frame with the ship's pose at their
// stamps: the fish in the ship frame (FLU, about the GNSS's reference point, level), rotated by the heading and
// put at the ship's fix; z stays (the reference point is at the surface). A fix without ship fixes and headings
// around its stamp is refused and counted in unplaced().
void SurveyRows::placeUsbl(double cutoff)
{
  std::vector<PendingUsbl> waiting;
  for (const PendingUsbl& f : usbl_)
  {
    if (f.t + settings_.usbl_latency > cutoff)
    {
      waiting.push_back(f);
      continue;
    }
    Eigen::Vector2d ship;
    double yaw = 0.0;
    if (!shipAt(f.t, ship, yaw))
    {
      ++refused_, ++unplaced_;
      continue;
    }
    const Eigen::Vector2d p_W = ship + Eigen::Rotation2Dd(yaw) * f.p_S.head<2>();
    queue_.add(f.t + settings_.usbl_latency,
               [&](SurveyMeasurement& m) { m.usbl_x = p_W.x(), m.usbl_y = p_W.y(), m.usbl_z = f.p_S.z(); });
  }
  usbl_.swap(waiting);
}

std::vector<SurveyMeasurement> SurveyRows::release(const ros::Time& now)
{
  if (!has_epoch_)
    return {};
  const double t = (now - epoch_).toSec();
  placeUsbl(t - settings_.hold);
  return queue_.release(t);
}

std::vector<SurveyMeasurement> SurveyRows::releaseAll()
{
  placeUsbl(std::numeric_limits<double>::infinity());
  return queue_.releaseAll();
}

double SurveyRows::ahead(const ros::Time& now) const
{
  return has_epoch_ ? newest_ - (now - epoch_).toSec() : 0.0;
}

}  // namespace tow_sim
