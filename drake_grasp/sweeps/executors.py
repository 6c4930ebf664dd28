"""Where a sweep's tasks run: in this process, in a local process pool, or as Ray tasks.

Every sweep (Fig. 4, 6, 7, reproduce) is a list of tasks, each a picklable module-level function
applied to plain data (a `TrialSpec`, a shape and a size, ...) that returns plain data (a record
dict, a list of rows). Drake Diagrams and Contexts do not pickle, so each task builds its own. An
executor maps such a function over the tasks and yields each result as soon as it is ready, so the
caller can write it to its resumable results file at once; the results do not depend on where a task
ran, only on its arguments (every random choice is seeded from them).

    with make_executor("ray", workers=2) as executor:
        for index, result in executor.imap_unordered(run_one, [(spec,) for spec in specs]):
            ...

Ray is an optional dependency (`pip install -e '.[ray]'`), imported only when a Ray executor runs.
"""

import concurrent.futures
import importlib.util
import logging
import multiprocessing
import os
import socket
import sys
from collections.abc import Callable, Iterator, Sequence

EXECUTORS = ("local", "ray")
RAY_INSTALL_HINT = "pip install -e '.[ray]' (or pip install 'ray>=2.9')"


class Executor:
    """Maps a function over argument tuples and yields (task index, result) as tasks complete.

    Use it as a context manager: `close()` releases what the executor started (a Ray instance).
    """

    name = "executor"

    def imap_unordered(self, fn: Callable, tasks: Sequence[tuple]) -> Iterator[tuple[int, object]]:
        raise NotImplementedError

    def describe(self) -> str:
        """One line for progress output and benchmark reports."""
        return self.name

    def slots(self) -> int:
        """How many tasks run at once, as far as known before the executor starts (at least 1)."""
        return 1

    def start(self) -> "Executor":
        """Starts what the executor needs now rather than on first use (a benchmark times it)."""
        return self

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class LocalExecutor(Executor):
    """Runs tasks here: inline with one worker, else in a "spawn" process pool of `workers` processes.

    Args:
        workers: processes at most (default: every core); a pool never has more processes than tasks.
    """

    name = "local"

    def __init__(self, workers: int | None = None):
        self.workers = max(1, workers or os.cpu_count() or 1)

    def describe(self) -> str:
        return f"local, {self.workers} worker{'s' if self.workers > 1 else ''}"

    def slots(self) -> int:
        return self.workers

    def imap_unordered(self, fn, tasks):
        workers = min(self.workers, len(tasks))
        if workers <= 1:
            for index, args in enumerate(tasks):
                yield index, fn(*args)
            return
        # "spawn": a fresh interpreter per worker (forking a process that holds Drake objects is unsafe).
        context = multiprocessing.get_context("spawn")
        pool = concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=context,
                                                      initializer=die_with_parent, initargs=(os.getpid(),))
        futures = {}
        try:
            futures = {pool.submit(fn, *args): index for index, args in enumerate(tasks)}
            for future in concurrent.futures.as_completed(futures):
                yield futures[future], future.result()
        finally:
            # On an error, an interrupt (Ctrl-C, SIGTERM) or an early close, the running tasks are
            # stopped with their workers (their results would be thrown away) and the rest dropped.
            if not all(f.done() for f in futures):
                _terminate_workers(pool)
            pool.shutdown(wait=True, cancel_futures=True)


def _terminate_workers(pool: concurrent.futures.ProcessPoolExecutor) -> None:
    """Sends SIGTERM to the pool's worker processes (the pool then notices them gone and shuts down)."""
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        if process.is_alive():
            process.terminate()


def die_with_parent(parent_pid: int, poll_seconds: float = 1.0) -> None:
    """A worker's initializer: the worker ends when the process that started it ends, however it ends
    (even `kill -9`, which gives the parent no chance to stop its workers).

    On Linux the kernel sends the worker SIGTERM when its parent dies (prctl PR_SET_PDEATHSIG); as a
    fallback elsewhere, a daemon thread checks every `poll_seconds` whether the parent is still this
    process's parent, and ends the process if not. The pool's helper processes (multiprocessing's
    resource tracker) end by themselves once no process holds their pipe.
    """
    import signal
    import threading
    import time

    if sys.platform.startswith("linux"):
        import ctypes

        PR_SET_PDEATHSIG = 1
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent_pid:  # the parent died before prctl took effect
        os._exit(1)

    def watch():
        while True:
            time.sleep(poll_seconds)
            if os.getppid() != parent_pid:
                os._exit(1)

    threading.Thread(target=watch, name="die-with-parent", daemon=True).start()


