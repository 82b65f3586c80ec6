"""Records of grasp trials: one trial, one experiment (Table 6.1)."""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from typing import Any

#: The thesis's Table 6.1: weight (g), representative planned grasp (x_COG, y_COG, theta) in
#: module units and radians, successes out of 5 (seed, Section 6.3).
THESIS_TABLE_6_1: dict[str, tuple[float, tuple[float, float, float], int]] = {
    "object-1": (23.8, (2.5, 1.0, 0.0), 5),
    "object-2": (25.3, (1.04, 0.96, math.pi / 4), 5),
    "object-3": (44.4, (1.5, 1.5, math.pi / 2), 5),
    "object-4": (52.0, (0.5, 1.2, 0.0), 5),
    "object-5": (64.9, (1.36, 1.5, math.pi / 2), 4),
    "object-6": (122.0, (1.55, 0.5, math.pi / 2), 5),
    "banana": (59.8, (1.0, 1.0, -math.pi / 4), 5),
    "toy": (131.6, (2.0, 1.0, -math.pi / 4), 5),
    "limes": (187.0, (1.5, 0.8, 0.0), 5),
    "cylinder": (88.9, (1.14, 1.0, math.pi / 2), 4),
    "charger": (312.3, (1.16, 1.0, math.pi / 2), 4),
}

#: Overall success rate of the thesis's Experiment 2 (52 of 55 trials).
THESIS_OVERALL_SUCCESS = 0.945

#: Why a trial failed, decided in this order from the physics and the true object:
#: ``contact_not_detected`` (the fingers reached the pad base unsensed: tips on a seam or off
#: the pad; the thesis's failure for object 5 and the charger); ``cog_outside_object`` (the
#: grasp failed and its planned COG lay outside the object's footprint: the thesis's cylinder
#: failure); ``jaws_hit_object`` (a jaw came down on the object); ``object_outside_jaws``;
#: ``slipped_during_hold``; ``object_too_narrow``: the object was between the jaws but thinner
#: than the mounting's minimum width; ``object_not_detected``: the planner found nothing;
#: ``box_fault``: the loop stopped on a box fault (a module read above the 3 kPa limit, which
#: the simulated box's module model reaches when a fingertip pushes a module with more than
#: about 1.5 N).
FAILURE_CAUSES = (
    "contact_not_detected",
    "cog_outside_object",
    "jaws_hit_object",
    "object_outside_jaws",
    "slipped_during_hold",
    "object_too_narrow",
    "object_not_detected",
    "box_fault",
)


@dataclass(frozen=True)
class TrialResult:
    """Outcome of one grasp trial.

    Attributes
    ----------
    object
        Catalogue name.
    trial
        0-based trial number of this object.
    seed
        Seed of this trial's random placement (derived from the experiment seed).
    placement
        Where the object was put: (x_m, y_m, yaw_rad), pad frame.
    mounting
        Gripper mounting (``"10/4"``, ``"6/2"``, ``"4/0"``).
    success
        The object was held at the end of the 15 s hold.
    cause
        One of :data:`FAILURE_CAUSES` for a failure, None for a success.
    modules
        Modules the planner saw the object on.
    increments_pa
        Pressure increment of every module after the object settled (mean of 10 reads minus
        the reference), pascals.
    cog
        Planned centre of grasp, module units, or None.
    theta
        Planned direction of grasp, radians, or None.
    opening_m
        Jaw opening during the approach, metres.
    contact_detected
        The pad sensed the fingers (filtered increment above t_g) during the descent.
    contact_delay_s
        From the first touch of a fingertip to the detection, seconds (None if either missing).
    finger_travel_mm
        Descent of the fingers between first touch and stop, millimetres (None if no touch).
    cog_outside_object_mm
        Distance of the planned COG from the object's footprint, millimetres (0 on it).
    sim_time_s
        Simulated duration of the trial, seconds.
    wall_time_s
        Wall-clock duration, seconds.
    detail
        Free text: what happened.
    """

    object: str
    trial: int
    seed: int
    placement: tuple[float, float, float]
    mounting: str
    success: bool
    cause: str | None
    modules: tuple[int, ...] = ()
    increments_pa: tuple[float, ...] = ()
    cog: tuple[float, float] | None = None
    theta: float | None = None
    opening_m: float = 0.0
    contact_detected: bool = False
    contact_delay_s: float | None = None
    finger_travel_mm: float | None = None
    cog_outside_object_mm: float | None = None
    sim_time_s: float = 0.0
    wall_time_s: float = 0.0
    detail: str = ""

    def __post_init__(self) -> None:
        if self.cause is not None and self.cause not in FAILURE_CAUSES:
            raise ValueError(f"unknown failure cause {self.cause!r}")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        r = 6
        return {
            "object": self.object,
            "trial": self.trial,
            "seed": self.seed,
            "placement": [round(v, 6) for v in self.placement],
            "mounting": self.mounting,
            "success": self.success,
            "cause": self.cause,
            "modules": list(self.modules),
            "increments_pa": [round(v, 2) for v in self.increments_pa],
            "cog": None if self.cog is None else [round(v, r) for v in self.cog],
            "theta": None if self.theta is None else round(self.theta, r),
            "opening_mm": round(self.opening_m * 1e3, 3),
            "contact_detected": self.contact_detected,
            "contact_delay_s": None
            if self.contact_delay_s is None
            else round(self.contact_delay_s, r),
            "finger_travel_mm": None
            if self.finger_travel_mm is None
            else round(self.finger_travel_mm, 3),
            "cog_outside_object_mm": None
            if self.cog_outside_object_mm is None
            else round(self.cog_outside_object_mm, 3),
            "sim_time_s": round(self.sim_time_s, 3),
            "wall_time_s": round(self.wall_time_s, 3),
            "detail": self.detail,
        }


