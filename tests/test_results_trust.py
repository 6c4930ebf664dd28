"""Results you can trust: fingerprints, damaged lines, the folder lock, output paths checked first,
exit codes, and a small fault injection (a sweep killed with SIGKILL, a damaged line, a rerun)."""

import csv
import io
import os
import pathlib
import subprocess
import sys
import time

import pytest

from drake_grasp import cli
from drake_grasp.studies import fig4
from drake_grasp.sweeps import lock
from drake_grasp.sweeps.fingerprint import object_fingerprint, scenario_fingerprint, trial_fingerprint
from drake_grasp.sweeps.results import ResultsFileError, ResultsTable
from drake_grasp.sweeps.runner import TrialSpec

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _error_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err  # one line, no traceback
    return err


# --- 1. Fingerprints. ------------------------------------------------------------------------------

def test_an_objects_fingerprint_follows_its_content(tmp_path):
    import trimesh

    mesh = tmp_path / "thing.stl"
    trimesh.creation.box((0.05, 0.05, 0.05)).export(mesh)
    before = object_fingerprint(str(mesh))
    assert object_fingerprint(str(mesh)) == before
    trimesh.creation.box((100.0, 100.0, 100.0)).export(mesh)  # same path, other content
    assert object_fingerprint(str(mesh)) != before
    assert object_fingerprint("sphere:0.1") != object_fingerprint("sphere:0.12")
    assert object_fingerprint("sphere:0.1") != object_fingerprint("sphere:0.1", scale=0.001)
    assert object_fingerprint("apple") != object_fingerprint("sponge")


def test_a_trials_fingerprint_follows_the_resolved_scenario(tmp_path):
    same = tmp_path / "same.yaml"
    same.write_text("default:\n  contact:\n    friction: 0.5\n")  # the default's value: same scenario
    slippery = tmp_path / "slippery.yaml"
    slippery.write_text("default:\n  contact:\n    friction: 0.0\n")
    assert scenario_fingerprint(str(same)) == scenario_fingerprint()
    assert scenario_fingerprint(str(slippery)) != scenario_fingerprint()
    spec = TrialSpec("sphere:0.1", "oracle", "spherical", 0)
    other = TrialSpec("sphere:0.1", "oracle", "spherical", 0, str(slippery))
    assert trial_fingerprint(spec) != trial_fingerprint(other)


def test_an_older_results_file_is_one_line_naming_it(tmp_path, capsys):
    old = tmp_path / "fig4.csv"
    old.write_text(",".join(fig4.FIELDS[1:]) + "\n")  # the columns before fingerprints
    assert cli.main(["fig4", "--quick", "--out", str(tmp_path)]) == 2
    err = _error_line(capsys)
    assert str(old) in err and "older version" in err and "move it away" in err


def test_a_sweep_with_other_settings_recomputes_and_reports_only_its_own_rows(tmp_path):
    config = fig4.Fig4Config(sizes=[0.08], errors=[0.0])
    rows = fig4.run_fig4(config, tmp_path, workers=1, progress=io.StringIO())
    other = fig4.Fig4Config(sizes=[0.08], errors=[0.0], friction=0.2)
    progress = io.StringIO()
    again = fig4.run_fig4(other, tmp_path, workers=1, progress=progress)
    assert "resuming" not in progress.getvalue()  # nothing reused from the other friction
    assert {r["fingerprint"] for r in again} == {other.fingerprint()} != {config.fingerprint()}
    assert len(again) == len(rows) == 3 * 2
    progress = io.StringIO()
    back = fig4.run_fig4(config, tmp_path, workers=1, progress=progress)
    assert "resuming, 3/3" in progress.getvalue() and back == rows  # each fingerprint keeps its results


# --- 3. Damaged lines. ------------------------------------------------------------------------------

FIELDS, KEY, TYPES = ["name", "x", "y", "note"], ["name", "x"], {"x": "float", "y": "float"}


def _table_with_rows(path, count=5):
    table = ResultsTable(path, FIELDS, KEY, TYPES)
    table.append([{"name": "a", "x": float(i), "y": i * 0.5, "note": f"row {i}"} for i in range(count)])
    return path.read_text().splitlines(keepends=True)


