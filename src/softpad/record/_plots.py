"""Pictures of a recording: pressure traces with the phases as bands, the pad with the grasps.

Figures are built on :class:`matplotlib.figure.Figure` directly: no pyplot, so drawing never
switches the global matplotlib backend or opens a window.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # the methods of RecordedRun call these (no import circle)
    from softpad.record._read import RecordedRun

#: Colours of the phases' bands.
PHASE_COLOURS = {
    "adjust": "#e4e4e4",
    "reference": "#c8c8c8",
    "wait_object": "#e8f0ff",
    "plan": "#cfe0ff",
    "approach": "#fff3d6",
    "descend": "#ffe0b3",
    "close": "#ffc9c9",
    "lift": "#e2f5e2",
    "hold": "#d0f0d0",
    "release": "#f0e6ff",
    "valve_check": "#f2f2e0",
    "safe": "#ffb3b3",
}

#: A rise above the hold's level, Pa, during ``release`` that is marked as the object landing.
LANDING_MARK_PA = 90.0

#: Events drawn as vertical lines.
MARKED_EVENTS = {
    "contact": "tab:red",
    "no_contact": "tab:orange",
    "retry": "tab:purple",
    "carried": "tab:green",
    "fault": "k",
}


def _modules(run: RecordedRun) -> int:
    from softpad.layout import parse_layout

    layout = run.metadata.get("layout")
    if isinstance(layout, str):
        return min(parse_layout(layout).n_modules, run.channels)
    if not len(run):
        return run.channels
    used = np.flatnonzero(np.nanmax(run.pressures_pa, axis=0) > 200.0)
    return int(np.max(used)) + 1 if used.size else run.channels


if TYPE_CHECKING:  # the methods of RecordedRun call these (no import circle)
    from softpad.record._read import RecordedRun


def plot_traces(run: RecordedRun, path: str | Path | None = None, title: str | None = None) -> Any:
    """Pressure of every module against box time, phases as shaded bands (cf. thesis Fig. 6.8).

    One legend entry per module and one per phase (so a phase too short to name inside its band
    is still named); wide bands are also named inside the plot; contact, missed contact and
    faults are vertical lines; the rise of a module while the held object is put back down
    (``release``: down at the approach speed, then the jaws open) is marked as its landing.

    Parameters
    ----------
    run
        The recording.
    path
        Write the figure there (PNG, SVG, PDF by suffix) when given.
    title
        Figure title (default: the objects of the run).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 4.8), layout="constrained")
    ax = fig.add_subplot()
    n = _modules(run)
    for ph, t0, t1 in run.phase_spans():
        ax.axvspan(t0, t1, color=PHASE_COLOURS.get(ph, "#f5f5f5"), lw=0)
        if t1 - t0 > 0.02 * max(run.duration_s, 1e-9):  # name the bands wide enough to read
            ax.text(
                (t0 + t1) / 2,
                0.99,
                ph.replace("_", " "),
                transform=ax.get_xaxis_transform(),
                rotation=90,
                va="top",
                ha="center",
                fontsize=7,
                color="0.35",
            )
    for k in range(n):
        ax.plot(run.t_s, run.pressures_pa[:, k] / 1e3, lw=0.9, label=f"module {k + 1}")
    for kind, colour in MARKED_EVENTS.items():
        for i, (t, _) in enumerate(run.events_of(kind)):
            ax.axvline(
                t, color=colour, ls="--", lw=0.8, label=kind.replace("_", " ") if i == 0 else None
            )
    _mark_landing(ax, run, n)
    ax.set_xlabel("box time (s)")
    ax.set_ylabel("gauge pressure (kPa)")
    ax.set_xlim(float(run.t_s[0]), float(run.t_s[-1])) if len(run) else None
    objects = ", ".join(run.metadata.get("objects") or []) or str(run.path.name)
    ax.set_title(title or f"{objects}: module pressures, phases shaded (outcome {run.outcome})")
    modules = ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8, frameon=False)
    ax.add_artist(modules)
    _phase_legend(ax, run)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def _phase_legend(ax: Any, run: RecordedRun) -> None:
    """A legend naming every phase's colour, in the order the run went through them."""
    from matplotlib.patches import Patch

    seen = list(dict.fromkeys(ph for ph, t0, t1 in run.phase_spans() if t1 > t0))
    handles = [
        Patch(color=PHASE_COLOURS.get(ph, "#f5f5f5"), label=ph.replace("_", " ")) for ph in seen
    ]
    if handles:
        ax.legend(
            handles=handles, title="phases", loc="lower left", bbox_to_anchor=(1.0, 0.0),
            fontsize=8, title_fontsize=8, frameon=False,
        )  # fmt: skip


