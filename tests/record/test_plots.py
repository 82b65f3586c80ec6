"""Pictures of a recording, checked on the figure objects (what a reader finds on them)."""

from __future__ import annotations

from pathlib import Path

from softpad.record import load_recording

DATA = Path(__file__).resolve().parents[1] / "data"


def test_trace_names_every_phase_and_marks_the_landing_in_release() -> None:
    run = load_recording(DATA / "banana.mcap")
    fig = run.plot()
    ax = fig.axes[0]
    legends = [c for c in ax.get_children() if type(c).__name__ == "Legend"] + fig.legends
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


def _srgb_to_lab(hex_colour: str, alpha: float = 1.0) -> tuple[float, float, float]:
    """CIE L*a*b* (D65) of ``hex_colour`` drawn with ``alpha`` over white (the sRGB and Lab
    formulas of IEC 61966-2-1 and CIE 15, written out: an implementation independent of the
    plotting code)."""
    rgb = [int(hex_colour[i : i + 2], 16) / 255 for i in (1, 3, 5)]
    rgb = [alpha * c + (1 - alpha) for c in rgb]
    lin = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in rgb]
    m = [(0.4124, 0.3576, 0.1805), (0.2126, 0.7152, 0.0722), (0.0193, 0.1192, 0.9505)]
    x, y, z = (sum(a * b for a, b in zip(row, lin, strict=True)) for row in m)
    white = (0.95047, 1.0, 1.08883)

    def f(t: float) -> float:
        return t ** (1 / 3) if t > (6 / 29) ** 3 else t / (3 * (6 / 29) ** 2) + 4 / 29

    fx, fy, fz = (f(v / w) for v, w in zip((x, y, z), white, strict=True))
    return 116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)


def test_every_two_phases_differ_in_colour() -> None:
    """The eleven phases of a loop (and the safe state) as drawn, each pair at least 10 apart
    in CIE76 colour difference (about four times a just noticeable difference, 2.3); the
    palette before had five pairs closer (lift/valve check 6.8, approach/valve check 7.3,
    wait object/release 8.4, lift/hold 8.8, adjust/wait object 9.1); this one's closest is
    plan/close at 13.2."""
    import itertools
    import math

    from softpad.record._plots import BAND_ALPHA, PHASE_COLOURS

    lab = {ph: _srgb_to_lab(c, BAND_ALPHA) for ph, c in PHASE_COLOURS.items()}
    assert len(lab) == 12
    for (a, la), (b, lb) in itertools.combinations(lab.items(), 2):
        assert math.dist(la, lb) >= 10.0, (a, b, math.dist(la, lb))


def _printed_pt(fig) -> dict[str, float]:  # type: ignore[no-untyped-def]
    """Every visible text of ``fig`` and its size when the figure is printed 3.5 in wide."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    FigureCanvasAgg(fig).draw()
    scale = 3.5 / fig.get_figwidth()
    return {
        t.get_text(): t.get_fontsize() * scale
        for t in fig.findobj(Text)
        if t.get_visible() and t.get_text().strip()
    }


def _landing_run(tmp_path: Path):  # type: ignore[no-untyped-def]
    from softpad.cli.main import main

    path = tmp_path / "object-4.mcap"
    assert main(["run", "--objects", "object-4", "--hold-s", "1", "--record", str(path)]) == 0
    return load_recording(path)


def test_trace_reads_at_a_columns_width_with_the_note_clear_of_the_title(tmp_path) -> None:
    """trace.png: object 4 put back down is marked; the note lies inside the plot, clear of
    the title; every label prints at >= 6.5 pt at 3.5 in wide."""
    run = _landing_run(tmp_path)
    fig = run.plot()
    ax = fig.axes[0]
    (note,) = [t for t in ax.texts if "put back down" in t.get_text()]
    sizes = _printed_pt(fig)
    renderer = fig.canvas.get_renderer()
    box, title = note.get_window_extent(renderer), ax.title.get_window_extent(renderer)
    assert not box.overlaps(title)
    assert ax.get_window_extent(renderer).contains(box.x0, box.y0)
    assert ax.get_window_extent(renderer).contains(box.x1, box.y1)
    assert min(sizes.values()) >= 6.5 - 1e-9, {k: v for k, v in sizes.items() if v < 6.5}
    assert {"module 1", "hold", "release"} <= set(sizes)


def test_pad_picture_in_mm_with_the_grid_labels_and_marks_explained(tmp_path) -> None:
    """pad.png: both axes labelled in mm, ticks and grid lines at every module boundary (45 mm),
    the fingertips named in the legend, every label >= 6.5 pt at 3.5 in wide."""
    run = _landing_run(tmp_path)
    fig = run.plot_pad()
    ax = fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x (mm)", "y (mm)")
    assert list(ax.get_xticks()) == [0.0, 45.0, 90.0, 135.0]
    assert list(ax.get_yticks()) == [0.0, 45.0, 90.0]
    xs = [line.get_xdata() for line in ax.lines]
    vertical = sorted({x[0] for x in xs if len(x) == 2 and x[0] == x[1]})
    assert vertical == [0.0, 45.0, 90.0, 135.0]
    sizes = _printed_pt(fig)
    assert "fingertips, jaws open" in sizes and "PCOM" in sizes and "COG" in sizes
    assert "y (mm)" in sizes  # drawn (the label was pushed off the page before)
    renderer = fig.canvas.get_renderer()
    assert ax.yaxis.label.get_window_extent(renderer).x0 >= 0.0
    assert min(sizes.values()) >= 6.5 - 1e-9, {k: v for k, v in sizes.items() if v < 6.5}
