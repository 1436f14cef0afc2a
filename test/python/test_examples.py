"""examples/ run on small inputs, their answers checked without trusting SciPy: the optimum against its
neighbours and the constraints, the fitted coefficient against the one that made the data."""
import os
import subprocess
import sys

import pytest
import yaml

import tow_sim

SOURCE = os.environ.get("TOW_SIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BIN = os.environ.get("TOW_SIM_BIN", "")
sys.path.insert(0, os.path.join(SOURCE, "examples"))

import fit_drag  # noqa: E402
import optimise_depressor  # noqa: E402


@pytest.mark.parametrize("limit", [30000.0, 12000.0])  # the second binds: the free optimum pulls 12.6 kN
def test_the_depressor_design_reaches_the_depth_and_beats_its_neighbours(limit):
    argv = ["--quick", "--tension-limit", str(limit)]
    best = optimise_depressor.main(argv)
    assert abs(best["depth"] - 400.0) <= 0.05 and best["tension_ship"] <= limit
    args = optimise_depressor.argparse.Namespace(speed=2.0, target_depth=400.0, tension_limit=limit, cable_cost=20.0,
                                                 clump_cost=5.0, segment_length=20.0)
    def cost(mass):  # the design's cost worked out here: 20 per metre of cable out, 5 per kg of clump
        cable_out, tension = optimise_depressor.design(mass, args)
        return 20.0 * cable_out + 5.0 * mass if tension <= limit else float("inf")

    at_best = cost(best["clump_mass"])
    assert at_best == pytest.approx(best["cost"], rel=1e-9)
    for neighbour in (0.95 * best["clump_mass"], 1.05 * best["clump_mass"]):
        assert cost(neighbour) > at_best, f"{neighbour:.1f} kg costs {cost(neighbour):.1f} against {at_best:.1f}"


def test_the_drag_fit_recovers_the_coefficient_that_made_the_data(tmp_path):
    doc = yaml.safe_load(tow_sim.load_scenario(os.path.join(SOURCE, "scenarios", "speed_change.yaml")).to_yaml())
    doc["simulation"]["duration"] = 200.0  # the speed change and the settling after it
    assert doc["cable"]["normal_drag_coefficient"] == 1.2
    (tmp_path / "model.yaml").write_text(yaml.safe_dump(doc))
    doc["cable"]["normal_drag_coefficient"] = 1.5  # the "sea trial": the batch runner with another cable
    (tmp_path / "trial.yaml").write_text(yaml.safe_dump(doc))
    subprocess.run([os.path.join(BIN, "tow_sim_batch"), "--scenario", str(tmp_path / "trial.yaml"), "--out",
                    str(tmp_path / "trial")], check=True, capture_output=True)
    value, misfit = fit_drag.main([str(tmp_path / "trial" / "timeseries.csv"), "--scenario", str(tmp_path / "model.yaml")])
    assert value == pytest.approx(1.5, abs=1e-3) and misfit < 1e-3
