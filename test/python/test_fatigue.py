"""tow_sim_fatigue against hand counts and closed forms, and on a batch run."""
import csv
import importlib.machinery
import importlib.util
import math
import os
import subprocess

import pytest
import yaml

import tow_sim

SOURCE = os.environ.get("TOW_SIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BIN = os.environ.get("TOW_SIM_BIN", "")
SCRIPT = os.path.join(SOURCE, "scripts", "tow_sim_fatigue")
_loader = importlib.machinery.SourceFileLoader("tow_sim_fatigue", SCRIPT)
fatigue = importlib.util.module_from_spec(importlib.util.spec_from_loader("tow_sim_fatigue", _loader))
_loader.exec_module(fatigue)


def totals(cycles):
    out = {}
    for rng, _, count in cycles:
        out[rng] = out.get(rng, 0.0) + count
    return sorted(out.items())


def test_the_astm_e1049_example_is_counted_as_the_standard_counts_it():
    # ASTM E1049-85 (2017), 5.4.4 and its figure: the history -2, 1, -3, 5, -1, 3, -4, 4, -2 gives ranges 3 (a
    # half), 4 (one and a half), 6 (a half), 8 (one) and 9 (a half).
    cycles = fatigue.rainflow([-2, 1, -3, 5, -1, 3, -4, 4, -2])
    assert totals(cycles) == [(3, 0.5), (4, 1.5), (6, 0.5), (8, 1.0), (9, 0.5)]
    # The same history sampled finely (points on the way and repeated values) counts the same.
    fine = [-2, -1, 0, 1, 1, -1, -3, 0, 5, 2, -1, 3, 0, -4, 4, 4, 1, -2]
    assert totals(fatigue.rainflow(fine)) == totals(cycles)


def test_a_constant_amplitude_history_does_the_closed_form_damage():
    breaking, mean, amplitude, n = 200e3, 40e3, 5e3, 500  # [N]; n whole cycles, ranges 2 amplitude
    history = [mean + amplitude * math.sin(2 * math.pi * k / 16) for k in range(16 * n + 1)]
    cycles = fatigue.rainflow(history)
    assert sum(c for _, _, c in cycles) == pytest.approx(n, abs=1.0)
    for name, (m, a, b) in fatigue.CURVES.items():
        k = 10 ** (a - b * mean / breaking)
        want = n * (2 * amplitude / breaking) ** m / k
        got = fatigue.damage(cycles, breaking, fatigue.CURVES[name], mean)
        assert got == pytest.approx(want, rel=2 / n), name  # within one half cycle of the residue
    # API RP 2SK's K at the mean load 0.3 of the breaking load: 231 (six strand), 166 (spiral strand).
    assert 10 ** (3.20 - 2.79 * 0.3) == pytest.approx(231, rel=3e-3)  # the tables round K to three digits
    assert 10 ** (3.25 - 3.43 * 0.3) == pytest.approx(166, rel=3e-3)
    assert fatigue.curve_of("3:1000") == (3.0, 3.0, 0.0)


def test_a_head_sea_run_has_its_damage_where_the_heave_reaches_the_cable(tmp_path):
    doc = yaml.safe_load(tow_sim.load_scenario(os.path.join(SOURCE, "scenarios", "head_seas.yaml")).to_yaml())
    doc["simulation"].update({"duration": 120.0, "output_interval": 0.5, "shape_interval": 0.5})
    doc["cable"]["breaking_load"] = 200e3
    (tmp_path / "run.yaml").write_text(yaml.safe_dump(doc))
    subprocess.run([os.path.join(BIN, "tow_sim_batch"), "--scenario", str(tmp_path / "run.yaml"), "--out",
                    str(tmp_path / "run")], check=True, capture_output=True)
    assert fatigue.main([str(tmp_path / "run"), "--from", "20"]) == 0
    with open(tmp_path / "run" / "fatigue.csv") as f:
        rows = {r["location"]: r for r in csv.DictReader(f)}
    assert {"ship", "vehicle", "joint_1"} <= set(rows)
    for r in rows.values():
        assert float(r["damage"]) >= 0 and float(r["life_hours"]) > 0
    # Joint 1 is the tow point: its history is the ship's tension, sampled alike.
    assert float(rows["joint_1"]["damage"]) == pytest.approx(float(rows["ship"]["damage"]), rel=1e-6)
    assert float(rows["ship"]["damage_per_hour"]) > float(rows["vehicle"]["damage_per_hour"]) > 0
    assert fatigue.main([str(tmp_path / "run"), "--curve", "0:5"]) == 2
    assert fatigue.main([str(tmp_path / "nowhere")]) == 2


def test_a_bag_counts_as_the_same_histories_in_a_run_folder(tmp_path):
    import rosbag
    from tow_sim.msg import CableState

    t = [0.5 * k for k in range(200)]
    ship = [40e3 + 5e3 * math.sin(0.7 * x) + 1e3 * math.sin(2.3 * x) for x in t]
    vehicle = [10e3 + 2e3 * math.cos(0.7 * x) for x in t]
    joints = [[s - 100.0 * j * (1.0 + math.sin(0.1 * x)) for j in range(4)] for s, x in zip(ship, t)]
    bag_path = tmp_path / "tow.bag"
    with rosbag.Bag(str(bag_path), "w") as bag:
        for k, x in enumerate(t):
            m = CableState()
            m.header.stamp = type(m.header.stamp).from_sec(100.0 + x)
            m.tension_ship, m.tension_vehicle, m.tension = ship[k], vehicle[k], joints[k]
            for _ in range(2 if k == 50 else 1):  # a state the node held and published again: counted once
                bag.write("/tow_sim/cable/state", m, m.header.stamp)
    # The same histories as a batch run's folder (joint 1 the tow point).
    run = tmp_path / "run"
    run.mkdir()
    with open(run / "timeseries.csv", "w") as f:
        f.write("t,tension_ship,tension_vehicle\n")
        f.writelines(f"{x!r},{s!r},{v!r}\n" for x, s, v in zip(t, ship, vehicle))
    with open(run / "shapes.csv", "w") as f:
        f.write("t,joint,tension\n")
        f.writelines(f"{x!r},{j + 1},{tension[j]!r}\n" for x, tension in zip(t, joints) for j in range(4))
    assert fatigue.main([str(bag_path), "--breaking-load", "200000", "--from", "10"]) == 0
    assert fatigue.main([str(run), "--breaking-load", "200000", "--from", "10"]) == 0
    with open(tmp_path / "tow" / "fatigue.csv") as f:
        from_bag = list(csv.DictReader(f))
    with open(run / "fatigue.csv") as f:
        from_run = list(csv.DictReader(f))
    assert [r["location"] for r in from_bag] == ["ship", "vehicle", "joint_1", "joint_2", "joint_3", "joint_4"]
    assert from_bag == from_run and float(from_bag[0]["cycles"]) > 10
    # A bag has no configuration: the breaking load must be given.
    assert fatigue.main([str(bag_path)]) == 2
    # Counting from past the bag's last message leaves nothing to count, as it does for a run folder.
    assert fatigue.main([str(bag_path), "--breaking-load", "200000", "--from", "1000"]) == 0
    assert fatigue.main([str(run), "--breaking-load", "200000", "--from", "1000"]) == 0
    header = "location,samples,cycles,max_range,mean_tension,damage,damage_per_hour,life_hours\n"
    with open(tmp_path / "tow" / "fatigue.csv") as f, open(run / "fatigue.csv") as g:
        assert f.read() == g.read() == header
