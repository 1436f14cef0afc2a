"""The scripts in scripts/ answer -h and --help with their usage and nothing else; the shell scripts refuse
unknown options and a bad SECONDS before anything runs."""
import os
import subprocess
import time

import pytest

SOURCE = os.environ.get("TOW_SIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
SHELL_SCRIPTS = ["check_install.sh", "install_deps.sh", "record_demo.sh", "record_golden.sh", "run_all_tests.sh",
                 "rviz_screenshot.sh"]
SCRIPTS = SHELL_SCRIPTS + ["tow_sim_rviz", "tow_sim_plot", "tow_sim_sweep", "tow_sim_fatigue"]
# A script that started its real work (roslaunch, apt-get, catkin_make, a batch run) takes longer than this.
HELP_SECONDS = 5


def run(script, *args, tmp_path):
    """Runs scripts/SCRIPT ARGS in tmp_path with the workspace pointed there; (exit status, stdout, stderr, s)."""
    env = dict(os.environ, WS=str(tmp_path / "ws"), ROS_HOME=str(tmp_path / "ros_home"))
    start = time.monotonic()
    done = subprocess.run([os.path.join(SOURCE, "scripts", script), *args], cwd=tmp_path, env=env,
                          stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=20)
    return done.returncode, done.stdout, done.stderr, time.monotonic() - start


@pytest.mark.parametrize("flag", ["--help", "-h"])
@pytest.mark.parametrize("script", SCRIPTS)
def test_help_prints_the_usage_and_exits_without_doing_anything_else(script, flag, tmp_path):
    status, out, err, seconds = run(script, flag, tmp_path=tmp_path)
    assert status == 0, err
    lines = out.splitlines()
    assert lines and lines[0].startswith("usage: ") and script in lines[0], out
    assert len(lines) > 2, out  # more than the usage line: what the script does
    assert seconds < HELP_SECONDS
    assert os.listdir(tmp_path) == []  # no workspace, output or ROS home made
    if script in SHELL_SCRIPTS:
        assert err == ""
        assert "-h, --help" in out
        assert out == header(script)  # one source of truth


def header(script):
    """The comment at the top of a shell script (after #!) without its "# "."""
    lines = []
    with open(os.path.join(SOURCE, "scripts", script)) as f:
        for line in list(f)[1:]:
            if not line.startswith("#"):
                break
            lines.append(line[2:] if line.startswith("# ") else line[1:])
    return "".join(lines)


@pytest.mark.parametrize("script, args", [("record_demo.sh", ["OUT", "--help"]),
                                          ("rviz_screenshot.sh", ["OUT.png", "5", "--help"]),
                                          ("check_install.sh", ["INSTALL", "-h"])])
def test_help_after_other_arguments_still_only_prints_the_usage(script, args, tmp_path):
    status, out, err, _ = run(script, *args, tmp_path=tmp_path)
    assert (status, err) == (0, "")
    assert out.startswith("usage: ")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("script", SHELL_SCRIPTS)
def test_an_unknown_option_is_refused(script, tmp_path):
    args = {"record_demo.sh": ["OUT", "5", "--bogus"], "rviz_screenshot.sh": ["--bogus", "5"]}.get(script, ["--bogus"])
    status, out, err, seconds = run(script, *args, tmp_path=tmp_path)
    assert status == 2
    assert out == ""
    assert err == f"{script}: unknown option '--bogus'; see --help\n"
    assert seconds < HELP_SECONDS
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("seconds", ["0", "0.0", "-3", "abc", "1m", "2,5"])
@pytest.mark.parametrize("script, first", [("record_demo.sh", "OUT"), ("rviz_screenshot.sh", "OUT.png")])
def test_a_bad_seconds_is_refused_naming_the_argument_and_its_range(script, first, seconds, tmp_path):
    status, out, err, _ = run(script, first, seconds, "straight", tmp_path=tmp_path)
    assert status == 2
    assert out == ""
    assert err.startswith(f"{script}: SECONDS must be a number of seconds > 0")
    assert f"'{seconds}'" in err
    assert ("'markers'" in err) == (script == "rviz_screenshot.sh")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("script, what", [("record_demo.sh", "OUT_DIR"), ("rviz_screenshot.sh", "OUT.png"),
                                          ("check_install.sh", "INSTALL_DIR")])
def test_a_missing_first_argument_is_refused(script, what, tmp_path):
    status, out, err, _ = run(script, tmp_path=tmp_path)
    assert (status, out) == (2, "")
    assert err == f"{script}: {what} missing; see --help\n"
