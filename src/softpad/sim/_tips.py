"""The contact state of a simulated fingertip (:class:`~softpad.sim.AnalyticWorld`): an
explicit state machine, walked by ``tests/sim/test_tip_states.py``.

::

    free -> on_pad      the tip crossed a module's top from above
    free -> on_object   the tip crossed an object's top from above
    on_pad / on_object -> free   the tip rose above where it touched

A tip pressing a surface stays on it while it slides (closing jaws drag it along); a tip
meeting the rigid line between modules, or the side of an object, does not land (only a
crossing from above onto a module or an object does).
"""

from __future__ import annotations

import enum
from collections.abc import Mapping


class TipState(enum.StrEnum):
    """Where a fingertip rests."""

    FREE = "free"
    ON_PAD = "on_pad"
    ON_OBJECT = "on_object"


#: The states each tip state may go on to (staying is always allowed).
TIP_TRANSITIONS: Mapping[TipState, frozenset[TipState]] = {
    TipState.FREE: frozenset({TipState.ON_PAD, TipState.ON_OBJECT}),
    TipState.ON_PAD: frozenset({TipState.FREE}),
    TipState.ON_OBJECT: frozenset({TipState.FREE}),
}


class TipStateError(RuntimeError):
    """A fingertip transition the table does not hold: a fault of the world's code."""


def next_tip_state(current: TipState, wanted: TipState) -> TipState:
    """``wanted`` when :data:`TIP_TRANSITIONS` lets a tip in ``current`` go on to it.

    Parameters
    ----------
    current
        The tip's state.
    wanted
        The state it goes to.

    Returns
    -------
    TipState
        ``wanted``.

    Raises
    ------
    TipStateError
        For a transition the table does not hold.
    """
    if wanted is not current and wanted not in TIP_TRANSITIONS[current]:
        raise TipStateError(f"fingertip: no transition from {current} to {wanted}")
    return wanted


__all__ = ["TIP_TRANSITIONS", "TipState", "TipStateError", "next_tip_state"]
