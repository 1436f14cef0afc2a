"""The Python module tow_sim (docs/python.md) against the command-line tools' output.

Run by `catkin_make run_tests` (pytest-python.xml) with TOW_SIM_SOURCE_DIR and TOW_SIM_BIN (the tools) set,
after sourcing the workspace.
"""
import csv
import glob
import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest
import yaml

import tow_sim

SOURCE = os.environ.get("TOW_SIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BIN = os.environ.get("TOW_SIM_BIN", "")
CONFIG = os.path.join(SOURCE, "config", "tow_sim.yaml")
SCENARIOS = sorted(
    p for p in glob.glob(os.path.join(SOURCE, "scenarios", "*.yaml")) if not os.path.basename(p).startswith("bathymetry_")
)
SECONDS = 40.0  # of each shipped scenario, in both the batch and the module


def read_csv(path):
    """The CSV's columns as float arrays, NaN for a blank cell."""
    with open(path) as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: np.array([float(r[i]) if r[i] else np.nan for r in body]) for i, name in enumerate(header)}


def shortened(path, tmp_path):
    """The scenario with every default filled in (absolute file names) and its duration cut to SECONDS."""
    doc = yaml.safe_load(tow_sim.load_scenario(path).to_yaml())
    doc["simulation"]["duration"] = min(SECONDS, float(doc["simulation"]["duration"]))
    out = tmp_path / os.path.basename(path)
    out.write_text(yaml.safe_dump(doc))
    return str(out)


def assert_columns_close(got, want, rtol):
    """Each column of `want` in `got`: NaN where it is NaN, elsewhere within rtol of the column's scale."""
    assert list(got) == list(want)
    for name, expected in want.items():
        actual = np.asarray(got[name])
        assert actual.shape == expected.shape, name
        assert np.array_equal(np.isnan(actual), np.isnan(expected)), name
        scale = max(1.0, np.nanmax(np.abs(expected), initial=0.0))
        err = np.nanmax(np.abs(actual - expected), initial=0.0)
        assert err <= rtol * scale, f"{name}: off by {err:.3g} (scale {scale:.3g})"


@pytest.mark.parametrize("path", SCENARIOS, ids=lambda p: os.path.basename(p)[:-5])
def test_a_scenarios_series_is_the_batch_runners_csv(path, tmp_path):
    scenario = shortened(path, tmp_path)
    out = tmp_path / "out"
    subprocess.run(
        [os.path.join(BIN, "tow_sim_batch"), "--scenario", scenario, "--out", str(out), "--precision", "17"],
        check=True,
        capture_output=True,
    )
    sc = tow_sim.load_scenario(scenario)
    series = tow_sim.Run(sc).run(until=sc.duration, every=sc.output_interval)
    assert_columns_close(series, read_csv(out / "timeseries.csv"), 1e-12)


def test_a_run_continued_in_pieces_gives_the_same_rows_once_each():
    sc = tow_sim.load_scenario(os.path.join(SOURCE, "scenarios", "turn_180.yaml"))
    whole = tow_sim.Run(sc).run(until=30.0, every=1.0)
    run = tow_sim.Run(sc)
    first, second = run.run(until=12.0, every=1.0), run.run(until=30.0, every=1.0)
    assert list(first["t"]) == list(range(13)) and list(second["t"]) == list(range(13, 31))
    for name in whole:
        assert np.array_equal(np.concatenate([first[name], second[name]]), whole[name], equal_nan=True), name
    s = run.snapshot()
    assert s.t == 30.0 and s.joints.shape == (s.segments + 2, 3) and s.tensions.shape == (s.segments + 1, 3)
    assert s.depth == pytest.approx(whole["depth"][-1], rel=1e-12)


