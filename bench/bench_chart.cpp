// Google Benchmark: a towing chart of the default configuration (config/tow_sim.yaml's defaults), 20 speeds
// (0.25 .. 5 m/s) x 10 lengths of cable out (100 .. 1000 m): the goal is under a second. And the response
// to ship motion (modes.h) of the default tow at 2 m/s cut into nu segments, heave at 100 periods from 2 to 60 s,
// from its steady state (found outside the timing): motionResponses (O(nu) per period; issue 31's goal at
// nu = 1000 is under a second) beside motionResponsesDense (O(nu^3)) at nu = 200; and its ten lowest natural modes,
// lowestModes (Arnoldi, O(nu) per iteration; the goal at nu = 1000: under a second) beside naturalModes (every
// mode, dense).
#include <benchmark/benchmark.h>

#include "tow_sim/scenario/towing_chart.h"

namespace
{
using namespace tow_sim;

void BM_TowingChart20x10(benchmark::State& state)
{
  const SimulationConfig config;
  const std::vector<double> speeds = parseRange("0.25:5:0.25", "speeds"), lengths = parseRange("100:1000:100", "out");
  for (auto _ : state)
    benchmark::DoNotOptimize(towingChart(config, speeds, lengths, Eigen::Vector3d::Zero()));
  state.counters["points"] = static_cast<double>(speeds.size() * lengths.size());
}
BENCHMARK(BM_TowingChart20x10)->Unit(benchmark::kMillisecond);

void BM_Response(benchmark::State& state, bool dense)
{
  SimulationConfig config;
  config.cable.segments = static_cast<int>(state.range(0));
  const std::unique_ptr<TowRun> run = steadyTowRun(config, 2.0, config.cable.length, Eigen::Vector3d::Zero());
  const Simulator& sim = run->simulator();
  const ChainState tow = sim.state();
  std::vector<double> periods;
  for (int k = 0; k < 100; ++k)
    periods.push_back(2.0 + 58.0 * k / 99.0);
  const double cg = config.vehicle.cg_from_bail / config.vehicle.tail_from_bail;
  for (auto _ : state)
    benchmark::DoNotOptimize((dense ? motionResponsesDense : motionResponses)(
        run->model(), sim.geometry(), sim.data(), sim.time(), sim.firstJoint(), tow.x, tow.v,
        { Eigen::Vector3d::UnitZ() }, periods, cg, 1e-6));
  state.counters["periods"] = static_cast<double>(periods.size());
}
BENCHMARK_CAPTURE(BM_Response, sparse, false)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Response, dense, true)->Arg(200)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_Modes(benchmark::State& state, bool dense)
{
  SimulationConfig config;
  config.cable.segments = static_cast<int>(state.range(0));
  const std::unique_ptr<TowRun> run = steadyTowRun(config, 2.0, config.cable.length, Eigen::Vector3d::Zero());
  const Simulator& sim = run->simulator();
  const ChainState tow = sim.state();
  for (auto _ : state)
  {
    if (dense)
      benchmark::DoNotOptimize(
          naturalModes(run->model(), sim.geometry(), sim.data(), sim.time(), sim.firstJoint(), tow.x, tow.v));
    else
      benchmark::DoNotOptimize(
          lowestModes(run->model(), sim.geometry(), sim.data(), sim.time(), sim.firstJoint(), tow.x, tow.v, 10));
  }
}
BENCHMARK_CAPTURE(BM_Modes, lowest10, false)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Modes, dense, true)->Arg(200)->Unit(benchmark::kMillisecond)->Iterations(1);
}  // namespace

BENCHMARK_MAIN();
