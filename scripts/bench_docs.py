#!/usr/bin/env python3
"""Writes the stepper benchmarks' figures into docs/benchmarks.md from a run, with the commit and date they
came from (issue 28: figures that cannot go stale).

    bench_docs.py BIN_DIR [--doc docs/benchmarks.md] [--json RUN.json] [--save-json RUN.json]

Runs BIN_DIR/bench_steppers (Google Benchmark, JSON output), or reads a saved run with --json, and replaces
what lies between the markers

    <!-- bench:steppers -->  ...  <!-- /bench -->        the steppers against nu, steady and turn, and the deep tow
    <!-- bench:steppers-more -->  ...  <!-- /bench -->   the elastic, parted and two-part rows

with tables of simulated seconds per CPU second (the benchmarks' `realtime` counter) and a line saying which
commit, date and machine they came from. A benchmark missing from the run shows as a dash. Exit 2 when a
marker is missing from the document or the run holds none of the benchmarks.
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys

SEGMENTS = (50, 100, 200, 1000, 2000)
STEPPERS = (("dopri5", "dopri5"), ("rk4", "rk4"), ("implicit", "implicit"), ("implicit_ros2", "ros2"))
MORE = (
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


def provenance(run, commit):
    context = run.get("context", {})
    date = context.get("date", "")[:10] or datetime.date.today().isoformat()
    load = context.get("load_avg", [])
    machine = f"{context.get('num_cpus', '?')} CPUs at {context.get('mhz_per_cpu', '?')} MHz"
    if load:
        machine += f", load average {load[0]:.2f} at the start"
    return (f"_Written by `scripts/bench_docs.py` from `bench_steppers` at commit {commit} on {date} "
            f"({machine}): simulated seconds per CPU second; read ratios, the machine is shared._")


def replace_block(text, marker, lines):
    """`text` with what lies between <!-- bench:MARKER --> and the next <!-- /bench --> replaced by `lines`."""
    start, end = f"<!-- bench:{marker} -->", "<!-- /bench -->"
    pattern = re.compile(re.escape(start) + r".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        raise ValueError(f"the document has no '{start}' ... '{end}' block")
    return pattern.sub(lambda _: "\n".join([start] + lines + [end]), text, count=1)


def write_doc(doc, run, commit):
    found = results(run)
    known = [f"{p}/{s}/nu:{n}" for p in ("steady", "turn") for s, _ in STEPPERS for n in SEGMENTS]
    known += [pattern.format(n) for pattern, segments, _ in MORE for n in segments]
    if not any(name in found for name in known):
        raise ValueError("the run holds none of bench_steppers' benchmarks")
    with open(doc, encoding="utf-8") as f:
        text = f.read()
    line = provenance(run, commit)
    text = replace_block(text, "steppers", [line, ""] + steppers_table(found))
    text = replace_block(text, "steppers-more", [line, ""] + more_table(found))
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
    parser.add_argument("--json", help="a saved run (bench_steppers --benchmark_format=json) instead of running")
    parser.add_argument("--save-json", help="also save the run here")
    args = parser.parse_args(argv)
    if args.json:
        with open(args.json, encoding="utf-8") as f:
            run = json.load(f)
    else:
        out = subprocess.run([os.path.join(args.bin_dir, "bench_steppers"), "--benchmark_format=json"],
                             capture_output=True, text=True, check=True).stdout
        run = json.loads(out)
    if args.save_json:
        with open(args.save_json, "w", encoding="utf-8") as f:
            json.dump(run, f, indent=1)
    try:
        write_doc(args.doc, run, commit_of(repo))
    except ValueError as e:
        print(f"bench_docs.py: {args.doc}: {e}", file=sys.stderr)
        return 2
    print(f"wrote {args.doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
