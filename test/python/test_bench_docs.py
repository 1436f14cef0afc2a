"""scripts/bench_docs.py: the steppers' tables of docs/benchmarks.md written from a benchmark run."""
import importlib.util
import json
import os

import pytest

SOURCE = os.environ.get("TOW_SIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
_spec = importlib.util.spec_from_file_location("bench_docs", os.path.join(SOURCE, "scripts", "bench_docs.py"))
bench_docs = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench_docs)

DOC = """# Benchmarks

Prose before.

<!-- bench:steppers -->
an old table
<!-- /bench -->

Prose between, 2035× typed by hand stays prose.

<!-- bench:steppers-more -->
<!-- /bench -->

<!-- bench:rhs -->
<!-- /bench -->

<!-- bench:chart -->
<!-- /bench -->

<!-- bench:python -->
an old output
<!-- /bench -->

Prose after.
"""

PYTHON = """bench_python: commit def5678 with local changes, 2026-12-04, 2 cores, load average 0.31
600 s of turn_180 at nu = 100, whole processes (median of 5):
  tow_sim_batch 0.598 s, python3 + tow_sim.Run.run 0.749 s: ratio 1.253
"""


def run_of(entries, bench="bench_steppers", date="2026-12-05T20:44:38+00:00"):
    benchmarks = []
    for name, counters in entries.items():
        suffix = "/iterations:5" if bench == "bench_steppers" else ""
        benchmarks.append(dict({"name": name + suffix, "run_type": "iteration"}, **counters))
    return {"context": {"date": date, "executable": "devel/lib/tow_sim/" + bench, "num_cpus": 2,
                        "mhz_per_cpu": 2695, "load_avg": [0.5, 1.0, 1.5]},
            "benchmarks": benchmarks}


RUN = run_of({
    "steady/implicit/nu:100": {"realtime": 2035.4},
    "turn/implicit/nu:1000": {"realtime": 98.92},
    "steady/rk4/nu:50": {"realtime": 1560.2, "step_ms": 108.0},
    "deep6km/dopri5/nu:1000": {"realtime": 7.31},
    "parted/implicit_elastic_ea1e8/nu:100": {"realtime": 0.8912},
    "two_part/implicit/nu:600+100": {"realtime": 409.3},
})
CHAIN = run_of({"BM_RhsSweep/100": {"cpu_time": 20.0, "time_unit": "us"},
                "BM_RhsSweep/1000": {"cpu_time": 199.0, "time_unit": "us"},
                "BM_RhsDense/10": {"cpu_time": 95123.0, "time_unit": "ns"}}, bench="bench_chain")
CHART = run_of({"BM_TowingChart20x10": {"cpu_time": 84.2, "time_unit": "ms"}}, bench="bench_chart")
RUNS = [RUN, CHAIN, CHART]


def table_rows(text, marker):
    block = text.split(f"<!-- bench:{marker} -->")[1].split("<!-- /bench -->")[0]
    return [line for line in block.splitlines() if line.startswith("|")]


def test_each_figure_lands_in_its_row_and_column_and_the_rest_are_dashes(tmp_path):
    doc = tmp_path / "benchmarks.md"
    doc.write_text(DOC)
    bench_docs.write_doc(str(doc), RUNS, "abc1234")
    text = doc.read_text()
    rows = table_rows(text, "steppers")
    head = [c.strip() for c in rows[0].strip("|").split("|")]
    assert head[:3] == ["ν", "steady dopri5", "steady rk4"]
    by_nu = {r.strip("|").split("|")[0].strip(): [c.strip() for c in r.strip("|").split("|")] for r in rows[2:]}
    assert by_nu["100"][head.index("steady implicit")] == "2035×"
    assert by_nu["1000"][head.index("turn implicit")] == "98.9×"
    assert by_nu["50"][head.index("steady rk4")] == "1560× (108 ms)"
    assert by_nu["deep 6 km, ν = 1000"][head.index("steady dopri5")] == "7.31×"
    assert by_nu["2000"][head.index("steady implicit")] == "—"
    more = "\n".join(table_rows(text, "steppers-more"))
    assert "| parted elastic cable, 0.10-0.13 s after the parting, implicit | 100 | 0.891× |" in more
    assert "| two-part deep tow, implicit | 600+100 | 409× |" in more
    assert "| its armoured cable alone, implicit | 700 | — |" in more
    rhs = table_rows(text, "rhs")
    assert "| 100 | 20 µs | — |" in rhs
    assert "| 10 | — | 95.1 µs |" in rhs
    assert "| 5000 | — | — |" in rhs
    assert "The sweep at ν = 1000 costs 9.95× its cost at ν = 100." in text
    assert "The 200 steady tows of the chart: 84.2 ms of CPU." in text


