"""Ranked results of a design sweep: table, Pareto front, CSV/Parquet, plot and report."""

from __future__ import annotations

import csv
import statistics
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from softpad.design._space import PadDesign

#: Columns of the CSV/Parquet table, in order (units in the names).
COLUMNS = (
    "rank",
    "name",
    "baseline",
    "rows",
    "cols",
    "pitch_mm",
    "thickness_mm",
    "material",
    "p0_kpa",
    "modules",
    "successes",
    "trials",
    "success",
    "success_low",
    "success_high",
    "min_detectable_mass_g",
    "detection_delay_ms",
    "height_mm",
    "rise_kpa_per_n",
    "sensitive_fraction",
    "pareto",
    "failures",
)


@dataclass(frozen=True)
class DesignRow:
    """One design's figures."""

    #: The design.
    design: PadDesign
    #: Its finite-element summary (:meth:`FemResponse.summary`).
    response: dict[str, Any]
    #: Held grasps and trials over the object set and seeds.
    successes: int
    #: Held grasps and trials over the object set and seeds.
    trials: int
    #: 95 % Wilson interval of the success rate.
    success_interval: tuple[float, float]
    #: Median time from the first fingertip touch to the detection, ms (None: never detected).
    detection_delay_ms: float | None
    #: Failed trials by outcome.
    failures: dict[str, int] = field(default_factory=dict)
    #: On the Pareto front of (success up, minimum detectable mass down, modules down).
    pareto: bool = False
    #: Held grasps and trials of each object, in the set's order.
    objects: dict[str, tuple[int, int]] = field(default_factory=dict)
    #: 1 = best: success rate, then its interval's lower end, minimum detectable mass,
    #: module count, detection delay.
    rank: int = 0

    @property
    def success(self) -> float:
        """Success rate."""
        return self.successes / self.trials if self.trials else 0.0

    @property
    def min_detectable_mass_g(self) -> float:
        """Minimum detectable mass at t_o on the module, grams (FEM)."""
        return float(self.response["min_detectable_mass_g"])

    def to_dict(self) -> dict[str, Any]:
        """The row with units in the keys (the JSON of ``softpad design --json``)."""
        d = self.design.to_dict()
        d.update(
            rank=self.rank,
            success=round(self.success, 4),
            success_interval=list(self.success_interval),
            successes=self.successes,
            trials=self.trials,
            min_detectable_mass_g=self.min_detectable_mass_g,
            detection_delay_ms=self.detection_delay_ms,
            fem=self.response,
            failures=dict(self.failures),
            pareto=self.pareto,
            objects={k: {"successes": v[0], "trials": v[1]} for k, v in self.objects.items()},
        )
        return d

    def flat(self) -> dict[str, Any]:
        """The row as one flat record of :data:`COLUMNS`."""
        d = self.to_dict()
        lo, hi = self.success_interval
        d.update(
            success_low=lo,
            success_high=hi,
            height_mm=self.response["height_mm"],
            rise_kpa_per_n=self.response["rise_kpa_per_n"],
            sensitive_fraction=self.response["sensitive_fraction"],
            failures=";".join(f"{k}={v}" for k, v in sorted(self.failures.items())),
        )
        return {k: d[k] for k in COLUMNS}


def design_row(
    design: PadDesign, response: dict[str, Any], trials: list[dict[str, Any]]
) -> DesignRow:
    """Aggregate one design's FEM response and trial records."""
    from softpad.design._response import FemResponse
    from softpad.trials import wilson_interval

    ok = sum(1 for t in trials if t["success"])
    delays = [t["contact_delay_s"] for t in trials if t.get("contact_delay_s") is not None]
    fails = Counter(t["outcome"] for t in trials if not t["success"])
    return DesignRow(
        design=design,
        response=FemResponse.from_dict(response).summary(),
        successes=ok,
        trials=len(trials),
        success_interval=wilson_interval(ok, len(trials)),
        detection_delay_ms=round(1e3 * statistics.median(delays), 1) if delays else None,
        failures=dict(fails),
        objects=_per_object(trials),
    )