def test_set_fins_differential_rolls_a_rolling_vehicle_to_port():
    # The same as the scenario's differential command: a roll command that reaches the vehicle, refused as NaN.
    sc = tow_sim.load_scenario(os.path.join(SOURCE, "scenarios", "rolling_towfish.yaml"))
    run = tow_sim.Run(sc)
    run.advance_to(10.0)
    assert run.set_fins(differential=0.05) is False
    rolled = run.run(until=40.0, every=1.0)
    assert rolled["vehicle_roll"][-1] < -0.05  # port side down, several degrees
    with pytest.raises(ValueError, match="differential"):
        run.set_fins(differential=float("nan"))


def test_the_steady_tow_is_tow_sim_charts(tmp_path):
    subprocess.run(
        [os.path.join(BIN, "tow_sim_chart"), "--config", CONFIG, "--speeds", "1:3:1", "--cable-out", "300:500:200",
         "--out", str(tmp_path), "--no-plot"],
        check=True,
        capture_output=True,
    )
    want = read_csv(tmp_path / "chart.csv")
    cfg = tow_sim.load_config(CONFIG)
    chart = tow_sim.towing_chart(cfg, speeds=[1.0, 2.0, 3.0], cable_outs=[300.0, 500.0])
    assert chart["converged"].all() and chart["converged"].dtype == bool
    numbers = {k: v for k, v in chart.items() if k not in ("converged", "error")}
    assert_columns_close(numbers, {k: v for k, v in want.items() if k != "converged"}, 1e-9)  # the CSV's 10 digits
    eq = tow_sim.steady_tow(cfg, speed=2.0, cable_out=500.0)
    assert (eq.depth, eq.layback, eq.tension_ship) == (chart["depth"][4], chart["layback"][4], chart["tension_ship"][4])
    # The steady tow's joints: from the tow point at the surface down to the vehicle, tensions balancing.
    assert eq.joints[0, 2] == pytest.approx(0.0, abs=1e-9) and eq.joints[-1, 2] < -100.0
    assert np.linalg.norm(eq.tensions[0]) == pytest.approx(eq.tension_ship, rel=1e-12)


def test_a_plan_puts_the_vehicle_at_the_target_depth():
    cfg = tow_sim.load_config(CONFIG)
    plan = tow_sim.plan_cable_out(cfg, speed=2.0, target_depth=100.0)
    assert plan["reachable"] and abs(plan["depth"] - 100.0) <= 0.01
    assert tow_sim.steady_tow(cfg, speed=2.0, cable_out=plan["cable_out"]).depth == pytest.approx(plan["depth"], rel=1e-12)
    far = tow_sim.plan_cable_out(cfg, speed=2.0, target_depth=5000.0)
    assert not far["reachable"] and "out of reach" in far["reason"]


def test_a_dict_is_read_as_the_file_with_its_content():
    with open(CONFIG) as f:
        doc = yaml.safe_load(f)
    from_file, from_dict = tow_sim.load_config(CONFIG), tow_sim.Config.from_dict(doc)
    assert from_dict.keys() == from_file.keys()
    doc["cable"]["length"] = 321.5
    doc["cable"]["segments"] = np.int64(64)  # NumPy's numbers are numbers
    changed = tow_sim.Config.from_dict(doc)
    assert changed.cable_length == 321.5 and changed.segments == 64
    assert tow_sim.Config.from_yaml(from_file.to_yaml()).keys() == from_file.keys()


@pytest.mark.parametrize(
    "doc, words",
    [
        ({"cabel": {"length": 300.0}}, ["cabel", "did you mean", "cable"]),
        ({"cable": {"lenght": 300.0}}, ["cable.lenght", "length"]),
        ({"cable": {"length": -3.0}}, ["cable.length", "-3", "(0, 100000]"]),
        ({"cable": {"sections": [{"length": 500.0, "segments": 10, "diamter": 0.02}]}}, ["cable.sections[0].diamter"]),
        ({"vehicle": {"mass": object()}}, ["vehicle.mass", "not a value"]),
    ],
)
def test_a_bad_configuration_is_a_value_error_naming_the_key(doc, words):
    with pytest.raises(ValueError) as error:
        tow_sim.Config.from_dict(doc)
    for word in words:
        assert word in str(error.value)