@pytest.mark.parametrize("damage", [
    lambda line: ",".join(line.split(",")[:2]) + "\n",  # cut after its key fields
    lambda line: line.replace(",1.5,", ",banana,").replace(",1.0,", ",banana,"),  # a non-numeric field
    lambda line: line[: len(line) // 2] + "\n",  # cut halfway
    lambda line: line.replace("row", "raw"),  # a changed text field
])
def test_a_damaged_line_in_the_middle_is_reported_once_dropped_and_recomputed(tmp_path, damage):
    path = tmp_path / "t.csv"
    lines = _table_with_rows(path)
    lines[3] = damage(lines[3])  # line 4 of the file: the record of x = 2.0
    path.write_text("".join(lines))
    report = io.StringIO()
    table = ResultsTable(path, FIELDS, KEY, TYPES, report=report)
    assert report.getvalue() == f"{path}:4: damaged record, recomputing\n"
    assert len(table) == 4 and ("a", 2.0) not in table and ("a", 3.0) in table
    assert table.append([{"name": "a", "x": 2.0, "y": 1.0, "note": "row 2"}]) == 1
    report = io.StringIO()
    again = ResultsTable(path, FIELDS, KEY, TYPES, report=report)
    assert report.getvalue() == "" and len(again) == 5  # reported once: the file was repaired


def test_a_line_joined_with_the_next_and_a_doubled_record_are_dropped(tmp_path):
    path = tmp_path / "t.csv"
    lines = _table_with_rows(path)
    path.write_text("".join(lines[:2]) + lines[2].rstrip("\n") + lines[3] + "".join(lines[4:]) + lines[5])
    report = io.StringIO()
    table = ResultsTable(path, FIELDS, KEY, TYPES, report=report)
    assert report.getvalue().splitlines() == [f"{path}:3: damaged record, recomputing",
                                              f"{path}:6: duplicate record, dropped"]
    assert len(table) == 3 and path.read_text().count("row 4") == 1


def test_a_read_only_table_skips_damage_without_touching_the_file(tmp_path):
    path = tmp_path / "t.csv"
    lines = _table_with_rows(path)
    lines[2] = "garbage\n"
    path.write_text("".join(lines))
    report = io.StringIO()
    table = ResultsTable(path, FIELDS, KEY, TYPES, read_only=True, report=report)
    assert len(table) == 4 and "damaged record, ignored" in report.getvalue()
    assert path.read_text() == "".join(lines)
    with pytest.raises(ResultsFileError, match="older version"):
        ResultsTable(path, ["fingerprint", "name"], ["fingerprint"])


# --- 2. One writer per folder. -----------------------------------------------------------------------

def test_a_second_writer_is_refused_naming_the_holder_and_a_dead_holders_lock_is_taken_over(tmp_path):
    holder = subprocess.Popen([sys.executable, "-c",
                               "import sys, time; from drake_grasp.sweeps.lock import acquire; "
                               f"acquire(__import__('pathlib').Path({str(tmp_path)!r})); print('held', flush=True); "
                               "time.sleep(60)"],
                              stdout=subprocess.PIPE, text=True, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    try:
        assert holder.stdout.readline().strip() == "held"
        with pytest.raises(lock.LockHeld, match=f"pid {holder.pid}"):
            lock.acquire(tmp_path)
    finally:
        holder.kill()  # as kill -9: the lock file stays behind
        holder.wait()
    assert lock.read_holder(tmp_path / lock.LOCK_NAME)["pid"] == holder.pid
    with lock.results_lock(tmp_path) as path:  # stale: taken over
        assert lock.read_holder(path)["pid"] == os.getpid()
        with lock.results_lock(tmp_path):  # re-entrant in one process
            pass
        assert path.exists()
    assert not path.exists()


def test_cli_refuses_a_folder_another_run_holds(tmp_path, capsys):
    holder = subprocess.Popen(["sleep", "30"])
    try:
        (tmp_path / lock.LOCK_NAME).write_text(f"pid={holder.pid}\nhost={os.uname().nodename}\nstarted=now\n")
        assert cli.main(["fig4", "--quick", "--out", str(tmp_path)]) == 2
        assert f"pid {holder.pid}" in _error_line(capsys)
    finally:
        holder.kill()
        holder.wait()


# --- 4 and 6. Bad input: one line, exit 2, before any work. --------------------------------------------

@pytest.fixture
def scenarios(tmp_path):
    files = {"empty": "", "banana": "default:\n  plant_config:\n    contact_model: banana\n"}
    for name, text in files.items():
        (tmp_path / f"{name}.yaml").write_text(text)
    (tmp_path / "a_file").write_text("x")
    return tmp_path


@pytest.mark.parametrize("argv, message", [
    (["trial", "--object", "sphere:1e-300"], "diameter 1e-300 m is outside"),
    (["trial", "--object", "sphere:1e9"], "diameter 1e+09 m is outside"),
    (["trial", "--object", ""], "empty object name"),
    (["trial", "--object", "sphere:0.1", "--scenario", "{tmp}/banana.yaml"], "contact_model must be one of"),
    (["trial", "--object", "sphere:0.1", "--scenario", "{tmp}/empty.yaml"], "scenario file is empty"),
    (["trial", "--object", "sphere:0.1", "--scenario-name", "nosuch"], "no scenario named 'nosuch'"),
    (["trial", "--object", "sphere:0.1", "--out", "{tmp}/a_file"], "exists and is not a directory"),
    (["trial", "--object", "sphere:0.1", "--replay", "{tmp}/a_file/r.html"], "does not exist"),
    (["demo", "--object", "sphere:0.1", "--out", "{tmp}/a_file/sub"], "is not a directory"),
    (["fig4", "--out", "{tmp}/a_file"], "exists and is not a directory"),
    (["fig6", "--seed", "4294967295", "--trials", "2", "--out", "{tmp}/o"], "past 2^32 - 1"),
    (["fig7", "--fig6", "{tmp}/a_file", "--out", "{tmp}/o"], "--fig6"),
])
def test_bad_input_is_one_line_and_exit_2(scenarios, capsys, argv, message):
    argv = [a.replace("{tmp}", str(scenarios)) for a in argv]
    start = time.perf_counter()
    assert cli.main(argv) == 2
    assert message in _error_line(capsys)
    assert time.perf_counter() - start < 20  # before any simulation


def test_options_that_do_nothing_are_gone_and_too_many_workers_are_capped(capsys):
    with pytest.raises(SystemExit) as e:
        cli.main(["fig4", "--seed", "3"])
    assert e.value.code == 2 and "--seed" in capsys.readouterr().err
    assert cli.main(["fig6", "--workers", "1000", "--objects", "nosuch_object"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0].endswith(f"--workers 1000 is more than this machine's {os.cpu_count()} cores; "
                           f"using {os.cpu_count()}")
    assert "nosuch_object" in err[1]


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_a_read_only_out_folder_is_refused_before_the_trial(tmp_path, capsys):
    tmp_path.chmod(0o555)
    try:
        assert cli.main(["trial", "--object", "sphere:0.1", "--out", str(tmp_path / "o")]) == 2
        assert "not writable" in _error_line(capsys)
    finally:
        tmp_path.chmod(0o755)


# --- 5 and 7. A small fault injection: a sweep killed with SIGKILL, its workers, a damaged line. -------

_SWEEP = """
import pathlib, sys
from drake_grasp.studies import fig4
config = fig4.Fig4Config(sizes=[0.05, 0.08, 0.11, 0.14, 0.17, 0.20], errors=[-0.02, 0.0, 0.02])
fig4.run_fig4(config, pathlib.Path(sys.argv[1]), workers=2)
"""


def _sweep(out: pathlib.Path, **kwargs) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", _SWEEP, str(out)], env=dict(os.environ, PYTHONPATH=str(ROOT)),
                            text=True, stderr=subprocess.PIPE, **kwargs)


def _children(pid: int) -> set[int]:
    out = subprocess.run(["ps", "-o", "pid=", "--ppid", str(pid)], capture_output=True, text=True).stdout
    return {int(p) for p in out.split()}


def _records(path: pathlib.Path) -> dict:
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    keys = [tuple(r[k] for k in fig4.KEY) for r in rows]
    assert len(keys) == len(set(keys)), "doubled records"
    return {k: {f: v for f, v in r.items() if f != "check"} for k, r in zip(keys, rows)}


def test_a_sweep_killed_with_sigkill_leaves_no_worker_and_a_rerun_gives_the_clean_records(tmp_path):
    clean, faulty = tmp_path / "clean", tmp_path / "faulty"
    assert _sweep(clean).wait() == 0
    reference = _records(clean / "fig4.csv")

    run = _sweep(faulty)
    for line in run.stderr:  # kill -9 once the first task's rows are written, the others running
        if "fig4: 1/" in line:
            break
    workers = _children(run.pid)
    assert workers, "the sweep runs in worker processes"
    run.kill()
    run.wait()
    deadline = time.monotonic() + 5.0
    while time.monotonic() < deadline and any(pathlib.Path(f"/proc/{p}").exists() for p in workers):
        time.sleep(0.1)
    alive = [p for p in workers if pathlib.Path(f"/proc/{p}").exists()
             and "Z" not in pathlib.Path(f"/proc/{p}/stat").read_text().rsplit(")", 1)[1].split()[:1]]
    assert alive == [], "workers outlived their parent"

    csv_path = faulty / "fig4.csv"
    lines = csv_path.read_text().splitlines(keepends=True)
    assert 2 <= len(lines) < len(reference) + 1  # killed part-way
    lines[1] = lines[1][: len(lines[1]) // 2] + "\n"  # and a damaged line in the middle
    csv_path.write_text("".join(lines))
    rerun = _sweep(faulty)
    _, err = rerun.communicate()
    assert rerun.returncode == 0, err
    assert f"{csv_path}:2: damaged record, recomputing" in err and "Traceback" not in err
    assert _records(csv_path) == reference  # nothing lost, doubled or stale


def test_the_reaper_ends_a_helper_that_would_outlive_a_killed_parent():
    # A helper in its own session ignores its parent's death (as Ray's agents do); the reaper ends it.
    parent = subprocess.Popen(
        [sys.executable, "-c", "import subprocess, time; from drake_grasp.sweeps import reaper; "
         "reaper.start(); helper = subprocess.Popen(['sleep', '60'], start_new_session=True); "
         "print(helper.pid, flush=True); time.sleep(60)"],
        stdout=subprocess.PIPE, text=True, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    helper = int(parent.stdout.readline())
    time.sleep(1.5)  # the reaper notes the helper (it looks twice a second)
    parent.kill()
    parent.wait()
    deadline = time.monotonic() + 5.0
    while time.monotonic() < deadline and pathlib.Path(f"/proc/{helper}").exists():
        time.sleep(0.1)
    assert not pathlib.Path(f"/proc/{helper}").exists()


def test_a_record_that_would_not_read_back_is_refused_when_written(tmp_path):
    table = ResultsTable(tmp_path / "t.csv", FIELDS, KEY, TYPES)
    with pytest.raises(RuntimeError, match="y does not match"):
        table.append([{"name": "a", "x": 1.0, "y": None, "note": ""}])
    assert len(ResultsTable(tmp_path / "t.csv", FIELDS, KEY, TYPES)) == 0


def test_reproduce_and_fig7_check_every_results_file_before_any_work(tmp_path, capsys):
    old = tmp_path / "fig6" / "fig6.csv"
    old.parent.mkdir()
    old.write_text("object,method,grasp,seed,success\n")  # an older version's file
    start = time.perf_counter()
    assert cli.main(["reproduce", "--quick", "--out", str(tmp_path)]) == 2
    assert f"{old}: written by an older version" in _error_line(capsys)
    assert cli.main(["fig7", "--quick", "--fig6", str(old.parent), "--out", str(tmp_path / "f7")]) == 2
    assert f"{old}: written by an older version" in _error_line(capsys)
    assert time.perf_counter() - start < 20  # no sweep, no planning
    assert not (tmp_path / "fig4" / "fig4.csv").exists()
