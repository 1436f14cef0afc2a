#!/usr/bin/env python3
"""Writes the benchmarks' figures into docs/benchmarks.md from a run, with the commit and date they came from
(issue 28: figures that cannot go stale).

    bench_docs.py BIN_DIR [--doc docs/benchmarks.md] [--json RUN.json ...] [--python-output FILE]
                          [--no-python] [--save-json DIR]

Runs BIN_DIR/bench_chain, bench_steppers and bench_chart (Google Benchmark, JSON output) and bench/bench_python.py
(the workspace sourced: it imports tow_sim), or reads saved runs with --json (each names its executable) and
--python-output (bench_python.py's output), and replaces what lies between the markers

    <!-- bench:rhs -->  ...  <!-- /bench -->             bench_chain: one right-hand side, O(nu) and dense
    <!-- bench:steppers -->  ...  <!-- /bench -->        bench_steppers: the steppers against nu, and the deep tow
    <!-- bench:steppers-more -->  ...  <!-- /bench -->   bench_steppers: the elastic, parted and two-part rows
    <!-- bench:chart -->  ...  <!-- /bench -->           bench_chart: a 20 x 10 towing chart, the response and modes
    <!-- bench:python -->  ...  <!-- /bench -->          bench_python.py: the Python module's costs, as printed

with tables (simulated seconds per CPU second: the `realtime` counter; CPU times per call) and a line saying
which commit, date and machine they came from (a run saved with --save-json keeps the commit it ran at). A
benchmark missing from the run shows as a dash. Exit 2 when a marker is missing from the document or a run
holds none of its benchmarks.
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys

BENCHES = ("bench_chain", "bench_steppers", "bench_chart")
RHS_SEGMENTS = (10, 30, 100, 1000, 5000)
SEGMENTS = (50, 100, 200, 1000, 2000)
STEPPERS = (("dopri5", "dopri5"), ("rk4", "rk4"), ("implicit", "implicit"), ("implicit_ros2", "ros2"))
MORE = (
    ("steady/implicit_world/nu:{}", SEGMENTS, "steady, implicit in the world frame (implicit_frame: world)"),
    ("turn/implicit_world/nu:{}", SEGMENTS, "turn, implicit in the world frame"),
    ("steady/implicit_elastic_ea1e8/nu:{}", (50, 100, 200, 1000), "steady, elastic cable (EA 1e8 N), implicit"),
    ("turn/implicit_elastic_ea1e8/nu:{}", (50, 100, 200, 1000), "turn, elastic cable (EA 1e8 N), implicit"),
    ("parted/implicit_elastic_ea1e8/nu:{}", (100,), "parted elastic cable, 0.10-0.13 s after the parting, implicit"),
    ("parted/dopri5_elastic_ea1e8/nu:{}", (100,), "parted elastic cable, the same window, dopri5"),
    ("two_part/implicit/nu:{}", ("600+100",), "two-part deep tow, implicit"),
    ("two_part/implicit_uniform/nu:{}", (700,), "its armoured cable alone, implicit"),
)


def rate(value):
    """A rate as the docs write it: 3 significant figures, whole numbers from 100 on."""
    if value >= 100:
        return f"{value:.0f}×"
    return f"{value:.3g}×"


def seconds_of(b):
    """A benchmark's CPU time per iteration [s]."""
    return b["cpu_time"] * {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]


def duration(b):
    """A benchmark's CPU time per iteration, in the unit that reads best."""
    seconds = seconds_of(b)
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6)):
        if seconds >= scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds / 1e-9:.3g} ns"


def rhs_table(found):
    lines = ["| ν | one RHS, O(ν) sweep | one RHS, dense reference |", "|---|---|---|"]
    for nu in RHS_SEGMENTS:
        sweep, dense = found.get(f"BM_RhsSweep/{nu}"), found.get(f"BM_RhsDense/{nu}")
        lines.append(f"| {nu} | {duration(sweep) if sweep else '—'} | {duration(dense) if dense else '—'} |")
    small, large = found.get("BM_RhsSweep/100"), found.get("BM_RhsSweep/1000")
    if small and large:
        lines += ["", f"The sweep at ν = 1000 costs {seconds_of(large) / seconds_of(small):.3g}× its cost at ν = 100."]
    return lines


