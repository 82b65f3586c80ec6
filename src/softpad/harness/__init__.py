"""The simulated lab: a robot on the simulated world, runs of the loop, ground truth.

The control layer knows nothing of the simulator; this package joins them.
:class:`SimulatedRobot` implements :class:`softpad.control.Robot` on a
:class:`softpad.sim.World` and logs each descent's first fingertip touch (ground truth, used
only to score a run); :func:`run_simulated` runs the loop with catalogue objects, in-process or
against a simulator served over ``zenoh://`` (:class:`RemoteRobot`,
:func:`simulation_extensions`).
"""

from softpad.harness._inflation_study import (
    InflationPoint,
    inflation_study,
    recommend_p0,
)
from softpad.harness._remote import (
    SIMULATION_OPS,
    RemoteRobot,
    has_simulation,
    simulation_extensions,
)
from softpad.harness._robot import SimulatedRobot, TouchTruth, open_sim_robot
from softpad.harness._run import SimulatedRun, resolve_objects, run_simulated

__all__ = [
    "SIMULATION_OPS",
    "InflationPoint",
    "RemoteRobot",
    "SimulatedRobot",
    "SimulatedRun",
    "TouchTruth",
    "has_simulation",
    "inflation_study",
    "open_sim_robot",
    "recommend_p0",
    "resolve_objects",
    "run_simulated",
    "simulation_extensions",
]
