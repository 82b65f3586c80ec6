"""Run log (in-memory recorder): hook, CSV, conversion to a RecordedRun, Fig. 6.8-like plot."""

from __future__ import annotations

import numpy as np

from softpad.box import PressureFrame
from softpad.record import RunLog


def _log() -> RunLog:
    log = RunLog({"box": "sim://"})
    for i in range(20):
        p = np.full(8, 1100.0 + i)
        p[3] = np.nan if i == 5 else p[3]
        log.frame(PressureFrame(0.01 * (i + 1), p, 10e3), "adjust" if i < 10 else "hold")
    log.event(0.05, "contact", modules=(1, 5), value=np.float64(2.5))
    return log


def test_phase_spans_and_csv_export_with_events(tmp_path) -> None:
    log = _log()
    assert [s[0] for s in log.phase_spans()] == ["adjust", "hold"]
    csv = log.to_recorded().to_csv(tmp_path / "run.csv").read_text().splitlines()
    assert csv[0].startswith("t_s,wall_ns,phase,p1_pa") and csv[0].endswith("event,event_json")
    assert len(csv) == 1 + 20 + 1  # header, frames, the contact event
    nan_row = next(line.split(",") for line in csv if line.startswith("0.06,"))
    assert nan_row[6] == "" and float(nan_row[5]) == 1105.0  # NaN of channel 4: empty field
    event = next(line for line in csv if ",contact," in line)
    assert event.startswith("0.05,") and "modules" in event


def test_to_recorded_keeps_frames_and_events() -> None:
    log = _log()
    run = log.to_recorded()
    np.testing.assert_array_equal(run.pressures_pa, log.pressures_pa)  # NaN kept
    assert run.events_of("contact") == [(0.05, {"modules": [1, 5], "value": 2.5})]


def test_plot_writes_a_png_with_one_line_per_module_and_keeps_the_backend(tmp_path) -> None:
    import matplotlib

    backend = matplotlib.get_backend()
    log = _log()
    log.meta["layout"] = "2x3"
    fig = log.plot(tmp_path / "trace.png")
    assert (tmp_path / "trace.png").stat().st_size > 1000
    ax = fig.axes[0]
    labels = ax.get_legend_handles_labels()[1]
    assert [lb for lb in labels if lb.startswith("module")] == [f"module {k}" for k in range(1, 7)]
    assert ax.get_xlabel() == "box time (s)" and ax.get_ylabel() == "gauge pressure (kPa)"
    assert matplotlib.get_backend() == backend
