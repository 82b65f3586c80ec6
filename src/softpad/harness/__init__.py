"""The simulated lab: a robot on the simulated world, runs of the loop, ground truth.

The control layer knows nothing of the simulator; this package joins them.
:func:`build_loop` is the one place the grasp loop is assembled, for every entry point.
:class:`SimulatedRobot` implements :class:`softpad.control.Robot` on a
:class:`softpad.sim.World` and logs each descent's first fingertip touch (ground truth, used
only to score a run); :func:`run_simulated` runs the loop with catalogue objects, in-process or
against a simulator served over ``zenoh://`` (:class:`RemoteRobot`,
:func:`simulation_extensions`).
"""

from softpad.harness._assembly import (
    BuiltLoop,
    WorldAccess,
    build_loop,
    execution_params,
    world_access,
)
from softpad.harness._command import (
    EVENT_TEXT,
    box_layout,
    box_loop_parts,
    fault_report,
    retry_text,
    run_objects,
    run_with_robot,
    timeline,
)
from softpad.harness._inflation_study import (
    InflationPoint,
    inflation_study,
    recommend_p0,
)
from softpad.harness._remote import (
    SIMULATION_OPS,
    RemoteRobot,
    has_simulation,
    served_simulation,
    simulation_extensions,
)
from softpad.harness._robot import SimulatedRobot, TouchTruth, open_sim_robot
from softpad.harness._run import SimulatedRun, resolve_objects, run_simulated

__all__ = [
    "EVENT_TEXT",
    "SIMULATION_OPS",
    "BuiltLoop",
    "InflationPoint",
    "RemoteRobot",
    "SimulatedRobot",
    "SimulatedRun",
    "TouchTruth",
    "WorldAccess",
    "box_layout",
    "box_loop_parts",
    "build_loop",
    "execution_params",
    "fault_report",
    "has_simulation",
    "inflation_study",
    "open_sim_robot",
    "recommend_p0",
    "resolve_objects",
    "retry_text",
    "run_objects",
    "run_simulated",
    "run_with_robot",
    "served_simulation",
    "simulation_extensions",
    "timeline",
    "world_access",
]
