"""No ground truth reaches the controller, for every registered planner and contact detector.

Each pair runs the same trial twice. In the second run, right after the object is placed, every
place where the simulated lab keeps the truth is poisoned: the world's contacts (``holding``,
``gripper_contacts``, the first-touch and jaw-on-object records), its object models and poses,
the object catalogue, and the geometry the trial scores with (another object). The physics keeps
running, so the pad's pressures and the robot's own readings are the same; the controller's
commands, its decisions (plan, contact, retry, carried objects, each grasp's outcome) and their
times must be the same too. Before issue 33 the loop's ``held``/``missed`` came from the world's
contacts (``robot.holding()`` asked ``world.holding()``): poisoning ``holding`` changed the
outcome events and the retries, and this test failed (checked by restoring that call).

With the thesis pair, the trial's ``truth`` alone is also swapped for a different object after
placement (formerly tests/trials/test_no_oracle.py): the pressures are the same, so the loop's
commands, their times and the opening the robot applied must be the same too. (Before issue 10
the robot opened its jaws to the true object's extent plus 10 mm a side, and both cases failed:
checked by patching that rule back in.)
"""

from __future__ import annotations

import itertools
from typing import Any

import pytest

import softpad.sim
import softpad.sim._objects
from softpad.planning import PLANNER_REGISTRY
from softpad.sensing import CONTACT_DETECTOR_REGISTRY
from softpad.sim import get_object
from softpad.trials import TrialConfig, run_trial, trial_execution_params
from softpad.trials import _loop as loop_module

#: Every registered planner with every registered contact detector (plug-ins included).
PAIRS = list(itertools.product(PLANNER_REGISTRY.names(), CONTACT_DETECTOR_REGISTRY.names()))
#: The pairs run in ``make test``: each planner once, with the detectors in turn, so every
#: planner and every detector is among them (the rest run in ``make test-slow``; issue 50).
_FAST = {
    (p, CONTACT_DETECTOR_REGISTRY.names()[i % len(CONTACT_DETECTOR_REGISTRY.names())])
    for i, p in enumerate(PLANNER_REGISTRY.names())
}
#: What the controller decides and commands (not the scorer's view of the world).
_DECISIONS = ("robot", "plan", "contact", "no_contact", "outcome", "retry", "carried")


class _Commands:
    """A recorder that keeps the robot's commands and the loop's decisions, with their times."""

    def __init__(self) -> None:
        self.events: list[tuple[float, str, dict[str, Any]]] = []

    def frame(self, frame: Any, phase: str) -> None:
        pass

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        if kind in _DECISIONS:
            self.events.append((round(t_s, 9), kind, data))


class _Poisoned(Exception):
    """Raised by every truth accessor that has no harmless lie to tell."""


def _lie(*_: Any, **__: Any) -> Any:
    raise _Poisoned("the controller asked the world's truth")


def _poison_after_placement(monkeypatch: pytest.MonkeyPatch) -> None:
    """Make ``_Trial.place`` poison the world and the catalogue once the object lies there."""
    place = loop_module._Trial.place

    def poisoned_place(trial: Any) -> None:
        place(trial)
        w = trial.world
        fake = w.gripper_contacts()  # contacts of an empty gripper, frozen from now on
        # the scorer may hear lies (its result is not compared); the controller must not ask
        monkeypatch.setattr(w, "holding", lambda: True)
        monkeypatch.setattr(w, "gripper_contacts", lambda: fake)
        monkeypatch.setattr(w, "object_pose", _lie)
        monkeypatch.setattr(w, "object_speed_m_s", _lie)
        monkeypatch.setattr(type(w), "tip_hit_object", property(lambda self: "a lie"))
        monkeypatch.setattr(softpad.sim, "get_object", _lie)
        monkeypatch.setattr(softpad.sim._objects, "get_object", _lie)
        monkeypatch.setattr(softpad.sim._objects, "load_catalogue", _lie)

    monkeypatch.setattr(loop_module._Trial, "place", poisoned_place)


def _run(name: str, pair: tuple[str, str], truth: str | None = None) -> tuple[Any, list[Any]]:
    rec = _Commands()
    cfg = TrialConfig(trial_execution_params(hold_s=0.5), planner=pair[0], detector=pair[1])
    result, _ = run_trial(
        get_object(name),
        seed=11,
        config=cfg,
        truth=None if truth is None else get_object(truth),
        recorder=rec,
    )
    assert result.cause != "trial_error", result.detail
    return result, rec.events


@pytest.mark.parametrize(
    "pair",
    [pr if pr in _FAST else pytest.param(pr, marks=pytest.mark.slow) for pr in PAIRS],
    ids=[f"{p}:{d}" for p, d in PAIRS],
)
def test_poisoned_truth_changes_no_command(
    pair: tuple[str, str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """The charger (a brick the jaws may land on, with a cable: retries and carried parts)."""
    result, events = _run("charger", pair)
    assert [e for e in events if e[1] == "robot"], "the loop commanded the robot"
    assert [e for e in events if e[1] == "outcome"], "the loop closed and judged a grasp"
    _poison_after_placement(monkeypatch)
    poisoned, events_poisoned = _run("charger", pair, truth="object-6")
    assert events_poisoned == events
    assert poisoned.opening_m == result.opening_m
    assert (poisoned.cog, poisoned.theta, poisoned.attempts) == (
        result.cog,
        result.theta,
        result.attempts,
    )


@pytest.mark.parametrize(
    ("name", "other"),
    [("object-1", "charger"), ("object-4", "object-6")],
    ids=["brick-as-charger", "stack-as-long-bricks"],
)
def test_swapping_the_true_geometry_changes_no_command(name: str, other: str) -> None:
    result, events = _run(name, ("thesis", "thesis"))
    swapped, events_swapped = _run(name, ("thesis", "thesis"), truth=other)
    assert [e for e in events if e[1] == "robot"], "the loop commanded the robot"
    assert events_swapped == events
    assert swapped.opening_m == result.opening_m
    assert swapped.cog == result.cog and swapped.theta == result.theta
    # the jaws open to the mounting's width, whatever the object
    assert result.opening_m == pytest.approx(0.06)


def test_the_controller_cannot_reach_the_world() -> None:
    """The loop (``softpad.control``) imports nothing of the simulator or its catalogue, and the
    simulated robot's ``holding`` reads only the gripper's state (read from the source)."""
    import ast
    import inspect
    from pathlib import Path

    import softpad.control
    from softpad.harness import SimulatedRobot

    for path in Path(softpad.control.__file__).parent.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else []
            if isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            for name in names:
                assert not name.startswith(("softpad.sim", "softpad.trials")), (path, name)
    tree = ast.parse(inspect.getsource(SimulatedRobot.holding).strip().replace("\n    ", "\n"))
    called = {n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)}
    assert "gripper_state" in called
    assert not called & {"holding", "gripper_contacts", "objects", "object_pose", "tip_hit_object"}
