#include "tow_sim/scenario/ship_path.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace tow_sim
{
ShipHistory buildShipPath(const Scenario& sc, double dt)
{
  const size_t samples = static_cast<size_t>(sc.duration / dt) + 40;
  ShipHistory path(1.0, samples + 10);
  double x = sc.start_position.x(), y = sc.start_position.y(), heading = sc.start_heading;
  double u = sc.manoeuvres.front().speed, r = 0.0, time = 0.0;
  size_t index = 0;           // current manoeuvre
  double started = 0.0;       // when it started
  double heading0 = heading;  // heading when it started
  double speed0 = u;          // speed when it started
  int leg = 0;                // zigzag leg / waypoint index
  auto advanceManoeuvre = [&]()
  {
    ++index;
    started = time;
    heading0 = heading;
    speed0 = u;
    leg = 0;
  };
  for (size_t k = 0; k < samples; ++k)
  {
    double u_target = u, r_target = 0.0;
    if (index < sc.manoeuvres.size())
    {
      const Manoeuvre& m = sc.manoeuvres[index];
      const double elapsed = time - started;
      const double turn_rate = std::abs(m.speed) / m.radius;
      switch (m.type)
      {
        case Manoeuvre::Type::kStraight:
          u_target = m.speed;
          if (elapsed >= m.duration)
            advanceManoeuvre();
          break;
        case Manoeuvre::Type::kSpeedChange:
          u_target = speed0 + (m.to_speed - speed0) * std::min(1.0, elapsed / m.duration);
          if (elapsed >= m.duration)
            advanceManoeuvre();
          break;
        case Manoeuvre::Type::kTurn:
          u_target = m.speed;
          r_target = m.direction * turn_rate;
          if (std::abs(heading - heading0) >= m.angle)
            advanceManoeuvre();
          break;
        case Manoeuvre::Type::kZigzag:
        {
          u_target = m.speed;
          const double side = (leg % 2 == 0 ? 1.0 : -1.0) * m.direction;
          r_target = side * turn_rate;
          if (side * (heading - heading0) >= m.angle && ++leg >= m.legs)
            advanceManoeuvre();
          break;
        }
        case Manoeuvre::Type::kWaypoints:
        {
          u_target = m.speed;
          const Eigen::Vector2d& w = m.points[static_cast<size_t>(leg)];
          const double wanted = std::atan2(w.y() - y, w.x() - x);
          const double error = std::atan2(std::sin(wanted - heading), std::cos(wanted - heading));
          r_target = std::clamp(error / 20.0, -turn_rate, turn_rate);
          if (std::hypot(w.x() - x, w.y() - y) < m.acceptance && ++leg >= static_cast<int>(m.points.size()))
            advanceManoeuvre();
          break;
        }
      }
    }
    // Store this sample, then integrate to the next one.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d v_ship = R * Eigen::Vector3d(u, 0.0, 0.0);
    const Eigen::Vector3d w_ship(0.0, 0.0, r);
    path.add(time, Eigen::Vector3d(x, y, 0.0) + R * sc.tow_point_S, v_ship + w_ship.cross(R * sc.tow_point_S),
             ShipPose{ x, y, heading, u });
    u += std::clamp(u_target - u, -0.1 * dt, 0.1 * dt);
    r += (r_target - r) * std::min(1.0, dt / 2.0);
    heading += r * dt;
    x += u * std::cos(heading) * dt;
    y += u * std::sin(heading) * dt;
    time += dt;
  }
  return path;
}

}  // namespace tow_sim
