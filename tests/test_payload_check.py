"""scripts/payload_check.py: the shapes it writes are simulated at the masses it names, and bad input
is refused in one line before any work."""

import warnings

import numpy as np
import pytest

from drake_grasp.objects import resolve_user_object
from script_loader import load_script


def _module():
    return load_script("payload_check")


def test_each_shape_is_loaded_at_its_mass_without_a_warning(tmp_path):
    module = _module()
    made = module.write_objects(tmp_path, [0.25, 1.5])
    assert len(made) == 2 * len(module.SHAPES)
    for name, mass, grasp, path in made[:4]:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # an implausible inertial would warn and be replaced
            spec = resolve_user_object(str(path))
        assert spec.mass == pytest.approx(mass, rel=1e-6)
        # The file's inertia is the mesh's at that mass: its moments positive, scaling with the mass.
        assert np.all(np.asarray(spec.inertia)[:3] > 0.0)
    light, heavy = (resolve_user_object(str(p)) for _, _, _, p in made[:2])
    assert np.allclose(np.asarray(heavy.inertia), np.asarray(light.inertia) * 1.5 / 0.25, rtol=1e-4)


@pytest.mark.parametrize("argv", [["--masses", "0.5,heavy"], ["--masses", "0,1"], ["--seeds", ""]])
def test_bad_input_is_one_line_and_exit_code_2(argv, tmp_path, capsys):
    assert _module().main(argv + ["--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("payload_check:") and "\n" not in err
    assert not (tmp_path / "out").exists()
