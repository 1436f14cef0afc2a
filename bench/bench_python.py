#!/usr/bin/env python3
"""What calling the core through the Python module costs (docs/benchmarks.md, "The Python module").

    bench_python.py [--repeats N]      (make bench; the workspace sourced, tow_sim_batch on PATH or TOW_SIM_BIN)

1. A 600 s run of scenarios/turn_180.yaml at nu = 100, as whole processes: tow_sim_batch (writing its CSVs)
   against python3 running tow_sim.Run(scenario).run(600) (the interpreter's start and the import included).
2. Short steps: 60 s in 0.05 s steps driven from Python (advance_to and snapshot per step) against the same steps
   in the module's C++ loop (Run.run), the difference per step.
3. A 200-run sweep (tow_sim_sweep, 60 s runs) as tow_sim_batch processes against in process through the module.
4. tow_sim_fatigue on a one-hour run's folder (outputs and shapes every 0.5 s, 52 joints: the size of
   scenarios/head_seas.yaml run for an hour; its tensions a made-up irregular history), the whole process.
Prints the medians and their ratio with the commit and the date, for the docs.
"""
import argparse
import datetime
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import yaml

import tow_sim

SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def median_seconds(command, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def scenario_at_nu_100(folder):
    doc = yaml.safe_load(tow_sim.load_scenario(os.path.join(SOURCE, "scenarios", "turn_180.yaml")).to_yaml())
    doc["cable"]["segments"] = 100
    path = os.path.join(folder, "turn_180_nu100.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(doc, f)
    return path


def per_call_cost(scenario, step=0.05, until=60.0, repeats=5):
    """[s] per step of `step` driven from Python (advance_to, then snapshot) over the same steps run by the C++
    loop of Run.run(every=step) (advanceTo, snapshot and the row's values in C++): what calling adds per step."""
    sc = tow_sim.load_scenario(scenario)
    steps = round(until / step)
    python_loop, cpp_loop = [], []
    for _ in range(repeats):
        run = tow_sim.Run(sc)
        start = time.perf_counter()
        for k in range(steps + 1):
            run.advance_to(k * step)
            run.snapshot()
        python_loop.append(time.perf_counter() - start)
        run = tow_sim.Run(sc)
        start = time.perf_counter()
        run.run(until=until, every=step)
        cpp_loop.append(time.perf_counter() - start)
    return (statistics.median(python_loop) - statistics.median(cpp_loop)) / (steps + 1), statistics.median(cpp_loop)


SWEEP_200 = """scenario:
  cable: {length: 300.0, segments: 30}
  ship: {manoeuvres: [{type: turn, speed: 2.0, radius: 200.0, angle: 1.0}]}
  simulation: {duration: 60.0, output_interval: 1.0, shape_interval: 30.0}
grid:
  cable.length: [200.0, 220.0, 240.0, 260.0, 280.0, 300.0, 320.0, 340.0, 360.0, 380.0]
  ship.manoeuvres[0].speed: [1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8, 1.9, 2.0, 2.1, 2.2, 2.3, 2.4, 2.5, 2.6, 2.7,
                             2.8, 2.9]
"""


def sweep_seconds(folder, batch, extra):
    """[s] of wall time for tow_sim_sweep over SWEEP_200 (200 runs of 60 s at nu = 20..38) on every core."""
    sweep = os.path.join(folder, "sweep.yaml")
    with open(sweep, "w") as f:
        f.write(SWEEP_200)
    out = os.path.join(folder, f"sweep_{len(os.listdir(folder))}")
    start = time.perf_counter()
    subprocess.run([sys.executable, os.path.join(SOURCE, "scripts", "tow_sim_sweep"), sweep, "--out", out] + extra,
                   check=True, capture_output=True)
    return time.perf_counter() - start


def fatigue_seconds(folder, repeats):
    """[s] of wall time for tow_sim_fatigue over a one-hour folder (7201 outputs and shapes of 52 joints)."""
    run = os.path.join(folder, "hour")
    os.makedirs(run, exist_ok=True)
    times = [0.5 * k for k in range(7201)]
    tension = [[40e3 + 3e3 * math.sin(0.6 * t + j) + 1e3 * math.sin(1.7 * t + 0.3 * j) for j in range(52)]
               for t in times]
    with open(os.path.join(run, "timeseries.csv"), "w") as f:
        f.write("t,tension_ship,tension_vehicle\n")
        f.writelines(f"{t},{row[0]:.6f},{row[-1]:.6f}\n" for t, row in zip(times, tension))
    with open(os.path.join(run, "shapes.csv"), "w") as f:
        f.write("t,joint,x,y,z,tension,slack\n")
        f.writelines(f"{t},{j + 1},0,0,0,{row[j]:.6f},0\n" for t, row in zip(times, tension) for j in range(52))
    script = os.path.join(SOURCE, "scripts", "tow_sim_fatigue")
    return median_seconds([sys.executable, script, run, "--breaking-load", "500000"], repeats)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    batch = os.path.join(os.environ.get("TOW_SIM_BIN", ""), "tow_sim_batch")
    commit = subprocess.run(["git", "-C", SOURCE, "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    dirty = subprocess.run(["git", "-C", SOURCE, "status", "--porcelain", "--untracked-files=no"], capture_output=True,
                           text=True).stdout.strip()
    # The line scripts/bench_docs.py reads the provenance from.
    print(f"bench_python: commit {commit.stdout.strip() or '?'}{' with local changes' if dirty else ''}, "
          f"{datetime.date.today()}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    with tempfile.TemporaryDirectory() as folder:
        scenario = scenario_at_nu_100(folder)
        t_batch = median_seconds([batch, "--scenario", scenario, "--out", os.path.join(folder, "out")], args.repeats)
        script = f"import tow_sim; tow_sim.Run(tow_sim.load_scenario({scenario!r})).run(until=600.0, every=1.0)"
        t_python = median_seconds([sys.executable, "-c", script], args.repeats)
        print(f"600 s of turn_180 at nu = 100, whole processes (median of {args.repeats}):")
        print(f"  tow_sim_batch {t_batch:.3f} s, python3 + tow_sim.Run.run {t_python:.3f} s: "
              f"ratio {t_python / t_batch:.3f}")
        t_import = median_seconds([sys.executable, "-c", "import tow_sim, numpy"], args.repeats)
        print(f"  of which python3 -c 'import tow_sim, numpy' {t_import:.3f} s; without it, ratio "
              f"{(t_python - t_import) / t_batch:.3f}")
        extra, cpp = per_call_cost(scenario)
        print(f"60 s in 0.05 s steps: the C++ loop (Run.run) {cpp:.3f} s; from Python (advance_to + snapshot per "
              f"step) {extra * 1e6:.1f} us more per step")
        processes = min(sweep_seconds(folder, batch, ["--batch", batch]) for _ in range(2))
        module = min(sweep_seconds(folder, batch, []) for _ in range(2))
        print(f"tow_sim_sweep, 200 runs of 60 s on {os.cpu_count()} cores (best of 2): tow_sim_batch processes "
              f"{processes:.2f} s, in process through the module {module:.2f} s: {processes / module:.2f}x faster")
        print(f"tow_sim_fatigue on a one-hour run (outputs and shapes every 0.5 s, 52 joints; median of "
              f"{args.repeats}): {fatigue_seconds(folder, args.repeats):.2f} s")


if __name__ == "__main__":
    main()
