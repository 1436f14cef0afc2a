#!/usr/bin/env python3
"""Runs a walk-through's commands as the document writes them, so that it cannot go stale.

    run_walkthrough.py DOC.md WORKSPACE [--cwd DIR]

Each ```bash block preceded by a marker comment runs, in order, in one scratch HOME:

    <!-- walkthrough: background -->   a terminal left running (roslaunch, rosbag play)
    <!-- walkthrough: run SECONDS -->  a command that must exit 0 within SECONDS

Blocks without a marker are shown to the reader only. The blocks run in DIR (default: the scratch HOME;
the README's commands run in the repository). The workspace's devel/setup.bash is sourced first (as the
document asks the reader to), ROS_MASTER_URI gets a free port of its own (roslaunch starts the master
there; after a background terminal the next block waits, up to 60 s, until the master answers, as a
reader waits for roslaunch) and DISPLAY is unset (rviz, if started, fails alone: it is not required).
The background terminals are stopped with SIGINT at the end, as Ctrl-C would. Exit status 0 if every run
block passed.
"""
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import time

MARKER = re.compile(r"<!--\s*walkthrough:\s*(background|run\s+(\d+))\s*-->\s*\n```bash\n(.*?)```", re.S)


def blocks(text):
    """(kind, timeout, script) for each marked block, in order."""
    return [("background" if m.group(1) == "background" else "run", int(m.group(2) or 0), m.group(3))
            for m in MARKER.finditer(text)]


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def wait_for_master(port, seconds=60.0):
    """Until something listens on the master's port (roslaunch starting it), or `seconds` have passed."""
    deadline = time.time() + seconds
    while time.time() < deadline:
        try:
            with socket.create_connection(("localhost", port), timeout=1.0):
                return
        except OSError:
            time.sleep(0.5)


def stop(process):
    """Ctrl-C to the terminal's process group, then SIGKILL if it has not ended within 20 s."""
    if process.poll() is not None:
        return
    os.killpg(process.pid, signal.SIGINT)
    try:
        process.wait(timeout=20)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()


def main():
    args = sys.argv[1:]
    cwd = None
    if len(args) == 4 and args[2] == "--cwd":
        cwd = os.path.abspath(args[3])
        args = args[:2]
    if len(args) != 2:
        sys.exit(__doc__)
    doc, workspace = args[0], os.path.abspath(args[1])
    with open(doc) as f:
        steps = blocks(f.read())
    if not steps:
        sys.exit(f"{doc}: no <!-- walkthrough: ... --> blocks")
    home = tempfile.mkdtemp(prefix="tow_sim_walkthrough_")
    port = free_port()
    env = dict(os.environ, HOME=home, ROS_MASTER_URI=f"http://localhost:{port}",
               PATH="/usr/bin:/bin:" + os.environ.get("PATH", ""), ROS_HOME=os.path.join(home, ".ros"))
    env.pop("DISPLAY", None)
    prologue = f"set -e\nsource {workspace}/devel/setup.bash\ncd \"{cwd or home}\"\n"
    terminals, failed = [], 0
    try:
        for i, (kind, timeout, script) in enumerate(steps, 1):
            print(f"--- block {i} ({kind}{' ' + str(timeout) + ' s' if timeout else ''}):\n{script.rstrip()}", flush=True)
            log = open(os.path.join(home, f"block{i}.log"), "w")
            p = subprocess.Popen(["bash", "-c", prologue + script], env=env, stdout=log, stderr=subprocess.STDOUT,
                                 start_new_session=True)
            if kind == "background":
                terminals.append(p)
                time.sleep(2.0)  # as a reader would open the next terminal
                wait_for_master(port)
                continue
            try:
                code = p.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                stop(p)
                code = "timed out"
            with open(log.name) as out:
                said = out.read()
            print(said[-3000:], flush=True)
            if code != 0:
                failed += 1
                print(f"--- block {i} FAILED ({code})", flush=True)
                break
    finally:
        for p in reversed(terminals):
            stop(p)
    if failed:
        for i in range(1, len(steps) + 1):
            path = os.path.join(home, f"block{i}.log")
            if os.path.exists(path):
                print(f"--- block {i}'s output (tail):")
                print(open(path).read()[-2000:])
    print(f"walkthrough {doc}: {len(steps)} blocks, {'FAILED' if failed else 'passed'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
