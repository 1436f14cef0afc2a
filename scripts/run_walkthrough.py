#!/usr/bin/env python3
"""Runs a walk-through's commands as the document writes them, so that it cannot go stale.

    run_walkthrough.py DOC.md WORKSPACE

Each ```bash block preceded by a marker comment runs, in order, in one scratch HOME:

    <!-- walkthrough: background -->   a terminal left running (roslaunch, rosbag play)
    <!-- walkthrough: run SECONDS -->  a command that must exit 0 within SECONDS

Blocks without a marker are shown to the reader only. The workspace's devel/setup.bash is sourced first
(as the document asks the reader to), ROS_MASTER_URI gets a free port of its own (roslaunch starts the
master there) and DISPLAY is unset (rviz, if started, fails alone: it is not required). The background
terminals are stopped with SIGINT at the end, as Ctrl-C would. Exit status 0 if every run block passed.
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
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    doc, workspace = sys.argv[1], os.path.abspath(sys.argv[2])
    with open(doc) as f:
        steps = blocks(f.read())
    if not steps:
        sys.exit(f"{doc}: no <!-- walkthrough: ... --> blocks")
    home = tempfile.mkdtemp(prefix="tow_sim_walkthrough_")
    env = dict(os.environ, HOME=home, ROS_MASTER_URI=f"http://localhost:{free_port()}",
               PATH="/usr/bin:/bin:" + os.environ.get("PATH", ""), ROS_HOME=os.path.join(home, ".ros"))
    env.pop("DISPLAY", None)
    prologue = f"set -e\nsource {workspace}/devel/setup.bash\ncd \"$HOME\"\n"
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
