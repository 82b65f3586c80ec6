"""softpad compare: pairs over seeds, Wilson intervals, the JSON contract."""

from __future__ import annotations

import json

import pytest

from softpad.cli.main import main
from softpad.trials import wilson_interval

pytestmark = pytest.mark.mujoco


@pytest.mark.parametrize(
    ("k", "n", "low", "high"),
    [(5, 5, 0.5655, 1.0), (0, 10, 0.0, 0.2775), (48, 55, 0.7599, 0.9369)],
    ids=["5of5", "0of10", "48of55"],
)
def test_wilson_interval_matches_the_closed_form(k: int, n: int, low: float, high: float) -> None:
    """Closed form (z = 1.96): (p + z^2/2n -+ z sqrt(p(1-p)/n + z^2/4n^2)) / (1 + z^2/n)."""
    assert wilson_interval(k, n) == pytest.approx((low, high), abs=2e-4)


def test_compare_json_has_every_pair_and_object(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["compare", "--seeds", "0", "--objects", "object-5", "--trials", "1"]
    argv += ["--idle-hours", "0.01", "--json", "--no-progress", "--workers", "1"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["schema_version"] >= 2 and d["seeds"] == [0]
    pairs = [(c["planner"], c["detector"]) for c in d["combinations"]]
    assert pairs == [("thesis", "thesis"), ("gripper-aware", "adaptive")]
    for c in d["combinations"]:
        assert c["trials"] == 1 and c["successes"] in (0, 1)
        lo, hi = c["success_interval"]
        assert 0.0 <= lo <= c["success"] <= hi <= 1.0
        assert [o["name"] for o in c["objects"]] == ["object-5"]
        assert c["false_alarms_per_hour"] >= 0 and c["delay_s_median"] is not None


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--seeds", "5-2"], "first <= last"),
        (["--seeds", "x"], "is not an integer or a range"),
        (["--pair", "thesis:glr"], "--pair must be"),
        (["--idle-hours", "0"], "--idle-hours"),
    ],
    ids=["reversed", "garbage", "pair", "idle"],
)
def test_bad_compare_input(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["compare", *argv]) == 2
    assert message in capsys.readouterr().err
