"""Executors: the CLI's checks, the local pool, and Ray (a local instance started here) giving the same
records as the local executor, with resuming after an interruption."""

import csv
import io
import logging

import pytest

from drake_grasp import cli
from drake_grasp.sweeps import executors
from drake_grasp.studies import fig4
from drake_grasp.sweeps.runner import TrialSpec, run_trials


def _error_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err  # one line, no traceback, no usage block
    return err


@pytest.mark.parametrize("argv, message", [
    (["fig6", "--ray-address", "auto"], "--ray-address needs --executor ray"),
    (["fig4", "--executor", "dask"], "unknown --executor 'dask' (choose from local, ray)"),
    (["reproduce", "--executor", "ray", "--ray-address", "auto", "--workers", "2"], "--workers does not apply"),
])
def test_cli_rejects_bad_executor_arguments(capsys, argv, message):
    assert cli.main(argv) == 2
    assert message in _error_line(capsys)


def test_cli_says_how_to_install_ray_when_it_is_missing(capsys, monkeypatch):
    monkeypatch.setattr(executors, "ray_available", lambda: False)
    assert cli.main(["fig7", "--executor", "ray"]) == 2
    assert "pip install -e '.[ray]'" in _error_line(capsys)


def test_local_executor_yields_every_task_once_with_its_index():
    tasks = [(2, 3), (3, 2), (5, 1)]
    for workers in (1, 2):  # inline, then a spawn pool (builtins: nothing to import in the workers)
        got = dict(executors.LocalExecutor(workers).imap_unordered(pow, tasks))
        assert got == {0: 8, 1: 9, 2: 5}


# --- Ray: a local instance, started once for the tests below. -------------------------------------

def _records(csv_path) -> dict:
    """Rows by key, without the wall time (the only field that may differ between runs) and the line
    checksum that covers it."""
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    keys = [(r["object"], r["method"], r["grasp"], r["seed"]) for r in rows]
    assert len(keys) == len(set(keys)), "duplicate rows"
    return {k: {f: v for f, v in r.items() if f not in ("wall_time", "check")} for k, r in zip(keys, rows)}


@pytest.fixture(scope="module")
def ray_instance():
    ray = pytest.importorskip("ray", reason="Ray is an optional extra: pip install -e '.[ray]'")
    ray.init(address="local", num_cpus=2, include_dashboard=False, logging_level=logging.WARNING)
    yield ray
    ray.shutdown()


class _InterruptAfterFirstTrial(io.StringIO):
    """A progress stream that raises KeyboardInterrupt (as Ctrl-C would) once one trial is written."""

    def write(self, text):
        super().write(text)
        if ": 1/" in text:
            raise KeyboardInterrupt


def test_ray_gives_the_local_records_and_resumes_after_an_interruption(ray_instance, tmp_path,
                                                                     short_scenario_file):
    scenario = str(short_scenario_file)
    specs = [TrialSpec("sponge", "oracle", "box", seed, scenario) for seed in (0, 1)]
    run_trials(specs, tmp_path / "local.csv", workers=1, progress=io.StringIO())
    with executors.make_executor("ray", workers=2) as ray_executor:
        run_trials(specs, tmp_path / "ray.csv", progress=io.StringIO(), executor=ray_executor)
        local = _records(tmp_path / "local.csv")
        assert len(local) == 2 and _records(tmp_path / "ray.csv") == local

        # Interrupted after the first record: the other trial is cancelled, the record kept.
        with pytest.raises(KeyboardInterrupt):
            run_trials(specs, tmp_path / "resumed.csv", progress=_InterruptAfterFirstTrial(), executor=ray_executor)
        first = _records(tmp_path / "resumed.csv")
        assert len(first) == 1
        progress = io.StringIO()
        run_trials(specs, tmp_path / "resumed.csv", progress=progress, executor=ray_executor)
        lines = progress.getvalue().splitlines()
        assert lines[0].startswith("trials: resuming, 1/2") and len(lines) == 2  # one trial computed
        assert _records(tmp_path / "resumed.csv") == local
    assert ray_instance.is_initialized()  # the executor left the test's instance running


def test_ray_runs_the_fig4_sweep_with_the_local_rows(ray_instance, tmp_path):
    config = fig4.Fig4Config(sizes=[0.1], errors=[0.0])
    local = fig4.run_fig4(config, tmp_path / "local", workers=1, progress=io.StringIO())
    with executors.make_executor("ray", workers=2) as ray_executor:
        remote = fig4.run_fig4(config, tmp_path / "ray", progress=io.StringIO(), executor=ray_executor)
    key = ("shape", "size", "axis", "error")
    assert len(local) == 6
    assert sorted(local, key=lambda r: [r[k] for k in key]) == sorted(remote, key=lambda r: [r[k] for k in key])
