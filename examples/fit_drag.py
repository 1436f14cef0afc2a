#!/usr/bin/env python3
"""Fit the cable's normal drag coefficient to a recorded tow with SciPy (docs/python.md, "Examples").

    fit_drag.py RECORDED.csv --scenario SCENARIO.yaml [--key cable.normal_drag_coefficient] [--bounds 0.5:3]

RECORDED.csv stands in for sea-trial data: a timeseries.csv with at least the columns t, depth and tension_ship
(tow_sim_batch's, or your own log of the towfish's depth and the load cell at the tow point). SCENARIO.yaml is the
same tow as the model knows it: the ship's manoeuvres, the commands, the cable with the coefficient to fit. The
fit re-runs the scenario in process for each trial value and minimises the misfit of the depth and the tension at
the ship at the recorded times, each relative to its recorded spread, with SciPy's bounded scalar search.
"""
import argparse
import csv

import numpy as np
import yaml
from scipy.optimize import minimize_scalar

import tow_sim


def read_recorded(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    missing = {"t", "depth", "tension_ship"} - set(rows[0] if rows else {})
    if missing:
        raise SystemExit(f"fit_drag: {path} lacks the columns {sorted(missing)}")
    return {k: np.array([float(r[k]) for r in rows]) for k in ("t", "depth", "tension_ship")}


def set_key(doc, key, value):
    *path, last = key.split(".")
    for part in path:
        doc = doc.setdefault(part, {})
    doc[last] = value


def misfit(value, base, key, recorded):
    """[-] the rms misfit of depth and tension at the recorded times, each over its recorded spread."""
    doc = yaml.safe_load(base.to_yaml())
    set_key(doc, key, float(value))
    sc = tow_sim.Scenario.from_dict(doc)
    until = min(float(recorded["t"][-1]), sc.duration)
    model = tow_sim.Run(sc).run(until=until, every=sc.output_interval)
    r = []
    for name in ("depth", "tension_ship"):
        at = np.interp(recorded["t"], model["t"], model[name])
        r.append((at - recorded[name]) / max(np.ptp(recorded[name]), 1e-3 * np.abs(recorded[name]).max(), 1e-9))
    return float(np.sqrt(np.mean(np.concatenate(r) ** 2)))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recorded", help="timeseries.csv with t, depth, tension_ship")
    parser.add_argument("--scenario", required=True, help="the tow as the model knows it")
    parser.add_argument("--key", default="cable.normal_drag_coefficient", help="the scenario key to fit")
    parser.add_argument("--bounds", default="0.5:3", help="LOW:HIGH of the value")
    args = parser.parse_args(argv)
    low, high = (float(x) for x in args.bounds.split(":"))
    recorded, base = read_recorded(args.recorded), tow_sim.load_scenario(args.scenario)
    best = minimize_scalar(misfit, bounds=(low, high), args=(base, args.key, recorded), method="bounded",
                           options={"xatol": 1e-5})
    print(f"{args.key} = {best.x:.5f}: rms misfit {best.fun:.3g} of the recorded spread ({best.nfev} runs)")
    return float(best.x), float(best.fun)


if __name__ == "__main__":
    main()