class RayExecutor(Executor):
    """Runs each task as a Ray task (one CPU each), on a local Ray instance or a cluster.

    Ray starts on first use. Without `address` it starts a local instance with `workers` CPUs (default:
    every core) and no dashboard, and `close()` shuts it down (if this process is killed instead, a
    `reaper` process ends the instance's processes); with `address` ("auto", "HOST:PORT" or
    "ray://HOST:10001") it joins that cluster, whose CPUs decide how many tasks run at once; the
    package must be installed on its nodes. If this process already has Ray initialised (a test, a
    notebook), that instance is used and left running.

    Args:
        workers: CPUs of the local instance (not used with `address`).
        address: the cluster to join, or None for a local instance.
        progress: where the one line about the Ray instance goes.
    """

    name = "ray"

    def __init__(self, workers: int | None = None, address: str | None = None, progress=sys.stderr):
        require_ray()
        self.workers = max(1, workers or os.cpu_count() or 1)
        self.address = address
        self.progress = progress
        self._started = False
        self._ready = False
        self._reaper = None

    def slots(self) -> int:
        return 1 if self.address else self.workers  # a cluster's CPUs are known once joined

    def describe(self) -> str:
        if self.address:
            return f"ray, cluster at {self.address}"
        return f"ray, local instance with {self.workers} CPUs"

    def start(self) -> "RayExecutor":
        self._start()
        return self

    def _start(self):
        import ray

        if self._ready:
            return ray
        if not ray.is_initialized():
            kwargs = {"include_dashboard": False, "logging_level": logging.WARNING}
            try:
                if self.address:
                    _probe(self.address)
                    ray.init(address=self.address, **kwargs)
                else:  # "local": a new instance, never one a `ray start` left running on this machine
                    from drake_grasp.sweeps import reaper

                    self._reaper = reaper.start()
                    ray.init(address="local", num_cpus=self.workers, **kwargs)
            except Exception as e:  # Ray raises ConnectionError, RuntimeError, ... : report one line
                where = f"join the Ray cluster at {self.address}" if self.address else "start a local Ray instance"
                first = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
                raise RuntimeError(f"could not {where}: {first}") from e
            self._started = True
            cpus = int(ray.cluster_resources().get("CPU", 0))
            print(f"ray: {'joined ' + self.address if self.address else 'started a local instance'}, "
                  f"{cpus} CPUs", file=self.progress, flush=True)
        self._ready = True
        return ray

    def imap_unordered(self, fn, tasks):
        if not tasks:
            return
        ray = self._start()
        remote = ray.remote(num_cpus=1)(fn)
        refs = {remote.remote(*args): index for index, args in enumerate(tasks)}
        pending = list(refs)
        try:
            while pending:
                ready, pending = ray.wait(pending, num_returns=1)
                for ref in ready:
                    yield refs[ref], _get(ray, ref)
        finally:
            for ref in pending:  # an error or an interrupt: do not leave tasks running on the cluster
                ray.cancel(ref)

    def close(self) -> None:
        if self._started:
            import ray

            ray.shutdown()
        if self._reaper is not None:
            self._reaper.stop()
            self._reaper = None
        self._started = self._ready = False


def _get(ray, ref):
    """A task's result; a task's exception is raised as itself (as the local executor does), not
    wrapped in Ray's RayTaskError, so that callers handle bad input the same way."""
    try:
        return ray.get(ref)
    except ray.exceptions.RayTaskError as e:
        if isinstance(e.cause, Exception):
            raise e.cause from e
        raise


def _probe(address: str, timeout: float = 5.0) -> None:
    """Fails fast (OSError) if a HOST:PORT address does not accept connections: ray.init would keep
    retrying for minutes. Other forms ("auto", "ray://...") fail quickly in ray.init itself."""
    if address == "auto" or "://" in address or ":" not in address:
        return
    host, _, port = address.rpartition(":")
    if not port.isdigit():
        raise OSError(f"expected HOST:PORT, got '{address}'")
    socket.create_connection((host, int(port)), timeout=timeout).close()


def ray_available() -> bool:
    """Whether Ray can be imported (without importing it: that takes a while)."""
    return importlib.util.find_spec("ray") is not None


def require_ray() -> None:
    if not ray_available():
        raise ValueError(f"--executor ray needs Ray, which is not installed: {RAY_INSTALL_HINT}")


def make_executor(kind: str = "local", workers: int | None = None, address: str | None = None,
                  progress=sys.stderr) -> Executor:
    """The executor named `kind` ("local" or "ray"); ValueError (one line) for bad combinations."""
    if kind not in EXECUTORS:
        raise ValueError(f"unknown executor '{kind}' (choose from {', '.join(EXECUTORS)})")
    if kind == "local":
        if address:
            raise ValueError("--ray-address needs --executor ray")
        return LocalExecutor(workers)
    return RayExecutor(workers, address, progress)
