"""How dense must a pad be? (issue 47, item 5): pads of more and smaller modules on about the
thesis's area, each with its own FEM response, under three planner/detector pairs, on a
development and a held-out object set, with ``--randomize`` and placements anywhere.

Every (set, pair) is one :func:`~softpad.design.design_sweep` of the study's pads (the same
tasks, keys and cache as ``softpad design``); :func:`density_study` collects the rows, the
mesh convergence of each pad's response (coarse against medium mesh) and answers: the pad
with the fewest modules on which a pair holds a share of the held-out objects.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from softpad.design._cache import ResultCache
from softpad.design._evaluate import TrialOptions
from softpad.design._response import fem_response
from softpad.design._space import THESIS_DESIGN, PadDesign
from softpad.errors import InputError

#: The study's pads on about the thesis's 90 x 135 mm: 2 x 3 at 45 mm (the thesis's),
#: 3 x 4 at 34 mm (102 x 136 mm), 3 x 5 at 27 mm (81 x 135 mm: between 12 and 24 modules, where
#: the 85 % line may fall), 4 x 6 at 22.5 mm (90 x 135 mm).
DENSITY_PADS: tuple[PadDesign, ...] = (
    THESIS_DESIGN,
    PadDesign(3, 4, 0.034),
    PadDesign(3, 5, 0.027),
    PadDesign(4, 6, 0.0225),
)
#: The planner/detector pairs (``--planner`` and ``--detector`` names).
DENSITY_PAIRS: tuple[tuple[str, str], ...] = (
    ("thesis", "thesis"),
    ("gripper-aware", "adaptive"),
    ("model-based", "adaptive"),
)
#: Cells along the quarter's side: the study's (coarse) mesh and the medium one it is
#: checked against (:data:`softpad.design.FEM_CELLS`).
COARSE_CELLS, MEDIUM_CELLS = 8, 12
#: Headline FEM figures whose mesh convergence is reported (``FemResponse`` fields).
CONVERGENCE_FIELDS = (
    "height_m",
    "compliance_m3_pa",
    "centre_rise_pa_n",
    "compact_min_detectable_mass_kg",
    "min_detectable_mass_kg",
    "centre_stiffness_n_m",
)


@dataclass(frozen=True)
class DensityStudy:
    """What :func:`density_study` found."""

    #: One row per (set, pair, pad): see :func:`_row`.
    rows: tuple[dict[str, Any], ...]
    #: Per pad name: each FEM figure's coarse value, medium value and relative difference.
    convergence: dict[str, dict[str, dict[str, float]]]
    #: Sets, seeds, trials, valves, objects per set.
    meta: dict[str, Any]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"rows": list(self.rows), "convergence": self.convergence, "meta": self.meta}

    def smallest_pad(self, pair: str, object_set: str, share: float = 0.85) -> dict[str, Any]:
        """The row of the pad with the fewest modules on which ``pair`` (``planner:detector``)
        holds at least ``share`` of ``object_set``'s trials, or, when none does, the row where
        it holds most (``reached`` says which)."""
        rows = [r for r in self.rows if r["pair"] == pair and r["set"] == object_set]
        if not rows:
            raise InputError(f"no rows for the pair {pair!r} on the set {object_set!r}")
        ok = [r for r in rows if r["success"] >= share]
        if ok:
            return {**min(ok, key=lambda r: r["modules"]), "reached": True}
        return {**max(rows, key=lambda r: (r["success"], -r["modules"])), "reached": False}

    def table_markdown(self) -> str:
        """One line per pad: its FEM figures, then each (set, pair)'s held share."""
        return _table_markdown(self)

    def plot(self, path: str | Path | None = None, held_out: str | None = None) -> Any:
        """The Pareto figure (:func:`_plot`); ``held_out``: the set drawn (default: the last)."""
        return _plot(self, held_out or self.meta["sets"][-1], path)


