"""One writer per results folder: a lock file that names its holder.

A sweep appends to the CSV files of its output folder and rewrites its figures there; two sweeps
writing into one folder would double records and race on the figures. `results_lock(folder)` creates
``folder/.drake-grasp.lock`` atomically (the file is written under a unique name, then hard-linked to
the lock's name, which fails if the lock exists) with the holder's pid, host and start time. A second
run finds it and stops at once with one line naming the holder (`LockHeld`, exit code 2). A lock
whose process is gone (a run killed with `kill -9`) is stale: the next run on the same host removes
it and takes over. The lock is re-entrant within one process (`reproduce` holds its folder while
each figure's sweep holds its own).
"""

import contextlib
import os
import pathlib
import socket
import tempfile
import time

LOCK_NAME = ".drake-grasp.lock"
_held: dict[pathlib.Path, int] = {}  # lock path -> how many times this process holds it


class LockHeld(ValueError):
    """Another live process holds the folder's lock: one line, exit code 2."""


def _alive(pid: int) -> bool:
    """Whether a process with this pid exists on this host (a zombie counts as gone)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return True


def read_holder(path: pathlib.Path) -> dict | None:
    """The lock file's fields (pid, host, started), or None if it is missing or unreadable."""
    try:
        fields = dict(line.split("=", 1) for line in path.read_text().splitlines() if "=" in line)
        fields["pid"] = int(fields["pid"])
        return fields
    except (OSError, KeyError, ValueError):
        return None


def _try_create(path: pathlib.Path) -> bool:
    """Creates the lock with this process's fields, atomically; False if it exists already."""
    text = f"pid={os.getpid()}\nhost={socket.gethostname()}\nstarted={time.strftime('%Y-%m-%dT%H:%M:%S%z')}\n"
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f"{LOCK_NAME}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.link(tmp, path)
        return True
    except FileExistsError:
        return False
    finally:
        os.unlink(tmp)


def acquire(folder: pathlib.Path) -> pathlib.Path:
    """Takes the folder's lock (creating the folder), or raises LockHeld naming the live holder."""
    folder.mkdir(parents=True, exist_ok=True)
    path = (folder / LOCK_NAME).resolve()
    if path in _held:
        _held[path] += 1
        return path
    for _ in range(3):
        if _try_create(path):
            _held[path] = 1
            return path
        holder = read_holder(path)
        if holder is None:  # written by the link in one step, so unreadable means removed meanwhile
            continue
        same_host = holder.get("host") == socket.gethostname()
        if same_host and (holder["pid"] == os.getpid() or not _alive(holder["pid"])):
            with contextlib.suppress(FileNotFoundError):  # stale: its run was killed; take it over
                os.unlink(path)
            continue
        where = "" if same_host else f" on {holder.get('host')}"
        raise LockHeld(f"{folder}: another drake-grasp run (pid {holder['pid']}{where}, started "
                       f"{holder.get('started', '?')}) is writing here; wait for it or choose another --out "
                       f"(if that process is gone, remove {path})")
    raise LockHeld(f"{folder}: could not take the lock {path}")


def release(path: pathlib.Path) -> None:
    """Gives the lock back (removes the file when this process's last hold ends)."""
    _held[path] -= 1
    if _held[path] == 0:
        del _held[path]
        holder = read_holder(path)
        if holder is not None and holder["pid"] == os.getpid():
            with contextlib.suppress(FileNotFoundError):
                os.unlink(path)


@contextlib.contextmanager
def results_lock(folder: str | os.PathLike):
    """Holds the folder's lock for the `with` block (see the module docstring)."""
    path = acquire(pathlib.Path(folder))
    try:
        yield path
    finally:
        release(path)
