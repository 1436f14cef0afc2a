// How far the implicit stepper's J is from the true derivative of the right-hand side (issue 32, item 1):
// on states of the shipped turn and zig-zag (the steady tow before the turn, the turn, the zig-zag), for a
// rigid and an elastic cable, Approach A and B, and nu from 50 to 1000, the relative error of J's
// linearised accelerations against central differences of the full solve (jacobian_check.h), per block:
// (elastic: EA 1e8 N with c = 1e6 N s, and without damping)
// K (positions) and D (velocities). Prints a table; not a Google Benchmark (it times nothing).
// Usage: bench_jacobian [--segments 50,100,...] [--quick]
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tow_sim/core/analysis/jacobian_check.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/scenario.h"
#include "tow_sim/scenario/ship_path.h"

namespace
{
using namespace tow_sim;

struct Case
{
  const char* scenario;
  double t;  // [s] the state's time
  const char* label;
};

// The state of the scenario at time t with its cable cut into `segments`, then J's error there.
void report(const Case& c, int segments, bool elastic, AddedMassApproach approach, double damping = 1e6)
{
  Scenario sc = loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/" + c.scenario + ".yaml");
  sc.config.cable.segments = segments;
  if (elastic)
  {
    sc.config.cable.axial_stiffness = 1e8;
    sc.config.cable.axial_damping = damping;
  }
  sc.config.vehicle.added_mass_approach = approach;
  TowRun run(sc.config, std::make_shared<ShipHistory>(buildShipPath(sc)), sc.initial);
  run.schedule(sc.commands);
  run.start(0.0);
  run.advanceTo(c.t);
  const Simulator& sim = run.simulator();
  const ChainState state = sim.state();
  const ShipEndState ship = sim.firstJoint();
  const JacobianError error =
      jacobianError(run.model(), sim.geometry(), sim.data(), sim.time(), ship, state.x, state.v);
  const char* cable = !elastic ? "rigid" : damping > 0.0 ? "elastic" : "el. c=0";
  std::printf("%-8s %-7s %-7s %s %6d   %9.2e %9.2e\n", c.scenario, c.label, cable,
              approach == AddedMassApproach::kA ? "A" : "B", segments, error.position, error.velocity);
  std::fflush(stdout);
}
}  // namespace

int main(int argc, char** argv)
{
  std::vector<int> segments = { 50, 100, 200, 400, 1000 };
  bool quick = false;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--quick"))
      quick = true;
    else if (!std::strcmp(argv[i], "--segments") && i + 1 < argc)
    {
      segments.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');)
        segments.push_back(std::stoi(item));
    }
    else
    {
      std::fprintf(stderr, "usage: bench_jacobian [--segments 50,100,...] [--quick]\n");
      return 2;
    }
  }
  const Case cases[] = { { "turn_180", 40.0, "steady" },
                         { "turn_180", 61.0, "entry" },
                         { "turn_180", 150.0, "turn" },
                         { "zigzag", 200.0, "zigzag" } };
  std::printf(
      "relative error of J's accelerations against central differences, max over 4 random length-keeping "
      "displacements\n");
  std::printf("%-8s %-7s %-7s %s %6s   %9s %9s\n", "scenario", "state", "cable", "AM", "nu", "K", "D");
  for (const Case& c : cases)
    for (int nu : segments)
    {
      report(c, nu, false, AddedMassApproach::kA);
      if (quick)
        continue;
      report(c, nu, true, AddedMassApproach::kA);
      report(c, nu, true, AddedMassApproach::kA, 0.0);
      report(c, nu, false, AddedMassApproach::kB);
    }
  return 0;
}
