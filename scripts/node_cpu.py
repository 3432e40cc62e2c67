"""CPU time of a process for the benchmark scripts (node_overhead.sh, replay_benchmark.sh)."""
import os


def cpu_seconds(pid):
    """utime + stime of process `pid` in seconds, from /proc/<pid>/stat."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()  # the name, in parentheses, may hold spaces
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
