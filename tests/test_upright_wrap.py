"""The standing bottle's wrap in full dynamics (docs/design.md §5.4g, "Standing off")."""

import json
import math

import trimesh

from drake_grasp.cli import main


def test_the_upright_wrap_holds_a_standing_cylinder_with_its_distal_links_on_it(tmp_path, capsys):
    """A standing cylinder 6.4 cm across and 18 cm tall, wrapped from its true pose (trial seed 1): held
    without turning in the hand, with a distal link pressing it short of the 48° limit. Driven into
    contact (behaviour 0.24.0) the palm left all three distal links on their limit, and this cylinder
    turned 10-16° in the hand at every mass tried (docs/results/payload.md)."""
    mesh = trimesh.creation.cylinder(radius=0.032, height=0.18, sections=48)
    mesh.apply_translation([0.0, 0.0, 0.09])
    path = tmp_path / "standing_cylinder.obj"
    mesh.export(path)
    assert main(["trial", "--object", str(path), "--oracle", "--grasp", "cylindrical", "--seed", "1", "--json"]) == 0
    record = json.loads(capsys.readouterr().out)
    assert record["success"], (record["failure"], record["detail"])
    assert math.degrees(record["slip_angle"]) < 10.0
    distal = [math.degrees(a) for a in record["finger_angles"][4:7]]
    assert min(distal) < 45.0, distal  # the limit is 48°