def test_bad_run_input_is_a_value_error_naming_it():
    cfg = tow_sim.load_config(CONFIG)
    with pytest.raises(ValueError, match=r"commands\[0\]\.ruder: unknown key"):
        tow_sim.Run(cfg, commands=[{"t": 1.0, "ruder": 0.1}])
    with pytest.raises(ValueError, match="current = .*three numbers"):
        tow_sim.steady_tow(cfg, speed=2.0, current=[0.1, 0.0])
    run = tow_sim.Run(cfg, speed=2.0, duration=20.0)
    with pytest.raises(ValueError, match="past the end of the ship's track"):
        run.advance_to(25.0)
    run.advance_to(5.0)  # the run goes on after a refusal
    assert run.time == pytest.approx(5.0)
    with pytest.raises(ValueError, match="scenario|simulation|duration"):
        tow_sim.Scenario.from_dict({"simulation": {"duration": -1.0}})


def test_a_ship_given_sample_by_sample_tows_as_the_scripted_one():
    cfg = tow_sim.load_config(CONFIG)
    t = np.arange(-2.0, 31.0)
    ship = {"t": t, "tow_point": np.c_[2.0 * t - 20.0, 0 * t, 0 * t], "velocity": np.c_[2.0 + 0 * t, 0 * t, 0 * t],
            "heading": 0 * t}
    sampled = tow_sim.Run(cfg, ship=ship)
    sampled.advance_to(0.0)
    straight = tow_sim.Run(cfg, speed=2.0, duration=30.0)  # the tow point 20 m aft of the ship's reference point
    a, b = sampled.run(until=30.0, every=10.0), straight.run(until=30.0, every=10.0)
    assert np.allclose(a["depth"], b["depth"], rtol=1e-6) and np.allclose(a["vehicle_x"], b["vehicle_x"], rtol=1e-6)
    sampled.add_ship_sample(31.0, [42.0, 0.0, 0.0], [2.0, 0.0, 0.0], 0.0)
    sampled.advance_to(31.0)
    with pytest.raises(ValueError, match="after the newest sample"):
        sampled.add_ship_sample(30.5, [41.0, 0.0, 0.0], [2.0, 0.0, 0.0], 0.0)


def test_runs_in_threads_give_the_sequential_results_and_release_the_gil():
    sc = tow_sim.load_scenario(os.path.join(SOURCE, "scenarios", "zigzag.yaml"))
    until = 600.0  # long enough (about 0.3 s a run here) for the main thread to wake dozens of times
    sequential = [tow_sim.Run(sc).run(until=until, every=1.0) for _ in range(2)]
    threaded, started, wakeups = [None, None], threading.Event(), [0]

    def work(i):
        run = tow_sim.Run(sc)
        started.set()
        threaded[i] = run.run(until=until, every=1.0)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for th in threads:
        th.start()
    started.wait()
    begun = time.perf_counter()
    while any(th.is_alive() for th in threads):
        time.sleep(0.005)  # wakes only when the runs let go of the GIL
        wakeups[0] += 1
    stepped = time.perf_counter() - begun
    for got in threaded:
        for name, want in sequential[0].items():
            assert np.array_equal(got[name], want, equal_nan=True), name
    assert wakeups[0] >= 20, (f"the main thread woke {wakeups[0]} times in the {stepped:.3f} s two runs stepped: "
                              "the GIL was held")


