"""Fig. 7 on one object, from the library's public names (drake_grasp.api): GraspIt!'s Eigengrasp
planner plans (the table loaded) and its best grasp the arm can reach is executed, against the
compliance-centric algorithm's own choice from the camera, with the same seed and success test.

Run: .venv/bin/python scripts/compare_fig7.py --object sponge [--seed 0] [--steps 70000]
This is one object and one trial of `drake-grasp fig7`.
"""

import argparse

from drake_grasp import api


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--object", default="sponge")
    parser.add_argument("--seed", type=int, default=0, help="the trial's seed (the object's placement)")
    parser.add_argument("--steps", type=int, default=70_000, help="the planner's step limit")
    parser.add_argument("--hold", type=float, help="hold time, s (default: the scenario's)")
    args = parser.parse_args(argv)

    scenario = api.load_scenario()
    if args.hold is not None:
        scenario.protocol.execution.hold_time = args.hold
    obj = api.resolve_object(args.object)

    # The planner: its best grasp that the WAM can reach (None, and why, if none).
    planned, why = api.plan_reachable_grasp(scenario, obj, api.PlannerSettings(steps=args.steps))
    if planned is None:
        print(f"Eigengrasp planner: {why}")
    else:
        record = api.run(api.TrialSpec(args.object, "eigengrasp", "planned", args.seed, planned=planned),
                         scenario=scenario, obj=obj)
        print(f"Eigengrasp planner (epsilon {planned.get('epsilon', float('nan')):.3f}): {record.summary()}")

    # The compliance-centric algorithm: explore, choose a compliant grasp, grasp.
    record = api.run(api.TrialSpec(args.object, "compliant", "", args.seed), scenario=scenario, obj=obj)
    print(f"compliance-centric ({record.chosen_grasp} chosen): {record.summary()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
