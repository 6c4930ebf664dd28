"""The `objects` command: object utilities: generate novel test objects, check an object file."""

import json

from drake_grasp.cli.common import UsageError, check_out_dir, check_seed
from drake_grasp.file_formats import MESH_FORMATS, MODEL_FORMATS


def add_objects(sub) -> None:
    """`drake-grasp objects`."""
    objects_cmd = sub.add_parser("objects", help="object utilities: generate novel test objects, check an object file")
    objects_sub = objects_cmd.add_subparsers(dest="objects_command", metavar="ACTION", required=True)
    generate = objects_sub.add_parser(
        "generate",
        help="write N generated test objects (metres) and a manifest",
        description="Writes N watertight objects in metres and manifest.json / manifest.csv. --kind novel "
        "(default): OBJ meshes, classes in turn: non-convex blobs, unions of boxes/cylinders/ellipsoids, "
        "thin plates, L and T shapes, rings, handles; largest extent 3-25 cm. --kind everyday: what "
        "users bring: polycubes, scans, mugs, bottles and boxes, every second one a URDF naming its mesh "
        "with a placeholder inertia. --kind flower: the thin, flat and small objects of the flower grasp: "
        "plates and tiles 6-12 mm thick, T and L shapes, sticks and pens, dominoes lying and standing, "
        "cubes of 2-3 cm, balls and fruit. --kind round: low round objects, fruit and balls 4-11 cm, every "
        "second one a URDF with a real mass. --kind tools: hand tools lying down, hammers, screwdrivers, spring "
        "clamps, markers and wrenches, every second one a URDF with its parts' real masses. --kind standing: "
        "slender objects standing on their end, pegs, pencils, markers, vials and sticks 0.8-3.4 cm across, every "
        "second one a URDF with a real mass. The same --seed gives byte-identical files.",
    )
    generate.add_argument("--kind", choices=("novel", "everyday", "flower", "round", "tools", "standing"), default="novel",
                          help="which generator (default novel)")
    generate.add_argument("--count", type=int, required=True, metavar="N", help="how many objects")
    generate.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    generate.add_argument("--out", required=True, metavar="DIR", help="directory for the meshes and manifest")
    generate.add_argument("--json", action="store_true", help="print the manifest as one JSON object")
    generate.set_defaults(run=_run_objects_generate)
    add_objects_check(objects_sub)


def _run_objects_generate(args) -> int:
    from drake_grasp.objects import everyday, flower, novel, round as round_objects, standing, tools

    check_seed(args.seed)
    if args.count < 1:
        raise UsageError(f"--count must be >= 1, got {args.count}")
    out = check_out_dir(args.out)
    generator = {"novel": novel, "everyday": everyday, "flower": flower, "round": round_objects, "tools": tools,
                 "standing": standing}[args.kind]
    rows = generator.generate(args.count, args.seed, out)
    if args.json:
        print(json.dumps({"out": str(out), "objects": rows}))
    else:
        classes = sorted({r["class"] for r in rows})
        print(f"objects generate: {len(rows)} {args.kind} objects ({', '.join(classes)}) in {out}; "
              f"{out / 'manifest.json'}")
    return 0




def add_objects_check(objects_sub) -> None:
    """`drake-grasp objects check`."""
    from drake_grasp.cli.common import add_mesh_options, object_argument

    check = objects_sub.add_parser(
        "check",
        help="load an object file as a trial would and say what was found and done",
        description=f"Loads FILE exactly as a trial would (mesh: {MESH_FORMATS}; model: {MODEL_FORMATS}) "
        "and prints what it found and did: repairs, shells joined into one object and their gaps, "
        "units, volume, mass and where the inertia came from, convex pieces, resting pose, load time. "
        "Exit code 0 for an accepted file, 2 (one line saying why) for a refused one.",
    )
    check.add_argument("file", metavar="FILE", type=object_argument, help="the object file (or a catalogue name or primitive)")
    add_mesh_options(check)
    check.add_argument("--replay", metavar="HTML", help="write a browser view of the convex pieces over the visual mesh")
    check.add_argument("--json", action="store_true", help="print one JSON object instead of lines")
    check.set_defaults(run=_run_objects_check)


def _run_objects_check(args) -> int:
    import dataclasses

    from drake_grasp.objects import check as object_check
    from drake_grasp.cli.common import jsonable, mesh_option_args, writable_file
    from drake_grasp.objects.names import is_mesh_file

    replay = writable_file(args.replay, ".html") if args.replay else None
    spec, report = object_check.check_object(args.file, **mesh_option_args(args))
    if replay:
        visual = args.file if is_mesh_file(args.file) and ":" not in args.file else None
        object_check.write_replay(spec, replay, visual, args.scale)
    if args.json:
        record = dataclasses.asdict(report)
        if replay:
            record["replay"] = str(replay)
        print(json.dumps(jsonable(record)))
    else:
        print("\n".join(report.lines()))
        if replay:
            print(f"replay: {replay}")
    return 0
