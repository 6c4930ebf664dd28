"""Gravity compensation for the WAM, as a feed-forward torque beside its joint PD actuators.

The real WAM runs gravity-compensated joint control; here the plant's implicit PD actuators track the
desired joint state and this system adds the torque that holds the arm (and the hand on it) against
gravity, computed on the plant itself at the measured configuration. The load of a grasped object is
not compensated (the controller does not know it), as on the real arm.
"""

from __future__ import annotations

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import ModelInstanceIndex
from pydrake.systems.framework import BasicVector, Context, LeafSystem


class GravityCompensation(LeafSystem):
    """Outputs -tau_g on one model instance's actuators.

    Input ports:
        plant_state: the whole plant's state [q; v] (plant.get_state_output_port()).
    Output ports:
        actuation: feed-forward torques, N*m, in the instance's actuator order
            (for plant.get_actuation_input_port(instance)).
    """

    def __init__(self, plant: MultibodyPlant, instance: ModelInstanceIndex):
        super().__init__()
        self._plant = plant
        self._plant_context = plant.CreateDefaultContext()
        self._instance = instance
        actuators = sorted(plant.GetJointActuatorIndices(instance), key=int)
        # Each actuated joint's velocity index in the whole plant, in the instance's actuator order.
        self._velocity_rows = np.array([plant.get_joint_actuator(a).joint().velocity_start() for a in actuators])
        self._plant_state_port = self.DeclareVectorInputPort("plant_state", plant.num_multibody_states())
        self.DeclareVectorOutputPort("actuation", len(actuators), self._CalcActuation)

    def _CalcActuation(self, context: Context, output: BasicVector) -> None:
        self._plant.SetPositionsAndVelocities(self._plant_context, self._plant_state_port.Eval(context))
        tau_g = self._plant.CalcGravityGeneralizedForces(self._plant_context)
        output.SetFromVector(-tau_g[self._velocity_rows])
