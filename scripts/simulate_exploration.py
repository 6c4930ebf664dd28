"""The visual primitives alone: the wrist camera explores an object, and the estimate (centre, axes,
size) and the three shape resemblances are printed beside the truth (drake_grasp.api).

Run: .venv/bin/python scripts/simulate_exploration.py --object bottle_case [--replay explore.html]
This is what `drake-grasp resemble` runs.
"""

import argparse

import numpy as np

from drake_grasp import api


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--object", default="bottle_case")
    parser.add_argument("--scenario-name", default="default")
    parser.add_argument("--replay", help="write a Meshcat replay here (.html)")
    args = parser.parse_args(argv)

    scenario = api.load_scenario(scenario_name=args.scenario_name)
    obj = api.resolve_object(args.object)
    result = api.explore(scenario, scenario.perception, obj, replay_html=args.replay)
    estimate = result.estimate
    print(f"{obj.name}: {estimate.status}")
    if not estimate.found:
        return 0
    print("  centre (m):     ", np.round(estimate.centre, 4))
    print("  extents (m):    ", np.round(estimate.extents, 4))
    print("  principal axis: ", None if estimate.principal_axis is None else np.round(estimate.principal_axis, 3))
    for shape, value in sorted(estimate.resemblances.items(), key=lambda item: -item[1]):
        print(f"  resembles a {shape:8s} {value:.3f}")
    # Evaluation only: the estimate against the object's true pose (never part of the decision).
    errors = api.compare(estimate, api.ground_truth(obj, result.X_WO_end))
    axis = "no long axis" if errors.axis_deg is None else f"axis {errors.axis_deg:.1f} deg"
    print(f"  against the truth: centre {errors.centre * 1000:.1f} mm, {axis}, "
          f"closest primitive named: {errors.shape_correct}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