def test_two_threads_first_runs_at_once_in_a_fresh_interpreter_finish():
    # The first arrays a process makes initialise pybind11's NumPy API; when two threads made theirs at once it
    # deadlocked (one held the GIL waiting for the initialisation, the other waited inside it for the GIL).
    script = (
        "import threading, tow_sim\n"
        f"sc = tow_sim.load_scenario({os.path.join(SOURCE, 'scenarios', 'zigzag.yaml')!r})\n"
        "threads = [threading.Thread(target=lambda: tow_sim.Run(sc).run(until=5.0, every=1.0)) for _ in range(2)]\n"
        "for th in threads:\n    th.start()\n"
        "for th in threads:\n    th.join()\n"
        "print('done')\n")
    for attempt in range(3):  # a race: a fresh interpreter each time
        out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
        assert out.returncode == 0 and out.stdout.strip() == "done", (attempt, out.stdout, out.stderr)


def test_bad_values_are_refused_naming_them_and_the_run_goes_on():
    cfg = tow_sim.load_config(CONFIG)
    run = tow_sim.Run(cfg, speed=2.0, duration=60.0)
    run.advance_to(10.0)
    nan = float("nan")
    refusals = [
        (lambda: run.advance_to(5.0), "not before the run's time"),
        (lambda: run.advance_to(-1.0), "not before the run's time"),
        (lambda: run.advance_to(nan), "must be finite"),
        (lambda: run.run(until=5.0), "before the run's time"),
        (lambda: run.run(until=20.0, every=0.0), "every = 0"),
        (lambda: run.set_fins(rudder=nan), "must be finite"),
        (lambda: run.set_current([nan, 0.0, 0.0]), r"environment.current\[0\]"),
        (lambda: run.set_winch(0.5), "winch.enabled"),
        (lambda: tow_sim.Config.from_dict({"cable": {"length": nan}}), "cable.length"),
        (lambda: tow_sim.Config.from_dict({"cable": {"segments": "many"}}), "cable.segments"),
        (lambda: tow_sim.Config.from_dict({"cable": {"length": [1.0]}}), "cable.length"),
        (lambda: tow_sim.Config.from_yaml("cable: {length: [1"), "cannot read the YAML text"),
        (lambda: tow_sim.Run(cfg, commands=[{"t": "soon"}]), r"commands\[0\]\.t = 'soon': must be a finite number"),
        (lambda: tow_sim.Run(cfg, commands=[{"t": nan}]), r"commands\[0\]\.t = nan"),
        (lambda: tow_sim.Run(cfg, speed=nan), "speed = nan"),
        (lambda: tow_sim.Run(cfg, ship=5), "ship: must be a dict"),
        (lambda: tow_sim.Run(cfg, ship={"t": [0.0, 1.0]}), "ship: needs the key 'tow_point'"),
        (lambda: tow_sim.Run(cfg, ship={"t": [0, 1], "tow_point": [[0, 0]], "velocity": [], "heading": []}), "ship:"),
        (lambda: tow_sim.steady_tow(cfg, speed=nan), "speed nan m/s.*must be finite"),
        (lambda: tow_sim.steady_tow(cfg, speed=2.0, cable_out=-5.0), r"cable out in \(0, 100000\] m"),
        (lambda: tow_sim.load_config("/nonexistent/tow_sim.yaml"), "/nonexistent/tow_sim.yaml"),
    ]
    for call, words in refusals:
        with pytest.raises(ValueError, match=words):
            call()
    chart = tow_sim.towing_chart(cfg, speeds=[nan, 2.0], cable_outs=[300.0])
    assert list(chart["converged"]) == [False, True] and "must be finite" in chart["error"][0]
    run.advance_to(12.0)  # the run went on from its last good state
    assert run.snapshot().t == pytest.approx(12.0) and np.isfinite(run.snapshot().joints).all()


