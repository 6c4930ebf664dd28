"""The task supervisor of the compliance-centric algorithm: explore → decide → approach → close → lift → hold.

The paper's algorithm (Sec. 1 and 5) as one LeafSystem in one Diagram with the station and the visual
primitives:

    ExplorationSequencer ──phase──────────────┐
    ObjectEstimator ──estimate────────────────┴─> CompliantGraspSupervisor ──arm_source──> PortSwitch
    CameraTwistController ──wam.desired_state──────────────────────────────────────────┘    │
    CompliantGraspSupervisor ──wam.desired_state──────────────────────────────────> PortSwitch ──> station
    CompliantGraspSupervisor ──hand.command, hand.finger_preshape─────────────────────────────────> station
    CompliantGraspSupervisor ──camera_motion_active──> CameraTwistController.active (0 once it grasps)

* **explore**: while the sequencer runs the primitives, the camera motion drives the arm (the switch
  routes it to the station) and the hand is held open.
* **decide**: when the exploration ends, the supervisor reads the estimate. The compliant grasp is the
  one of the most resembling shape (`grasps.GRASP_OF_SHAPE`), unless the caller forced one (Fig. 6
  executes all three). Its hand pose is computed from the estimate alone (`grasps.plan_compliant_grasp`):
  no object model, no ground truth, no contact planning. With the funnel search (a scenario's
  `perception.grasp_search`, beyond the paper), each grasp's pose is varied and scored by closing the
  hand quasi-statically on the shape the depth views saw, a grasp with an empty funnel is not chosen
  when another has one, and a grasp whose own pose has an empty funnel is moved to the centre of the
  widest one (`funnel.planning.choose_grasp`). A study of how far off an estimate may be
  (issue 15) gives a known `estimate_error.EstimateError`, added to the estimate before the grasp
  is computed from it (the decision, the grasp of the most resembling shape, is not affected).
* **approach, close, lift, hold**: the same sequence, controller and timings as every other method
  (`GraspExecutor`), from where the exploration left the arm; the switch now routes the supervisor's
  arm command.

If the object was never seen (`OBJECT_NOT_FOUND`), the estimate cannot place a grasp (`PERCEPTION_FAILED`:
a size that is not positive, a principal axis that did not converge, a value that is not finite, no
usable silhouette; `ObjectEstimate.problem` says which), or the arm cannot reach the chosen grasp, the
sequence ends (GraspPhase.DONE) with that outcome and its detail instead of grasping: a trial's failure
reason, never a simulation error.
"""

import dataclasses

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import Context, DiagramBuilder, InputPortIndex
from pydrake.systems.primitives import PortSwitch

from drake_grasp.control.arm_motion import UNREACHABLE, ReachError
from drake_grasp.control.grasp_executor import ConnectGraspExecutor, GraspExecutor, _Progress
from drake_grasp.estimate_error import EstimateError, perturb_estimate
from drake_grasp.protocol import ExecutionTimes
from drake_grasp.funnel.params import FunnelParams
from drake_grasp.funnel.planning import choose_grasp
from drake_grasp.grasps import GraspPlan, GraspType
from drake_grasp.primitives.estimate import OBJECT_NOT_FOUND, PERCEPTION_FAILED, ObjectEstimate
from drake_grasp.primitives.sequencer import phase_value
from drake_grasp.primitives.table_top import HeightMap


@dataclasses.dataclass(frozen=True)
class Decision:
    """What the supervisor decided when the exploration ended.

    Attributes:
        time: when, s.
        estimate: the primitives' estimate it decided on (without any added estimate error).
        chosen: the grasp of the most resembling shape ("" if the object was not found or its
            estimate cannot place a grasp).
        executed: the grasp executed: `chosen`, or the one the caller forced.
        plan: the executed grasp's plan, from the estimate with the added error if any (None if the
            object was not found or its estimate cannot place a grasp).
        paper_choice: the paper's argmax alone ("" as `chosen`); differs from `chosen` where the funnel
            search vetoed it (`primitives.decision.choose_with_funnels`).
        grasp_search: the funnel search's summary (`funnel.search.FunnelSearch.summary`), or None
            without one (the paper's algorithm).
    """

    time: float
    estimate: ObjectEstimate
    chosen: str
    executed: str
    plan: GraspPlan | None
    paper_choice: str = ""
    grasp_search: dict | None = None