def chart_lines(found):
    b = found.get("BM_TowingChart20x10")
    lines = [f"The 200 steady tows of the chart: {duration(b)} of CPU." if b is not None else "The chart: —"]
    sparse = {n: found.get(f"BM_Response/sparse/{n}") for n in (200, 1000)}
    dense = found.get("BM_Response/dense/200")
    lowest = {n: found.get(f"BM_Modes/lowest10/{n}") for n in (200, 1000)}
    every = found.get("BM_Modes/dense/200")

    def cell(b):
        return duration(b) if b is not None else "—"
    if any(sparse.values()) or dense or any(lowest.values()) or every:
        lines += ["", "The analyses of the default tow at 2 m/s (the linearisation included), CPU:", "",
                  "| ν | response to heave at 100 periods, O(ν) per period | the same, dense "
                  "| ten lowest modes, Arnoldi | every mode, dense |", "|---|---|---|---|---|",
                  f"| 200 | {cell(sparse[200])} | {cell(dense)} | {cell(lowest[200])} | {cell(every)} |",
                  f"| 1000 | {cell(sparse[1000])} | — | {cell(lowest[1000])} | — |"]
    return lines


def results(run):
    """{name without /iterations:N: the benchmark's entry} of a Google Benchmark JSON run."""
    out = {}
    for b in run.get("benchmarks", []):
        out[re.sub(r"/iterations:\d+$", "", b["name"])] = b
    return out


def cell(found, name, step=False):
    b = found.get(name)
    if b is None or "realtime" not in b:
        return "—"
    text = rate(b["realtime"])
    if step and "step_ms" in b:
        step_ms = b["step_ms"]
        text += f" ({step_ms:.0f} ms)" if step_ms >= 10 else f" ({step_ms:.2g} ms)"
    return text


def steppers_table(found):
    head = ["ν"] + [f"{path} {label}" for path in ("steady", "turn") for _, label in STEPPERS]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for nu in SEGMENTS:
        row = [str(nu)]
        for path in ("steady", "turn"):
            for name, _ in STEPPERS:
                row.append(cell(found, f"{path}/{name}/nu:{nu}", step=name == "rk4"))
        lines.append("| " + " | ".join(row) + " |")
    deep = ["deep 6 km, ν = 1000"] + [cell(found, f"deep6km/{name}/nu:1000", step=name == "rk4") for name, _ in STEPPERS]
    lines.append("| " + " | ".join(deep + [""] * (len(head) - len(deep))) + " |")
    return lines


def more_table(found):
    lines = ["| run | ν | simulated s per CPU s |", "|---|---|---|"]
    for pattern, segments, what in MORE:
        for nu in segments:
            lines.append(f"| {what} | {nu} | {cell(found, pattern.format(nu))} |")
    return lines


def provenance(run, commit, bench):
    context = run.get("context", {})
    commit = context.get("tow_sim_commit", commit)  # a saved run's own
    date = context.get("date", "")[:10] or datetime.date.today().isoformat()
    load = context.get("load_avg", [])
    machine = f"{context.get('num_cpus', '?')} CPUs at {context.get('mhz_per_cpu', '?')} MHz"
    if load:
        machine += f", load average {load[0]:.2f} at the start"
    return (f"_Written by `scripts/bench_docs.py` from `{bench}` at commit {commit} on {date} "
            f"({machine}); read ratios, the machine is shared._")


