"""Control: inflation and adjustment, the robot interface, the grasp execution.

``inflate_and_adjust`` brings every module to p0 within t_adj and saves the reference (seed,
Section 6.2.1.1); :class:`GraspExecution` runs the closed loop of Section 6.2.2 on any
:class:`~softpad.box.Box` and :class:`Robot`, with the planner, object detector, contact
detector and :class:`Recorder` it is given. Nothing here knows the simulator
(``softpad.harness`` joins the two).
"""

from softpad.control._execution import (
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
    FillRates,
    InflationController,
    InflationParams,
    SampleNoise,
    check_frame,
    inflate_and_adjust,
    make_safe,
)
from softpad.control._parts import loop_parts
from softpad.control._phases import TRANSITIONS, Phase, PhaseError, next_phase
from softpad.control._robot import Robot, RobotState, RobotWrapper, ToolPose
from softpad.control._robots import (
    ROBOT_REGISTRY,
    RobotContext,
    RobotFactory,
    available_robots,
    make_robot,
    register_robot,
)
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
from softpad.control._watch import ObjectWatch, plan_from_reads

__all__ = [
    "DEFAULT_MAX_PRESSURE_PA",
    "DEFAULT_TARGET_PA",
    "DEFAULT_TOLERANCE_PA",
    "ROBOT_REGISTRY",
    "TRANSITIONS",
    "AdjustmentResult",
    "DetectedFault",
    "ExecutionError",
    "ExecutionParams",
    "ExecutionResult",
    "FaultMonitor",
    "FaultThresholds",
    "FillRates",
    "GraspExecution",
    "GraspRecord",
    "InflationController",
    "InflationParams",
    "MonitoredFault",
    "ObjectWatch",
    "Phase",
    "PhaseError",
    "Recorder",
    "Robot",
    "RobotContext",
    "RobotFactory",
    "RobotState",
    "RobotWrapper",
    "RunSafety",
    "SafeStateResult",
    "SampleNoise",
    "ToolPose",
    "available_robots",
    "check_frame",
    "check_valves",
    "inflate_and_adjust",
    "loop_parts",
    "make_robot",
    "make_safe",
    "next_phase",
    "plan_from_reads",
    "reach_safe_state",
    "register_robot",
]
