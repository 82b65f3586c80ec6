"""The grasp loop's phases as a state machine (softpad.control.Phase, TRANSITIONS): the table
walked, the transitions simulated grasps take checked against it, illegal ones refused."""

from __future__ import annotations

import itertools

import pytest

from softpad.box import SimBox
from softpad.control import TRANSITIONS, ExecutionParams, Phase, PhaseError, next_phase
from softpad.control._phases import LOADING_PHASES, PRESSING_PHASES
from softpad.harness import build_loop, run_simulated
from softpad.sim import AnalyticWorld, SimGripper, get_object

FAST = ExecutionParams(hold_s=1.0)


def _reachable(start: Phase) -> set[Phase]:
    seen, todo = {start}, [start]
    while todo:
        for nxt in TRANSITIONS[todo.pop()]:
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return seen


def test_the_table_names_every_phase_once() -> None:
    assert set(TRANSITIONS) == set(Phase)
    assert all(set(targets) <= set(Phase) for targets in TRANSITIONS.values())
    assert LOADING_PHASES <= set(Phase) and PRESSING_PHASES <= LOADING_PHASES


def test_every_phase_is_reachable_from_idle() -> None:
    assert _reachable(Phase.IDLE) == set(Phase)


@pytest.mark.parametrize("phase", [p for p in Phase if p is not Phase.DONE], ids=str)
def test_every_phase_can_end_in_done(phase: Phase) -> None:
    assert Phase.DONE in _reachable(phase)


def test_done_is_final() -> None:
    assert TRANSITIONS[Phase.DONE] == frozenset()


_ILLEGAL = [(a, b) for a, b in itertools.product(Phase, Phase) if b not in TRANSITIONS[a]]


@pytest.mark.parametrize(("current", "wanted"), _ILLEGAL, ids=[f"{a}-{b}" for a, b in _ILLEGAL])
def test_an_illegal_transition_raises(current: Phase, wanted: Phase) -> None:
    with pytest.raises(PhaseError, match=f"no transition from {current} to {wanted}"):
        next_phase(current, wanted)


def test_a_legal_transition_by_name_gives_the_phase() -> None:
    assert next_phase(Phase.APPROACH, "descend") is Phase.DESCEND


def test_the_loop_refuses_an_illegal_transition() -> None:
    world = AnalyticWorld()
    loop = build_loop(SimBox(world, seed=1), params=FAST).execution
    assert loop.phase is Phase.IDLE
    with pytest.raises(PhaseError, match="no transition from idle to descend"):
        loop._enter(Phase.DESCEND)
    assert loop.phase is Phase.IDLE


def _transitions(phases: tuple[tuple[str, float], ...]) -> set[tuple[Phase, Phase]]:
    names = [Phase.IDLE, *(Phase(name) for name, _t in phases)]
    return set(itertools.pairwise(names))


def _not_detected_phases() -> tuple[tuple[str, float], ...]:
    """Fingertips on the 2|5 line (test_execution's case): the descent senses nothing."""
    g = SimGripper(max_width_m=0.043, min_width_m=0.0, tip_thickness_m=0.002, tip_width_m=0.002)
    world = AnalyticWorld(gripper=g)
    place = lambda: world.place_object(get_object("object-3"))  # noqa: E731
    with build_loop(SimBox(world, seed=4), params=FAST, place_objects=place) as loop:
        result = loop.run()
    assert result.grasps[0].outcome == "contact_not_detected"
    return result.phases


def test_simulated_grasps_take_only_transitions_of_the_table() -> None:
    """A held grasp, two objects grasped in turn and a descent that senses nothing: every
    transition they take is in the table, and together they take these ones."""
    held = run_simulated(["object-5"], "sim://?seed=11", FAST).result
    two = run_simulated(["object-1", "object-4"], "sim://?seed=4", FAST, gripper="6/2").result
    taken = _transitions(held.phases) | _transitions(two.phases)
    taken |= _transitions(_not_detected_phases())
    table = {(a, b) for a, targets in TRANSITIONS.items() for b in targets}
    assert taken <= table, taken - table
    assert {
        (Phase.IDLE, Phase.ADJUST),
        (Phase.DESCEND, Phase.CLOSE),
        (Phase.RELEASE, Phase.APPROACH),  # the second object
        (Phase.RELEASE, Phase.VALVE_CHECK),
        (Phase.DESCEND, Phase.VALVE_CHECK),  # no contact: retreat, then the valve check
        (Phase.VALVE_CHECK, Phase.DONE),
    } <= taken