def density_study(
    object_sets: Sequence[Any],
    seeds: dict[str, Sequence[int]],
    trials: int = 1,
    pads: Sequence[PadDesign] = DENSITY_PADS,
    pairs: Sequence[tuple[str, str]] = DENSITY_PAIRS,
    valves: str = "sized",
    cache: ResultCache | None = None,
    progress: Callable[[str], None] | None = None,
) -> DensityStudy:
    """Every pad under every pair on every set (randomized inputs, 2 s hold, coarse mesh, in
    this process), and the pads' mesh convergence.

    Parameters
    ----------
    object_sets
        :class:`~softpad.design.ObjectSet` s, development first, held-out last.
    seeds
        Experiment seeds by set name.
    trials
        Trials per object and seed.
    pads, pairs
        The pads (the thesis's pad is always among them) and ``(planner, detector)`` pairs.
    valves
        :attr:`TrialOptions.valves` (``"sized"``: the small modules can be adjusted to p0).
    cache
        Where FEM responses and trial batches are kept (the sweeps' cache).
    progress
        Called with a line as each sweep starts.
    """
    from softpad.design._sweep import design_sweep

    cache = cache or ResultCache(None)
    rows: list[dict[str, Any]] = []
    for s in object_sets:
        if s.name not in seeds:
            raise InputError(f"no seeds given for the object set {s.name!r}")
        for planner, detector in pairs:
            if progress is not None:
                progress(f"{s.name}: {planner}:{detector} on {len(pads)} pads")
            opts = TrialOptions(trials, planner, detector, 2.0, randomize=True, valves=valves)
            result = design_sweep(
                pads, s, opts, tuple(seeds[s.name]), quick=True, workers=1, cache=cache
            )
            rows += [_row(s.name, f"{planner}:{detector}", r) for r in result.rows]
    meta = {
        "sets": [s.name for s in object_sets],
        "objects": {s.name: len(s.objects) for s in object_sets},
        "seeds": {k: list(v) for k, v in seeds.items()},
        "trials_per_object": trials,
        "valves": valves,
        "randomize": True,
        "hold_s": 2.0,
        "fem_cells": COARSE_CELLS,
    }
    return DensityStudy(tuple(rows), pad_convergence(pads, cache), meta)


def _row(set_name: str, pair: str, r: Any) -> dict[str, Any]:
    """One (set, pair, pad) row from a :class:`~softpad.design.DesignRow`."""
    d = r.design
    return {
        "set": set_name,
        "pair": pair,
        "pad": pad_label(d),
        "rows": d.rows,
        "cols": d.cols,
        "pitch_mm": round(d.pitch_m * 1e3, 3),
        "modules": d.n_modules,
        "successes": r.successes,
        "trials": r.trials,
        "success": r.success,
        "success_interval": list(r.success_interval),
        "failures": dict(r.failures),
        "fem": dict(r.response),
    }


def pad_label(design: PadDesign) -> str:
    """``"RxC P mm"``: the pad's grid and pitch."""
    return f"{design.rows}x{design.cols} {design.pitch_m * 1e3:g} mm"


def pad_convergence(
    pads: Sequence[PadDesign], cache: ResultCache | None = None
) -> dict[str, dict[str, dict[str, float]]]:
    """Each pad's FEM figures on the coarse and the medium mesh and their relative difference
    ``coarse / medium - 1``.

    Parameters
    ----------
    pads
        The pad designs (each module's geometry, its pitch and channel).
    cache
        Where the FEM responses are kept, under the sweeps' keys; None: a cache in memory.

    Returns
    -------
    dict
        Per pad label, per figure (:data:`CONVERGENCE_FIELDS`): ``coarse``, ``medium`` and
        ``relative_difference``.
    """
    cache = cache or ResultCache(None)
    out: dict[str, dict[str, dict[str, float]]] = {}
    for pad in pads:
        coarse, medium = (cached_fem_response(pad, c, cache) for c in (COARSE_CELLS, MEDIUM_CELLS))
        out[pad_label(pad)] = {
            f: {
                "coarse": coarse[f],
                "medium": medium[f],
                "relative_difference": coarse[f] / medium[f] - 1.0,
            }
            for f in CONVERGENCE_FIELDS
        }
    return out


def cached_fem_response(design: PadDesign, cells: int, cache: ResultCache) -> dict[str, Any]:
    """The FEM response dict of ``design``'s module on ``cells`` cells, from ``cache`` when
    there (the key a sweep uses: :meth:`softpad.design._sweep._SweepJob.fem_key`)."""
    v = design.fem_variables()
    key = cache.key("fem", {**v, "cells": cells})
    hit = cache.get("fem", key)
    if hit is not None:
        return dict(hit)
    result = fem_response(v["width_m"], v["thickness_m"], v["material"], v["p0_pa"], cells)
    d = result.to_dict()
    cache.put("fem", key, d)
    return d


def subset(object_set: Any, count: int | None) -> Any:
    """The first ``count`` objects of ``object_set`` (all when None)."""
    if count is None:
        return object_set
    if not 1 <= count <= len(object_set.objects):
        raise InputError(f"object count must be from 1 to {len(object_set.objects)}, got {count}")
    return dataclasses.replace(object_set, objects=object_set.objects[:count])


