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

#: Colours of the phases' bands: ColorBrewer's qualitative "Set3" (twelve light colours made
#: to be told apart), one per phase in the loop's order, the safe state in its red.
PHASE_COLOURS = {
    "adjust": "#d9d9d9",
    "reference": "#8dd3c7",
    "wait_object": "#ffffb3",
    "plan": "#bebada",
    "approach": "#80b1d3",
    "descend": "#fdb462",
    "close": "#fccde5",
    "lift": "#b3de69",
    "hold": "#ccebc5",
    "release": "#bc80bd",
    "valve_check": "#ffed6f",
    "safe": "#fb8072",
}

#: Opacity of the phases' bands over white (the traces stay the figure's darkest marks).
BAND_ALPHA = 0.7

#: Width a figure is printed at in a paper's column, inches, and the smallest font size it
#: may then show, points: every label of these figures is sized to read at that width.
COLUMN_WIDTH_IN = 3.5
SMALLEST_PRINTED_PT = 6.5


def font_pt(fig_width_in: float, printed_pt: float = SMALLEST_PRINTED_PT) -> float:
    """The font size, points, that prints at ``printed_pt`` when a figure ``fig_width_in``
    wide is scaled to :data:`COLUMN_WIDTH_IN`."""
    return printed_pt * fig_width_in / COLUMN_WIDTH_IN


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

    Every phase has its own colour (:data:`PHASE_COLOURS`) and is named in a legend below the
    plot, in the order the run went through it (so a phase too short to see is still named);
    modules and the contact, missed contact and faults (vertical lines) in a second legend; the
    rise of a module while the held object is put back down (``release``: down at the approach
    speed, then the jaws open) is marked as its landing, the note inside the plot below the
    peak, clear of the title. Labels read at a column's width (:data:`COLUMN_WIDTH_IN`).

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

    width = 7.0
    pt = font_pt(width)
    fig = Figure(figsize=(width, 6.2), layout="constrained")
    ax = fig.add_subplot()
    n = _modules(run)
    for ph, t0, t1 in run.phase_spans():
        ax.axvspan(t0, t1, color=PHASE_COLOURS.get(ph, "#f5f5f5"), alpha=BAND_ALPHA, lw=0)
    for k in range(n):
        ax.plot(run.t_s, run.pressures_pa[:, k] / 1e3, lw=0.9, label=f"module {k + 1}")
    for kind, colour in MARKED_EVENTS.items():
        for i, (t, _) in enumerate(run.events_of(kind)):
            ax.axvline(
                t, color=colour, ls="--", lw=1.0, label=kind.replace("_", " ") if i == 0 else None
            )
    _mark_landing(ax, run, n, pt)
    ax.set_xlabel("box time (s)", fontsize=pt)
    ax.set_ylabel("gauge pressure (kPa)", fontsize=pt)
    ax.tick_params(labelsize=pt)
    ax.set_xlim(float(run.t_s[0]), float(run.t_s[-1])) if len(run) else None
    objects = ", ".join(run.metadata.get("objects") or []) or str(run.path.name)
    ax.set_title(title or f"{objects}: outcome {run.outcome}", fontsize=pt)
    _legend(fig, ax, run, pt)
    if path is not None:
        fig.savefig(path, dpi=150)
    return fig


def _legend(fig: Any, ax: Any, run: RecordedRun, pt: float) -> None:
    """One legend below the plot: the modules and marked events, then every phase's colour in
    the order the run went through them."""
    from matplotlib.patches import Patch

    handles, labels = ax.get_legend_handles_labels()
    seen = list(dict.fromkeys(ph for ph, t0, t1 in run.phase_spans() if t1 > t0))
    for ph in seen:
        handles.append(Patch(color=PHASE_COLOURS.get(ph, "#f5f5f5"), alpha=BAND_ALPHA))
        labels.append(ph.replace("_", " "))
    fig.legend(
        handles, labels, loc="outside lower center", ncols=4, fontsize=pt, frameon=False,
        columnspacing=1.0, handlelength=1.2, handletextpad=0.4,
        title="modules, events (dashed) and phases (bands)", title_fontsize=pt,
    )  # fmt: skip


def _mark_landing(ax: Any, run: RecordedRun, n: int, pt: float) -> None:
    """Mark the largest rise above the hold's level during ``release``: the held object landing
    on the pad as it is put back down (its weight and the arm's push), before the jaws open.
    The note sits left of and below the peak, inside the axes (never on the title)."""
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
        f"object put back down:\nmodule {k + 1} rises as it lands", xy=(t, p),
        xytext=(-12, -2), textcoords="offset fontsize", ha="right", va="top", fontsize=pt,
        arrowprops={"arrowstyle": "->", "lw": 0.8},
        bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.8},
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
    fingertips of its planned grasp (cf. thesis Fig. 6.10), titled with the outcome; millimetres
    of the pad frame, the module grid drawn, labels readable at a column's width.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    from softpad.layout import parse_layout
    from softpad.planning import plan_legend_handles, plot_plans

    layout = parse_layout(str(run.metadata.get("layout", "2x3")))
    plan_events = run.events_of("plan")
    data = plan_events[-1][1] if plan_events else {}
    if "increments_pa" in data:
        delta = np.asarray(data["increments_pa"], dtype=float)
    else:
        delta = 1e3 * np.asarray(data.get("increments_kpa", [0.0] * layout.n_modules), dtype=float)
    width = 4.6
    height = width * (layout.rows + 0.6) / (layout.cols + 1.6) + 0.5
    fig = Figure(figsize=(width, height), layout="constrained")
    ax = fig.add_subplot()
    objects = ", ".join(run.metadata.get("objects") or [])
    pt = font_pt(width)
    plot_plans(
        delta, _grasp_plans(run.plans()), layout, ax=ax, title=f"{objects}: {run.outcome}",
        font_pt=pt, legend=False,
    )  # fmt: skip
    # below the pad, in the layout (an axes legend beside it pushed the y label off the page)
    fig.legend(
        handles=plan_legend_handles(one_line=True), loc="outside lower center", ncols=3,
        fontsize=pt, frameon=False, columnspacing=1.2,
    )  # fmt: skip
    if path is not None:
        fig.savefig(path, dpi=200)
    return fig