class CompliantGraspSupervisor(GraspExecutor):
    """Explores, decides the compliant grasp from the estimate, and executes it (module docstring).

    Input ports (besides GraspExecutor's `wam.state` and `contact_results`):
        exploration_phase (1): the ExplorationSequencer's phase.
        object_estimate: the ObjectEstimator's estimate (abstract).
        height_map: the depth views' `table_top.HeightMap` (abstract; connected with the table-top
            estimate): the shape the funnel search closes the hand on. Unconnected: no search.
    Output ports (besides GraspExecutor's):
        arm_source: the InputPortIndex of the arm switch's port that drives the WAM: the camera
            motion while exploring (and after a sequence that ended without a grasp), the
            supervisor's own `wam.desired_state` from the decision on.
        camera_motion_active (1): 1 while the camera motion drives the arm, 0 from the decision to
            grasp on (for the camera motion controller's `active`: its output then goes nowhere,
            and it never drives the arm again).
    """

    def __init__(self, plant, scene_graph, wam, hand_bodies: list, q_start: np.ndarray, times: ExecutionTimes,
                 arm_sources: tuple[InputPortIndex, InputPortIndex], forced_grasp: str | None = None,
                 estimate_error: EstimateError | None = None, grasp_search: FunnelParams | None = None,
                 exclude: tuple = ()):
        """
        Args:
            plant, scene_graph, wam, hand_bodies, times: as GraspExecutor's.
            q_start: the arm's joint angles at time 0 (the exploration's start), rad.
            arm_sources: the arm switch's input port indices of (the camera motion, this system).
            forced_grasp: execute this grasp instead of the most resembling shape's (Fig. 6); the
                default of the context's `forced_grasp` parameter (`set_forced_grasp`).
            estimate_error: a known error added to the estimate before the grasp is computed from it.
            grasp_search: the funnel search's choices (`funnel.search`; it reads `height_map`); None:
                each grasp at its primitive's pose, as the paper.
            exclude: grasps that already failed on this object, once per failure (a later attempt:
                `trial.attempts`; `funnel.planning.choose_grasp`).
        """
        self._estimate_error = estimate_error
        self._exclude = tuple(exclude)
        self._grasp_search = grasp_search
        self._arm_sources = arm_sources
        super().__init__(plant, scene_graph, wam, hand_bodies, None, q_start, times)
        self._phase_port = self.DeclareVectorInputPort("exploration_phase", 1)
        self._estimate_port = self.DeclareAbstractInputPort(
            "object_estimate", AbstractValue.Make(ObjectEstimate(status=OBJECT_NOT_FOUND)))
        self._height_map_port = self.DeclareAbstractInputPort(
            "height_map", AbstractValue.Make(HeightMap(np.zeros(2), 0.003, np.full((1, 1), np.nan))))
        # The grasp to execute instead of the chosen one ("": the chosen one). A parameter, not a
        # constant of the system, so that one exploration can be continued with each grasp from a
        # clone of its context (`trial.execution.execute_branches`).
        self._forced_grasp_index = self.DeclareAbstractParameter(AbstractValue.Make(_grasp_name(forced_grasp)))
        self.DeclareAbstractOutputPort("arm_source", lambda: AbstractValue.Make(arm_sources[0]), self._CalcArmSource,
                                       {self.abstract_state_ticket(self._progress_index)})
        self.DeclareVectorOutputPort("camera_motion_active", 1, self._CalcCameraMotionActive,
                                     {self.abstract_state_ticket(self._progress_index)})

    def set_forced_grasp(self, context: Context, grasp: str | None) -> None:
        """Makes the decision in `context` (this system's) execute `grasp` instead of the chosen
        one (None: the chosen one). Takes effect at the decision, so only before it."""
        context.get_mutable_abstract_parameter(self._forced_grasp_index).set_value(_grasp_name(grasp))

    def forced_grasp(self, context: Context) -> str | None:
        """The grasp the decision in `context` will execute instead of the chosen one (None: the chosen one)."""
        return context.get_abstract_parameter(self._forced_grasp_index).get_value() or None

    def decision(self, context: Context) -> Decision | None:
        """The decision, once made (None while exploring)."""
        return self.progress(context).decision

    def _CalcArmSource(self, context: Context, output: AbstractValue) -> None:
        grasping = self.progress(context).motion is not None
        output.set_value(self._arm_sources[1] if grasping else self._arm_sources[0])

    def _CalcCameraMotionActive(self, context: Context, output) -> None:
        output.SetAtIndex(0, 0.0 if self.progress(context).motion is not None else 1.0)

    def _Explore(self, context: Context, progress: _Progress) -> _Progress:
        if not phase_value(self._phase_port.Eval(context)[0]).finished:
            return progress
        t = context.get_time()
        estimate: ObjectEstimate = self._estimate_port.Eval(context)
        forced = self.forced_grasp(context)
        problem = estimate.problem()
        if problem:
            decision = Decision(t, estimate, "", forced or "", None)
            not_found = estimate.status == OBJECT_NOT_FOUND
            outcome, detail = (OBJECT_NOT_FOUND, "") if not_found else (PERCEPTION_FAILED, problem)
            return dataclasses.replace(self._end(progress, t, outcome, detail), decision=decision)
        height_map = self._height_map_port.Eval(context) if self._height_map_port.HasValue(context) else None
        choice = choose_grasp(estimate, perturb_estimate(estimate.as_grasp_estimate(), self._estimate_error), forced,
                              self._grasp_search, height_map, self._exclude)
        decision = Decision(t, estimate, choice.chosen, choice.executed, choice.plan, choice.paper_choice,
                            None if choice.search is None else choice.search.summary())
        q_now = np.asarray(self._wam_state_port.Eval(context), float)[:7]
        try:
            started = self._start_grasp(progress, choice.plan, q_now, t, choice.alternatives)
        except ReachError as e:
            return dataclasses.replace(self._end(progress, t, UNREACHABLE, str(e)), decision=decision)
        return dataclasses.replace(started, decision=decision)


