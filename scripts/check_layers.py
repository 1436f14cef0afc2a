#!/usr/bin/env python3
"""Checks that includes point down the layer order (docs/architecture.md), never up.

    check_layers.py [REPO]

Libraries, lowest first: core, config, scenario, ros; nodes/ and tools/ may include any of them. A file
of one library includes only headers of its own library or a lower one (the ROS messages and services
generated into tow_sim/ count as ros). Inside the core each header has a layer (LAYERS below, lowest
first) and a source file takes the layer of the header it implements (of the same name, or as SOURCES
says); a core file includes only core headers of its own layer or a lower one. A core header or source
missing from LAYERS and SOURCES is itself a violation, so that a new one is placed deliberately. Prints each violation as FILE:LINE and
exits 1 if there is any.
"""
import pathlib
import re
import sys

LIBRARIES = ["core", "config", "scenario", "ros"]
LAYERS = [
    ["constants", "attitude", "geometry", "param_table", "angle_grid", "cable_loading", "survey_measurement", "layback_rules", "survey_row_queue"],
    ["waves", "params", "param_tables", "numeric_csv", "tension_limits", "measurement_csv"],
    ["fins", "seabed", "element", "ship_response"],
    ["added_mass", "vehicle"],
    ["chain_model"],
    ["chain_state", "chain_solver", "element_equations", "chain_jacobian", "rosenbrock_tableau", "run_report", "winch"],
    ["chain", "implicit_stepper", "explicit_stepper", "jacobian_check", "modes", "strumming"],
    ["simulator"],
    ["equilibrium", "ship_track", "odometry_check", "gnss_track", "depth_autopilot", "track_trail", "simulation_config"],
    ["tow_run"],
    ["saved_state", "live_run", "survey_sensors", "tow_nav"],
]
LAYER = {name: i for i, names in enumerate(LAYERS) for name in names}
# Core sources that implement a header of another name.
SOURCES = {
    "joint_response": "modes",
    "faired_loads": "element",
    "simulator_implicit": "simulator",
    "simulator_parting": "simulator",
    "simulator_state": "simulator",
    "snapshot_interpolation": "tow_run",
    "tow_nav_analysis": "tow_nav",
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"tow_sim/([^"]+)\.h"', re.M)


def library_of(path):
    """The library of a source or header (None: nodes, tools and tests, which may include anything)."""
    parts = path.parts
    if parts[0] == "include" and len(parts) > 2 and parts[1] == "tow_sim":
        return parts[2]
    if parts[0] == "src" and len(parts) > 1:
        return parts[1] if parts[1] in LIBRARIES else None
    return None


def included_library(target):
    return target.split("/")[0] if "/" in target else "ros"  # tow_sim/Foo.h: a generated message


def check(repo):
    problems = []
    files = sorted(p for folder in ("include", "src") for p in (repo / folder).rglob("*") if p.suffix in (".h", ".cpp"))
    for path in files:
        name = path.relative_to(repo)
        library = library_of(name)
        if library is None:
            continue
        text = path.read_text()
        includes = [(text.count("\n", 0, m.start()) + 1, m.group(1)) for m in INCLUDE.finditer(text)]
        rank = LIBRARIES.index(library)
        for line, target in includes:
            other = included_library(target)
            if other in LIBRARIES and LIBRARIES.index(other) > rank:
                problems.append(f"{name}:{line}: {library} includes tow_sim/{target}.h of {other}, a higher library")
        if library != "core":
            continue
        own = SOURCES.get(name.stem, name.stem)
        if own not in LAYER:
            problems.append(f"{name}:1: {name.stem} has no layer in scripts/check_layers.py (LAYERS or SOURCES)")
            continue
        for line, target in includes:
            stem = target.rsplit("/", 1)[-1]  # core/<folder>/<stem>
            if target.startswith("core/") and LAYER.get(stem, len(LAYERS)) > LAYER[own]:
                problems.append(f"{name}:{line}: core/{own} (layer {LAYER[own]}) includes {target}.h "
                                f"(layer {LAYER.get(stem, 'none')}), up the layer order")
    return files, problems


def main(argv):
    repo = pathlib.Path(argv[0] if argv else pathlib.Path(__file__).resolve().parent.parent)
    files, problems = check(repo)
    for problem in problems:
        print(problem)
    print(f"layers: {len(files)} files checked, {len(problems)} includes up the layer order")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