def _per_object(trials: list[dict[str, Any]]) -> dict[str, tuple[int, int]]:
    """Held grasps and trials of each object of ``trials``, in the order first seen."""
    out: dict[str, tuple[int, int]] = {}
    for t in trials:
        k, n = out.get(t["object"], (0, 0))
        out[t["object"]] = (k + bool(t["success"]), n + 1)
    return out


def _dominates(a: DesignRow, b: DesignRow) -> bool:
    """a is at least as good as b in every objective and better in one."""
    ka = (-a.success, a.min_detectable_mass_g, a.design.n_modules)
    kb = (-b.success, b.min_detectable_mass_g, b.design.n_modules)
    return all(x <= y for x, y in zip(ka, kb, strict=True)) and ka != kb


def rank_rows(rows: list[DesignRow]) -> list[DesignRow]:
    """The rows with Pareto flags and ranks, best first."""
    from dataclasses import replace

    flagged = [
        replace(r, pareto=not any(_dominates(o, r) for o in rows if o is not r)) for r in rows
    ]
    order = sorted(
        flagged,
        key=lambda r: (
            -r.success,
            -r.success_interval[0],
            r.min_detectable_mass_g,
            r.design.n_modules,
            r.detection_delay_ms if r.detection_delay_ms is not None else float("inf"),
        ),
    )
    return [replace(r, rank=i + 1) for i, r in enumerate(order)]


