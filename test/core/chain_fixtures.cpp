#include "core/chain_fixtures.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace tow_sim
{
namespace test
{
std::shared_ptr<ShipHistory> steamingShip(const Eigen::Vector2d& start, double heading, int seconds)
{
  auto ship = std::make_shared<ShipHistory>(1.0, 1000);
  const Eigen::Vector3d u(std::cos(heading), std::sin(heading), 0.0);
  for (int i = 0; i <= seconds; ++i)
  {
    const Eigen::Vector3d p = Eigen::Vector3d(start.x(), start.y(), 0.0) + 2.0 * i * u;
    ShipPose pose;
    pose.x = p.x();
    pose.y = p.y();
    pose.heading = heading;
    pose.speed = 2.0;
    ship->add(i, p, 2.0 * u, pose);
  }
  return ship;
}

VehicleOutputs VehicleTow::out() const
{
  return vehicle->outputs(sim->time(), sim->elementKinematics(sim->geometry().segments), sim->data().environment,
                          sim->data().actuators);
}

double VehicleTow::bailTension() const
{
  return sim->tensions().col(sim->geometry().segments).norm();
}

NumericsParams suiteNumerics()
{
  NumericsParams n;
  const char* name = std::getenv("TOW_SIM_TEST_STEPPER");
  if (!name || !*name)
    return n;
  const std::string s = name;
  if (s == "dopri5")
    n.stepper = StepperType::kDopri5;
  else if (s == "rk4")
    n.stepper = StepperType::kRk4;
  else if (s == "implicit")
    n.stepper = StepperType::kImplicit;
  else if (s == "implicit_fixed")
    n.stepper = StepperType::kImplicitFixed;
  else
    throw std::invalid_argument("TOW_SIM_TEST_STEPPER: '" + s + "' must be dopri5, rk4, implicit or implicit_fixed");
  return n;
}

double chainEnergy(const ChainModel& model, const CableParams& cable, const EndElementParams& end, double gravity,
                   const ShipEndState& ship, const ChainState& state)
{
  double energy = 0.0;
  Eigen::Vector3d x_f = ship.p_W, v_f = ship.v_W;
  for (int e = 0; e < model.elementCount(); ++e)
  {
    const bool is_end = e == model.segments();
    const double d = model.elementLength(e);
    const double m = is_end ? end.mass : cable.mass_per_length * d;
    const double gamma = is_end ? end.cg_from_bail / end.length : 0.5;
    const double inertia = is_end ? end.transverseInertia() : m * d * d / 12.0;
    const Eigen::Vector3d x_a = state.x.col(e), v_a = state.v.col(e);
    const Eigen::Vector3d x_g = x_f + gamma * (x_a - x_f);
    const Eigen::Vector3d v_g = v_f + gamma * (v_a - v_f);
    const Eigen::Vector3d s = (x_a - x_f).normalized();
    const Eigen::Vector3d w = s.cross((v_a - v_f) / d);
    energy += 0.5 * m * v_g.squaredNorm() + 0.5 * inertia * w.squaredNorm() + m * gravity * x_g.z();
    x_f = x_a;
    v_f = v_a;
  }
  return energy;
}

}  // namespace test
}  // namespace tow_sim
