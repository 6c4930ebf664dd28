"""Generated novel objects through whole trials: a failed grasp is fine, a crash is not.

The default suite runs the hardest classes (a blob and a ring whose CoACD pieces had sub-5e-11 m²
triangles before cleaning: "Cannot instantiate plane from normal" at t = 0); `-m slow` runs 40
objects, every oracle grasp and the camera-driven method.
"""

import pytest

from drake_grasp.geometry import novel
from drake_grasp.grasps import GraspType, oracle_estimate, plan_compliant_grasp
from drake_grasp.objects import object_from_mesh, pose_warnings_announced
from drake_grasp.station import load_scenario
from drake_grasp.trial import SIMULATION_ERROR, run_compliant_trial, run_trial

HARD = ((0, 7), (0, 5))  # (seed, index): blob_0_007 (3.7 cm) and ring_0_005, both crashed at t = 0


def _spec(tmp_path, seed, index):
    obj = novel.novel_object(seed, index)
    path = tmp_path / f"{obj.name}.obj"
    path.write_text(novel.obj_text(obj.mesh))
    with pose_warnings_announced():
        return object_from_mesh(path)


def _oracle(spec, grasp, seed=0, scenario=None):
    def plan(X_WO, object_spec):
        return plan_compliant_grasp(grasp, oracle_estimate(X_WO, object_spec))

    return run_trial(scenario or load_scenario(), spec, plan, seed=seed, method="oracle", grasp=grasp)


@pytest.mark.parametrize("seed, index", HARD)
def test_hardest_generated_objects_simulate(tmp_path, seed, index, short_scenario):
    # They crashed at t = 0: the short hold is enough to show they no longer do.
    record = _oracle(_spec(tmp_path, seed, index), "box", scenario=short_scenario)
    assert record.failure != SIMULATION_ERROR, record.summary()


@pytest.mark.slow
@pytest.mark.parametrize("index", range(40))
def test_forty_generated_objects_never_crash(tmp_path, index):
    spec = _spec(tmp_path, 0, index)
    records = [_oracle(spec, grasp) for grasp in (g.value for g in GraspType)]
    records.append(run_compliant_trial(load_scenario(), spec, seed=0))
    crashed = [r.summary() for r in records if r.failure == SIMULATION_ERROR]
    assert not crashed, crashed
