"""The `objects` command: object utilities (today: generate novel test objects)."""

import json

from drake_grasp.cli.common import UsageError, check_out_dir, check_seed


def add_objects(sub) -> None:
    """`drake-grasp objects`."""
    objects_cmd = sub.add_parser("objects", help="object utilities: generate novel test objects")
    objects_sub = objects_cmd.add_subparsers(dest="objects_command", metavar="ACTION", required=True)
    generate = objects_sub.add_parser(
        "generate",
        help="write N novel watertight meshes (metres) and a manifest",
        description="Writes N watertight OBJ meshes in metres (classes in turn: non-convex blobs, unions "
        "of boxes/cylinders/ellipsoids, thin plates, L and T shapes, rings, handles; largest extent "
        "3-25 cm) and manifest.json / manifest.csv. The same --seed gives byte-identical files.",
    )
    generate.add_argument("--count", type=int, required=True, metavar="N", help="how many objects")
    generate.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    generate.add_argument("--out", required=True, metavar="DIR", help="directory for the meshes and manifest")
    generate.add_argument("--json", action="store_true", help="print the manifest as one JSON object")
    generate.set_defaults(run=_run_objects_generate)


def _run_objects_generate(args) -> int:
    from drake_grasp.geometry import novel

    check_seed(args.seed)
    if args.count < 1:
        raise UsageError(f"--count must be >= 1, got {args.count}")
    out = check_out_dir(args.out)
    rows = novel.generate(args.count, args.seed, out)
    if args.json:
        print(json.dumps({"out": str(out), "objects": rows}))
    else:
        classes = sorted({r["class"] for r in rows})
        print(f"objects generate: {len(rows)} meshes ({', '.join(classes)}) in {out}; {out / 'manifest.json'}")
    return 0


