"""Run log: hook, save/load round trip, CSV, corrupt files, Fig. 6.8-like plot."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.box import PressureFrame
from softpad.errors import InputError
from softpad.record import RunLog


def _log() -> RunLog:
    log = RunLog({"box": "sim://"})
    for i in range(20):
        p = np.full(8, 1100.0 + i)
        p[3] = np.nan if i == 5 else p[3]
        log.frame(PressureFrame(0.01 * (i + 1), p, 10e3), "adjust" if i < 10 else "hold")
    log.event(0.05, "contact", modules=(1, 5), value=np.float64(2.5))
    return log


def test_save_load_round_trip(tmp_path) -> None:
    log = _log()
    path = log.save(tmp_path / "run.npz")
    back = RunLog.load(path)
    np.testing.assert_array_equal(back.t_s, log.t_s)
    np.testing.assert_array_equal(back.pressures_pa, log.pressures_pa)  # NaN kept
    assert back.phases == log.phases and back.meta == {"box": "sim://"}
    assert back.events == [(0.05, "contact", {"modules": [1, 5], "value": 2.5})]


def test_phase_spans_and_csv() -> None:
    log = _log()
    assert [s[0] for s in log.phase_spans()] == ["adjust", "hold"]
    csv = log.to_csv().splitlines()
    assert csv[0].startswith("t_s,phase,p1_kpa") and len(csv) == 21
    assert ",," in csv[6]  # the NaN reading is an empty field


@pytest.mark.parametrize("content", [b"garbage", b""], ids=["garbage", "empty"])
def test_corrupt_or_missing_log(tmp_path, content: bytes) -> None:
    bad = tmp_path / "bad.npz"
    bad.write_bytes(content)
    with pytest.raises(InputError, match="corrupt"):
        RunLog.load(bad)
    with pytest.raises(InputError, match="does not exist"):
        RunLog.load(tmp_path / "none.npz")
    with pytest.raises(InputError, match=r"\.npz"):
        _log().save(tmp_path / "run.json")


def test_plot_writes_a_png_with_one_line_per_module(tmp_path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    fig = _log().plot(tmp_path / "trace.png", channels=6)
    assert (tmp_path / "trace.png").stat().st_size > 1000
    assert len(fig.axes[0].lines) >= 6
