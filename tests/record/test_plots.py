"""Pictures of a recording, checked on the figure objects (what a reader finds on them)."""

from __future__ import annotations

from pathlib import Path

from softpad.record import load_recording

DATA = Path(__file__).resolve().parents[1] / "data"


def test_trace_names_every_phase_and_marks_the_landing_in_release() -> None:
    run = load_recording(DATA / "banana.mcap")
    fig = run.plot()
    ax = fig.axes[0]
    legends = [c for c in ax.get_children() if type(c).__name__ == "Legend"]
    texts = {t.get_text() for legend in legends for t in legend.get_texts()}
    phases = {ph.replace("_", " ") for ph, t0, t1 in run.phase_spans() if t1 > t0}
    # short phases too (reference, plan, approach, lift last 0.1-0.3 s: no room inside a band)
    assert {"reference", "plan", "lift"} <= phases <= texts
    assert {f"module {k}" for k in range(1, 7)} <= texts
    notes = [t.get_text() for t in ax.texts if "put back down" in t.get_text()]
    assert len(notes) <= 1  # named once, when a module rises in release above the hold's level
    assert ax.get_xlabel() == "box time (s)" and ax.get_ylabel() == "gauge pressure (kPa)"


def test_reference_plans_share_one_colour_scale_and_no_legend_covers_a_cell(tmp_path) -> None:
    """plans_reference.png: every panel's heat map on the largest increment of all cases."""
    import numpy as np
    from matplotlib.figure import Figure

    from softpad.layout import PadLayout
    from softpad.planning import TABLE_6_1, plan_grasps, plot_plans

    layout = PadLayout()
    vmax = max(float(np.max(c.delta_pa)) for c in TABLE_6_1) / 1e3
    fig = Figure()
    for i, case in enumerate(TABLE_6_1[:3]):
        ax = fig.add_subplot(1, 3, i + 1)
        plans = plan_grasps(case.delta_pa, layout)
        plot_plans(case.delta_pa, plans, layout, ax=ax, vmax_kpa=vmax, legend=False, colorbar=False)
        assert ax.images[0].get_clim() == (0.0, vmax) and ax.get_legend() is None
    # alone, a panel keeps its own scale and puts its legend beside the pad, not on it
    ax = Figure().add_subplot()
    plot_plans(TABLE_6_1[0].delta_pa, plan_grasps(TABLE_6_1[0].delta_pa, layout), layout, ax=ax)
    anchor = ax.get_legend().get_bbox_to_anchor().transformed(ax.transAxes.inverted())
    assert anchor.x0 >= 1.0 - 1e-9  # at the axes' right edge, outside the pad's cells
