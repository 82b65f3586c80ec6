"""Records of grasp trials: one trial, one experiment (Table 6.1)."""

from __future__ import annotations

import csv
import io
import math
import statistics
from dataclasses import dataclass, field
from typing import Any

#: The thesis's Table 6.1: weight (g), representative planned grasp (x_COG, y_COG, theta) in
#: module units and radians, successes out of 5 (thesis, Section 6.3).
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

#: The thesis's three failures (Section 6.3), by object and cause: object 5 and the charger
#: "due to a missing contact detection, because the gripper touched the non-sensitive line
#: between modules"; the cylinder because "the resulting COG was ... around 1 cm outside of
#: the object".
THESIS_FAILURES: dict[str, dict[str, int]] = {
    "object-5": {"contact_not_detected": 1},
    "charger": {"contact_not_detected": 1},
    "cylinder": {"cog_outside_object": 1},
}

#: Why a trial failed, decided in this order from the physics and the true object:
#: ``contact_not_detected`` (the fingers reached the pad base unsensed: tips on a seam or off
#: the pad; the thesis's failure for object 5 and the charger); ``cog_outside_object`` (the
#: grasp failed and its planned COG lay outside the object's footprint: the thesis's cylinder
#: failure); ``jaws_hit_object`` (a jaw came down on the object); ``object_outside_jaws``;
#: ``slipped_during_hold``; ``object_too_narrow``: the object was between the jaws but thinner
#: than the mounting's minimum width; ``object_not_detected``: the planner found nothing;
#: ``box_fault``: the loop stopped on a box fault (a module read above the 3 kPa limit, which
#: the simulated box's module model reaches when a fingertip pushes a module with more than
#: about 1.5 N); ``trial_error``: the trial raised an exception, a defect of the loop or the
#: simulator and not a grasp outcome (``detail`` holds the traceback; the commands that run
#: trials exit with the internal-error code when any trial has it).
FAILURE_CAUSES = (
    "contact_not_detected",
    "cog_outside_object",
    "jaws_hit_object",
    "object_outside_jaws",
    "slipped_during_hold",
    "object_too_narrow",
    "object_not_detected",
    "box_fault",
    "trial_error",
)


@dataclass(frozen=True)
class TrialResult:
    """Outcome of one grasp trial."""

    #: Catalogue name.
    object: str
    #: 0-based trial number of this object.
    trial: int
    #: Seed of this trial's random placement (derived from the experiment seed).
    seed: int
    #: Where the object was put: (x_m, y_m, yaw_rad), pad frame.
    placement: tuple[float, float, float]
    #: Gripper mounting (``"10/4"``, ``"6/2"``, ``"4/0"``).
    mounting: str
    #: The object was held at the end of the 15 s hold.
    success: bool
    #: One of :data:`FAILURE_CAUSES` for a failure, None for a success.
    cause: str | None
    #: Modules the planner saw the object on.
    modules: tuple[int, ...] = ()
    #: Pressure increment of every module after the object settled (mean of 10 reads minus
    #: the reference), pascals.
    increments_pa: tuple[float, ...] = ()
    #: Planned centre of grasp, module units, or None.
    cog: tuple[float, float] | None = None
    #: Planned direction of grasp, radians, or None.
    theta: float | None = None
    #: The rule of the first plan (the planner's words: ``"catalogue NAME ..."`` for a known
    #: object of the catalogue planner, ``"unknown -> ..."`` for one it handed on), or None.
    rule: str | None = None
    #: Jaw opening during the approach, metres.
    opening_m: float = 0.0
    #: The pad sensed the fingers (filtered increment above t_g) during the descent.
    contact_detected: bool = False
    #: From the first touch of a fingertip to the detection, seconds (None if either missing).
    contact_delay_s: float | None = None
    #: Descent of the fingers between first touch and stop, millimetres (None if no touch).
    finger_travel_mm: float | None = None
    #: Distance of the planned COG from the object's footprint, millimetres (0 on it).
    cog_outside_object_mm: float | None = None
    #: Grasps tried: more than one when the loop retreated after its jaws landed on the
    #: object and tried the planner's next grasp (``cog`` and ``theta`` are the last's).
    attempts: int = 1
    #: Simulated duration of the trial, seconds.
    sim_time_s: float = 0.0
    #: Wall-clock duration, seconds.
    wall_time_s: float = 0.0
    #: Free text: what happened.
    detail: str = ""
    #: The uncertain parameters drawn for this trial (``--randomize``, names of
    #: :data:`softpad.sim.UNCERTAIN_PARAMETERS`), None when every one was at its nominal value.
    parameters: dict[str, float] | None = None

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
            "rule": self.rule,
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
            "attempts": self.attempts,
            "sim_time_s": round(self.sim_time_s, 3),
            "wall_time_s": round(self.wall_time_s, 3),
            "detail": self.detail,
            "parameters": self.parameters,
        }