@dataclass(frozen=True)
class ObjectSummary:
    """Trials of one object.

    Attributes
    ----------
    name
        Catalogue name.
    mass_g
        Mass, grams.
    trials
        Number of trials.
    successes
        Number of successful trials.
    failures
        Count of each failure cause that occurred.
    representative
        The plan of the first trial with one: (x_COG, y_COG, theta), module units and radians.
    """

    name: str
    mass_g: float
    trials: int
    successes: int
    failures: dict[str, int]
    representative: tuple[float, float, float] | None

    def to_dict(self) -> dict[str, Any]:
        """The per-object entry of ``softpad trials --json``."""
        return {
            "name": self.name,
            "trials": self.trials,
            "successes": self.successes,
            "failures": dict(self.failures),
        }


@dataclass(frozen=True)
class ExperimentResult:
    """All trials of an experiment (Experiment 2 of Section 6.3 by default).

    Attributes
    ----------
    trials
        Every trial, ordered by object (catalogue order) and trial number.
    seed
        Experiment seed.
    masses_g
        Mass of each object, grams.
    wall_time_s
        Wall-clock time of the whole experiment, seconds.
    workers
        Worker processes used.
    """

    trials: tuple[TrialResult, ...]
    seed: int
    masses_g: dict[str, float] = field(default_factory=dict)
    wall_time_s: float = 0.0
    workers: int = 1

    @property
    def object_names(self) -> tuple[str, ...]:
        """Objects in the order they were run."""
        seen: dict[str, None] = {}
        for t in self.trials:
            seen.setdefault(t.object, None)
        return tuple(seen)

    def summaries(self) -> list[ObjectSummary]:
        """One summary per object."""
        out = []
        for name in self.object_names:
            ts = [t for t in self.trials if t.object == name]
            failures: dict[str, int] = {}
            for t in ts:
                if t.cause is not None:
                    failures[t.cause] = failures.get(t.cause, 0) + 1
            rep = next(
                (
                    (t.cog[0], t.cog[1], t.theta)
                    for t in ts
                    if t.cog is not None and t.theta is not None
                ),
                None,
            )
            out.append(
                ObjectSummary(
                    name=name,
                    mass_g=self.masses_g.get(name, math.nan),
                    trials=len(ts),
                    successes=sum(t.success for t in ts),
                    failures=failures,
                    representative=rep,
                )
            )
        return out

    @property
    def overall_success(self) -> float:
        """Fraction of successful trials."""
        return sum(t.success for t in self.trials) / len(self.trials) if self.trials else 0.0

    def failures_by_cause(self) -> dict[str, int]:
        """Count of every failure cause over the experiment."""
        out: dict[str, int] = {}
        for t in self.trials:
            if t.cause is not None:
                out[t.cause] = out.get(t.cause, 0) + 1
        return out

    def to_dict(self) -> dict[str, Any]:
        """The JSON of ``softpad trials --json`` (per-object counts, then every trial)."""
        return {
            "objects": [s.to_dict() for s in self.summaries()],
            "overall_success": round(self.overall_success, 6),
            "thesis_overall_success": THESIS_OVERALL_SUCCESS,
            "failures": self.failures_by_cause(),
            "seed": self.seed,
            "wall_time_s": round(self.wall_time_s, 3),
            "workers": self.workers,
            "trials": [t.to_dict() for t in self.trials],
        }

    def table_rows(self) -> list[dict[str, str]]:
        """Rows of the Table 6.1-like table, as text."""
        rows = []
        for s in self.summaries():
            thesis = THESIS_TABLE_6_1.get(s.name)
            plan = "-" if s.representative is None else _fmt_plan(s.representative)
            rows.append(
                {
                    "object": s.name,
                    "weight_g": f"{s.mass_g:.1f}",
                    "planned_grasp": plan,
                    "thesis_grasp": "-" if thesis is None else _fmt_plan(thesis[1]),
                    "success": f"{s.successes}/{s.trials}",
                    "thesis_success": "-" if thesis is None else f"{thesis[2]}/5",
                    "failures": ", ".join(f"{k} x{v}" for k, v in sorted(s.failures.items()))
                    or "-",
                }
            )
        return rows

    def to_markdown(self) -> str:
        """The table in Markdown, with the overall rate next to the thesis's."""
        head = (
            "| object | weight (g) | planned grasp (x_COG, y_COG, theta) | thesis grasp "
            "| success | thesis | failures |\n|---|---:|---|---|---:|---:|---|\n"
        )
        body = "".join(
            f"| {r['object']} | {r['weight_g']} | {r['planned_grasp']} | {r['thesis_grasp']} "
            f"| {r['success']} | {r['thesis_success']} | {r['failures']} |\n"
            for r in self.table_rows()
        )
        n = len(self.trials)
        k = sum(t.success for t in self.trials)
        causes = ", ".join(f"{c}: {v}" for c, v in sorted(self.failures_by_cause().items()))
        return (
            head + body + f"\nOverall success: {k}/{n} = {100 * self.overall_success:.1f} % "
            f"(thesis: 52/55 = {100 * THESIS_OVERALL_SUCCESS:.1f} %). "
            f"Failures by cause: {causes or 'none'}.\n"
        )

    def to_text(self) -> str:
        """The table as aligned plain text (the CLI's output)."""
        rows = self.table_rows()
        cols = [
            "object",
            "weight_g",
            "planned_grasp",
            "thesis_grasp",
            "success",
            "thesis_success",
            "failures",
        ]
        heads = [
            "object",
            "weight (g)",
            "planned grasp",
            "thesis grasp",
            "success",
            "thesis",
            "failures",
        ]
        widths = [max(len(h), *(len(r[c]) for r in rows)) for c, h in zip(cols, heads, strict=True)]
        lines = ["  ".join(h.ljust(w) for h, w in zip(heads, widths, strict=True))]
        lines += ["  ".join(r[c].ljust(w) for c, w in zip(cols, widths, strict=True)) for r in rows]
        n = len(self.trials)
        k = sum(t.success for t in self.trials)
        causes = ", ".join(f"{c} x{v}" for c, v in sorted(self.failures_by_cause().items()))
        lines.append(
            f"overall success: {k}/{n} = {100 * self.overall_success:.1f} % "
            f"(thesis 94.5 %); failures: {causes or 'none'}"
        )
        return "\n".join(lines)

    def to_csv(self) -> str:
        """The table as CSV (one row per object)."""
        buf = io.StringIO()
        rows = self.table_rows()
        writer = csv.DictWriter(buf, fieldnames=list(rows[0]) if rows else ["object"])
        writer.writeheader()
        writer.writerows(rows)
        return buf.getvalue()


def _fmt_plan(plan: tuple[float, float, float]) -> str:
    x, y, th = plan
    return f"({x:.2f}, {y:.2f}, {_fmt_angle(th)})"


def _fmt_angle(theta: float) -> str:
    """Angle as a multiple of pi when it is one of the usual fractions, else in radians."""
    for num, den, text in (
        (0, 1, "0"),
        (1, 4, "pi/4"),
        (-1, 4, "-pi/4"),
        (1, 2, "pi/2"),
        (-1, 2, "-pi/2"),
    ):
        if abs(theta - num * math.pi / den) < 1e-3:
            return text
    return f"{theta:.3f}"