def test_the_modes_are_tow_sim_modes(tmp_path):
    config = tmp_path / "c.yaml"
    config.write_text("cable: {length: 200.0, segments: 40}\n")
    subprocess.run([os.path.join(BIN, "tow_sim_modes"), "--config", str(config), "--speed", "0.2", "--count", "12",
                    "--out", str(tmp_path)], check=True, capture_output=True)
    with open(tmp_path / "modes.csv") as f:
        want = list(csv.DictReader(f))
    got = tow_sim.modes(tow_sim.load_config(str(config)), speed=0.2)  # every mode: the dense eigenproblem
    # 82 angles: one mode per complex pair of eigenvalues, one per real eigenvalue (a mode that only decays)
    assert 2 * 41 <= len(got) <= 4 * 41 and got[0]["shape"].shape == (41, 3)
    lowest = tow_sim.modes(tow_sim.load_config(str(config)), speed=0.2, count=12)  # the tool's: by Arnoldi
    assert len(lowest) == len(want) == 12
    for row, mode, dense in zip(want, lowest, got):
        for key in ("period", "frequency", "damping_ratio"):
            assert mode[key] == pytest.approx(float(row[key]), rel=1e-9), key
            assert mode[key] == pytest.approx(dense[key], rel=1e-6), key
        assert mode["dominant"] == row["dominant"] == dense["dominant"]
    with pytest.raises(ValueError, match="count"):
        tow_sim.modes(tow_sim.load_config(str(config)), speed=0.2, count=0)
    yaw = next(m for m in got if m["dominant"] == "vehicle yaw")
    assert 6.0 < yaw["period"] < 7.0 and 0.0 < yaw["damping_ratio"] < 0.1  # test_modes rings it in the time domain


def test_the_response_is_tow_sim_responses(tmp_path):
    subprocess.run([os.path.join(BIN, "tow_sim_response"), "--config", CONFIG, "--speed", "2", "--input", "pitch",
                    "--periods", "4:12:4", "--out", str(tmp_path)], check=True, capture_output=True)
    want = read_csv(tmp_path / "response.csv")
    got = tow_sim.response(tow_sim.load_config(CONFIG), speed=2.0, input="pitch", periods=[4.0, 8.0, 12.0])
    assert list(got["period"]) == [4.0, 8.0, 12.0]
    for name in ("vehicle_heave", "vehicle_pitch", "tension_ship", "tension_vehicle"):
        assert np.allclose(np.abs(got[name]), want[name], rtol=1e-9), name
        assert np.allclose(np.degrees(np.angle(got[name])), want[name + "_phase"], atol=1e-7), name
    # The ship's pitch moves the tow point 20 m aft of its reference point by 20 m per radian: 20x heave.
    heave = tow_sim.response(tow_sim.load_config(CONFIG), speed=2.0, input="heave", periods=[4.0, 8.0, 12.0])
    assert np.allclose(got["vehicle_heave"], 20.0 * heave["vehicle_heave"], rtol=1e-6)
    with pytest.raises(ValueError, match="input 'roll': one of heave, surge, sway, pitch"):
        tow_sim.response(tow_sim.load_config(CONFIG), speed=2.0, input="roll", periods=[4.0])


def assert_plots(folder, png):
    """tow_sim_plot draws the analysis's plot from its folder."""
    subprocess.run([sys.executable, os.path.join(SOURCE, "scripts", "tow_sim_plot"), str(folder)], check=True,
                   capture_output=True)
    assert os.path.getsize(os.path.join(folder, png)) > 5000


TWO_PART = """cable:
  diameter: 0.0173
  mass_per_length: 1.2
  sections:
    - {length: 600.0, segments: 60}
    - {length: 100.0, segments: 20, diameter: 0.02, mass_per_length: 0.35}
  bodies:
    - {at: 600.0, mass: 1000.0, displaced_volume: 0.13, drag_area: 0.4, added_mass: 100.0}
"""


