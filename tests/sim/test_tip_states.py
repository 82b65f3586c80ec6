"""The fingertip contact states of the analytic world (softpad.sim.TipState, TIP_TRANSITIONS):
the table walked, the states simulated descents go through checked against it."""

from __future__ import annotations

import itertools

import pytest

from softpad.box import SimBox
from softpad.control import ExecutionParams
from softpad.harness import build_loop
from softpad.sim import TIP_TRANSITIONS, AnalyticWorld, TipState, TipStateError
from softpad.sim._tips import next_tip_state


def test_every_state_is_reachable_and_every_contact_ends_free() -> None:
    assert set(TIP_TRANSITIONS) == set(TipState)
    assert set().union(*TIP_TRANSITIONS.values()) | {TipState.FREE} == set(TipState)
    for s in TipState:
        assert s is TipState.FREE or TipState.FREE in TIP_TRANSITIONS[s]


_ILLEGAL = [
    (a, b) for a, b in itertools.product(TipState, TipState) if a is not b
    if b not in TIP_TRANSITIONS[a]
]  # fmt: skip


@pytest.mark.parametrize(("current", "wanted"), _ILLEGAL, ids=[f"{a}-{b}" for a, b in _ILLEGAL])
def test_an_illegal_tip_transition_raises(current: TipState, wanted: TipState) -> None:
    with pytest.raises(TipStateError, match=f"no transition from {current} to {wanted}"):
        next_tip_state(current, wanted)


class _TipWatch:
    """A recorder noting the world's fingertip states at every frame (ground truth)."""

    def __init__(self, world: AnalyticWorld) -> None:
        self.world = world
        self.states = [world.tip_states]

    def frame(self, frame, phase) -> None:  # type: ignore[no-untyped-def]
        if self.world.tip_states != self.states[-1]:
            self.states.append(self.world.tip_states)

    def event(self, t_s, kind, **data) -> None:  # type: ignore[no-untyped-def]
        pass


@pytest.mark.parametrize(
    ("objects", "landed_on"),
    [(["object-5"], TipState.ON_PAD), (["cylinder"], TipState.ON_OBJECT)],
    ids=["object-5", "cylinder"],
)
def test_a_grasp_takes_only_tip_transitions_of_the_table(objects, landed_on) -> None:
    world = AnalyticWorld()
    watch = _TipWatch(world)
    box = SimBox(world, seed=11)
    with build_loop(
        box, objects=objects, params=ExecutionParams(hold_s=1.0), recorder=watch
    ) as loop:
        loop.run()
    taken = {
        (a[i], b[i]) for a, b in itertools.pairwise(watch.states) for i in range(2) if a[i] != b[i]
    }
    table = {(a, b) for a, targets in TIP_TRANSITIONS.items() for b in targets}
    assert taken <= table
    assert (TipState.FREE, landed_on) in taken and (landed_on, TipState.FREE) in taken
