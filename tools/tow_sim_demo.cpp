// Offline steady-tow example: the default 500 m cable and the example vehicle (2 m long, 0.3 m
// diameter, tail fins) towed straight at 2 m/s from a straight initial line, integrated until the
// shape settles, then an elevator step. Prints a status line per simulated minute.
// Usage: tow_sim_demo [duration_s (default 900)]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>

#include "tow_sim/core/simulator.h"
#include "tow_sim/core/vehicle.h"

int main(int argc, char** argv)
{
  using namespace tow_sim;
  const double duration = argc > 1 ? std::atof(argv[1]) : 900.0;
  if (!(duration >= 60.0 && duration <= 1e6))
  {
    std::fprintf(stderr, "tow_sim_demo: duration = %s is out of range: must be in [60, 1e6] [s]\n", argv[1]);
    return 2;
  }
  try
  {
    const CableParams cable;
    const Environment env;
    const NumericsParams numerics;
    auto vehicle = std::make_shared<Vehicle>(VehicleParams(), numerics);
    auto model = std::make_shared<ChainModel>(cable, vehicle, env, numerics);
    const Eigen::Vector3d ship_velocity(2.0, 0.0, 0.0);
    Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), ship_velocity));
    sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -0.5), ship_velocity));

    std::printf(
        "tow_sim offline demo: %.0f m cable (%d segments, D = %.3f m, %.2f kg/m), %.0f kg vehicle, ship at "
        "%.1f m/s; elevator +0.2 rad at t = %.0f s\n",
        cable.length, cable.segments, cable.diameter, cable.mass_per_length, vehicle->params().mass,
        ship_velocity.norm(), duration - 120.0);
    std::printf("%7s %10s %10s %11s %11s %11s %13s %9s\n", "t [s]", "depth [m]", "pitch [deg]", "layback [m]",
                "divers. [m]", "T_ship [N]", "T_vehicle [N]", "elev [deg]");
    const auto wall_start = std::chrono::steady_clock::now();
    const int nu = cable.segments;
    int steps = 0;
    for (double t = 60.0; t <= duration + 1e-9; t += 60.0)
    {
      if (std::abs(t - (duration - 60.0)) < 1e-9)
        sim.command(0.0, 0.2, 0.0);
      steps += sim.advanceTo(t).steps;
      const VehicleOutputs o =
          vehicle->outputs(sim.time(), sim.elementKinematics(nu), sim.data().environment, sim.data().actuators);
      const ShipEndState ship = sim.shipEnd();
      const Diversion div = lateralDiversion(o.p_cg_W, o.v_cg_W, ship, Eigen::Vector3d::UnitX());
      std::printf("%7.0f %10.2f %10.2f %11.2f %11.3f %11.1f %13.1f %9.2f\n", sim.time(), o.depth,
                  o.pitch * 180.0 / M_PI, ship.p_W.x() - o.p_cg_W.x(), div.offset, sim.tensions().col(0).norm(),
                  sim.tensions().col(nu).norm(), o.elevator * 180.0 / M_PI);
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    const Eigen::Vector3d tow_force = -sim.tensions().col(0);
    std::printf(
        "\ntow force on the ship: %.1f N aft, %.1f N down; largest relative length error %.2e; %d steps; "
        "%.0fx faster than real time\n",
        -tow_force.x(), -tow_force.z(), sim.lengthError(), steps, sim.time() / wall);
    return 0;
  }
  catch (const std::exception& error)
  {
    std::fprintf(stderr, "tow_sim_demo: %s\n", error.what());
    return 1;
  }
}