def replace_block(text, marker, lines):
    """`text` with what lies between <!-- bench:MARKER --> and the next <!-- /bench --> replaced by `lines`."""
    start, end = f"<!-- bench:{marker} -->", "<!-- /bench -->"
    pattern = re.compile(re.escape(start) + r".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        raise ValueError(f"the document has no '{start}' ... '{end}' block")
    return pattern.sub(lambda _: "\n".join([start] + lines + [end]), text, count=1)


def bench_name(run):
    """Which benchmark program a run came from (its context's executable)."""
    return os.path.basename(run.get("context", {}).get("executable", ""))


def blocks(bench, found):
    """{marker: lines} a run of `bench` writes, or ValueError when it holds none of that program's benchmarks."""
    if bench == "bench_chain":
        out, known = {"rhs": rhs_table(found)}, [f"BM_RhsSweep/{n}" for n in RHS_SEGMENTS]
    elif bench == "bench_chart":
        out, known = {"chart": chart_lines(found)}, ["BM_TowingChart20x10"]
    elif bench == "bench_steppers":
        out = {"steppers": steppers_table(found), "steppers-more": more_table(found)}
        known = [f"{p}/{s}/nu:{n}" for p in ("steady", "turn") for s, _ in STEPPERS for n in SEGMENTS]
        known += [pattern.format(n) for pattern, segments, _ in MORE for n in segments]
    else:
        raise ValueError(f"a run of '{bench}', not of {', '.join(BENCHES)}")
    if not any(name in found for name in known):
        raise ValueError(f"the run holds none of {bench}'s benchmarks")
    return out


PYTHON_HEADER = re.compile(r"^bench_python: commit (.+?), (\d{4}-\d\d-\d\d), (\d+) cores(?:, load average ([\d.]+))?$")


def python_block(output):
    """The python block's lines from bench_python.py's output (its first line names the commit, date, cores and
    load), or ValueError when that line is missing."""
    lines = output.strip().splitlines()
    header = PYTHON_HEADER.match(lines[0]) if lines else None
    if not header or len(lines) < 2:
        raise ValueError("the Python output does not start with bench_python.py's 'bench_python: commit ...' line")
    commit, date, cores, load = header.groups()
    machine = f"{cores} CPUs" + (f", load average {float(load):.2f} at the start" if load else "")
    return [f"_Written by `scripts/bench_docs.py` from `bench/bench_python.py` at commit {commit} on {date} "
            f"({machine}); read ratios, the machine is shared._", "", "```"] + lines[1:] + ["```"]


def write_doc(doc, runs, commit, python_output=None):
    """Writes each run's blocks, and the python block from bench_python.py's output when given, into `doc`
    (all or nothing)."""
    with open(doc, encoding="utf-8") as f:
        text = f.read()
    for run in runs:
        bench = bench_name(run)
        line = provenance(run, commit, bench)
        for marker, lines in blocks(bench, results(run)).items():
            text = replace_block(text, marker, [line, ""] + lines)
    if python_output is not None:
        text = replace_block(text, "python", python_block(python_output))
    with open(doc, "w", encoding="utf-8") as f:
        f.write(text)


def commit_of(repo):
    try:
        commit = subprocess.run(["git", "-C", repo, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                                check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", repo, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
        return commit + (" with local changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("bin_dir", help="where bench_steppers is (the workspace's devel/lib/tow_sim)")
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("--doc", default=os.path.join(repo, "docs", "benchmarks.md"), help="the document to write")
    parser.add_argument("--json", action="append", default=[],
                        help="a saved run (BENCH --benchmark_format=json) instead of running; repeatable")
    parser.add_argument("--python-output", help="bench_python.py's saved output instead of running it")
    parser.add_argument("--no-python", action="store_true", help="leave the python block as it is")
    parser.add_argument("--save-json", help="also save each run here as BENCH.json (and bench_python.txt)")
    args = parser.parse_args(argv)
    if args.no_python and args.python_output:
        parser.error("--no-python and --python-output exclude each other")
    runs, commit = [], commit_of(repo)
    for path in args.json:
        with open(path, encoding="utf-8") as f:
            runs.append(json.load(f))
    if not args.json:
        for bench in BENCHES:
            out = subprocess.run([os.path.join(args.bin_dir, bench), "--benchmark_format=json"], capture_output=True,
                                 text=True, check=True).stdout
            runs.append(json.loads(out))
            runs[-1].setdefault("context", {})["tow_sim_commit"] = commit
    python_output = None
    if args.python_output:
        with open(args.python_output, encoding="utf-8") as f:
            python_output = f.read()
    elif not args.no_python and not args.json:
        python_output = subprocess.run([sys.executable, os.path.join(repo, "bench", "bench_python.py")],
                                       capture_output=True, text=True, check=True,
                                       env=dict(os.environ, TOW_SIM_BIN=args.bin_dir)).stdout
    if args.save_json:
        os.makedirs(args.save_json, exist_ok=True)
        for run in runs:
            with open(os.path.join(args.save_json, bench_name(run) + ".json"), "w", encoding="utf-8") as f:
                json.dump(run, f, indent=1)
        if python_output is not None:
            with open(os.path.join(args.save_json, "bench_python.txt"), "w", encoding="utf-8") as f:
                f.write(python_output)
    try:
        write_doc(args.doc, runs, commit, python_output)
    except ValueError as e:
        print(f"bench_docs.py: {args.doc}: {e}", file=sys.stderr)
        return 2
    print(f"wrote {args.doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
