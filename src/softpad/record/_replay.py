"""Replay a recording: as a box (``replay://run.mcap``) and through today's sensing and planning.

:class:`ReplayBox` plays the recorded frames back, as fast as they are read or at the recorded
speed; valve commands are accepted and kept (:attr:`ReplayBox.commands`) but change nothing.
:func:`compare_replay` re-runs the reference, the object detection and planning, and the
contact detection of the current code on the recorded frames and says whether they decide
what was recorded: how a change is checked against recordings from the real pad.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad.box import Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.errors import InputError
from softpad.record._read import RecordedRun, load_recording

#: Agreement of recomputed and recorded plans (module units, radians).
PLAN_TOLERANCE = 1e-6


class ReplayBox(Box):
    """A box that plays a recording's frames back (the ``replay://`` back-end).

    Parameters
    ----------
    recording
        A :class:`RecordedRun` or the path of a recording.
    speed
        ``0`` (default): frames as fast as they are read; ``1.0``: at the recorded speed;
        any other positive factor scales it.

    Notes
    -----
    Reading past the last frame raises :class:`~softpad.box.ConnectionLost` (the recording
    ended). Valve commands are recorded in :attr:`commands` as ``(t_s, channel, command)``.
    """

    def __init__(self, recording: RecordedRun | str | Path, speed: float = 0.0) -> None:
        super().__init__()
        self.recording = (
            recording if isinstance(recording, RecordedRun) else load_recording(recording)
        )
        if len(self.recording) < 2:
            raise InputError(f"{str(self.recording.path)!r} holds fewer than 2 frames to replay")
        if not (isinstance(speed, int | float) and np.isfinite(speed) and speed >= 0):
            raise InputError(f"replay speed must be 0 (fast) or a factor > 0, got {speed!r}")
        self.speed = float(speed)
        self.commands: list[tuple[float, int, ValveCommand]] = []
        self._i = 0
        self._t = -np.inf
        self._wall0: float | None = None

    @property
    def channels(self) -> int:
        """Recorded channel count."""
        return self.recording.channels

    @property
    def sample_rate_hz(self) -> float:
        """Recorded frame rate, hertz."""
        return self.recording.sample_rate_hz

    def _read(self) -> PressureFrame:
        r = self.recording
        if self._i >= len(r):
            raise ConnectionLost(f"replay: the recording {str(r.path)!r} ended ({len(r)} frames)")
        i = self._i
        self._i += 1
        t = float(r.t_s[i])
        if self.speed > 0:
            now = time.monotonic()
            if self._wall0 is None:
                self._wall0 = now - (t - r.t_s[0]) / self.speed
            delay = self._wall0 + (t - r.t_s[0]) / self.speed - now
            if delay > 0:
                time.sleep(delay)
        self._t = t
        return PressureFrame(t, r.pressures_pa[i].copy(), float(r.supply_pa[i]))

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        self.commands.append((self._t, channel, command))

    def _close(self) -> None:
        pass


def open_replay_url(location: str, options: dict[str, str]) -> ReplayBox:
    """Open ``replay://PATH.mcap[?speed=recorded|fast|FACTOR]``."""
    unknown = set(options) - {"speed"}
    if unknown:
        raise InputError(f"unknown replay:// option {sorted(unknown)[0]!r}; allowed: speed")
    text = options.get("speed", "fast")
    if text == "fast":
        speed = 0.0
    elif text == "recorded":
        speed = 1.0
    else:
        try:
            speed = float(text)
        except ValueError:
            raise InputError(
                f"replay speed must be 'fast', 'recorded' or a factor > 0, got {text!r}"
            ) from None
        if not (np.isfinite(speed) and speed > 0):
            raise InputError(f"replay speed factor must be > 0, got {text!r}")
    if not location:
        raise InputError("replay:// needs a file, e.g. replay://run.mcap")
    return ReplayBox(location, speed)


def _frames_between(run: RecordedRun, t0: float, t1: float) -> NDArray[np.float64]:
    """Pressures of the frames with t0 < t <= t1 (the frames read in one phase)."""
    sel = (run.t_s > t0 + 1e-9) & (run.t_s <= t1 + 1e-9)
    return run.pressures_pa[sel]


