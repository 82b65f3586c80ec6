"""Every example runs, and pins a value (scikit-fem style)."""

from __future__ import annotations

import math
import runpy
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_plan_from_increments_example(capsys: pytest.CaptureFixture[str]) -> None:
    ns = runpy.run_path(str(EXAMPLES / "plan_from_increments.py"))
    result = ns["main"]()
    # COG (1, 1) module units = (0.045, 0.045) m, rotated by 90 deg and shifted.
    assert result["x"] == pytest.approx(0.40 - 0.045)
    assert result["y"] == pytest.approx(-0.10 + 0.045)
    assert result["yaw"] == pytest.approx(math.pi / 4)
    assert "n3-diagonal-corner" in capsys.readouterr().out
