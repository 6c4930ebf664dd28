"""One trial as plain data (`TrialSpec`): what to grasp, by which method, with which seed, where.

A spec is all a worker needs to run a trial (`trial.run`): Drake Diagrams and Contexts do not pickle,
so every worker builds its own from the spec. A spec also decides its record's fingerprint
(`sweeps.fingerprint.trial_fingerprint`).
"""

import dataclasses

from drake_grasp.estimate_error import EstimateError

# The methods a trial can run: a compliant grasp from the ground truth, the compliance-centric
# algorithm (camera), the Eigengrasp planner's grasp.
METHODS = ("oracle", "compliant", "eigengrasp")
MAX_ATTEMPTS = 10  # a grasp's attempts at most (`trial.attempts`)


@dataclasses.dataclass(frozen=True)
class PlannerSettings:
    """How a planner trial plans when its spec has no planned grasp yet (the command line's
    `trial --method eigengrasp`; Fig. 7 plans once per object and gives each trial its grasp).

    Attributes:
        energy: the planner's energy, "contact" or "contact-quality".
        steps: its step limit (GraspIt!'s counter, which starts at 30,000).
        seed: its random seed.
        rank: execute the rank-th best of its grasps that the arm can reach (1 = the best).
    """

    energy: str = "contact-quality"
    steps: int = 70_000
    seed: int = 0
    rank: int = 1

    @property
    def label(self) -> str:
        """The grasp label of such a trial, as Fig. 7 labels the same plan's grasp: "energy/steps/seedS#rank"."""
        return f"{self.energy}/{self.steps}/seed{self.seed}#{self.rank}"


@dataclasses.dataclass(frozen=True)
class TrialSpec:
    """One trial as plain data.

    Attributes:
        object: catalogue name, primitive or mesh path.
        method: "oracle" (compliant grasp from ground truth), "compliant" (from the camera), or
            "eigengrasp" (a planned grasp: given in `planned`, or planned in the trial with `planner`).
        grasp: "spherical" | "cylindrical" | "box" for compliant methods ("" with "compliant": the
            algorithm's own choice); a label for planned grasps.
        seed: the trial's seed (its variation; shared by every method).
        scenario_file, scenario_name: the station scenario; no name (None): the paper's algorithm for
            the paper's objects and primitives, the best estimate (table-top) for object files and
            generated objects (`station.default_scenario_name`), resolved when the spec is made.
        planned: for planned grasps: {"X_OH": 4x4 list, "joint_angles": 8 floats} (and what else the
            planner said of it: epsilon, energy, planner_rank).
        scale, largest_component, join_gap, inertia, package_path: an object file's options
            (`objects.resolve_user_object`).
        estimate_error: a known error added to the estimate the grasp is computed from (issue 15's
            capture regions; `estimate_error.EstimateError`): for "oracle" the ground-truth estimate,
            for "compliant" the camera's; for "eigengrasp" the object pose the planned hand pose is
            expressed against (X_WH = X_WO_erred X_OH; no size error: the planner has the exact model).
        planner: for "eigengrasp" with no `planned` grasp: plan in the trial with these settings
            (default `PlannerSettings()`).
        attempts: how often the compliance-centric algorithm may try (`trial.attempts`): 1, the paper's
            protocol; more: an attempt the wrist camera sees fail is followed by a fresh look and the next
            candidate.
    """

    object: str
    method: str
    grasp: str
    seed: int
    scenario_file: str = ""
    scenario_name: str | None = None
    planned: dict | None = None
    scale: float = 1.0
    largest_component: bool = False
    join_gap: float | None = None
    inertia: str = "check"
    package_path: tuple[str, ...] = ()
    estimate_error: EstimateError | None = None
    planner: PlannerSettings | None = None
    attempts: int = 1

    def __post_init__(self):
        if not (isinstance(self.attempts, int) and 1 <= self.attempts <= MAX_ATTEMPTS):
            raise ValueError(f"attempts must be an integer from 1 to {MAX_ATTEMPTS}, got {self.attempts}")
        if self.attempts > 1 and (self.method != "compliant" or self.grasp):
            raise ValueError("attempts: only the compliance-centric algorithm's own choice tries again "
                             "(method compliant, no grasp named)")
        if self.scenario_name is None:
            from drake_grasp.station import default_scenario_name

            object.__setattr__(self, "scenario_name", default_scenario_name(self.object, self.scenario_file))
        error = self.estimate_error
        if self.method == "eigengrasp" and error is not None and error.size_scale != 1:
            raise ValueError("a size error does not apply to the Eigengrasp planner (it has the exact model)")

    def object_options(self) -> dict:
        """The object-file options that differ from their defaults and that the object takes
        (keyword arguments)."""
        from drake_grasp.objects.names import mesh_options, options_for

        return options_for(self.object, **mesh_options(self.scale, self.largest_component, self.join_gap,
                                                       self.inertia, self.package_path))

    @property
    def has_estimate_error(self) -> bool:
        """Whether the spec adds a (non-zero) error to the estimate."""
        return self.estimate_error is not None and not self.estimate_error.is_zero
