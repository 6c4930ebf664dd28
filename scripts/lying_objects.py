"""Lying bottles and cylinders as OBJ files, with a list for `scripts/holding_study.py --files`.

What: from `numpy.random.default_rng(SEED)`, six bottles (`objects.everyday`'s revolved profile:
5-9 cm across, 12-24 cm long) and then six plain cylinders (3-8 cm across, 8-22 cm long), each turned
to lie with its axis along x and written centred on its box. The loader rests each on its side.

Why: a bottle, a can or a marker lying on the table is among the commonest things a user asks the hand
to pick up, and none of the generators lays one down (the everyday set's bottles stand). The fingers
close on such an object under its widest line, where the funnel search's ε is 0 (docs/design.md
§5.4s); these files measured that (docs/results/holding/cradle.md: seed 2001 while developing, 2002
fresh).

Run: .venv/bin/python scripts/lying_objects.py --seed 2002 --out out/lying
     .venv/bin/python scripts/holding_study.py --files out/lying/list.tsv --seeds 1,2 --attempts 1 \\
         --scenarios funnel --workers 2 --out out/lying_study
"""

import argparse
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.everyday import _bottle


def lying_objects(seed: int) -> list[tuple[str, str, trimesh.Trimesh]]:
    """(class, name, mesh) of the twelve objects of `seed`, in the order they are drawn."""
    rng = np.random.default_rng(seed)
    lay = trimesh.transformations.rotation_matrix(np.pi / 2, [0.0, 1.0, 0.0])
    objects = []
    for i in range(6):
        mesh = _bottle(rng)
        mesh.apply_transform(lay)
        mesh.apply_translation(-mesh.bounds.mean(axis=0))
        objects.append(("bottle", f"bottle_{i}", mesh))
    for i in range(6):
        radius, length = rng.uniform(0.015, 0.04), rng.uniform(0.08, 0.22)
        mesh = trimesh.creation.cylinder(radius=radius, height=length, sections=48)
        mesh.apply_transform(lay)
        objects.append(("cylinder", f"cylinder_{i}", mesh))
    return objects


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=2002, help="numpy's default_rng seed")
    parser.add_argument("--out", default="out/lying", help="the folder the OBJ files and list.tsv go to")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"# lying bottles and cylinders: scripts/lying_objects.py --seed {args.seed}"]
    for shape_class, name, mesh in lying_objects(args.seed):
        mesh.export(out / f"{name}.obj")
        lines.append(f"{shape_class}\t{name}.obj")
    (out / "list.tsv").write_text("\n".join(lines) + "\n")
    print(f"{len(lines) - 1} objects in {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
