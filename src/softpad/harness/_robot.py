"""The simulated robot: the control layer's :class:`~softpad.control.Robot` on a simulated world."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from softpad.control import RobotState, ToolPose
from softpad.errors import InputError
from softpad.sim import GripperState, World

#: Reach of the simulated arm around the pad's origin in x and y, metres (pad frame).
WORKSPACE_XY_M = 1.0
#: Lowest and highest fingertip height of the simulated arm, metres (pad frame).
WORKSPACE_Z_M = (-0.01, 1.0)
#: Widest gripper opening that may be commanded, metres (wider commands are clamped to the
#: mounting's maximum by the gripper).
MAX_COMMAND_WIDTH_M = 1.0
#: Fastest commanded arm or jaw speed, m/s.
MAX_SPEED_M_S = 2.0
#: Jaws that stopped this much short of their fully closed opening hold something, metres: the
#: gripper's own report (the Sawyer's electric gripper tells "gripping" from its position and
#: force, thesis Section 6.3). 1 mm: 100 steps of the 10 um encoder and ten times the
#: contacts' 0.1 mm penetration; an object less than 1 mm wider than the mounting's minimum
#: reads as nothing.
HOLD_MARGIN_M = 1e-3
#: How close to their commanded opening the jaws must come before an opening counts as done,
#: m. An opening is never stopped by the object just held: a jaw still on it after the grip
#: relaxes (a step or two of no motion) is still opening, and an arm moving off then would
#: carry the object up and drop it.
OPENED_MARGIN_M = 0.5e-3
#: Simulated time an opening may go without the jaws moving before they count as blocked
#: (an object pressing a jaw from outside) and the opening as done, s: a relaxing grip holds
#: them still for a few milliseconds.
OPEN_STALL_S = 0.5


def check_target(x_m: float, y_m: float, z_m: float, width_m: float) -> None:
    """Raise InputError unless a target lies in the simulated arm's workspace.

    Finite coordinates within +/- ``WORKSPACE_XY_M`` in x and y, a height within
    ``WORKSPACE_Z_M`` and a gripper width within 0 .. ``MAX_COMMAND_WIDTH_M``.
    """
    for name, v, lo, hi in (
        ("x_m", x_m, -WORKSPACE_XY_M, WORKSPACE_XY_M),
        ("y_m", y_m, -WORKSPACE_XY_M, WORKSPACE_XY_M),
        ("z_m", z_m, *WORKSPACE_Z_M),
        ("width_m", width_m, 0.0, MAX_COMMAND_WIDTH_M),
    ):
        if not (math.isfinite(v) and lo <= v <= hi):
            raise InputError(f"robot target {name} must be within {lo:g}..{hi:g} m, got {v!r}")


def _kept_width(measured_m: float) -> float:
    """The jaw width an arm motion keeps: the measured one, within 0 .. MAX_COMMAND_WIDTH_M.

    Jaws closed on nothing (a 4/0 mounting) read a little below zero, their contact
    penetration; a motion keeps them closed instead of commanding a negative width.
    """
    return min(max(measured_m, 0.0), MAX_COMMAND_WIDTH_M)


@dataclass(frozen=True)
class TouchTruth:
    """Ground truth of one descent, read from the simulated world after it.

    Attributes
    ----------
    first_touch_s
        Box time of the first fingertip touch, seconds (None: the fingers touched nothing).
    first_touch_z_m
        Fingertip height at the first touch, metres.
    """

    first_touch_s: float | None
    first_touch_z_m: float | None


def _robot_state(s: GripperState) -> RobotState:
    return RobotState(s.x_m, s.y_m, s.z_m, s.yaw_rad, s.width_m)


class SimulatedRobot:
    """A kinematic robot driving the gripper of a simulated :class:`~softpad.sim.World`.

    Commands are non-blocking; the world advances with the box's reads. After each descent
    the world's first-touch record is appended to :attr:`touches` (ground truth for scoring).

    Parameters
    ----------
    world
        The world whose gripper this robot moves.
    max_opening_m
        Widest opening the robot commands, metres (the world clamps to the mounting's).
    closed_width_m
        Opening the jaws read when closed on nothing, metres: the installed mounting's minimum
        (an installation figure, not the object's). :meth:`holding` compares the measured
        opening with it; None: the world gripper's minimum.
    """

    def __init__(
        self, world: World, max_opening_m: float = math.inf, closed_width_m: float | None = None
    ) -> None:
        self.world = world
        self.max_opening_m = max_opening_m
        self._closed_width_m = closed_width_m
        self._closing = False
        self._opening = False
        self._moved_at_s = 0.0  # world time the opening jaws last moved
        #: Opening the jaws were last commanded to close to (None: fully closed).
        self._close_to_m: float | None = None
        self.touches: list[TouchTruth] = []
        self._target: GripperState | None = None
        self._last: GripperState | None = None
        self._fresh = False
        self._descending = False

    def _end_descent(self) -> None:
        if self._descending:
            w = self.world
            self.touches.append(TouchTruth(w.first_touch_s, w.first_touch_z_m))
            self._descending = False

    def _command(self, target: GripperState, speed_m_s: float) -> None:
        if not (math.isfinite(speed_m_s) and 0 < speed_m_s <= MAX_SPEED_M_S):
            raise InputError(
                f"robot speed must be > 0 and at most {MAX_SPEED_M_S:g} m/s, got {speed_m_s!r}"
            )
        check_target(target.x_m, target.y_m, target.z_m, target.width_m)
        self._target = target
        self._fresh = True
        self._opening = False
        self.world.command_gripper(target, speed_m_s)

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        self._end_descent()
        width = _kept_width(self.world.gripper_state().width_m)
        self._command(GripperState(pose.x_m, pose.y_m, pose.z_m, pose.yaw_rad, width), speed_m_s)

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        self._end_descent()
        s = self.world.gripper_state()
        self.world.reset_touch()
        width = _kept_width(s.width_m)
        self._command(GripperState(s.x_m, s.y_m, min_z_m, s.yaw_rad, width), speed_m_s)
        self._descending = True

    def stop(self) -> None:
        self._end_descent()
        s = self.world.gripper_state()
        self._target = s
        self.world.command_gripper(s, 0.0)

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
        self._end_descent()
        width_m = min(width_m, self.max_opening_m)
        s = self.world.gripper_state()
        self._closing = width_m < s.width_m
        self._close_to_m = width_m
        self._command(GripperState(s.x_m, s.y_m, s.z_m, s.yaw_rad, width_m), speed_m_s)
        self._opening = width_m > s.width_m
        self._moved_at_s = self.world.time_s

    def is_moving(self) -> bool:
        s = self.world.gripper_state()
        if self._target is None or s == self._target:
            self._last = s
            return False
        if self._opening and s.width_m < min(self._target.width_m, self.widest_m) - OPENED_MARGIN_M:
            if self._last is None or s.width_m != self._last.width_m:
                self._moved_at_s = self.world.time_s
            if self.world.time_s - self._moved_at_s < OPEN_STALL_S:
                self._last = s  # a grip relaxing before the jaws open: still opening
                return True
        if not self.world.jaws_settled():  # stopped on an object, the grip still building up
            self._last = s
            return True
        moved = s != self._last
        self._last = s
        if self._fresh:  # a command was just given: allow one step before judging
            self._fresh = False
            return True
        return moved  # False when the jaws stopped on an object short of their target

    def state(self) -> RobotState:
        return _robot_state(self.world.gripper_state())

    def holding(self) -> bool:
        """What the gripper itself reports: its jaws, last commanded to close, stopped more
        than :data:`HOLD_MARGIN_M` short of the commanded opening (or of the fully closed one,
        when asked to close further): on nothing a parallel-jaw gripper reaches its target; on
        an object it stops at the object's width. The force adds nothing here: the servo
        reaches its limit at the closed stops too. The world's contacts are not asked (they
        only score a trial)."""
        width = self.world.gripper_state().width_m
        goal = self.closed_width_m
        if self._close_to_m is not None:
            goal = max(goal, self._close_to_m)
        return self._closing and width > goal + HOLD_MARGIN_M

    @property
    def widest_m(self) -> float:
        """The widest the jaws open, m: ``max_opening_m``, or the world gripper's maximum
        opening where that is narrower."""
        world_max = getattr(getattr(self.world, "gripper", None), "max_width_m", math.inf)
        return min(self.max_opening_m, float(world_max))

    @property
    def closed_width_m(self) -> float:
        """The installed mounting's closed opening, m: the one given, else the world gripper's
        minimum when asked (a mounting installed after this robot was made counts)."""
        if self._closed_width_m is not None:
            return self._closed_width_m
        return float(getattr(getattr(self.world, "gripper", None), "min_width_m", 0.0))


def open_sim_robot(location: str, options: dict[str, str], context: Any) -> SimulatedRobot:
    """The ``sim://`` factory of :data:`softpad.control.ROBOT_REGISTRY`: the arm of the
    simulated box in ``context.box`` (:class:`softpad.box.SimBox`).

    Parameters
    ----------
    location, options
        The robot URL's location and options: none are taken.
    context
        A :class:`softpad.control.RobotContext` whose ``box`` is simulated in this process.
    """
    from softpad.box import simulator_of

    if location not in ("", "/") or options:
        raise InputError(f"the simulated robot is plain sim:// (no options), got {location!r}")
    box = getattr(context, "box", None)
    sim = simulator_of(box) if box is not None else None
    if sim is None:
        raise InputError(f"a sim:// robot needs a simulated box (sim://), got {type(box).__name__}")
    return SimulatedRobot(sim.world)
