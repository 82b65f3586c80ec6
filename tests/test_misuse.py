"""Misuse of the Python API and the command line: a clear error naming the value and its limit.

Each case was accepted silently, or failed with a foreign exception, before the checks it
exercises (issue "A box that is safe to put on a network", items 15 and 16).
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from softpad.errors import InputError


def _api_cases():
    from softpad.box import PressureFrame
    from softpad.config import PadSettings, Thresholds, parse_installation
    from softpad.control import ExecutionParams
    from softpad.fem import ModuleGeometry
    from softpad.harness import resolve_objects
    from softpad.layout import GripperSpec, PadPose, parse_layout
    from softpad.planning import format_plans
    from softpad.sensing import detect_objects, increments
    from softpad.sim import SensorBank, SensorParams
    from softpad.trials import TrialConfig, trial_seed, wilson_interval

    nan = float("nan")
    rng = np.random.default_rng(0)
    return {
        "p0 in kPa": (lambda: Thresholds(p0_pa=1.1), "p0_pa"),
        "window 0": (lambda: Thresholds(filter_window=0), "filter_window"),
        "max 300 kPa": (lambda: Thresholds(max_pressure_pa=300_000), "max_pressure_pa"),
        "p0 above max": (lambda: Thresholds(p0_pa=2800, max_pressure_pa=2000), "maximum"),
        "rows -1": (lambda: PadSettings(rows=-1), "rows"),
        "pitch in mm": (lambda: PadSettings(pitch_m=45), "millimetres"),
        "gripper in mm": (lambda: GripperSpec(max_width_m=60), "millimetres"),
        "module in mm": (lambda: ModuleGeometry(width_m=45), "millimetres"),
        "sigma in mm": (lambda: TrialConfig(position_sigma_m=3), "millimetres"),
        "speed in mm/s": (lambda: ExecutionParams(approach_speed_m_s=50), "approach_speed_m_s"),
        "kPa increments": (lambda: increments([1.2] * 6, [1.1] * 6), "not kPa"),
        "NaN pad pose": (lambda: PadPose(x_m=nan), "x_m"),
        "NaN frame time": (lambda: PressureFrame(nan, np.zeros(6), 0.0), "t_s"),
        "more successes than trials": (lambda: wilson_interval(10, 5), "trials = 5"),
        "negative seed": (lambda: trial_seed(-1, "banana", 0), "seed"),
        "negative period": (lambda: SensorBank(6, -1.0, SensorParams(), rng), "dt_s"),
        "layout as text": (lambda: detect_objects([0.0] * 6, layout="2x3"), "parse_layout"),
        "installation list": (lambda: parse_installation([]), "table"),
        "short increments": (lambda: format_plans([0.0] * 5, [], parse_layout("2x3"), 50.0), "5"),
        "object name string": (lambda: resolve_objects("object-5"), "list of names"),
    }


@pytest.mark.parametrize("case", sorted(_api_cases()))
def test_api_misuse_is_an_input_error_naming_the_value(case):
    make, words = _api_cases()[case]
    with pytest.raises(InputError, match=words):
        make()


def test_api_records_keep_accepting_the_thesis_values():
    from softpad.config import PadSettings, Thresholds
    from softpad.layout import GripperSpec, PadPose
    from softpad.sensing import increments

    assert Thresholds().p0_pa == 1100.0
    assert PadSettings(rows=16, cols=16, pitch_m=0.045).rows == 16
    assert GripperSpec.from_mounting("10/4").max_width_m == pytest.approx(0.10)
    assert PadPose(0.4, -0.1, 0.02, 1.0).x_m == 0.4
    # a deflated pad reads zero everywhere: not a unit mix-up
    assert list(increments([0.0] * 6, [0.0] * 6)) == [0.0] * 6
    np.testing.assert_allclose(increments([1160.0, 1092.0], [1100.0, 1092.0]), [60.0, 0.0])


CLI_CASES = {
    "below ambient": (["plan", "--delta", "0,-5,0,0,0,0"], "module 2"),
    "arabic-indic digit": (["plan", "--delta", "\u0660,0,0,0,0,0"], "not a number"),
    "digit separator": (["plan", "--delta", "1_0,0,0,0,0,0"], "not a number"),
    "semicolon": (["plan", "--delta", "0;0,0,0,0,0"], "not a number"),
    "overflow": (["plan", "--delta", "1e308,0,0,0,0,0"], "finite"),
    "delta with reference": (
        ["plan", "--delta", "0,0.1,0,0,0,0", "--reference", "1,1,1,1,1,1"],
        "--reference",
    ),
    "negative duration": (["box", "serve", "--sim", "--duration-s", "-1"], "--duration-s"),
    "nan duration": (["box", "serve", "--sim", "--duration-s", "nan"], "--duration-s"),
    "empty objects": (["run", "--objects", ""], "--objects"),
    "empty grid": (["design", "--grid", ""], "--grid"),
    "grid twice": (["design", "--grid", "2x3,2x3"], "twice"),
    "pitch twice": (["design", "--pitch-mm", "45,45"], "twice"),
}


@pytest.mark.parametrize("case", sorted(CLI_CASES))
def test_cli_misuse_exits_2_naming_the_value(case):
    argv, words = CLI_CASES[case]
    r = subprocess.run(
        [sys.executable, "-m", "softpad", *argv],
        capture_output=True,
        text=True,
        timeout=120,
        stdin=subprocess.DEVNULL,
    )
    assert r.returncode == 2, r.stderr
    assert words in r.stderr
    assert "Traceback" not in r.stderr


def test_a_frame_file_with_both_increments_and_pressures_is_refused(tmp_path):
    f = tmp_path / "frame.json"
    f.write_text('{"delta_kpa": [0,0,0,0,0,0], "pressures_kpa": [1,1,1,1,1,1]}')
    r = subprocess.run(
        [sys.executable, "-m", "softpad", "plan", "--frame", str(f)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 2
    assert "both delta_kpa and pressures_kpa" in r.stderr