def _table_markdown(study: DensityStudy) -> str:
    """Markdown table: pad, modules, FEM figures, then held/trials per (set, pair)."""
    cols = [
        (s, p) for s in study.meta["sets"] for p in dict.fromkeys(r["pair"] for r in study.rows)
    ]
    pads = list(dict.fromkeys(r["pad"] for r in sorted(study.rows, key=lambda r: r["modules"])))
    head = ["pad", "modules", "h mm", "k N/mm", "centre kPa/N", "m_min 10x10 g", "m_min brick g"]
    head += [f"{s} {p.split(':')[0]}" for s, p in cols]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for pad in pads:
        mine = {(r["set"], r["pair"]): r for r in study.rows if r["pad"] == pad}
        any_row = next(iter(mine.values()))
        f = any_row["fem"]
        cells = [pad, str(any_row["modules"]), f"{f['height_mm']:.2f}",
                 f"{f['centre_stiffness_n_per_mm']:.3f}", f"{f['centre_rise_kpa_per_n']:.2f}",
                 f"{f['compact_min_detectable_mass_g']:.2f}", f"{f['min_detectable_mass_g']:.2f}"]  # fmt: skip
        for key in cols:
            r = mine.get(key)
            cells.append("-" if r is None else f"{r['successes']}/{r['trials']}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def _plot(study: DensityStudy, held_out: str, path: str | Path | None) -> Any:
    """Two panels, 3.5 in wide: the held-out share (95 % Wilson bars) of each pair against the
    module count (top) and against the FEM's minimum detectable mass of a 10 x 10 mm weight
    (bottom); the model-based pair solid, its Pareto front (share up, modules or mass down)
    ringed; the 85 % line dashed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 1, figsize=(3.5, 4.6))
    pairs = list(dict.fromkeys(r["pair"] for r in study.rows))
    markers = dict(zip(pairs, ("s", "^", "o", "D", "v"), strict=False))
    mine = [r for r in study.rows if r["set"] == held_out]
    for ax, x_of, label in (
        (axes[0], lambda r: r["modules"], "modules (pads of 90 x 135 mm)"),
        (axes[1], lambda r: r["fem"]["compact_min_detectable_mass_g"],
         "min. detectable mass, 10x10 mm weight (g)"),
    ):  # fmt: skip
        span = max(x_of(r) for r in mine) - min(x_of(r) for r in mine) or 1.0
        for i, pair in enumerate(pairs):
            rows = sorted((r for r in mine if r["pair"] == pair), key=x_of)
            dodge = (i - (len(pairs) - 1) / 2) * 0.015 * span  # pairs side by side
            _plot_pair(ax, rows, lambda r, f=x_of, d=dodge: f(r) + d, pair, markers[pair])
        ax.axhline(85, ls="--", lw=0.8, color="0.4")
        ax.set_xlabel(label, fontsize=8)
        ax.set_ylabel(f"held on {held_out} (%)", fontsize=8)
        ax.set_ylim(-5, 105)
        ax.tick_params(labelsize=7)
    modules = sorted({r["modules"] for r in mine})
    axes[0].set_xticks(modules, [str(m) for m in modules])
    axes[0].legend(fontsize=6, loc="best", framealpha=0.8)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=200)
    return fig


def _plot_pair(ax: Any, rows: list[dict[str, Any]], x_of: Any, pair: str, marker: str) -> None:
    """One pair's points with their intervals; the model-based pair's front joined."""
    xs = [x_of(r) for r in rows]
    ys = [100 * r["success"] for r in rows]
    lo = [100 * (r["success"] - r["success_interval"][0]) for r in rows]
    hi = [100 * (r["success_interval"][1] - r["success"]) for r in rows]
    line = "-" if pair.startswith("model-based") else ":"
    ax.errorbar(xs, ys, yerr=[lo, hi], fmt=marker + line, ms=4, lw=0.9, capsize=2,
                label=pair.split(":")[0])  # fmt: skip
    if line == "-":
        front = pareto_front(xs, ys)
        ax.scatter([xs[i] for i in front], [ys[i] for i in front], s=90, facecolors="none",
                   edgecolors="k", lw=0.8, label="Pareto front")  # fmt: skip


def pareto_front(costs: Sequence[float], gains: Sequence[float]) -> list[int]:
    """Indices of the points no other point dominates (cost no higher and gain no lower,
    one of them strictly)."""
    pts = list(zip(costs, gains, strict=True))
    return [
        i
        for i, (c, g) in enumerate(pts)
        if not any((c2 <= c and g2 >= g) and (c2 < c or g2 > g) for c2, g2 in pts)
    ]
