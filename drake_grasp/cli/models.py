"""The `models` command: write the robot's model files (models/*/*.sdf) from its facts.

`drake_grasp.robot.modelgen` is how the SDFormat files of the BarrettHand and the WAM were made from
the named constants of `robot.hand` and `robot.arm`; after changing a fact, run `drake-grasp models`
(or `python -m drake_grasp.robot.modelgen`). A test checks that the committed files equal what it writes.
"""

import json


def add_models(sub) -> None:
    """`drake-grasp models`."""
    models = sub.add_parser("models", help="write the hand's and the arm's SDF files from the robot's facts",
                            description="Writes models/barrett_hand/bh280.sdf and models/wam/wam7.sdf from the "
                            "constants of drake_grasp.robot.hand and drake_grasp.robot.arm (each with its source).")
    models.add_argument("--json", action="store_true", help="print one JSON object instead of lines")
    models.set_defaults(run=_run_models)


def _run_models(args) -> int:
    from drake_grasp.robot import modelgen

    written = [str(p) for p in modelgen.write_models()]
    print(json.dumps({"written": written}) if args.json else "\n".join(f"wrote {p}" for p in written))
    return 0
