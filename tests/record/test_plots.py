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
