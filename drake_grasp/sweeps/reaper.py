"""A reaper: ends the processes a command started when the command itself ends, even by `kill -9`.

Some helpers cannot be told to die with their parent: a local Ray instance starts a GCS server and a
raylet (these do follow the driver), whose agents notice the raylet's death only after many seconds
or not at all. `start(pid)` starts this module as a small process that, while `pid` lives, notes
every process below it (pid and start time, read from /proc twice a second); once `pid` is gone it
sends SIGKILL to each noted process that is still the same process, and exits. The command stops
the reaper itself on a normal exit (`Reaper.stop`). Linux only (/proc); elsewhere `start` does nothing.

    python -m drake_grasp.sweeps.reaper PID
"""

import os
import pathlib
import signal
import subprocess
import sys
import time

POLL_SECONDS = 0.5


def process_table() -> dict[int, tuple[int, str]]:
    """Every process's (parent pid, start time), from /proc."""
    table = {}
    for entry in pathlib.Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            table[int(entry.name)] = (int(fields[1]), fields[19])  # ppid, starttime (clock ticks)
        except (OSError, IndexError, ValueError):
            continue
    return table


def descendants(root: int, table: dict[int, tuple[int, str]]) -> dict[int, str]:
    """The processes below root in `table`, with their start times. Pure."""
    children: dict[int, list[int]] = {}
    for pid, (ppid, _) in table.items():
        children.setdefault(ppid, []).append(pid)
    found, stack = {}, [root]
    while stack:
        for child in children.get(stack.pop(), []):
            if child not in found:
                found[child] = table[child][1]
                stack.append(child)
    return found


def watch(root: int, poll_seconds: float = POLL_SECONDS) -> int:
    """Notes root's descendants while root lives; then kills those still alive. Returns how many."""
    noted: dict[int, str] = {}
    me = os.getpid()
    while True:
        table = process_table()
        if root not in table:
            break
        noted.update(descendants(root, table))
        noted.pop(me, None)
        time.sleep(poll_seconds)
    table = process_table()
    killed = 0
    for pid, started in noted.items():
        if pid in table and table[pid][1] == started:  # the same process, not a reused pid
            try:
                os.kill(pid, signal.SIGKILL)
                killed += 1
            except OSError:
                pass
    return killed


class Reaper:
    """A running reaper process for this process (see the module docstring)."""

    def __init__(self, process: subprocess.Popen | None):
        self.process = process

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        self.process = None


def start(pid: int | None = None) -> Reaper:
    """Starts a reaper for `pid` (default: this process); on systems without /proc, a no-op."""
    if not pathlib.Path("/proc/self/stat").exists():
        return Reaper(None)
    process = subprocess.Popen([sys.executable, "-m", "drake_grasp.sweeps.reaper", str(pid or os.getpid())],
                               stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, start_new_session=True)
    return Reaper(process)


if __name__ == "__main__":
    watch(int(sys.argv[1]))
