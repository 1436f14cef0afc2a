// Google Benchmark: a towing chart of the default configuration (config/tow_sim.yaml's defaults), 20 speeds
// (0.25 .. 5 m/s) x 10 lengths of cable out (100 .. 1000 m): the goal is under a second.
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
}  // namespace

BENCHMARK_MAIN();
