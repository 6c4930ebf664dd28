"""How much of a Fig. 6 study could sharing save? Measures, warm and in one process, the set-up of a
trial (station Diagram, scenario, supervisor) against its simulation, and the exploration alone
against the three forced grasps of one (object, seed), for the planning of issue 23 ("share what
trials have in common"). Nothing is changed; it only times today's code.

Run: .venv/bin/python scripts/profile_study_sharing.py   (about 3 minutes on 2 cores)
"""

import time, warnings
warnings.simplefilter("ignore")
from drake_grasp import trial
from drake_grasp.trial import TrialSpec
from drake_grasp.perception import explore
from drake_grasp.station import load_scenario
from drake_grasp.objects import resolve_object
sc = load_scenario()
trial.run(TrialSpec("apple", "compliant", "box", 0))  # warm: imports, renderer, caches
# Exploration: the camera-driven trial's exploration alone (what `resemble` runs), the object at its
# nominal pose; the three grasps: whole camera-driven trials, seed 1, each exploring again.
for name in ("apple", "bottle_case", "sponge", "soccer_ball"):
    obj = resolve_object(name)
    t = time.perf_counter(); explore(sc, None, obj); e = time.perf_counter() - t
    ts = []
    for g in ("spherical", "cylindrical", "box"):
        t = time.perf_counter(); trial.run(TrialSpec(name, "compliant", g, 1), scenario=sc, obj=obj); ts.append(time.perf_counter() - t)
    full = sum(ts)
    shared = e + sum(t - e for t in ts)
    print(f"{name:12s} exploration {e:5.2f} s; three grasps {full:5.2f} s; with one shared exploration {shared:5.2f} s ({shared/full:.2f})")