def _params(run: RecordedRun) -> Any:
    """The run's execution parameters (recorded ones over today's defaults)."""
    from softpad.control import ExecutionParams, InflationParams
    from softpad.planning import PlannerParams

    rec = run.metadata.get("params")
    defaults = ExecutionParams()
    if not isinstance(rec, dict):
        return defaults
    scalars = {k: v for k, v in rec.items() if k in asdict(defaults) and not isinstance(v, dict)}
    try:
        infl = InflationParams(**rec.get("inflation", {}))
        planner = PlannerParams(**rec.get("planner", {}))
        return ExecutionParams(**scalars, inflation=infl, planner=planner)
    except (TypeError, ValueError, InputError):
        return defaults


def _phase_starts(run: RecordedRun) -> list[tuple[str, float]]:
    return [(d["phase"], t) for t, d in run.events_of("phase")]


def _phase_window(
    phases: list[tuple[str, float]], name: str, end: float
) -> list[tuple[float, float]]:
    """(start, end) box times of every occurrence of phase ``name``."""
    out = []
    for i, (ph, t) in enumerate(phases):
        if ph == name:
            out.append((t, phases[i + 1][1] if i + 1 < len(phases) else end))
    return out


def _same_plans(a: list[dict[str, Any]], b: list[dict[str, Any]]) -> bool:
    if len(a) != len(b):
        return False
    for x, y in zip(a, b, strict=True):
        if list(x["modules"]) != list(y["modules"]) or x["rule"] != y["rule"]:
            return False
        if np.max(np.abs(np.subtract(x["cog"], y["cog"]))) > PLAN_TOLERANCE:
            return False
        if abs(float(x["theta"]) - float(y["theta"])) > PLAN_TOLERANCE:
            return False
    return True


def _reference(run: RecordedRun, phases: list[tuple[str, float]], n: int, reads: int) -> Any:
    ev = run.events_of("reference")
    windows = _phase_window(phases, "reference", run.t_s[-1])
    if not ev or not windows:
        return None
    return _frames_between(run, windows[0][0], ev[0][0])[-reads:, :n].mean(axis=0)


def _parts(run: RecordedRun, layout: Any, params: Any) -> tuple[Any, Any]:
    """A factory of the recorded run's contact detector and its planner, by the names in its
    metadata (``contact_detector``, ``planner``; the thesis's when absent: older recordings),
    the planner told the recorded gripper mounting (``gripper`` or ``mounting``)."""
    from softpad.layout import GripperSpec
    from softpad.planning import planner_for
    from softpad.sensing import ThesisContactDetector, make_contact_detector

    meta = run.metadata
    detector_name = str(meta.get("contact_detector") or "thesis")
    planner_name = str(meta.get("planner") or "thesis")
    rate = run.sample_rate_hz

    def detector() -> Any:
        if detector_name == "thesis":
            return ThesisContactDetector(params.contact_threshold_pa, params.filter_length)
        return make_contact_detector(detector_name, rate, layout)

    mounting = str(meta.get("gripper") or meta.get("mounting") or "6/2")
    gripper = GripperSpec.from_mounting(mounting)
    return detector, planner_for(planner_name, gripper, params.planner, detector(), rate, layout)


def _replan(
    run: RecordedRun, phases: Any, reference: Any, layout: Any, params: Any, planner: Any
) -> Any:
    from softpad.sensing import ThesisObjectDetector

    ev = run.events_of("plan")
    windows = _phase_window(phases, "plan", run.t_s[-1])
    if reference is None or not ev or not windows:
        return None
    frames = _frames_between(run, windows[0][0], ev[0][0])[
        -params.planning_reads :, : layout.n_modules
    ]
    delta = frames.mean(axis=0) - reference
    objects = ThesisObjectDetector(params.planner.object_threshold_pa).objects(delta, layout)
    plans = planner.plan(delta, objects, layout)
    return [pl.to_dict(layout) for pl in plans]


def _redetect_contacts(
    run: RecordedRun, phases: Any, n: int, params: Any, make_detector: Any
) -> list[dict[str, Any]]:
    """Contact detection of today's code over every recorded descent, next to the recording's."""
    out = []
    for t0, t1 in _phase_window(phases, "descend", float(run.t_s[-1])):
        before = run.pressures_pa[run.t_s <= t0 + 1e-9][-params.pre_descent_reads :, :n]
        detector = make_detector()
        detector.reset(before.mean(axis=0))
        now: dict[str, Any] | None = None
        for t, p in zip(run.t_s, run.pressures_pa, strict=True):
            if t0 + 1e-9 < t <= t1 + 1e-9 and detector.update(p[:n]):
                now = {"t_s": float(t), "modules": [int(m) for m in detector.triggered_modules]}
                break
        rec = [
            {"t_s": t, "modules": [int(m) for m in d["modules"]]}
            for t, d in run.events_of("contact")
            if t0 < t <= t1 + 1e-9
        ]
        recorded: dict[str, Any] | None = rec[0] if rec else None
        same = (recorded is None and now is None) or (
            recorded is not None
            and now is not None
            and abs(recorded["t_s"] - now["t_s"]) < 1e-6
            and recorded["modules"] == now["modules"]
        )
        out.append({"descent_start_s": t0, "recorded": recorded, "now": now, "same": same})
    return out