def test_the_provenance_names_commit_date_and_machine_and_prose_is_untouched(tmp_path):
    doc = tmp_path / "benchmarks.md"
    doc.write_text(DOC)
    bench_docs.write_doc(str(doc), RUNS, "abc1234")
    text = doc.read_text()
    assert text.count("at commit abc1234 on 2026-12-05 (2 CPUs at 2695 MHz, load average 0.50 at the start)") == 4
    assert "from `bench_chain` at commit" in text.split("<!-- bench:rhs -->")[1].split("<!-- /bench -->")[0]
    assert "an old table" not in text
    for prose in ("Prose before.", "Prose between, 2035× typed by hand stays prose.", "Prose after."):
        assert prose in text
    once = text
    bench_docs.write_doc(str(doc), RUNS, "abc1234")
    assert doc.read_text() == once  # a second write changes nothing


def test_the_python_block_is_bench_pythons_output_under_its_own_provenance(tmp_path):
    doc = tmp_path / "benchmarks.md"
    doc.write_text(DOC)
    bench_docs.write_doc(str(doc), RUNS, "abc1234", PYTHON)
    block = doc.read_text().split("<!-- bench:python -->")[1].split("<!-- /bench -->")[0]
    assert ("from `bench/bench_python.py` at commit def5678 with local changes on 2026-12-04 (2 CPUs, load "
            "average 0.31 at the start)") in block
    assert "```\n600 s of turn_180 at nu = 100, whole processes (median of 5):\n  tow_sim_batch 0.598 s," in block
    assert "an old output" not in block and "bench_python: commit" not in block
    doc.write_text(DOC)
    bench_docs.write_doc(str(doc), RUNS, "abc1234")  # no output given: the block is left as it is
    assert "an old output" in doc.read_text()
    doc.write_text(DOC)
    with pytest.raises(ValueError, match="bench_python: commit"):
        bench_docs.write_doc(str(doc), RUNS, "abc1234", "600 s of turn_180 ...\n")
    assert doc.read_text() == DOC


def test_a_saved_run_keeps_the_commit_it_ran_at(tmp_path):
    doc = tmp_path / "benchmarks.md"
    doc.write_text(DOC)
    saved = json.loads(json.dumps(RUN))
    saved["context"]["tow_sim_commit"] = "0ld0ld0"
    bench_docs.write_doc(str(doc), [saved], "abc1234")
    block = doc.read_text().split("<!-- bench:steppers -->")[1].split("<!-- /bench -->")[0]
    assert "at commit 0ld0ld0 on 2026-12-05" in block and "abc1234" not in block


def test_a_missing_marker_or_an_empty_run_is_refused_and_the_document_kept(tmp_path):
    doc = tmp_path / "benchmarks.md"
    doc.write_text(DOC.replace("<!-- bench:steppers-more -->\n", ""))
    before = doc.read_text()
    with pytest.raises(ValueError, match="bench:steppers-more"):
        bench_docs.write_doc(str(doc), RUNS, "abc1234")
    with pytest.raises(ValueError, match="a run of 'bench_other'"):
        bench_docs.write_doc(str(doc), [run_of({}, bench="bench_other")], "abc1234")
    assert doc.read_text() == before
    doc.write_text(DOC)
    with pytest.raises(ValueError, match="none of bench_steppers"):
        bench_docs.write_doc(str(doc), [run_of({"BM_Other": {"realtime": 1.0}})], "abc1234")
    saved = tmp_path / "run.json"
    saved.write_text(json.dumps(run_of({})))
    assert bench_docs.main(["unused", "--doc", str(doc), "--json", str(saved)]) == 2
    assert doc.read_text() == DOC


def test_the_shipped_document_has_every_block_filled():
    with open(os.path.join(SOURCE, "docs", "benchmarks.md"), encoding="utf-8") as f:
        text = f.read()
    for marker in ("rhs", "steppers", "steppers-more"):
        rows = table_rows(text, marker)
        assert len(rows) > 3, marker
        assert "Written by `scripts/bench_docs.py`" in text.split(f"<!-- bench:{marker} -->")[1]
    assert "The 200 steady tows of the chart:" in text
    python = text.split("<!-- bench:python -->")[1].split("<!-- /bench -->")[0]
    assert "from `bench/bench_python.py` at commit" in python and "tow_sim_sweep, 200 runs" in python