def _grasp_name(grasp: str | None) -> str:
    """A grasp's canonical name ("" for none; ValueError for an unknown one)."""
    return GraspType.parse(grasp).value if grasp else ""


def AddCompliantGraspSupervisor(builder: DiagramBuilder, station, primitives, sequencer,
                                q_start: np.ndarray, times: ExecutionTimes, forced_grasp: str | None = None,
                                estimate_error: EstimateError | None = None,
                                grasp_search: FunnelParams | None = None, exclude: tuple = ()
                                ) -> CompliantGraspSupervisor:
    """Adds the supervisor and the arm switch, and connects them to the station, the primitives'
    estimator, the sequencer and the camera motion controller.

    Args:
        builder: holds the station's Diagram (`station.diagram`), and the primitives added by
            `perception.AddVisualPrimitives(..., connect_arm=False)` and `AddExplorationSequencer`.
        station: the station (its Diagram, plant, scene graph, arm and hand).
        primitives: `perception.VisualPrimitives`.
        sequencer: the ExplorationSequencer.
        q_start: the arm's joint angles at time 0, rad.
        times: the grasp sequence's timings (the scenario's protocol.execution).
        forced_grasp: execute this grasp instead of the chosen one.
        estimate_error: a known error added to the estimate before the grasp is computed from it.
        grasp_search: the funnel search's choices (the scenario's `perception.grasp_search`).
        exclude: grasps that already failed on this object, once per failure (a later attempt).
    """
    station_system = station.diagram
    switch = builder.AddNamedSystem("arm_command_switch", PortSwitch(14))
    camera_port = switch.DeclareInputPort("camera_motion")
    grasp_port = switch.DeclareInputPort("grasp")
    plant = station.plant
    supervisor = builder.AddNamedSystem("supervisor", CompliantGraspSupervisor(
        plant, station.scene_graph, station.wam, plant.GetBodyIndices(station.hand), q_start, times,
        (camera_port.get_index(), grasp_port.get_index()), forced_grasp, estimate_error, grasp_search, exclude))
    builder.Connect(primitives.camera_motion.GetOutputPort("wam.desired_state"), camera_port)
    builder.Connect(supervisor.GetOutputPort("wam.desired_state"), grasp_port)
    builder.Connect(supervisor.GetOutputPort("arm_source"), switch.get_port_selector_input_port())
    builder.Connect(supervisor.GetOutputPort("camera_motion_active"), primitives.camera_motion.GetInputPort("active"))
    builder.Connect(switch.get_output_port(), station_system.GetInputPort("wam.desired_state"))
    builder.Connect(sequencer.GetOutputPort("phase"), supervisor.GetInputPort("exploration_phase"))
    builder.Connect(primitives.estimator.GetOutputPort("estimate"), supervisor.GetInputPort("object_estimate"))
    if primitives.depth_views is not None:
        builder.Connect(primitives.depth_views.GetOutputPort("height_map"), supervisor.GetInputPort("height_map"))
    ConnectGraspExecutor(builder, station_system, supervisor, arm=False)
    return supervisor
