"""Pictures of a recording: pressure traces with the phases as bands, the pad with the grasps.

Figures are built on :class:`matplotlib.figure.Figure` directly: no pyplot, so drawing never
switches the global matplotlib backend or opens a window.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

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
    "safe": "#ffb3b3",
}

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


def plot_traces(run: RecordedRun, path: str | Path | None = None, title: str | None = None) -> Any:
    """Pressure of every module against box time, phases as shaded bands (cf. seed Fig. 6.8).

    One legend entry per module; each band is named once, inside the plot above the traces;
    contact, missed contact and faults are vertical lines.

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
    ax.set_xlabel("box time (s)")
    ax.set_ylabel("gauge pressure (kPa)")
    ax.set_xlim(float(run.t_s[0]), float(run.t_s[-1])) if len(run) else None
    objects = ", ".join(run.metadata.get("objects") or []) or str(run.path.name)
    ax.set_title(title or f"{objects}: module pressures, phases shaded (outcome {run.outcome})")
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8, frameon=False)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


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
    fingertips of its planned grasp (cf. seed Fig. 6.10), titled with the outcome.

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
