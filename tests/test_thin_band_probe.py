"""scripts/thin_band_probe.py: its objects are the heights and footprints it names, the same files every
time, and bad input is refused in one line before any work."""

import pytest
import trimesh

from script_loader import load_script


def _module():
    return load_script("thin_band_probe")


def test_the_objects_have_the_named_heights_and_are_made_the_same_twice(tmp_path):
    module = _module()
    files = module.make_objects(tmp_path / "a")
    assert len(files) == 6 * len(module.HEIGHTS)
    for file in files:
        name, footprint, height = file.stem.rsplit("_", 2)
        mesh = trimesh.load(file, force="mesh")
        assert mesh.is_watertight, file.name
        assert mesh.extents[2] == pytest.approx(int(height) / 1000, abs=2e-4)
        a, b = (int(x) / 100 for x in footprint.split("x"))
        assert max(mesh.extents[:2]) == pytest.approx(a, abs=2e-3) and min(mesh.extents[:2]) == pytest.approx(b, abs=2e-3)
    again = module.make_objects(tmp_path / "b")
    assert [f.read_bytes() for f in files] == [f.read_bytes() for f in again]


@pytest.mark.parametrize("argv", [["--seeds", ""], ["--seeds", "1,x"], ["--workers", "0"]])
def test_bad_input_is_one_line_and_exit_code_2(argv, tmp_path, capsys):
    assert _module().main(argv + ["--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "error" in err
    assert not (tmp_path / "out").exists()
