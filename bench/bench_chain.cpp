// Google Benchmark: cost of one right-hand-side evaluation (O(nu) sweep against the dense reference)
// and wall time per simulated second of a steady 2 m/s tow of a 500 m cable.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <memory>

#include "core/dense_reference.h"
#include "tow_sim/core/chain/chain_solver.h"
#include "tow_sim/core/integration/simulator.h"

namespace
{
using namespace tow_sim;

std::shared_ptr<ChainModel> makeModel(int segments)
{
  CableParams cable;
  cable.segments = segments;
  const NumericsParams numerics;
  return std::make_shared<ChainModel>(cable, std::make_shared<RigidEndElement>(EndElementParams(), numerics),
                                      Environment(), numerics);
}

// A towed shape at roughly the critical angle with a small transverse motion on every joint.
ChainState towedState(const ChainModel& model)
{
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  ChainState s = straightChain(model, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1.0, 0.0, -0.38), u);
  for (int j = 0; j < s.v.cols(); ++j)
    s.v.col(j) += Eigen::Vector3d(0.0, 0.05 * std::sin(0.1 * j), 0.0);
  return s;
}

void BM_RhsSweep(benchmark::State& state)
{
  auto model = makeModel(static_cast<int>(state.range(0)));
  ChainSolver solver;
  const ChainData data = model->initialData();
  const ChainGeometry geometry = model->initialGeometry();
  const ChainState s = towedState(*model);
  ShipEndState ship;
  ship.v_W = Eigen::Vector3d(2.0, 0.0, 0.0);
  Eigen::Matrix3Xd a(3, model->jointCount()), tensions(3, model->jointCount());
  for (auto _ : state)
  {
    solver.solve(*model, geometry, data, 0.0, ship, s.x, s.v, a, &tensions);
    benchmark::DoNotOptimize(a.data());
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_RhsSweep)->Arg(10)->Arg(100)->Arg(1000)->Arg(5000)->Unit(benchmark::kMicrosecond)->Complexity();

void BM_RhsDense(benchmark::State& state)
{
  auto model = makeModel(static_cast<int>(state.range(0)));
  const ChainState s = towedState(*model);
  ShipEndState ship;
  ship.v_W = Eigen::Vector3d(2.0, 0.0, 0.0);
  for (auto _ : state)
  {
    test::DenseSolution d = test::solveDense(*model, 0.0, ship, s.x, s.v);
    benchmark::DoNotOptimize(d.accelerations.data());
  }
}
// Full-pivot LU on 6(nu+1) unknowns: nu = 1000 already needs about 0.3 GB and minutes per call.
BENCHMARK(BM_RhsDense)->Arg(10)->Arg(30)->Arg(100)->Unit(benchmark::kMicrosecond);

// Wall time per simulated second of a steady tow (after a 20 s settling run outside the timing).
void BM_SteadyTow(benchmark::State& state)
{
  auto model = makeModel(static_cast<int>(state.range(0)));
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), u));
  sim.reset(0.0, towedState(*model));
  sim.advanceTo(20.0);
  double simulated = 0.0;
  for (auto _ : state)
  {
    sim.advanceTo(sim.time() + 1.0);
    simulated += 1.0;
  }
  state.counters["realtime_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SteadyTow)->Arg(50)->Arg(100)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
