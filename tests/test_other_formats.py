"""Files users bring that are not read here are refused in one line that says what to give instead
(drake_grasp.objects.other_formats), before any work, with exit code 2."""

import pytest

from drake_grasp import cli
from drake_grasp.objects.other_formats import advice


@pytest.mark.parametrize("name, words", [
    ("arm.urdf.xacro", "xacro FILE > object.urdf"),
    ("part.STEP", "a CAD file (STEP)"),
    ("mug.skp", "a SketchUp model"),
    ("scene.blend", "a Blender file"),
    ("cloud.pcd", "reconstruct a surface"),
])
def test_each_format_names_what_to_give_instead(tmp_path, capsys, name, words):
    path = tmp_path / name
    path.write_bytes(b"not a mesh\n")
    assert words in advice(path)
    assert cli.main(["trial", "--object", str(path), "--method", "compliant"]) == 2
    err = capsys.readouterr().err
    assert words in err and err.strip().count("\n") == 0 and "Traceback" not in err


def test_formats_read_here_have_no_advice():
    assert advice("mug.obj") is None and advice("mug.3mf") is None and advice("model.urdf") is None


def _glb_requiring(extension: str) -> bytes:
    """A box as a GLB whose JSON chunk also requires `extension` (the geometry itself left plain)."""
    import json
    import struct

    import trimesh

    data = trimesh.creation.box((0.05, 0.06, 0.07)).export(file_type="glb")
    length = struct.unpack_from("<I", data, 12)[0]
    document = json.loads(data[20:20 + length])
    document["extensionsRequired"] = document["extensionsUsed"] = [extension]
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    rest = data[20 + length:]
    return b"glTF" + struct.pack("<II", 2, 12 + 8 + len(text) + len(rest)) + struct.pack("<II", len(text), 0x4E4F534A) + text + rest


@pytest.mark.parametrize("extension, words", [("EXT_meshopt_compression", "not decoded here"),
                                              ("KHR_texture_transform", None)])
def test_a_gltf_whose_meshes_are_compressed_says_so_in_one_line(tmp_path, capsys, extension, words):
    """Draco- or meshopt-compressed glTF geometry reads as placeholder zeros without a decoder (a "flat"
    mesh): the file's extensionsRequired says why. An extension that compresses nothing changes nothing."""
    path = tmp_path / "box.glb"
    path.write_bytes(_glb_requiring(extension))
    code = cli.main(["objects", "check", str(path)])
    err = capsys.readouterr().err.strip().splitlines()
    if words is None:
        assert code == 0
    else:
        assert code == 2 and len(err) == 1 and f"compressed (glTF extension {extension})" in err[0] and words in err[0]