def compare_replay(recording: RecordedRun | str | Path) -> dict[str, Any]:
    """Run today's reference capture, planning and contact detection on a recording.

    The reference is the mean of the recorded reference reads; the plan comes from the mean of
    the frames read in the ``plan`` phase (:class:`softpad.sensing.ThesisObjectDetector` and
    the recorded planner: :class:`softpad.planning.ThesisPlanner`, or the one named in the
    metadata's ``planner`` for the recorded gripper); contact is detected (the detector named
    in ``contact_detector``; the thesis's with the recorded t_g and filter length when none is)
    on every frame of each descent, a retried grasp's too, from the mean of the reads before
    it.

    Parameters
    ----------
    recording
        The recording (a :class:`RecordedRun`, or its .mcap file).

    Returns
    -------
    dict
        ``plan`` (``recorded``, ``now``, ``same``), ``contacts`` (per descent: ``recorded``
        and ``now`` contact sample ``{t_s, modules}``, ``same``), ``same`` (everything
        agrees) and ``outcome`` (recorded).
    """
    from softpad.layout import parse_layout

    run = recording if isinstance(recording, RecordedRun) else load_recording(recording)
    if len(run) == 0:
        raise InputError(
            f"recording {str(run.path)!r} holds no frames (cut short before the first was "
            "written?): nothing to replay"
        )
    params = _params(run)
    layout = parse_layout(str(run.metadata.get("layout", "2x3")))
    phases = _phase_starts(run)
    reference = _reference(run, phases, layout.n_modules, params.inflation.reference_reads)
    make_detector, planner = _parts(run, layout, params)
    now = _replan(run, phases, reference, layout, params, planner)
    recorded = run.plans()
    plan_same = now is not None and _same_plans(recorded, now)
    contacts = _redetect_contacts(run, phases, layout.n_modules, params, make_detector)
    return {
        "path": str(run.path),
        "reference_pa": None if reference is None else [float(v) for v in reference],
        "plan": {"recorded": recorded, "now": now, "same": plan_same},
        "contacts": contacts,
        "same": bool(plan_same and all(c["same"] for c in contacts)),
        "outcome": run.outcome,
    }


def _plan_text(o: dict[str, Any]) -> str:
    mods = ",".join(map(str, o["modules"]))
    return (
        f"modules {mods}  COG ({o['cog'][0]:.3f}, {o['cog'][1]:.3f})  theta {o['theta']:+.4f} rad "
        f"({math.degrees(o['theta']):+.0f} deg)  [{o['rule']}]"
    )


def _contact_text(c: dict[str, Any] | None) -> str:
    if c is None:
        return "none"
    return f"t = {c['t_s']:.3f} s on module(s) {', '.join(map(str, c['modules']))}"


def replay_lines(d: dict[str, Any]) -> list[str]:
    """The comparison of :func:`compare_replay` as text: the plans recorded and now, each
    descent's contact recorded and now, and the verdict.

    Parameters
    ----------
    d
        The comparison.
    """
    lines = [f"softpad replay: {d['path']} (recorded outcome: {d['outcome']})"]
    plan = d["plan"]
    for label, plans in (("recorded", plan["recorded"]), ("now", plan["now"] or [])):
        for o in plans or [{}]:
            lines.append(f"  plan {label:8s} {_plan_text(o) if o else 'none'}")
    lines.append(f"  plan: {'same' if plan['same'] else 'DIFFERENT'}")
    for i, c in enumerate(d["contacts"], 1):
        lines.append(f"  descent {i}: recorded contact {_contact_text(c['recorded'])}")
        lines.append(f"  descent {i}: now      contact {_contact_text(c['now'])}")
        lines.append(f"  descent {i}: {'same contact sample' if c['same'] else 'DIFFERENT'}")
    lines.append(
        "verdict: " + ("today's code decides what was recorded" if d["same"] else "DIFFERENT")
    )
    return lines
