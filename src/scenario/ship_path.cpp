#include "tow_sim/scenario/ship_path.h"

#include <Eigen/Geometry>

#include "tow_sim/scenario/scripted_ship.h"

namespace tow_sim
{
ShipHistory buildShipPath(const Scenario& sc, double dt)
{
  const size_t samples = static_cast<size_t>(sc.duration / dt) + 40;
  ShipHistory path(1.0, samples + 10);
  ScriptedShip ship(sc.manoeuvres, sc.start_position.x(), sc.start_position.y(), sc.start_heading);
  for (size_t k = 0; k < samples; ++k)
  {
    // The tow point moves with the ship: v + w x r, r the tow point's offset turned into the world.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(ship.heading(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d v_ship = R * Eigen::Vector3d(ship.speed(), 0.0, 0.0);
    const Eigen::Vector3d w_ship(0.0, 0.0, ship.yawRate());
    path.add(ship.time(), Eigen::Vector3d(ship.x(), ship.y(), 0.0) + R * sc.tow_point_S,
             v_ship + w_ship.cross(R * sc.tow_point_S), ShipPose{ ship.x(), ship.y(), ship.heading(), ship.speed() });
    ship.step(dt);
  }
  return path;
}

}  // namespace tow_sim
