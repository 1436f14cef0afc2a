// Offline steady-tow example: the default 500 m cable and the example vehicle (2 m long, 0.3 m
// diameter, tail fins) towed straight at 2 m/s from a straight initial line, integrated until the
// shape settles, then an elevator step. Prints a status line per simulated minute.
// Usage: tow_sim_demo [DURATION]   (DURATION [s] in [60, 1e6], default 900; tow_sim_demo --help says more)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>

#include "cli.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/ship_path.h"

namespace
{
using namespace tow_sim;

constexpr char kTool[] = "tow_sim_demo";
constexpr char kUsage[] = "tow_sim_demo [DURATION]";
constexpr char kHelp[] = R"(
The core alone, without roscore: the default 500 m cable and the example vehicle (2 m long, 0.3 m
diameter, tail fins) towed straight at 2 m/s from a straight initial line until the shape settles,
then +0.2 rad of elevator two minutes before the end.

Arguments:
  DURATION     the simulated time [s], a number in [60, 1e6] (default 900).
  -h, --help   prints this help and exits.

Output: a table on stdout, a line per simulated minute (time [s], depth [m], pitch [deg], layback
[m], diversion [m], the tension at the ship and at the vehicle [N], elevator [deg]), then the tow
force on the ship and the run's speed; no file.
Exit codes: 0 done; 1 the run failed; 2 bad arguments.
)";

// The duration [s] from the command line: "" or what is wrong with it.
std::string parseDuration(int argc, char** argv, double& duration)
{
  duration = 900.0;
  if (argc > 2)
    return "takes at most one argument, the duration [s]";
  if (argc < 2)
    return "";
  const std::string text = argv[1];
  char* end = nullptr;
  duration = std::strtod(text.c_str(), &end);
  if (end != text.c_str() && *end == '\0' && duration >= 60.0 && duration <= 1e6)
    return "";
  if (text[0] == '-' && end == text.c_str())
    return "unknown argument '" + text + "'";
  return "duration: '" + text + "' is not a number of seconds in [60, 1e6]";
}

// The ship straight along +x at 2 m/s, the tow point at its reference point; a straight initial line;
// +0.2 rad of elevator two minutes before the end.
Scenario demoScenario(double duration)
{
  Scenario sc;
  sc.tow_point_S.setZero();
  Manoeuvre straight;
  straight.speed = 2.0;
  straight.duration = duration + 60.0;
  sc.manoeuvres = { straight };
  sc.initial.type = InitialShape::Type::kLine;
  sc.initial.line_direction_S = Eigen::Vector3d(-1.0, 0.0, -0.5);
  CommandEvent step;
  step.t = duration - 120.0;
  step.elevator = 0.2;
  sc.commands = { step };
  sc.duration = duration;
  return sc;
}

void printLine(const TowSnapshot& s)
{
  std::printf("%7.0f %10.2f %10.2f %11.2f %11.3f %11.1f %13.1f %9.2f\n", s.t, s.depth, s.pitch * 180.0 / tow_sim::kPi,
              s.layback, s.diversion.offset, s.tension_ship, s.tension_vehicle,
              s.vehicle.elevator * 180.0 / tow_sim::kPi);
}
}  // namespace

int main(int argc, char** argv)
{
  if (cli::wantsHelp(argc, argv))
    return cli::printHelp(kUsage, kHelp);
  double duration = 0.0;
  const std::string wrong = parseDuration(argc, argv, duration);
  if (!wrong.empty())
    return cli::fail(kTool, kUsage, wrong);
  try
  {
    const Scenario sc = demoScenario(duration);
    TowRun run(sc.config, std::make_shared<ShipHistory>(buildShipPath(sc)), sc.initial);
    run.schedule(sc.commands);
    run.start(0.0);
    const CableParams& cable = sc.config.cable;
    std::printf(
        "tow_sim offline demo: %.0f m cable (%d segments, D = %.3f m, %.2f kg/m), %.0f kg vehicle, ship at "
        "%.1f m/s; elevator +0.2 rad at t = %.0f s\n",
        cable.length, cable.segments, cable.diameter, cable.mass_per_length, sc.config.vehicle.mass,
        sc.manoeuvres.front().speed, duration - 120.0);
    std::printf("%7s %10s %10s %11s %11s %11s %13s %9s\n", "t [s]", "depth [m]", "pitch [deg]", "layback [m]",
                "divers. [m]", "T_ship [N]", "T_vehicle [N]", "elev [deg]");
    const auto wall_start = std::chrono::steady_clock::now();
    int steps = 0;
    TowSnapshot s;
    for (double t = 60.0; t <= duration + 1e-9; t += 60.0)
    {
      steps += run.advanceTo(t).steps;
      printLine(s = run.snapshot());
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    const Eigen::Vector3d tow_force = -s.tensions.col(0);
    std::printf(
        "\ntow force on the ship: %.1f N aft, %.1f N down; largest relative length error %.2e; %d steps; "
        "%.0fx faster than real time\n",
        -tow_force.x(), -tow_force.z(), run.simulator().lengthError(), steps, s.t / wall);
    return 0;
  }
  catch (const std::exception& error)
  {
    std::fprintf(stderr, "tow_sim_demo: %s\n", error.what());
    return 1;
  }
}
