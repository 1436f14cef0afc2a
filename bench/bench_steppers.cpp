// Google Benchmark: simulated seconds per wall second of the whole run (TowRun with the example vehicle)
// for each stepper, as the cable is cut finer (issue #12):
//   steady   a 500 m cable towed at 2 m/s in a straight line, from its equilibrium;
//   turn     the same ship turning 180 degrees to port on a 200 m radius from t = 0;
//   deep     6000 m of 0.04 m, 6 kg/m cable at 1.5 m/s (steady), nu = 1000;
//   two_part a two-part deep tow (sections, a clump and a float; nu = 600 + 100) beside its uniform cable;
//   parted   the steady tow's elastic cable (EA 1e8 N) parted at the tow point in the first step, the whole
//            cable sinking from a free end: on the implicit stepper (which steps a parted cable's chains:
//            docs/solver.md (S27)) beside dopri5 (what the steppers fell back to once parted, before).
// Steppers: dopri5 (default tolerances), rk4 at its largest stable fixed step (from 2.5 / omega_max, the
// zig-zag mode omega_max^2 = 12 T / (m_eff d^2) at the tow point's tension, shortened until 60 s of the run
// go through), implicit (default tolerances, the default frame: numerics.implicit_frame: tow_point),
// implicit_world (the same in the world frame), implicit_ros2; and implicit on an elastic cable (EA 1e8 N,
// c = 0.01 s EA).
// Counter `realtime`: simulated seconds per wall second. Each iteration advances `chunk` simulated
// seconds; the first 2 s (start-up) are outside the timing.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"

