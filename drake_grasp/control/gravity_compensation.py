"""Gravity compensation for the WAM, as a feed-forward torque beside its joint PD actuators.

The real WAM runs gravity-compensated joint control; here the plant's implicit PD actuators track the
desired joint state and this system adds the torque that holds the arm (and the hand on it) against
gravity, computed on the plant itself at the measured configuration. The load of a grasped object is
not compensated (the controller does not know it), as on the real arm.

It is built from Drake's own compiled systems (docs/performance.md): `InverseDynamics` in its
gravity-compensation mode computes -tau_g(q) for every generalized velocity of the plant, and a
`Selector` keeps the rows of the instance's actuated joints. The torque is evaluated at every plant
step (it feeds the plant's actuation input directly), so a Python callback here cost about 0.1 ms a
step; the numbers are the same (`MultibodyPlant.CalcGravityGeneralizedForces` either way).
"""

from __future__ import annotations

from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import ModelInstanceIndex
from pydrake.systems.controllers import InverseDynamics
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.primitives import Selector, SelectorParams


class GravityCompensation(Diagram):
    """Outputs -tau_g on one model instance's actuators.

    Input ports:
        plant_state: the whole plant's state [q; v] (plant.get_state_output_port()).
    Output ports:
        actuation: feed-forward torques, N*m, in the instance's actuator order
            (for plant.get_actuation_input_port(instance)).
    """

    def __init__(self, plant: MultibodyPlant, instance: ModelInstanceIndex):
        super().__init__()
        actuators = sorted(plant.GetJointActuatorIndices(instance), key=int)
        # Each actuated joint's velocity index in the whole plant, in the instance's actuator order.
        velocity_rows = [plant.get_joint_actuator(a).joint().velocity_start() for a in actuators]
        builder = DiagramBuilder()
        gravity = builder.AddNamedSystem("gravity_torque", InverseDynamics(
            plant, InverseDynamics.InverseDynamicsMode.kGravityCompensation))
        select = builder.AddNamedSystem("actuated_rows", Selector(SelectorParams(
            inputs=[SelectorParams.InputPortParams(name="generalized_force", size=plant.num_velocities())],
            outputs=[SelectorParams.OutputPortParams(name="actuation", selections=[
                SelectorParams.OutputSelection(input_port_index=0, input_offset=int(row))
                for row in velocity_rows])])))
        builder.Connect(gravity.get_output_port_generalized_force(), select.get_input_port(0))
        builder.ExportInput(gravity.get_input_port_estimated_state(), "plant_state")
        builder.ExportOutput(select.get_output_port(0), "actuation")
        builder.BuildInto(self)
