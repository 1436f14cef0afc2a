#!/usr/bin/env python3
"""The towfish estimator against the layback rules on a lawn-mower survey (issue 29, docs/survey.md).

    survey_benchmark.py BIN_DIR OUT_DIR [--seeds N] [--plot PNG] [--doc MARKDOWN] [--nav-config YAML] [--reuse]

Runs bench/survey/lawnmower.yaml with tow_sim_batch (the truth and its measurements.csv), then tow_sim_nav with
bench/survey/nav.yaml (no current, drag 20 % high) for each seed of the ensemble, once with the USBL fixes
and once with them taken out. It prints a markdown table of the horizontal error (RMS and 95th percentile) on
the lines and in the turns, for the estimate and each rule; with --doc writes it into that file between
<!-- survey-bench --> and <!-- /survey-bench -->, under a line naming the commit, the date and the machine; with
--plot draws the tracks and the errors (the figure's footer names the commit and the date).

A turn lasts from when the ship starts turning until the fish's heading is back within 10 degrees of the
ship's; the lines are the rest after the first 300 s (the estimator's start-up).
"""
import argparse
import csv
import datetime
import os
import subprocess
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load(path):
    rows = list(csv.DictReader(open(path)))
    return {k: np.array([float(r[k]) if r[k] != "" else np.nan for r in rows]) for k in rows[0]}


def run(cmd):
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({out.returncode}):\n{out.stderr}")
    return out.stdout


def turn_mask(truth, t):
    """Rows in a turn: from when the ship's heading starts to change by more than 0.1 degree/s until the fish's
    heading is back within 10 degrees of the ship's (a cross current alone sets it a few degrees off)."""
    tt = truth["t"]
    heading = np.unwrap(np.arctan2(np.gradient(truth["ship_y"]), np.gradient(truth["ship_x"])))
    turning = np.abs(np.gradient(heading, tt)) > np.radians(0.1)
    off = np.abs(np.angle(np.exp(1j * (truth["vehicle_yaw"] - heading)))) > np.radians(10.0)
    mask = turning.copy()
    for i in range(1, len(tt)):
        mask[i] |= mask[i - 1] and off[i]
    return np.interp(t, tt, mask.astype(float)) > 0.5


