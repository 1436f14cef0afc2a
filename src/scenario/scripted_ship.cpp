#include "tow_sim/scenario/scripted_ship.h"

#include <algorithm>
#include <cmath>

#include "tow_sim/core/constants.h"

namespace tow_sim
{
namespace
{
constexpr double kMinRadius = 10.0;  // [m] the tightest radius a scenario allows: the course-holding limit

// Heading change while the yaw rate, |r0| now, goes over to the opposite full rate `rate` with the lag tau
// (r(t) = -rate + (r0 + rate) exp(-t / tau)) until it passes zero: tau (r0 - rate ln(1 + r0 / rate)).
double swingBeyondReversal(double r0, double rate, double tau)
{
  return rate > 0.0 ? tau * (r0 - rate * std::log1p(r0 / rate)) : 0.0;
}
}  // namespace

ScriptedShip::ScriptedShip(std::vector<Manoeuvre> manoeuvres, double x, double y, double heading)
    : manoeuvres_(std::move(manoeuvres)),
      x_(x),
      y_(y),
      heading_(heading),
      u_(manoeuvres_.empty() ? 0.0 : manoeuvres_.front().speed),
      course_(heading),
      heading0_(heading),
      speed0_(u_)
{
}

double ScriptedShip::holdCourse(double limit) const
{
  return std::clamp((course_ - heading_) / kHeadingTime, -limit, limit);
}

void ScriptedShip::next()
{
  ++index_;
  started_ = time_;
  // The next manoeuvre starts from the course steered, not the heading reached: a turn hands over while
  // the heading still closes on its goal, and a second turn or a zigzag must count from that goal.
  heading0_ = course_;
  speed0_ = u_;
  leg_ = 0;
}

ScriptedShip::Targets ScriptedShip::targets()
{
  if (finished())
    return { u_, holdCourse(std::abs(u_) / kMinRadius) };
  const Manoeuvre& m = manoeuvres_[index_];
  const double elapsed = time_ - started_;
  const double turn_rate = std::abs(m.speed) / m.radius;
  switch (m.type)
  {
    case Manoeuvre::Type::kStraight:
    case Manoeuvre::Type::kSpeedChange:
    {
      const bool change = m.type == Manoeuvre::Type::kSpeedChange;
      const double speed = change ? speed0_ + (m.to_speed - speed0_) * std::min(1.0, elapsed / m.duration) : m.speed;
      const Targets t{ speed, holdCourse(std::abs(speed) / kMinRadius) };
      if (elapsed >= m.duration)
        next();
      return t;
    }
    case Manoeuvre::Type::kTurn:
    {
      const double goal = heading0_ + m.direction * m.angle;
      const double error = goal - heading_;
      const Targets t{ m.speed, std::clamp(error / kHeadingTime, -turn_rate, turn_rate) };
      if (std::abs(error) <= turn_rate * kHeadingTime)  // steadying: the course holds from here
      {
        course_ = goal;
        next();
      }
      return t;
    }
    case Manoeuvre::Type::kZigzag:
    {
      const double side = (leg_ % 2 == 0 ? 1.0 : -1.0) * m.direction;
      const Targets t{ m.speed, side * turn_rate };
      // Reverse when the swing still to come after the reversal brings the heading to the angle.
      const double swing = swingBeyondReversal(std::abs(r_), turn_rate, kYawLag);
      if (side * r_ > 0.0 && side * (heading_ - heading0_) >= m.angle - swing && ++leg_ >= m.legs)
      {
        course_ = heading0_;  // back to the zigzag's course
        next();
      }
      return t;
    }
    case Manoeuvre::Type::kWaypoints:
    {
      const Eigen::Vector2d& w = m.points[static_cast<size_t>(leg_)];
      const double bearing = std::atan2(w.y() - y_, w.x() - x_);
      course_ = heading_ + std::remainder(bearing - heading_, 2.0 * kPi);
      const Targets t{ m.speed, holdCourse(turn_rate) };
      if (std::hypot(w.x() - x_, w.y() - y_) < m.acceptance && ++leg_ >= static_cast<int>(m.points.size()))
      {
        course_ = heading_;
        next();
      }
      return t;
    }
  }
  return { u_, 0.0 };
}

void ScriptedShip::step(double dt, const Teleop* teleop)
{
  Targets t{ u_, r_ };
  if (teleop)
  {
    t = { teleop->speed, teleop->yaw_rate };
    started_ += dt;  // the script waits
  }
  else
  {
    if (teleop_)  // back from teleop: go on from here
    {
      course_ = heading0_ = heading_;
      speed0_ = u_;
    }
    t = targets();
  }
  teleop_ = teleop != nullptr;
  const double u0 = u_, r0 = r_, heading0 = heading_;
  u_ += std::clamp(t.speed - u_, -kMaxAcceleration * dt, kMaxAcceleration * dt);
  r_ += (t.yaw_rate - r_) * std::min(1.0, dt / kYawLag);
  // Over the step the speed and the yaw rate go linearly from (u0, r0) to (u_, r_), so the heading is the
  // trapezoid's integral and the position Simpson's integral of the velocity (an error of O(dt^5)): the
  // velocity reported at each sample then agrees with the positions on both sides of it. A yaw rate held
  // constant over each step would jump at every sample, and the tow point's interpolated path (whose lever
  // arm turns with it) would swing at the sampling rate, which the simulation would have to follow.
  heading_ += 0.5 * (r0 + r_) * dt;
  const double heading_mid = heading0 + (3.0 * r0 + r_) * dt / 8.0, u_mid = 0.5 * (u0 + u_);
  x_ += dt / 6.0 * (u0 * std::cos(heading0) + 4.0 * u_mid * std::cos(heading_mid) + u_ * std::cos(heading_));
  y_ += dt / 6.0 * (u0 * std::sin(heading0) + 4.0 * u_mid * std::sin(heading_mid) + u_ * std::sin(heading_));
  time_ += dt;
}

std::vector<Manoeuvre> presetManoeuvres(const ShipMotionParams& p)
{
  auto make = [&](Manoeuvre::Type type, double duration)
  {
    Manoeuvre m;
    m.type = type;
    m.speed = p.speed;
    m.duration = duration;
    m.radius = std::abs(p.turn_radius);
    m.direction = p.turn_radius > 0.0 ? 1 : -1;
    return m;
  };
  std::vector<Manoeuvre> list;
  const bool delayed = p.manoeuvre == "turn" || p.manoeuvre == "zigzag";
  if (delayed && p.turn_start > 0.0)
    list.push_back(make(Manoeuvre::Type::kStraight, p.turn_start));
  if (p.manoeuvre == "turn")
  {
    list.push_back(make(Manoeuvre::Type::kTurn, 0.0));
    list.back().angle = 1e9;  // [rad] turning for good (1.6e8 turns)
  }
  else if (p.manoeuvre == "zigzag")
  {
    list.push_back(make(Manoeuvre::Type::kZigzag, 0.0));
    list.back().angle = std::abs(p.speed) / std::abs(p.turn_radius) * p.zigzag_period / 4.0;
    list.back().legs = 1000;
  }
  else if (p.manoeuvre == "speed_change")
  {
    list.push_back(make(Manoeuvre::Type::kStraight, std::max(p.change_time, 1e-3)));
    list.push_back(make(Manoeuvre::Type::kSpeedChange, p.change_duration));
    list.back().to_speed = p.speed_2;
  }
  else if (p.manoeuvre == "waypoints")
  {
    list.push_back(make(Manoeuvre::Type::kWaypoints, 0.0));
    list.back().acceptance = p.waypoint_radius;
    list.back().points = p.waypoints;
  }
  list.push_back(make(Manoeuvre::Type::kStraight, 1e6));
  if (p.manoeuvre == "speed_change")
    list.back().speed = p.speed_2;
  return list;
}

}  // namespace tow_sim