def _mark_landing(ax: Any, run: RecordedRun, n: int) -> None:
    """Mark the largest rise above the hold's level during ``release``: the held object landing
    on the pad as it is put back down (its weight and the arm's push), before the jaws open."""
    spans = {ph: (t0, t1) for ph, t0, t1 in run.phase_spans()}
    if "release" not in spans or "hold" not in spans or not len(run):
        return
    (h0, h1), (r0, r1) = spans["hold"], spans["release"]
    hold = (run.t_s >= h0) & (run.t_s < h1)
    release = (run.t_s >= r0) & (run.t_s < r1)
    if not hold.any() or not release.any():
        return
    rise = run.pressures_pa[release, :n] - np.nanmedian(run.pressures_pa[hold, :n], axis=0)
    if not np.isfinite(rise).any() or np.nanmax(rise) < LANDING_MARK_PA:
        return
    i, k = np.unravel_index(np.nanargmax(rise), rise.shape)
    t, p = float(run.t_s[release][i]), float(run.pressures_pa[release][i, k]) / 1e3
    ax.annotate(
        f"object put back down:\nmodule {k + 1} rises as it lands", xy=(t, p), xytext=(-40, 22),
        textcoords="offset points", ha="right", fontsize=8, arrowprops={"arrowstyle": "->", "lw": 0.8},
    )  # fmt: skip


def _grasp_plans(plans: list[dict[str, Any]]) -> list[Any]:
    from softpad.planning import GraspPlan

    return [
        GraspPlan(
            tuple(o["modules"]),
            (float(o["pcom"][0]), float(o["pcom"][1])),
            (float(o["cog"][0]), float(o["cog"][1])),
            float(o["theta"]),
            str(o["rule"]),
            tuple(o["modules"]),
            tentative=o.get("tentative") is True,  # absent in runs recorded before it
        )
        for o in plans
    ]


def plot_pad(run: RecordedRun, path: str | Path | None = None) -> Any:
    """The pad from above: recorded increments as a heat map, each object's PCOM, COG and the
    fingertips of its planned grasp (cf. thesis Fig. 6.10), titled with the outcome.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    from softpad.layout import parse_layout
    from softpad.planning import plot_plans

    layout = parse_layout(str(run.metadata.get("layout", "2x3")))
    plan_events = run.events_of("plan")
    data = plan_events[-1][1] if plan_events else {}
    if "increments_pa" in data:
        delta = np.asarray(data["increments_pa"], dtype=float)
    else:
        delta = 1e3 * np.asarray(data.get("increments_kpa", [0.0] * layout.n_modules), dtype=float)
    fig = Figure(figsize=(1.6 * layout.cols + 2.2, 1.6 * layout.rows + 1.0), layout="constrained")
    ax = fig.add_subplot()
    objects = ", ".join(run.metadata.get("objects") or [])
    plot_plans(delta, _grasp_plans(run.plans()), layout, ax=ax, title=f"{objects}: {run.outcome}")
    pitch_mm = layout.pitch_m * 1e3 if hasattr(layout, "pitch_m") else 45.0
    ax.set_xlabel(f"x (module units, 1 = {pitch_mm:g} mm)")
    ax.set_ylabel(f"y (module units, 1 = {pitch_mm:g} mm)")
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig
