"""One run of the loop as ``softpad run`` runs it: the parts made for the box's pad, the arm
chosen by URL (the box's simulated arm, or a registered robot), and the run's report as
text (its timeline, a hardware fault and the safe state reached)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

from softpad.box import Box, simulator_of
from softpad.control import ExecutionParams, ExecutionResult, loop_parts, make_robot
from softpad.errors import HardwareFault
from softpad.harness._assembly import build_loop
from softpad.harness._robot import TouchTruth
from softpad.harness._run import SimulatedRun, resolve_objects, run_simulated
from softpad.layout import GripperSpec, PadLayout


def box_layout(box: Any) -> PadLayout:
    """The pad on ``box``: a simulated box's world's, else the thesis's 2 x 3 (a served
    simulator states its pad only when the run sets it up).

    Parameters
    ----------
    box
        The box.
    """
    layout = getattr(getattr(box, "world", None), "layout", None)
    return layout if isinstance(layout, PadLayout) else PadLayout()


def box_loop_parts(
    box: Box, params: ExecutionParams, mounting: str, planner: str, detector: str
) -> dict[str, Any]:
    """The planner and contact detector named ``planner`` and ``detector`` made by their
    registries for the box's sample rate, its pad and the gripper
    (:func:`softpad.control.loop_parts`, as the ROS node's ``~grasp`` makes them).

    Parameters
    ----------
    box
        The box the loop runs on.
    params
        The loop's parameters (thresholds, window).
    mounting
        Gripper mounting ``"10/4"``, ``"6/2"`` or ``"4/0"``.
    planner, detector
        Registered names.
    """
    spec = GripperSpec.from_mounting(mounting)
    return loop_parts(planner, detector, box.sample_rate_hz, box_layout(box), spec, params)


def run_with_robot(
    objects: Sequence[str] | None,
    box: Box | str,
    robot: Any,
    params: Any = None,
    recorder: Any = None,
    gripper: str | None = None,
    **parts: Any,
) -> ExecutionResult:
    """Run the loop (:func:`build_loop`) once on ``box`` with ``robot``; ``parts``
    (``planner``, ``object_detector``, ``contact_detector``) replace the thesis's.

    When the box is a simulator served over ``zenoh://`` (``softpad sim arm-node`` or
    ``softpad box serve --sim``), the gripper mounting is set up and the catalogue
    ``objects`` are placed through its ``sim.setup``/``sim.place`` requests; on any other box a
    person places the object and the pad layout is the default 2 x 3.

    Parameters
    ----------
    objects
        Catalogue names; ``object-5`` when None.
    box
        The box or its URL (opened and closed here).
    robot
        The arm (:class:`softpad.control.Robot`).
    params
        Loop parameters; None: the thesis's.
    recorder
        Receives frames and events, or None.
    gripper
        Gripper mounting; None: the first object's.

    Returns
    -------
    ExecutionResult
        The timeline and outcome. A fault (box or arm lost) raises
        :class:`~softpad.errors.HardwareFault` after the box was made safe.
    """
    from softpad.box import open_box

    names = [s.name for s in resolve_objects(objects)]
    owned = isinstance(box, str)
    b = open_box(box) if isinstance(box, str) else box
    try:
        with build_loop(
            b, robot, params=params, recorder=recorder, objects=names, gripper=gripper, **parts
        ) as loop:
            try:
                return loop.run()
            except HardwareFault as exc:
                # same exception (its safe state and faults kept), the phase named in the message
                exc.args = (f"run stopped in phase {loop.phase!r}: {exc}", *exc.args[1:])
                raise
    finally:
        if owned:
            b.close()


def run_objects(
    names: Sequence[str],
    box: Box,
    params: ExecutionParams,
    recorder: Any,
    gripper: str | None,
    robot: str,
    planner: str,
    detector: str,
) -> SimulatedRun:
    """One run of ``softpad run``: the catalogue objects ``names`` on ``box`` with the arm
    ``robot`` names.

    Parameters
    ----------
    names
        Catalogue objects placed and grasped.
    box
        The (open) box.
    params
        The loop's parameters.
    recorder
        Receives frames and events.
    gripper
        Gripper mounting; None: the first object's.
    robot
        Robot URL: ``sim://`` is the box's own simulated arm (with the touches' ground
        truth); any other on an in-process simulated box is made on its world; on any other
        box the robot registry's arm (no ground truth).
    planner, detector
        The registered planner and contact detector (:func:`box_loop_parts`).

    Returns
    -------
    SimulatedRun
        The run and the touches' ground truth (None where unknown).
    """
    mounting = gripper or resolve_objects(names)[0].gripper
    parts = box_loop_parts(box, params, mounting, planner, detector)
    if robot.partition("://")[0].lower() == "sim" or simulator_of(box) is not None:
        arm = None
        if robot.rstrip("/").lower() != "sim:":
            spec = GripperSpec.from_mounting(mounting)
            arm = make_robot(robot, box=box, layout=box_layout(box), gripper=spec)
        return run_simulated(names, box, params, recorder, gripper, arm, **parts)
    made = make_robot(robot, box=box)
    try:
        result = run_with_robot(names, box, made, params, recorder, gripper=gripper, **parts)
    finally:
        close = getattr(made, "close", None)
        if close is not None:
            close()
    # no ground truth of the touches through ROS: the report leaves them empty
    return SimulatedRun(result, tuple(TouchTruth(None, None) for _ in result.grasps))


def fault_report(
    exc: Exception, names: Sequence[str], events: Sequence[Any], frames: int
) -> tuple[dict[str, Any], list[str]]:
    """What a run stopped by a hardware fault reports: its dict and its lines.

    The dict has ``outcome``, ``faults``, ``safe_state`` and ``phases`` at the top and the
    command-line contract's ``error`` object (kind ``hardware``, message, events and frames
    recorded so far); the lines name each fault and the safe state reached.

    Parameters
    ----------
    exc
        The fault (its ``faults`` and ``safe_state`` read when it has them).
    names
        The run's objects.
    events
        The run's events as ``(t_s, kind, data)``.
    frames
        Frames recorded.
    """
    faults = [f.to_dict() for f in getattr(exc, "faults", ())]
    safe = getattr(exc, "safe_state", None)
    d = {
        "outcome": "fault",
        "objects": list(names),
        "faults": faults,
        "safe_state": None if safe is None else safe.to_dict(),
        "phases": [{"phase": e["phase"], "t_s": round(t, 4)} for t, k, e in events if k == "phase"],
        "error": {
            "kind": "hardware",
            "message": str(exc),
            "events": [[t, kind, data] for t, kind, data in events],
            "frames": frames,
        },
    }
    lines = [
        f"t = {f['t_s']:7.2f} s  fault on channel {f['channel']} ({f['cause']})" for f in faults
    ]
    if safe is not None:
        kpa = ", ".join("nan" if v != v else f"{v / 1e3:.3f}" for v in safe.pressures_pa)
        state = "verified" if safe.verified else f"NOT verified: {safe.reason}"
        lines.append(f"safe state {state}; pressures {kpa} kPa")
    return d, lines


def _kpa(values: Any) -> str:
    return " ".join(f"{v / 1e3:.3f}" for v in values)


def _modules(d: dict[str, Any]) -> str:
    return ", ".join(map(str, d["modules"]))


def _plan_lines(d: dict[str, Any]) -> list[str]:
    lines = [f"increments (kPa): {_kpa(d['increments_pa'])}"]
    for o in d["objects"]:
        lines.append(
            f"plan: modules {','.join(map(str, o['modules']))}  PCOM "
            f"({o['pcom'][0]:.2f}, {o['pcom'][1]:.2f})  COG ({o['cog'][0]:.2f}, {o['cog'][1]:.2f})  "
            f"theta {o['theta']:+.3f} rad ({math.degrees(o['theta']):+.0f} deg)  [{o['rule']}]"
        )
    return lines


def retry_text(d: dict[str, Any]) -> str:
    """The timeline's line for a ``retry`` event.

    Parameters
    ----------
    d
        The event's data: ``z_m`` (m), ``cog``, ``theta`` (rad), ``rule`` and ``closed``
        (whether the jaws had closed; absent: they had).
    """
    landed = f"the fingers landed {d['z_m'] * 1e3:.1f} mm above the pad base"
    why = (
        f"the jaws closed on nothing after {landed}, on the object"
        if d.get("closed", True)
        else f"{landed}, on one side of the object: not closing"
    )
    grasp = f"COG ({d['cog'][0]:.2f}, {d['cog'][1]:.2f}) theta {d['theta']:+.3f} rad"
    return f"{why}; trying {grasp} [{d['rule']}]"


#: How each event kind of a run reads in the timeline (kinds not listed are not shown).
EVENT_TEXT: dict[str, Callable[[dict[str, Any]], list[str]]] = {
    "adjusted": lambda d: [
        f"adjusted: every module within tolerance of {d['target_pa'] / 1e3:.3f} kPa"
    ],
    "reference": lambda d: [f"reference saved (kPa): {_kpa(d['reference_pa'])}"],
    "object_seen": lambda d: [f"object detected on module(s) {_modules(d)}"],
    "plan": _plan_lines,
    "contact": lambda d: [f"contact detected on module(s) {_modules(d)}"],
    "no_contact": lambda d: [
        f"no contact detected down to {d['z_m'] * 1e3:.1f} mm: gripper not closed"
    ],
    "retry": lambda d: [retry_text(d)],
    "carried": lambda d: [
        f"module(s) {_modules(d)} unloaded during the hold: that object went up with this "
        "one, not grasped again"
    ],
    "outcome": lambda d: [d["outcome"]],
}
_SHOWN_PHASES = ("approach", "descend", "close", "lift", "hold", "release")


def timeline(events: Sequence[Any], result: SimulatedRun) -> list[str]:
    """A run's timeline as lines: the phases, the events of :data:`EVENT_TEXT`, and each
    grasp's contact delay and finger travel where the ground truth knows them.

    Parameters
    ----------
    events
        The run's events as ``(t_s, kind, data)``.
    result
        The run.
    """
    lines = []
    for t, kind, d in events:
        if kind == "phase" and d["phase"] in _SHOWN_PHASES:
            lines.append(f"t = {t:7.2f} s  {d['phase']}")
        elif kind in EVENT_TEXT:
            lines += [f"t = {t:7.2f} s  {text}" for text in EVENT_TEXT[kind](d)]
    for i, g in enumerate(result.result.grasps):
        delay, travel = result.contact_delay_s(i), result.finger_travel_m(i)
        if delay is not None and travel is not None:
            lines.append(
                f"grasp {i + 1}: contact {delay * 1e3:.0f} ms after the first fingertip touch, "
                f"finger travel {travel * 1e3:.1f} mm; outcome {g.outcome}"
            )
        else:
            lines.append(f"grasp {i + 1}: outcome {g.outcome}")
    return lines


__all__ = [
    "EVENT_TEXT", "box_layout", "box_loop_parts", "fault_report", "retry_text", "run_objects",
    "run_with_robot", "timeline",
]  # fmt: skip
