"""tow_sim_sweep through the Python module in process against the same sweep run as tow_sim_batch processes."""
import csv
import os
import subprocess

SOURCE = os.environ.get("TOW_SIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BIN = os.environ.get("TOW_SIM_BIN", "")
SWEEP = os.path.join(SOURCE, "scripts", "tow_sim_sweep")
SWEEP_FILE = """scenario:
  cable: {length: 150.0, segments: 15}
  ship: {manoeuvres: [{type: turn, speed: 2.0, radius: 200.0, angle: 1.0}]}
  simulation: {duration: 20.0, output_interval: 1.0, shape_interval: 10.0}
grid:
  cable.length: [150.0, -1.0]
  ship.manoeuvres[0].speed: [1.5, 2.5]
"""


def summary(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        del r["wall_time_s"]
    return rows


def test_in_process_runs_write_what_the_processes_write(tmp_path):
    (tmp_path / "sweep.yaml").write_text(SWEEP_FILE)
    common = ["/usr/bin/python3", SWEEP, str(tmp_path / "sweep.yaml"), "--jobs", "2"]
    module = subprocess.run(common + ["--out", str(tmp_path / "module")], capture_output=True, text=True)
    tool = subprocess.run(common + ["--out", str(tmp_path / "tool"), "--batch", os.path.join(BIN, "tow_sim_batch")],
                          capture_output=True, text=True)
    assert module.returncode == tool.returncode == 1, module.stderr + tool.stderr  # two runs are refused
    a, b = summary(tmp_path / "module" / "summary.csv"), summary(tmp_path / "tool" / "summary.csv")
    assert a == b
    assert [r["status"] for r in a] == ["ok", "ok", "refused", "refused"]
    assert "cable.length = -1" in a[2]["error"]
    for run in ("0000", "0001"):
        for name in ("timeseries.csv", "shapes.csv", "scenario.yaml", "events.csv"):
            got = (tmp_path / "module" / "runs" / run / name).read_text().splitlines()
            want = (tmp_path / "tool" / "runs" / run / name).read_text().splitlines()
            if name == "scenario.yaml":  # its first line names the input file, in each sweep's own folder
                got, want = got[1:], want[1:]
            assert got == want, (run, name)