def errored_records(trials: Any) -> list[dict[str, Any]]:
    """The ``to_dict()`` records of the trials that raised (cause ``trial_error``)."""
    return [t.to_dict() for t in trials if t.cause == "trial_error"]


@dataclass(frozen=True)
class ObjectSummary:
    """Trials of one object, next to the thesis's Table 6.1 entry."""

    #: Catalogue name.
    name: str
    #: Mass, grams.
    mass_g: float
    #: Number of trials.
    trials: int
    #: Number of successful trials.
    successes: int
    #: Count of each failure cause that occurred.
    failures: dict[str, int]
    #: The plan of the first trial with one: (x_COG, y_COG, theta), module units and radians.
    representative: tuple[float, float, float] | None
    #: The predicted grasp over all trials: the trials' most frequent theta and the median
    #: x_COG and y_COG of the trials that planned it, or None when no trial planned.
    planned: tuple[float, float, float] | None = None
    #: Fraction of the planned trials whose theta is that most frequent one.
    theta_share: float | None = None

    @property
    def success_interval(self) -> tuple[float, float]:
        """95 % Wilson score interval of the success rate."""
        from softpad.trials._stats import wilson_interval

        return wilson_interval(self.successes, self.trials)

    def grasp_difference(self) -> dict[str, float] | None:
        """Predicted minus thesis grasp: ``dx``, ``dy``, ``distance`` (module units) and
        ``theta_rad`` (wrapped to (-pi/2, pi/2], a parallel-jaw grasp being the same under pi);
        None without a plan or a thesis entry."""
        thesis = THESIS_TABLE_6_1.get(self.name)
        if thesis is None or self.planned is None:
            return None
        (x, y, th), (tx, ty, tth) = self.planned, thesis[1]
        dth = (th - tth + math.pi / 2) % math.pi - math.pi / 2
        if dth <= -math.pi / 2 + 1e-12:
            dth += math.pi
        return {
            "dx": round(x - tx, 4),
            "dy": round(y - ty, 4),
            "distance": round(math.hypot(x - tx, y - ty), 4),
            "theta_rad": round(dth, 4),
        }

    def to_dict(self) -> dict[str, Any]:
        """The per-object entry of ``softpad trials --json``: the prediction and the thesis's."""
        thesis = THESIS_TABLE_6_1.get(self.name)
        planned = None
        if self.planned is not None:
            planned = {
                "cog": [round(self.planned[0], 4), round(self.planned[1], 4)],
                "theta": round(self.planned[2], 6),
                "theta_share": None if self.theta_share is None else round(self.theta_share, 4),
            }
        return {
            "name": self.name,
            "trials": self.trials,
            "successes": self.successes,
            "success": round(self.successes / self.trials, 4) if self.trials else None,
            "success_interval": list(self.success_interval),
            "failures": dict(self.failures),
            "planned_grasp": planned,
            "thesis": None
            if thesis is None
            else {
                "trials": 5,
                "successes": thesis[2],
                "failures": dict(THESIS_FAILURES.get(self.name, {})),
                "grasp": {"cog": list(thesis[1][:2]), "theta": round(thesis[1][2], 6)},
            },
            "grasp_difference": self.grasp_difference(),
        }


def _predicted_grasp(
    ts: list[TrialResult],
) -> tuple[tuple[float, float, float] | None, float | None]:
    """Most frequent theta of the trials' plans, the median COG of the plans with that theta,
    and that theta's share of the plans."""
    plans = [(t.cog, t.theta) for t in ts if t.cog is not None and t.theta is not None]
    if not plans:
        return None, None
    counts: dict[float, int] = {}
    for _, th in plans:
        key = round(th, 6)
        counts[key] = counts.get(key, 0) + 1
    theta = max(counts, key=lambda k: counts[k])
    # the COG of the trials that planned that direction (a plan that flips between two
    # directions has two COGs; their median would lie between them, on neither)
    xs = [c[0] for c, th in plans if round(th, 6) == theta]
    ys = [c[1] for c, th in plans if round(th, 6) == theta]
    planned = (statistics.median(xs), statistics.median(ys), theta)
    return planned, counts[theta] / len(plans)


@dataclass(frozen=True)
class ExperimentResult:
    """All trials of an experiment (Experiment 2 of Section 6.3 by default)."""

    #: Every trial, ordered by object (catalogue order) and trial number.
    trials: tuple[TrialResult, ...]
    #: Experiment seed.
    seed: int
    #: Mass of each object, grams.
    masses_g: dict[str, float] = field(default_factory=dict)
    #: Wall-clock time of the whole experiment, seconds.
    wall_time_s: float = 0.0
    #: Worker processes used.
    workers: int = 1
    #: Experiment seeds pooled into this result (:meth:`pooled`); ``(seed,)`` by default.
    seeds: tuple[int, ...] = ()
    #: Placement noise of the trials: ``position_sigma_mm`` (millimetres) and ``yaw_sigma_deg``
    #: (degrees).
    placement_noise: dict[str, float] = field(default_factory=dict)

    @classmethod
    def pooled(cls, experiments: list[ExperimentResult]) -> ExperimentResult:
        """The trials of several experiments (e.g. seeds 0-9) as one result."""
        if not experiments:
            raise ValueError("nothing to pool")
        return cls(
            trials=tuple(t for e in experiments for t in e.trials),
            seed=experiments[0].seed,
            masses_g={k: v for e in experiments for k, v in e.masses_g.items()},
            wall_time_s=sum(e.wall_time_s for e in experiments),
            workers=max(e.workers for e in experiments),
            seeds=tuple(s for e in experiments for s in (e.seeds or (e.seed,))),
            placement_noise=dict(experiments[0].placement_noise),
        )

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
            planned, share = _predicted_grasp(ts)
            out.append(
                ObjectSummary(
                    name=name,
                    mass_g=self.masses_g.get(name, math.nan),
                    trials=len(ts),
                    successes=sum(t.success for t in ts),
                    failures=failures,
                    representative=rep,
                    planned=planned,
                    theta_share=share,
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

    def overall(self) -> dict[str, Any]:
        """Trials, successes, their 95 % Wilson interval and failures by cause, all objects."""
        from softpad.trials._stats import wilson_interval

        n, k = len(self.trials), sum(t.success for t in self.trials)
        return {
            "trials": n,
            "successes": k,
            "success": round(k / n, 4) if n else None,
            "success_interval": list(wilson_interval(k, n)),
            "failures": self.failures_by_cause(),
        }

    def thesis_overall(self) -> dict[str, Any]:
        """The thesis's figures for the objects of this run (5 trials each, Table 6.1), its
        failures by cause, and which of those causes this run reproduced."""
        names = [n for n in self.object_names if n in THESIS_TABLE_6_1]
        causes: dict[str, int] = {}
        for n in names:
            for c, v in THESIS_FAILURES.get(n, {}).items():
                causes[c] = causes.get(c, 0) + v
        mine = self.failures_by_cause()
        return {
            "trials": 5 * len(names),
            "successes": sum(THESIS_TABLE_6_1[n][2] for n in names),
            "failures": causes,
            "causes_reproduced": sorted(c for c in causes if mine.get(c, 0) > 0),
            "causes_not_seen": sorted(c for c in causes if mine.get(c, 0) == 0),
        }

    def to_dict(self) -> dict[str, Any]:
        """The JSON of ``softpad trials --json``: per object the trials, successes, their 95 %
        Wilson interval, failures by cause and the predicted grasp next to the thesis's; the
        same overall; then every trial."""
        return {
            "objects": [s.to_dict() for s in self.summaries()],
            "overall": self.overall(),
            "thesis": self.thesis_overall(),
            "overall_success": round(self.overall_success, 6),
            "thesis_overall_success": THESIS_OVERALL_SUCCESS,
            "failures": self.failures_by_cause(),
            "seed": self.seed,
            "seeds": list(self.seeds or (self.seed,)),
            "placement_noise": dict(self.placement_noise),
            "wall_time_s": round(self.wall_time_s, 3),
            "workers": self.workers,
            "trials": [t.to_dict() for t in self.trials],
        }

    def table_rows(self) -> list[dict[str, str]]:
        """Rows of the Table 6.1-like table, as text: the prediction next to the thesis."""
        rows = []
        for s in self.summaries():
            thesis = THESIS_TABLE_6_1.get(s.name)
            diff = s.grasp_difference()
            lo, hi = s.success_interval
            rows.append(
                {
                    "object": s.name,
                    "weight_g": f"{s.mass_g:.1f}",
                    "planned_grasp": "-" if s.planned is None else _fmt_plan(s.planned),
                    "thesis_grasp": "-" if thesis is None else _fmt_plan(thesis[1]),
                    "difference": "-"
                    if diff is None
                    else f"{diff['distance']:.2f}, {math.degrees(diff['theta_rad']):+.0f} deg",
                    "success": f"{s.successes}/{s.trials}",
                    "interval": f"{100 * lo:.0f}-{100 * hi:.0f} %",
                    "thesis_success": "-" if thesis is None else f"{thesis[2]}/5",
                    "failures": _fmt_causes(s.failures),
                    "thesis_failures": _fmt_causes(THESIS_FAILURES.get(s.name, {})),
                }
            )
        return rows

    def _summary_line(self) -> str:
        o, t = self.overall(), self.thesis_overall()
        lo, hi = o["success_interval"]
        seeds = self.seeds or (self.seed,)
        return (
            f"Overall success: {o['successes']}/{o['trials']} = {100 * self.overall_success:.1f} % "
            f"(95 % interval {100 * lo:.1f}-{100 * hi:.1f} %; {len(seeds)} seed(s)); thesis: "
            f"{t['successes']}/{t['trials']}. Failures by cause: "
            f"{_fmt_causes(o['failures'])}; thesis: {_fmt_causes(t['failures'])}; thesis causes "
            f"reproduced: {', '.join(t['causes_reproduced']) or 'none'}."
        )

    def to_markdown(self) -> str:
        """The table in Markdown, with the overall rate next to the thesis's."""
        cols = list(_HEADS)
        head = "| " + " | ".join(_HEADS[c] for c in cols) + " |\n"
        head += "|" + "|".join("---:" if c in ("weight_g", "success") else "---" for c in cols)
        body = "".join("| " + " | ".join(r[c] for c in cols) + " |\n" for r in self.table_rows())
        return head + "|\n" + body + "\n" + self._summary_line() + "\n"

    def to_text(self) -> str:
        """The table as aligned plain text (the CLI's output)."""
        rows = self.table_rows()
        cols = list(_HEADS)
        widths = [max(len(_HEADS[c]), *(len(r[c]) for r in rows)) for c in cols]
        lines = ["  ".join(_HEADS[c].ljust(w) for c, w in zip(cols, widths, strict=True))]
        lines += ["  ".join(r[c].ljust(w) for c, w in zip(cols, widths, strict=True)) for r in rows]
        lines.append(self._summary_line())
        return "\n".join(lines)

    def to_csv(self) -> str:
        """The table as CSV (one row per object)."""
        buf = io.StringIO()
        rows = self.table_rows()
        writer = csv.DictWriter(buf, fieldnames=list(rows[0]) if rows else ["object"])
        writer.writeheader()
        writer.writerows(rows)
        return buf.getvalue()


#: Column titles of the Table 6.1-like table.
_HEADS: dict[str, str] = {
    "object": "object",
    "weight_g": "weight (g)",
    "planned_grasp": "predicted grasp",
    "thesis_grasp": "thesis grasp",
    "difference": "difference",
    "success": "success",
    "interval": "95 % interval",
    "thesis_success": "thesis",
    "failures": "failures",
    "thesis_failures": "thesis failures",
}


def _fmt_causes(causes: dict[str, int]) -> str:
    return ", ".join(f"{k} x{v}" for k, v in sorted(causes.items())) or "-"


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