def test_the_strumming_analysis_is_tow_sim_strummings(tmp_path):
    config = tmp_path / "c.yaml"
    config.write_text(TWO_PART)
    subprocess.run([os.path.join(BIN, "tow_sim_strumming"), "--config", str(config), "--speed", "2", "--current",
                    "0.3:90", "--bandwidth", "0.25", "--out", str(tmp_path)], check=True, capture_output=True)
    rows, spans = read_csv(tmp_path / "strumming.csv"), read_csv(tmp_path / "strumming_spans.csv")
    got = tow_sim.strumming(tow_sim.load_config(str(config)), speed=2.0, current=(0.0, 0.3, 0.0), bandwidth=0.25)
    assert got["bandwidth"] == 0.25 and len(got["segments"]["tension"]) == 80 and len(got["spans"]["start"]) == 2
    for name, values in got["segments"].items():
        assert np.allclose(values, rows[name], rtol=1e-8, atol=1e-12), name
    for name, values in got["spans"].items():
        assert np.allclose(values, spans[name], rtol=1e-8, atol=1e-12), name
    assert list(got["segments"]["section"][58:62]) == [0, 0, 1, 1] and spans["end"][0] == pytest.approx(600.0)
    # The cross current sheds vortices all along; the tether below the clump is a string of its own.
    assert (got["segments"]["shedding_frequency"] > 0).all() and (got["spans"]["dominant_mode"] > 0).all()
    with pytest.raises(ValueError, match="bandwidth"):
        tow_sim.strumming(tow_sim.load_config(str(config)), speed=2.0, bandwidth=1.0)
    assert_plots(tmp_path, "strumming.png")


def test_a_strumming_cable_tows_shallower():
    bare = tow_sim.Config.from_dict({"cable": {"length": 300.0, "segments": 30}})
    strums = tow_sim.Config.from_dict({"cable": {"length": 300.0, "segments": 30, "strumming": "vandiver"}})
    a, b = tow_sim.steady_tow(bare, speed=2.0), tow_sim.steady_tow(strums, speed=2.0)
    assert b.depth < 0.9 * a.depth  # more normal drag: a flatter cable
    assert tow_sim.strumming(strums, speed=2.0)["segments"]["drag_amplification"][0] == pytest.approx(
        1.0 + 1.043 * 2.0 ** 0.325)
    with pytest.raises(ValueError, match="cable.strumming_amplitude"):
        tow_sim.Config.from_dict({"cable": {"strumming": "blevins", "strumming_amplitude": 0.0}})


def test_the_sea_state_is_tow_sim_responses(tmp_path):
    scenario = os.path.join(SOURCE, "scenarios", "head_seas.yaml")
    subprocess.run([os.path.join(BIN, "tow_sim_response"), "--scenario", scenario, "--cable-out", "200",
                    "--out", str(tmp_path)], check=True, capture_output=True)
    want = read_csv(tmp_path / "sea_state.csv")
    got = tow_sim.sea_state(tow_sim.load_scenario(scenario), cable_out=200.0)
    assert got["speed"] == 2.0 and len(got["components"]["frequency"]) == 100
    for name in ("frequency", "encounter_frequency", "amplitude"):
        assert np.allclose(got["components"][name], want[name], rtol=1e-9), name
    amplitude = got["components"]["amplitude"]
    for name, values in got["components"].items():
        if values.dtype == complex:
            assert np.allclose(amplitude * np.abs(values), want[name], rtol=1e-8, atol=1e-15), name
            phase = np.degrees(np.angle(values)) - np.array(want[name + "_phase"])
            assert np.allclose((phase + 180.0) % 360.0 - 180.0, 0.0, atol=1e-6), name
    # Head seas: the ship meets the waves faster than they come; the standard deviations sum the components.
    assert (got["components"]["encounter_frequency"] > got["components"]["frequency"]).all()
    heave = got["components"]["vehicle_heave"]
    assert got["standard_deviation"]["vehicle_heave"] == pytest.approx(np.sqrt(np.sum(0.5 * amplitude**2 *
                                                                                       np.abs(heave)**2)))
    calm = tow_sim.Scenario.from_dict({"ship": {"manoeuvres": [{"type": "straight", "speed": 2.0}]}})
    with pytest.raises(ValueError, match="a sea state needs waves"):
        tow_sim.sea_state(calm)
    assert_plots(tmp_path, "sea_state.png")