namespace
{
using namespace tow_sim;

enum class Path
{
  kStraight,
  kTurn
};

// The ship's reference point at speed U along +x, or turning to port on radius R from t = 0; the tow
// point 20 m astern. Samples every 0.1 s for `duration`.
std::shared_ptr<ShipHistory> shipPath(Path path, double speed, double duration)
{
  const double radius = 200.0, astern = 20.0;
  auto ship = std::make_shared<ShipHistory>(1.0, static_cast<size_t>(duration / 0.1) + 10);
  for (long i = 0; i * 0.1 <= duration; ++i)
  {
    const double t = i * 0.1;
    ShipPose pose;
    double rate = 0.0;
    if (path == Path::kTurn && t * speed / radius < tow_sim::kPi)
    {
      rate = speed / radius;
      pose.heading = rate * t;
      pose.x = radius * std::sin(pose.heading);
      pose.y = radius * (1.0 - std::cos(pose.heading));
    }
    else if (path == Path::kTurn)
    {
      const double after = t - tow_sim::kPi * radius / speed;
      pose.heading = tow_sim::kPi;
      pose.x = -speed * after;
      pose.y = 2.0 * radius;
    }
    else
      pose.x = speed * t;
    pose.speed = speed;
    const Eigen::Vector3d along(std::cos(pose.heading), std::sin(pose.heading), 0.0);
    const Eigen::Vector3d port(-std::sin(pose.heading), std::cos(pose.heading), 0.0);
    const Eigen::Vector3d p = Eigen::Vector3d(pose.x, pose.y, 0.0) - astern * along;
    const Eigen::Vector3d v = speed * along - astern * rate * port;
    ship->add(t, p, v, pose);
  }
  return ship;
}

SimulationConfig config(int segments, bool deep)
{
  SimulationConfig c;
  c.cable.segments = segments;
  c.cable.length = deep ? 6000.0 : 500.0;
  if (deep)
  {
    c.cable.diameter = 0.04;
    c.cable.mass_per_length = 6.0;
  }
  return c;
}

// rk4's largest stable step for the cable at the tow point's tension [N].
double rk4Step(const SimulationConfig& c, double tension)
{
  const double d = c.cable.segmentLength();
  const double m = c.cable.mass_per_length + c.cable.added_mass_coefficient * c.environment.water_density *
                                                 tow_sim::kPi * c.cable.diameter * c.cable.diameter / 4.0;
  const double omega = std::sqrt(12.0 * tension / (m * d * d));
  return std::min(1.0, 2.5 / omega);
}

void timeRun(benchmark::State& state, const SimulationConfig& c, std::shared_ptr<ShipHistory> ship, double chunk,
             double startup = 2.0);

void BM_Tow(benchmark::State& state, Path path, bool deep, StepperType stepper, int segments, double chunk,
            ImplicitMethod method, double axial_stiffness, ImplicitFrame frame)
{
  SimulationConfig c = config(segments, deep);
  c.numerics.implicit_method = method;
  c.numerics.implicit_frame = frame;
  if (axial_stiffness > 0.0)  // the elastic cable, with an axial damping time of 0.01 s
  {
    c.cable.axial_stiffness = axial_stiffness;
    c.cable.axial_damping = 0.01 * axial_stiffness;
  }
  const double speed = deep ? 1.5 : 2.0;
  const double duration = 12.0 + chunk * 6.0;  // every iteration (at most 5) and a margin
  if (stepper == StepperType::kRk4)
  {
    // From the zig-zag mode's limit at the equilibrium's tension, shortened by 0.8 until 60 s of the
    // run go through (other modes, the vehicle's, can bind first on coarse cables).
    SimulationConfig probe_config = c;
    probe_config.numerics.stepper = StepperType::kRk4;
    TowRun tension(c, shipPath(path, speed, 10.0));
    tension.start(0.0);
    probe_config.numerics.fixed_step = rk4Step(c, tension.snapshot().tension_ship);
    for (bool stable = false; !stable;)
    {
      try
      {
        TowRun probe(probe_config, shipPath(path, speed, 70.0));
        probe.start(0.0);
        probe.advanceTo(60.0);  // longer than the timed run
        stable = true;
      }
      catch (const std::exception&)
      {
        probe_config.numerics.fixed_step *= 0.8;
      }
    }
    c.numerics.fixed_step = probe_config.numerics.fixed_step;
    state.counters["step_ms"] = 1e3 * c.numerics.fixed_step;
  }
  c.numerics.stepper = stepper;
  timeRun(state, c, shipPath(path, speed, duration), chunk);
}

// A two-part deep tow (issue 27): 3000 m of armoured cable (0.0173 m, 1.2 kg/m) in 600 segments, a 1000 kg
// clump, 200 m of near-neutral tether (0.02 m, 0.35 kg/m) in 100 segments with a float 100 m above the
// vehicle, at 1 m/s; beside it (uniform) the armoured cable alone, 3200 m in 700 segments. Implicit stepper.
void BM_TwoPart(benchmark::State& state, bool two_part)
{
  SimulationConfig c;
  c.cable.diameter = 0.0173;
  c.cable.mass_per_length = 1.2;
  c.cable.length = 3200.0;
  c.cable.segments = 700;
  if (two_part)
  {
    CableParams main = c.cable, tether = c.cable;
    main.length = 3000.0;
    main.segments = 600;
    tether.length = 200.0;
    tether.segments = 100;
    tether.diameter = 0.02;
    tether.mass_per_length = 0.35;
    c.sections = { main, tether };
    c.bodies.resize(2);
    c.bodies[0].at = 3000.0;
    c.bodies[0].body.mass = 1000.0;
    c.bodies[0].body.displaced_volume = 0.13;
    c.bodies[0].body.drag_area = 0.4;
    c.bodies[0].body.added_mass = 100.0;
    c.bodies[1].at = 3100.0;
    c.bodies[1].body.mass = 20.0;
    c.bodies[1].body.displaced_volume = 0.05;
    c.bodies[1].body.drag_area = 0.15;
    c.bodies[1].body.added_mass = 50.0;
  }
  timeRun(state, c, shipPath(Path::kStraight, 1.0, 100.0), 10.0);
}

// The steady tow's elastic cable (EA 1e8 N, c = 0.01 s EA) parted at the tow point at once (a breaking load
// of 1 N), then timed sinking on `stepper` from 0.1 s.
void BM_Parted(benchmark::State& state, StepperType stepper, int segments, double chunk)
{
  SimulationConfig c = config(segments, false);
  c.cable.axial_stiffness = 1.0e8;
  c.cable.axial_damping = 0.01 * 1.0e8;
  c.cable.breaking_load = 1.0;
  c.cable.break_at_breaking_load = true;
  c.numerics.stepper = stepper;
  timeRun(state, c, shipPath(Path::kStraight, 2.0, 12.0 + chunk * 6.0), chunk, 0.1);
}

// Times `chunk` simulated seconds an iteration of a TowRun of c on `ship` after `startup` seconds.
void timeRun(benchmark::State& state, const SimulationConfig& c, std::shared_ptr<ShipHistory> ship, double chunk,
             double startup)
{
  TowRun run(c, std::move(ship));
  run.start(0.0);
  run.advanceTo(startup);
  double simulated = 0.0;
  for (auto _ : state)
  {
    try
    {
      run.advanceTo(run.time() + chunk);
    }
    catch (const std::exception& e)
    {
      state.SkipWithError(e.what());
      break;
    }
    simulated += chunk;
  }
  state.counters["realtime"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}

// The steppers compared: the explicit ones, the default implicit (ros34pw2, the tow point's frame), the same
// in the world frame, and ros2.
struct Variant
{
  StepperType stepper;
  ImplicitMethod method;
  ImplicitFrame frame;
  const char* label;
};
const ImplicitFrame kDefaultFrame = NumericsParams().implicit_frame;
const Variant kVariants[] = { { StepperType::kDopri5, ImplicitMethod::kRos34pw2, kDefaultFrame, "dopri5" },
                              { StepperType::kRk4, ImplicitMethod::kRos34pw2, kDefaultFrame, "rk4" },
                              { StepperType::kImplicit, ImplicitMethod::kRos34pw2, kDefaultFrame, "implicit" },
                              { StepperType::kImplicit, ImplicitMethod::kRos34pw2, ImplicitFrame::kWorld,
                                "implicit_world" },
                              { StepperType::kImplicit, ImplicitMethod::kRos2, kDefaultFrame, "implicit_ros2" } };

void registerAll()
{
  for (Path path : { Path::kStraight, Path::kTurn })
    for (int segments : { 50, 100, 200, 1000, 2000 })
      for (const Variant& v : kVariants)
      {
        // Enough simulated time per iteration to time, little enough for the explicit steppers at nu = 2000.
        const bool slow = v.stepper != StepperType::kImplicit && segments >= 1000;
        const double chunk = slow ? 1.0 : 10.0;
        const std::string label =
            std::string(path == Path::kTurn ? "turn" : "steady") + "/" + v.label + "/nu:" + std::to_string(segments);
        benchmark::RegisterBenchmark(label.c_str(), BM_Tow, path, false, v.stepper, segments, chunk, v.method, 0.0,
                                     v.frame)
            ->Iterations(slow ? 3 : 5)
            ->Unit(benchmark::kMillisecond);
      }
  // The elastic cable (steel-like EA 1e8 N) with the implicit stepper, beside the rigid one above.
  for (Path path : { Path::kStraight, Path::kTurn })
    for (int segments : { 50, 100, 200, 1000 })
      benchmark::RegisterBenchmark((std::string(path == Path::kTurn ? "turn" : "steady") +
                                    "/implicit_elastic_ea1e8/nu:" + std::to_string(segments))
                                       .c_str(),
                                   BM_Tow, path, false, StepperType::kImplicit, segments, 10.0,
                                   ImplicitMethod::kRos34pw2, 1.0e8, kDefaultFrame)
          ->Iterations(5)
          ->Unit(benchmark::kMillisecond);
  for (const Variant& v : kVariants)
    benchmark::RegisterBenchmark((std::string("deep6km/") + v.label + "/nu:1000").c_str(), BM_Tow, Path::kStraight,
                                 true, v.stepper, 1000, 10.0, v.method, 0.0, v.frame)
        ->Iterations(3)
        ->Unit(benchmark::kMillisecond);
  // The same window for both, 0.10 .. 0.13 s, inside the snap transient; nu = 100 only: at nu = 1000 the first
  // 0.2 s after the parting take minutes on either stepper (docs/benchmarks.md).
  for (StepperType stepper : { StepperType::kImplicit, StepperType::kDopri5 })
  {
    const bool dopri5 = stepper == StepperType::kDopri5;
    benchmark::RegisterBenchmark(dopri5 ? "parted/dopri5_elastic_ea1e8/nu:100" : "parted/implicit_elastic_ea1e8/nu:100",
                                 BM_Parted, stepper, 100, 0.01)
        ->Iterations(3)
        ->Unit(benchmark::kMillisecond);
  }
  for (bool two_part : { false, true })
    benchmark::RegisterBenchmark(two_part ? "two_part/implicit/nu:600+100" : "two_part/implicit_uniform/nu:700",
                                 BM_TwoPart, two_part)
        ->Iterations(5)
        ->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv)
{
  registerAll();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
