"""Stopping a command run in its own process group the way Ctrl-C in a terminal does, and waiting
until every process of the group is gone.

Waiting for the group's leader is not enough: `rosbag record` is a Python wrapper whose SIGINT
handler forwards the signal to the `record` program and exits at once, while `record` is still
closing the bag (BAG.active is renamed to BAG only then). A test that reads the bag as soon as the
leader is gone races `record` and, on a loaded machine, finds only BAG.active."""
import os
import signal
import time


def live_members(pgid):
    """PIDs of the processes of group `pgid` that still run (zombies excluded), read from /proc:
    an orphaned member is no longer our child, so waitpid cannot see it."""
    pids = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open("/proc/%s/stat" % entry) as f:
                stat = f.read()
        except OSError:  # the process ended while we looked
            continue
        # After the command name's closing parenthesis: state, ppid, pgrp, ...
        fields = stat[stat.rindex(")") + 2:].split()
        if fields[0] != "Z" and int(fields[2]) == pgid:
            pids.append(int(entry))
    return pids


def interrupt_group(process, timeout_s=30.0):
    """Sends SIGINT to the process group led by `process` (a subprocess.Popen started with
    start_new_session=True) and waits until the leader is reaped and no member runs. After
    timeout_s the group is killed (SIGKILL). Returns True if the group ended on the SIGINT."""
    pgid = process.pid
    deadline = time.monotonic() + timeout_s
    if process.poll() is None or live_members(pgid):
        try:
            os.killpg(pgid, signal.SIGINT)
        except ProcessLookupError:
            pass
    while time.monotonic() < deadline:
        if process.poll() is not None and not live_members(pgid):
            return True
        time.sleep(0.05)
    try:
        os.killpg(pgid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    process.wait()
    return False
