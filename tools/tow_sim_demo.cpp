// Offline steady-tow example: the default 500 m cable and 2 m end body towed straight at 2 m/s from a
// straight initial line, integrated until the shape settles. Prints a status line per simulated
// minute and the settled result. Usage: tow_sim_demo [duration_s (default 900)]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>

#include "tow_sim/core/simulator.h"

int main(int argc, char** argv)
{
  using namespace tow_sim;
  const double duration = argc > 1 ? std::atof(argv[1]) : 900.0;
  if (!(duration > 0.0 && duration <= 1e6))
  {
    std::fprintf(stderr, "tow_sim_demo: duration = %s is out of range: must be in (0, 1e6] [s]\n", argv[1]);
    return 2;
  }
  try
  {
    const CableParams cable;
    const EndElementParams end;
    const Environment env;
    const NumericsParams numerics;
    auto model = std::make_shared<ChainModel>(cable, std::make_shared<RigidEndElement>(end, numerics), env, numerics);
    const Eigen::Vector3d ship_velocity(2.0, 0.0, 0.0);
    Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), ship_velocity));
    sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -0.5), ship_velocity));

    std::printf("tow_sim offline demo: %.0f m cable (%d segments, D = %.3f m, %.2f kg/m), %.0f kg end body, "
                "ship at %.1f m/s\n",
                cable.length, cable.segments, cable.diameter, cable.mass_per_length, end.mass, ship_velocity.norm());
    std::printf("%8s %15s %12s %12s %14s %10s\n", "t [s]", "bail depth [m]", "layback [m]", "T_ship [N]", "T_vehicle [N]",
                "steps");
    const auto wall_start = std::chrono::steady_clock::now();
    int total_steps = 0;
    const int bail = cable.segments;  // the bail x_{nu+1}: column nu of jointPositions(), T_{nu+1} at nu
    for (double t = 60.0; t <= duration + 1e-9; t += 60.0)
    {
      total_steps += sim.advanceTo(t).steps;
      const Eigen::Matrix3Xd joints = sim.jointPositions();
      std::printf("%8.0f %15.2f %12.2f %12.1f %14.1f %10d\n", sim.time(), -joints(2, bail),
                  joints(0, 0) - joints(0, bail), sim.tensions().col(0).norm(), sim.tensions().col(bail).norm(),
                  total_steps);
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    const Eigen::Matrix3Xd joints = sim.jointPositions();
    const Eigen::Vector3d tow_force = -sim.tensions().col(0);
    std::printf("\nsettled after %.0f s: bail depth %.2f m, layback %.2f m, cable angle at the ship %.2f deg below "
                "horizontal\n",
                sim.time(), -joints(2, bail), joints(0, 0) - joints(0, bail),
                std::atan2(joints(2, 0) - joints(2, 1), joints(0, 0) - joints(0, 1)) * 180.0 / M_PI);
    std::printf("tension at the ship %.1f N (on the ship: %.1f N aft, %.1f N down), at the vehicle %.1f N\n",
                sim.tensions().col(0).norm(), -tow_force.x(), -tow_force.z(), sim.tensions().col(bail).norm());
    std::printf("largest relative length error %.2e; %d steps; %.0fx faster than real time\n", sim.lengthError(),
                total_steps, sim.time() / wall);
    return 0;
  }
  catch (const std::exception& error)
  {
    std::fprintf(stderr, "tow_sim_demo: %s\n", error.what());
    return 1;
  }
}
