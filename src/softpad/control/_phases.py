"""The phases of the grasp loop (:class:`~softpad.control.GraspExecution`) and the transitions
between them: an explicit state machine, walked by ``tests/control/test_phases.py``.

::

    idle -> adjust -> reference -> wait_object -> plan -> approach -> descend
    (idle -> wait_object when the adjustment was made before the loop)
    descend -> close -> lift -> hold -> release
    descend / release -> approach   (a retry, or the next object)
    descend / release -> valve_check -> done

A descent that senses no contact retreats and goes on with the next object (or the valve
check); a landing on the object goes up and approaches again.
"""

from __future__ import annotations

import enum
from collections.abc import Mapping


class Phase(enum.StrEnum):
    """A phase of the grasp loop (its value is the name recorded with every frame)."""

    IDLE = "idle"
    ADJUST = "adjust"
    REFERENCE = "reference"
    WAIT_OBJECT = "wait_object"
    PLAN = "plan"
    APPROACH = "approach"
    DESCEND = "descend"
    CLOSE = "close"
    LIFT = "lift"
    HOLD = "hold"
    RELEASE = "release"
    VALVE_CHECK = "valve_check"
    DONE = "done"


#: The phases each phase may go on to (module docstring).
TRANSITIONS: Mapping[Phase, frozenset[Phase]] = {
    Phase.IDLE: frozenset({Phase.ADJUST, Phase.WAIT_OBJECT}),
    Phase.ADJUST: frozenset({Phase.REFERENCE}),
    Phase.REFERENCE: frozenset({Phase.WAIT_OBJECT}),
    Phase.WAIT_OBJECT: frozenset({Phase.PLAN}),
    Phase.PLAN: frozenset({Phase.APPROACH}),
    Phase.APPROACH: frozenset({Phase.DESCEND}),
    Phase.DESCEND: frozenset({Phase.CLOSE, Phase.APPROACH, Phase.VALVE_CHECK}),
    Phase.CLOSE: frozenset({Phase.LIFT}),
    Phase.LIFT: frozenset({Phase.HOLD}),
    Phase.HOLD: frozenset({Phase.RELEASE}),
    Phase.RELEASE: frozenset({Phase.APPROACH, Phase.VALVE_CHECK}),
    Phase.VALVE_CHECK: frozenset({Phase.DONE}),
    Phase.DONE: frozenset(),
}

#: Phases in which an object is being placed on the pad (what wait_object waits for: its
#: modules rise while it settles), the fingers may touch it (descend, stopped at the first
#: contact) or the robot presses the pad or an object on it, see
#: FaultMonitor.loads_expected.
LOADING_PHASES = frozenset(
    {Phase.WAIT_OBJECT, Phase.DESCEND, Phase.CLOSE, Phase.LIFT, Phase.RELEASE}
)
#: Phases in which the robot presses the pad or an object on it for seconds: closing the jaws
#: (an object pushed or rolled along the pad), lifting, putting the object back down (it
#: lands, bounces and settles); FaultMonitor.robot_pressing.
PRESSING_PHASES = frozenset({Phase.CLOSE, Phase.LIFT, Phase.RELEASE})


class PhaseError(RuntimeError):
    """A transition the table does not hold: a fault of the loop's code, not of the rig."""


def next_phase(current: Phase, wanted: Phase | str) -> Phase:
    """``wanted`` as a :class:`Phase` when :data:`TRANSITIONS` lets ``current`` go on to it.

    Parameters
    ----------
    current
        The phase the loop is in.
    wanted
        The phase it enters (a :class:`Phase` or its name).

    Returns
    -------
    Phase
        The phase entered.

    Raises
    ------
    PhaseError
        When the table has no such transition (naming both phases and the allowed ones).
    """
    target = Phase(wanted)
    if target not in TRANSITIONS[current]:
        allowed = ", ".join(sorted(TRANSITIONS[current])) or "none (it is final)"
        raise PhaseError(f"no transition from {current} to {target}; allowed: {allowed}")
    return target


__all__ = ["LOADING_PHASES", "PRESSING_PHASES", "TRANSITIONS", "Phase", "PhaseError", "next_phase"]