@dataclass(frozen=True)
class SweepResult:
    """A ranked design sweep."""

    #: Ranked designs, best first.
    rows: tuple[DesignRow, ...]
    #: Name of the object set.
    object_set: str
    #: How it was run (seeds, options, workers, wall time, tasks computed and cached).
    meta: dict[str, Any]
    #: Every trial record by design name.
    trials: dict[str, list[dict[str, Any]]] = field(default_factory=dict)

    @property
    def baseline(self) -> DesignRow:
        """The thesis's pad's row."""
        return next(r for r in self.rows if r.design.is_thesis)

    def to_dict(self, with_trials: bool = False) -> dict[str, Any]:
        """``{"object_set", "designs": [...ranked rows], ...meta}``."""
        d: dict[str, Any] = {
            "object_set": self.object_set,
            "designs": [r.to_dict() for r in self.rows],
        }
        d.update(self.meta)
        if with_trials:
            d["trials"] = self.trials
        return d

    def to_text(self) -> str:
        """The ranked table as aligned text."""
        head = f"{'#':>2} {'design':<34} {'mod':>3} {'success':>8} {'95% interval':>13} {'m_min g':>7} {'delay ms':>8} {'h mm':>5}  P"
        lines = [head, "-" * len(head)]
        for r in self.rows:
            lo, hi = r.success_interval
            delay = "-" if r.detection_delay_ms is None else f"{r.detection_delay_ms:.0f}"
            name = r.design.name + (" *" if r.design.is_thesis else "")
            lines.append(
                f"{r.rank:>2} {name:<34} {r.design.n_modules:>3} {r.successes:>3}/{r.trials:<4}"
                f" {lo:>6.2f}-{hi:<6.2f} {r.min_detectable_mass_g:>7.1f} {delay:>8} "
                f"{r.response['height_mm']:>5.1f}  {'P' if r.pareto else ''}"
            )
        lines.append(
            "* the thesis's pad (baseline); P: on the Pareto front (success, minimum detectable mass, modules)"
        )
        return "\n".join(lines)

    def to_csv(self, path: str | Path) -> Path:
        """Write the table (:data:`COLUMNS`)."""
        p = Path(path)
        with p.open("w", newline="", encoding="utf-8") as f:
            w = csv.DictWriter(f, fieldnames=list(COLUMNS))
            w.writeheader()
            for r in self.rows:
                w.writerow(r.flat())
        return p

    def to_parquet(self, path: str | Path) -> Path:
        """Write the table as Parquet (needs pyarrow: ``pip install softpad[design]``)."""
        from softpad.errors import InputError

        try:
            import pyarrow as pa
            import pyarrow.parquet as pq
        except ImportError:
            raise InputError(
                "Parquet output needs pyarrow: pip install 'softpad[design]'"
            ) from None
        pq.write_table(pa.Table.from_pylist([r.flat() for r in self.rows]), str(path))
        return Path(path)

    def plot(self, path: str | Path | None = None) -> Any:
        """Pareto plot: success rate (95 % interval bars) against the minimum detectable mass,
        colour = module count; designs on the (success, mass, modules) front ringed in black,
        the thesis's pad in red; each point labelled with its rank (points closer than a label
        share one label, ranks left to right). Returns the figure."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7.5, 4.8))
        xs = [r.min_detectable_mass_g for r in self.rows]
        ys = [r.success for r in self.rows]
        err = [
            [r.success - r.success_interval[0] for r in self.rows],
            [r.success_interval[1] - r.success for r in self.rows],
        ]
        ax.errorbar(xs, ys, yerr=err, fmt="none", ecolor="0.75", lw=1, zorder=1)
        edges = ["k" if r.pareto else "none" for r in self.rows]
        sc = ax.scatter(
            xs,
            ys,
            c=[r.design.n_modules for r in self.rows],
            cmap="viridis",
            s=70,
            edgecolors=edges,
            linewidths=1.5,
            zorder=3,
        )
        fig.colorbar(sc, ax=ax, label="modules (cost proxy)")
        b = self.baseline
        ax.scatter(
            [b.min_detectable_mass_g],
            [b.success],
            s=260,
            facecolors="none",
            edgecolors="r",
            lw=1.5,
            label="thesis pad",
            zorder=4,
        )
        ax.scatter([], [], s=70, facecolors="none", edgecolors="k", label="Pareto front")
        ax.set_xlabel("minimum detectable mass at t_o (g, FEM)")
        ax.set_ylabel("grasp success rate")
        ax.set_ylim(-0.05, 1.05)
        self._rank_labels(ax)
        ax.set_title(f"design sweep on {self.object_set} (numbers: rank)")
        ax.legend(loc="lower right", fontsize=8)
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig

    def _rank_labels(self, ax: Any, near_px: float = 16.0) -> None:
        """One label per group of points closer than ``near_px`` on screen: their ranks, left
        to right, above the group (so no label sits on another label or on a point)."""
        ax.autoscale_view()
        points = sorted(
            ((*ax.transData.transform((r.min_detectable_mass_g, r.success)), r) for r in self.rows),
            key=lambda p: (p[0], p[1]),
        )
        groups: list[list[tuple[float, float, DesignRow]]] = []
        for p in points:
            near = next(
                (
                    g
                    for g in groups
                    if any(abs(p[0] - q[0]) < near_px and abs(p[1] - q[1]) < near_px for q in g)
                ),
                None,
            )
            near.append(p) if near is not None else groups.append([p])
        for g in groups:
            top = max(g, key=lambda q: q[1])[2]
            ax.annotate(
                ", ".join(str(q[2].rank) for q in g),
                (sum(q[2].min_detectable_mass_g for q in g) / len(g), top.success),
                textcoords="offset points", xytext=(0, 12), ha="center", fontsize=9,
            )  # fmt: skip

    def report(self) -> str:
        """A short Markdown report: the best design against the thesis's, the table."""
        best, base = self.rows[0], self.baseline
        m = self.meta
        lines = [
            f"# Design sweep on {self.object_set}",
            "",
            f"{len(self.rows)} designs x {m.get('objects', '?')} objects x {m.get('trials_per_object', '?')} "
            f"trials x seeds {m.get('seeds')}; planner {m.get('planner')}, detector {m.get('detector')}, "
            f"world {m.get('world')}; {m.get('computed', 0)} tasks computed, {m.get('cached', 0)} from the cache, "
            f"{m.get('wall_time_s', 0):.1f} s on {m.get('workers', 0)} workers.",
            "",
            f"Best: **{best.design.name}** ({best.successes}/{best.trials}, minimum detectable mass "
            f"{best.min_detectable_mass_g:.1f} g, {best.design.n_modules} modules); the thesis's pad "
            f"ranks {base.rank} ({base.successes}/{base.trials}, {base.min_detectable_mass_g:.1f} g).",
            "",
            "```",
            self.to_text(),
            "```",
            "",
            "Held grasps per object (best design; the thesis's pad):",
            "",
            *(
                f"- {name}: {k}/{n}; {base.objects.get(name, (0, 0))[0]}/"
                f"{base.objects.get(name, (0, 0))[1]}"
                for name, (k, n) in best.objects.items()
            ),
        ]
        return "\n".join(lines) + "\n"