def without_usbl(src, dst):
    rows = list(csv.DictReader(open(src)))
    with open(dst, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            for k in ("usbl_x", "usbl_y", "usbl_z"):
                r[k] = ""
            if any(v != "" for k, v in r.items() if k != "t"):
                w.writerow(r)


def errors(truth, est, base):
    t = est["t"]
    fx = np.interp(t, truth["t"], truth["vehicle_x"])
    fy = np.interp(t, truth["t"], truth["vehicle_y"])
    e = {"tow_nav": np.hypot(est["x"] - fx, est["y"] - fy)}
    for name in ("pythagoras", "track", "catenary"):
        e[name] = np.hypot(base[name + "_x"] - fx, base[name + "_y"] - fy)
    return t, e


def stats(values):
    v = values[~np.isnan(values)]
    return (np.sqrt(np.mean(v ** 2)), np.percentile(v, 95)) if len(v) else (np.nan, np.nan)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bin_dir")
    parser.add_argument("out_dir")
    parser.add_argument("--seeds", type=int, default=6)
    parser.add_argument("--plot")
    parser.add_argument("--doc", action="append", default=[],
                        help="a markdown file whose survey-bench block gets the table (may be given again)")
    parser.add_argument("--nav-config", default=os.path.join(REPO, "bench/survey/nav.yaml"),
                        help="the estimator's configuration (default bench/survey/nav.yaml)")
    parser.add_argument("--reuse", action="store_true", help="keep the runs already in OUT_DIR (table and plot only)")
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    truth_dir = os.path.join(args.out_dir, "truth")
    if not (args.reuse and os.path.exists(os.path.join(truth_dir, "measurements.csv"))):
        run([os.path.join(args.bin_dir, "tow_sim_batch"), "--scenario",
             os.path.join(REPO, "bench/survey/lawnmower.yaml"), "--out", truth_dir])
    truth = load(os.path.join(truth_dir, "timeseries.csv"))
    measurements = {"USBL": os.path.join(truth_dir, "measurements.csv"),
                    "no USBL": os.path.join(args.out_dir, "measurements_no_usbl.csv")}
    without_usbl(measurements["USBL"], measurements["no USBL"])
    nav_config = open(args.nav_config).read()
    results = {}
    for case, path in measurements.items():
        for seed in range(1, args.seeds + 1):
            config = os.path.join(args.out_dir, f"nav_{seed}.yaml")
            open(config, "w").write(nav_config.replace("nav: {", f"nav: {{seed: {seed}, "))
            out = os.path.join(args.out_dir, f"nav_{case.replace(' ', '_')}_{seed}")
            if not (args.reuse and os.path.exists(os.path.join(out, "estimate.csv"))):
                print(run([os.path.join(args.bin_dir, "tow_sim_nav"), "--config", config, "--measurements", path,
                           "--out", out]).strip(), file=sys.stderr)
            estimate = load(os.path.join(out, "estimate.csv"))
            results[(case, seed)] = errors(truth, estimate, load(os.path.join(out, "baselines.csv"))) + (estimate,)
    t = results[("USBL", 1)][0]
    turns = turn_mask(truth, t)
    lines = ~turns & (t > 300.0)
    table = markdown_table(results, list(measurements), args.seeds, lines, turns)
    print(table)
    for doc in args.doc:
        write_doc(doc, table)
    if args.plot:
        plot(args.plot, truth, results, t, turns)


def markdown_table(results, cases, seeds, lines, turns):
    rows = ["| horizontal error [m], RMS / 95th percentile | lines | turns |", "|---|---|---|"]
    first = results[(cases[0], 1)][1]
    names = {"pythagoras": "Pythagoras", "track": "follow-the-dog", "catenary": "catenary factor (0.9)"}
    for name, label in names.items():
        (lr, lp), (tr, tp) = stats(first[name][lines]), stats(first[name][turns])
        rows.append(f"| {label} | {lr:.1f} / {lp:.1f} | {tr:.1f} / {tp:.1f} |")
    for case in cases:
        cells = []
        for mask in (lines, turns):
            s = [stats(results[(case, seed)][1]["tow_nav"][mask]) for seed in range(1, seeds + 1)]
            cells.append(f"{min(x[0] for x in s):.1f}–{max(x[0] for x in s):.1f} / "
                         f"{min(x[1] for x in s):.1f}–{max(x[1] for x in s):.1f}")
        rows.append(f"| tow_nav, {case} ({seeds} seeds) | {cells[0]} | {cells[1]} |")
    return "\n".join(rows)


def provenance():
    commit = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip() or "unknown"
    return commit, datetime.date.today().isoformat()


def write_doc(path, table):
    text = open(path).read()
    start, end = "<!-- survey-bench -->", "<!-- /survey-bench -->"
    if start not in text or end not in text:
        sys.exit(f"{path}: no {start} ... {end} block")
    commit, date = provenance()
    block = (f"{start}\n_Measured by `scripts/survey_benchmark.py` at commit {commit} on {date}, "
             f"{os.cpu_count()} cores._\n\n{table}\n")
    open(path, "w").write(text[:text.index(start)] + block + text[text.index(end):])


def plot(path, truth, results, t, turns):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (plan, err) = plt.subplots(2, 1, figsize=(9, 9), gridspec_kw={"height_ratios": [1.1, 1]})
    plan.plot(truth["ship_x"], truth["ship_y"], color="0.6", lw=1, label="ship")
    plan.plot(truth["vehicle_x"], truth["vehicle_y"], color="k", lw=1.5, label="fish (truth)")
    est = results[("no USBL", 1)][2]
    plan.plot(est["x"], est["y"], color="tab:red", lw=1, ls="--", label="tow_nav, no USBL")
    plan.set_aspect("equal")
    plan.set_xlabel("x (east) [m]")
    plan.set_ylabel("y (north) [m]")
    plan.legend(loc="upper right", fontsize=8)
    e = results[("no USBL", 1)][1]
    eu = results[("USBL", 1)][1]
    err.plot(t, e["pythagoras"], lw=0.8, label="Pythagoras")
    err.plot(t, e["track"], lw=0.8, label="follow-the-dog")
    err.plot(t, e["catenary"], lw=0.8, label="catenary factor")
    err.plot(t, e["tow_nav"], lw=1.5, color="k", label="tow_nav, no USBL")
    err.plot(t, eu["tow_nav"], lw=1.5, color="tab:red", label="tow_nav, sparse USBL")
    ymax = err.get_ylim()[1]
    err.fill_between(t, 0, ymax, where=turns, color="0.9", label="turns")
    err.set_yscale("log")
    err.set_xlabel("t [s]")
    err.set_ylabel("horizontal error [m]")
    err.legend(loc="upper left", fontsize=8, ncol=2)
    commit, date = provenance()
    fig.text(0.01, 0.005, f"scripts/survey_benchmark.py, commit {commit}, {date}", fontsize=7, color="0.4")
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
