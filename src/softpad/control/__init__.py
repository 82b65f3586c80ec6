"""Control: inflation and adjustment, the robot interface, the grasp-execution state machine.

``inflate_and_adjust`` brings every module to p0 within t_adj and saves the reference (seed,
Section 6.2.1.1); :class:`GraspExecution` runs the closed loop of Section 6.2.2 on any
:class:`~softpad.box.Box` and :class:`Robot`; :func:`run_simulated` runs it on the simulator
with objects of the catalogue, in-process or served over ``tcp://`` (:class:`RemoteRobot`,
:func:`simulation_extensions`).
"""

from softpad.control._execution import (
    OUTCOMES,
    ExecutionError,
    ExecutionParams,
    ExecutionResult,
    GraspExecution,
    GraspRecord,
    Recorder,
)
from softpad.control._inflation import (
    DEFAULT_MAX_PRESSURE_PA,
    DEFAULT_TARGET_PA,
    DEFAULT_TOLERANCE_PA,
    AdjustmentResult,
    InflationParams,
    check_frame,
    inflate_and_adjust,
    make_safe,
)
from softpad.control._remote import (
    SIMULATION_OPS,
    RemoteRobot,
    has_simulation,
    simulation_extensions,
)
from softpad.control._robot import Robot, SimulatedRobot, ToolPose
from softpad.control._safety import (
    DetectedFault,
    FaultMonitor,
    FaultThresholds,
    MonitoredFault,
    RunSafety,
    SafeStateResult,
    check_valves,
    reach_safe_state,
)
from softpad.control._simulation import resolve_objects, run_simulated

__all__ = [
    "DEFAULT_MAX_PRESSURE_PA",
    "DEFAULT_TARGET_PA",
    "DEFAULT_TOLERANCE_PA",
    "OUTCOMES",
    "SIMULATION_OPS",
    "AdjustmentResult",
    "DetectedFault",
    "ExecutionError",
    "ExecutionParams",
    "ExecutionResult",
    "FaultMonitor",
    "FaultThresholds",
    "GraspExecution",
    "GraspRecord",
    "InflationParams",
    "MonitoredFault",
    "Recorder",
    "RemoteRobot",
    "Robot",
    "RunSafety",
    "SafeStateResult",
    "SimulatedRobot",
    "ToolPose",
    "check_frame",
    "check_valves",
    "has_simulation",
    "inflate_and_adjust",
    "make_safe",
    "reach_safe_state",
    "resolve_objects",
    "run_simulated",
    "simulation_extensions",
]
