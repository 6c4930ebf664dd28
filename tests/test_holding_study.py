"""scripts/holding_study.py refuses what it cannot run in one line, exit code 2, before any trial."""

import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
SHEET = "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 2 3\nf 1 2 4\n"  # two triangles: no solid


def _study(out, *extra, workers=1):
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "holding_study.py"), "--objects", "novel",
                           "--count", "7", "--seed", "0", "--seeds", "1", "--attempts", "1",
                           "--scenarios", "funnel", "--workers", str(workers), "--out", str(out), *extra],
                          capture_output=True, text=True, timeout=300)


def test_an_unknown_class_is_refused(tmp_path):
    done = _study(tmp_path / "out", "--classes", "blob,teapot")
    assert done.returncode == 2
    assert done.stderr.strip().count("\n") == 0 and "--classes" in done.stderr
    assert not (tmp_path / "out" / "trials.csv").exists()


def test_an_object_that_does_not_load_is_refused_before_any_trial(tmp_path):
    out = tmp_path / "out"
    made = subprocess.run([sys.executable, "-m", "drake_grasp.cli", "objects", "generate", "--kind", "novel",
                           "--count", "7", "--seed", "0", "--out", str(out / "objects")],
                          capture_output=True, text=True, timeout=300)
    assert made.returncode == 0, made.stderr
    (out / "objects" / "blob_0_000.obj").write_text(SHEET)
    done = _study(out)
    assert done.returncode == 2
    assert done.stderr.strip().count("\n") == 0
    assert "blob_0_000.obj" in done.stderr and "sheet" in done.stderr
    assert not (out / "trials.csv").exists()


def test_a_files_list_with_a_missing_file_or_a_bad_scale_is_refused(tmp_path):
    (tmp_path / "box.obj").write_text(SHEET)
    for line, said in (("mug\tno_such.stl\n", "no such file"), ("box\tbox.obj\tmm\n", "scale"),
                       ("box.obj\n", "class and a path")):
        listed = tmp_path / "objects.tsv"
        listed.write_text("# class, path, scale\n" + line)
        done = _study(tmp_path / "out", "--files", str(listed))
        assert done.returncode == 2, done.stderr
        assert done.stderr.strip().count("\n") == 0 and said in done.stderr and "objects.tsv:2" in done.stderr
        assert not (tmp_path / "out" / "trials.csv").exists()


def test_a_files_list_is_loaded_before_any_trial(tmp_path):
    (tmp_path / "sheet.obj").write_text(SHEET)
    (tmp_path / "objects.tsv").write_text("scan\tsheet.obj\n")
    done = _study(tmp_path / "out", "--files", str(tmp_path / "objects.tsv"))
    assert done.returncode == 2
    assert done.stderr.strip().count("\n") == 0 and "sheet.obj" in done.stderr
    assert not (tmp_path / "out" / "trials.csv").exists()


def test_the_files_are_checked_on_the_workers_and_the_first_bad_one_is_named(tmp_path):
    """With two workers the files load in a process pool before any trial; the one line names the
    first file of the list that does not load, whichever worker finished first."""
    (tmp_path / "sheet_a.obj").write_text(SHEET)
    (tmp_path / "sheet_b.obj").write_text(SHEET)
    listed = tmp_path / "objects.tsv"
    listed.write_text("box\tsheet_a.obj\nbox\tsheet_b.obj\n")
    done = _study(tmp_path / "out", "--files", str(listed), workers=2)
    assert done.returncode == 2, done.stderr
    assert done.stderr.strip().count("\n") == 0 and "sheet_a.obj" in done.stderr and "sheet_b" not in done.stderr
    assert not (tmp_path / "out" / "trials.csv").exists()


def test_an_unknown_forced_grasp_is_refused(tmp_path):
    done = _study(tmp_path / "out", "--grasps", "box,pinch")
    assert done.returncode == 2
    assert done.stderr.strip().count("\n") == 0 and "--grasps" in done.stderr
    assert not (tmp_path / "out" / "trials.csv").exists()


def test_the_tools_generator_names_its_classes(tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "holding_study.py"), "--objects", "tools",
                           "--classes", "hammer,teapot", "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 2
    assert "hammer, screwdriver, clamp, marker, wrench" in done.stderr
