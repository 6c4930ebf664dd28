"""Mesh options (--scale, --largest-component) travel with a sweep's objects to its workers and into
every record's fingerprint; they apply to mesh files only."""

import trimesh

from drake_grasp import cli
from drake_grasp.studies import fig6, fig7
from drake_grasp.sweeps.fingerprint import trial_fingerprint
from drake_grasp.sweeps.runner import fingerprints
from drake_grasp.objects import is_mesh_file, mesh_options


def test_only_mesh_files_take_mesh_options():
    assert is_mesh_file("mug.stl") and is_mesh_file("scans/mug.obj")
    assert not any(is_mesh_file(o) for o in ("sponge", "sphere:0.1", "model.sdf", "arm.urdf"))
    assert mesh_options() == {} and mesh_options(0.001) == {"scale": 0.001}
    assert mesh_options(largest_component=True) == {"largest_component": True}


def test_a_sweep_carries_the_scale_of_its_mesh_files_into_specs_and_fingerprints(tmp_path):
    mesh = tmp_path / "brick_mm.stl"
    trimesh.creation.box((50.0, 120.0, 50.0)).export(mesh)  # millimetres
    scaled = fig6.Fig6Config(objects=(str(mesh), "sponge"), trials=1, method="oracle", scale=0.001)
    specs = fig6.trial_specs(scaled)
    assert {(s.object, s.scale) for s in specs} == {(str(mesh), 0.001), ("sponge", 1.0)}
    plain = fig6.trial_specs(fig6.Fig6Config(objects=(str(mesh), "sponge"), trials=1, method="oracle"))
    a, b = fingerprints(specs), fingerprints(plain)
    # The mesh's records differ with its scale; the sponge's do not.
    assert [x != y for x, y in zip(a, b)] == [s.object == str(mesh) for s in specs]
    assert [trial_fingerprint(s) for s in specs] == a  # a spec alone: its mesh options too
    config7 = fig7.Fig7Config(objects=(str(mesh),), scale=0.001)
    assert fig7.plan_fingerprint(str(mesh), object_options=config7.object_options(str(mesh))) != \
        fig7.plan_fingerprint(str(mesh))


def test_sweeps_reject_a_scale_with_no_mesh_file(tmp_path, capsys):
    assert cli.main(["fig6", "--objects", "sponge,sphere:0.1", "--scale", "0.001", "--out", str(tmp_path / "o")]) == 2
    assert "--scale applies to object files (mesh or model files) that take it, and --objects names none" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_output_piped_into_a_reader_that_stops_early_ends_quietly():
    """`drake-grasp objects check X | head -1`: no BrokenPipeError traceback on stderr (the reader here,
    `true`, exits at once, so that the command's output always meets a closed pipe)."""
    import subprocess
    import sys

    pipe = subprocess.run(f"{sys.executable} -m drake_grasp.cli objects check cube:0.05 | true", shell=True,
                          capture_output=True, text=True, timeout=120)
    assert "Traceback" not in pipe.stderr and "BrokenPipe" not in pipe.stderr, pipe.stderr
