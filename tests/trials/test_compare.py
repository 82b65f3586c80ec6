"""softpad compare: pairs over seeds, Wilson intervals, the JSON contract."""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import pytest

from softpad.cli.main import main
from softpad.trials import TrialResult, wilson_interval
from softpad.trials._compare import summarise

pytestmark = pytest.mark.mujoco


@pytest.mark.parametrize(
    ("k", "n", "low", "high"),
    [(5, 5, 0.5655, 1.0), (0, 10, 0.0, 0.2775), (48, 55, 0.7599, 0.9369)],
    ids=["5of5", "0of10", "48of55"],
)
def test_wilson_interval_matches_the_closed_form(k: int, n: int, low: float, high: float) -> None:
    """Closed form (z = 1.96): (p + z^2/2n -+ z sqrt(p(1-p)/n + z^2/4n^2)) / (1 + z^2/n)."""
    assert wilson_interval(k, n) == pytest.approx((low, high), abs=2e-4)


def test_the_summary_counts_retried_trials_and_scores_their_last_grasp() -> None:
    """A trial retried after a miss counts once, with the outcome of its last grasp."""

    def trial(k: int, attempts: int, success: bool) -> TrialResult:
        cause = None if success else "jaws_hit_object"
        return TrialResult(
            "cylinder", k, k, (0.0, 0.0, 0.0), "6/2", success, cause, attempts=attempts
        )

    s = summarise([trial(0, 1, True), trial(1, 2, True), trial(2, 2, False), trial(3, 1, False)])
    assert s["trials"] == 4 and s["successes"] == 2 and s["retried"] == 2
    assert s["failures"] == {"jaws_hit_object": 2}
    assert trial(1, 2, True).to_dict()["attempts"] == 2


@pytest.fixture(scope="module")
def compared() -> dict:
    """One small comparison (object 5, one trial, seed 0) by the command, both default pairs."""
    argv = ["compare", "--seeds", "0", "--objects", "object-5", "--trials", "1"]
    argv += ["--idle-hours", "0.01", "--json", "--no-progress", "--workers", "1"]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(argv) == 0
    return json.loads(out.getvalue())


def test_compare_json_has_every_pair_and_object(compared: dict) -> None:
    d = compared
    assert d["schema_version"] >= 2 and d["seeds"] == [0]
    pairs = [(c["planner"], c["detector"]) for c in d["combinations"]]
    assert pairs == [("thesis", "thesis"), ("gripper-aware", "adaptive")]
    for c in d["combinations"]:
        assert c["trials"] == 1 and c["successes"] in (0, 1)
        lo, hi = c["success_interval"]
        assert 0.0 <= lo <= c["success"] <= hi <= 1.0
        assert [o["name"] for o in c["objects"]] == ["object-5"]
        assert c["false_alarms_per_hour"] >= 0 and c["delay_s_median"] is not None
        assert c["retried"] == 0  # object 5 is held at the first grasp


def _halves(d: dict, tmp_path: Path) -> tuple[str, str]:
    """The comparison's two pairs as two files, as if run apart."""
    paths = []
    for k, combo in enumerate(d["combinations"]):
        path = tmp_path / f"pair{k}.json"
        path.write_text(json.dumps({**d, "combinations": [combo]}))
        paths.append(str(path))
    return paths[0], paths[1]


def test_merged_comparisons_are_the_comparison(
    compared: dict, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Two pairs run apart and merged give back the document run together; the figure is drawn."""
    a, b = _halves(compared, tmp_path)
    png = tmp_path / "both.png"
    assert main(["compare", "--merge", a, "--merge", b, "--json", "--png", str(png)]) == 0
    assert json.loads(capsys.readouterr().out) == compared
    assert png.stat().st_size > 1000
    assert main(["compare", "--merge", b]) == 0  # a table of one pair
    assert "| gripper-aware | adaptive |" in capsys.readouterr().out


def test_bad_merges_are_named(
    compared: dict, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    a, b = _halves(compared, tmp_path)
    other = tmp_path / "seeds.json"
    other.write_text(json.dumps({**json.loads(Path(b).read_text()), "seeds": [1]}))
    broken = tmp_path / "broken.json"
    broken.write_text('{"schema_version": 2, "seeds": [0], "combinations": [')
    old = tmp_path / "old.json"
    old.write_text(json.dumps({**compared, "schema_version": 1}))
    partial = tmp_path / "partial.json"
    combo = {k: v for k, v in compared["combinations"][0].items() if k != "success_interval"}
    partial.write_text(json.dumps({**compared, "combinations": [combo]}))
    cases = [
        (
            [str(partial)],
            "every combination needs planner, detector, trials, successes, success, "
            "success_interval",
        ),
        ([a, a], "the pair thesis:thesis is given twice"),
        ([a, str(other)], "seeds 1..1 (1) differ from the first's 0..0 (1)"),
        ([str(broken)], "is not valid JSON"),
        ([str(old)], "not a softpad comparison of schema 2 (schema_version 1)"),
        ([str(tmp_path / "none.json")], "cannot read comparison"),
    ]
    for files, message in cases:
        argv = ["compare"] + [x for f in files for x in ("--merge", f)]
        assert main(argv) == 2, files
        err = capsys.readouterr().err
        assert message in err and "Traceback" not in err
    assert main(["compare", "--merge", a, "--pair", "thesis:cusum"]) == 2
    assert "--merge runs no pair" in capsys.readouterr().err


def test_a_bad_figure_path_is_refused_before_any_trial(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Hours of trials are not run to fail at the end on the figure's path."""
    import softpad.trials

    def never(*args: object, **kwargs: object) -> None:
        raise AssertionError("the trials started before --png was checked")

    monkeypatch.setattr(softpad.trials, "compare", never)
    argv = ["compare", "--seeds", "0", "--objects", "object-5", "--trials", "1"]
    assert main([*argv, "--png", str(tmp_path / "none" / "x.png")]) == 2
    assert "does not exist" in capsys.readouterr().err
    (tmp_path / "x.png").write_bytes(b"old")
    assert main([*argv, "--png", str(tmp_path / "x.png")]) == 2
    assert "exists; add --force" in capsys.readouterr().err
    assert main([*argv, "--png", str(tmp_path / "x.txt")]) == 2
    assert "must name a .png file" in capsys.readouterr().err


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
