"""``softpad learn`` and ``--pair catalogue:...``: a recorded trial becomes a known object."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from softpad.cli.main import main


@pytest.mark.mujoco
def test_a_recorded_held_trial_is_recognised_and_its_grasp_reused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Object 5, seed 0, recorded with the thesis pair (held); learned; the same trial with
    the catalogue planner recognises it and grasps where the recording did (the model-based
    fallback would plan elsewhere)."""
    from softpad.planning import load_catalogue
    from softpad.sim import get_object
    from softpad.trials import TrialConfig, run_trial
    from softpad.trials._compare import summarise

    spec = get_object("object-5")
    rec = tmp_path / "train.mcap"
    taught, _ = run_trial(spec, 0, 0, TrialConfig(record_path=str(rec)))
    assert taught.success
    out = tmp_path / "catalogue.toml"
    assert main(["learn", str(rec), "--out", str(out)]) == 0
    assert "1 known objects from 1 trials (1 held; 0 recordings" in capsys.readouterr().out
    (known,) = load_catalogue(out).objects
    assert known.name == "object-5" and known.grasps[0][:2] == pytest.approx(taught.cog)
    config = TrialConfig(planner="catalogue", detector="thesis", catalogue=str(out))
    again, _ = run_trial(spec, 0, 0, config)
    assert again.cog == pytest.approx(taught.cog) and again.theta == pytest.approx(taught.theta)
    # the trial record carries the plan's rule: the recognition is counted from it
    assert again.to_dict()["rule"].startswith("catalogue: object-5 (d=")
    assert summarise([again])["recognised_as"] == {"object-5": 1}
    fallback, _ = run_trial(spec, 0, 0, TrialConfig(planner="model-based"))
    assert fallback.cog != pytest.approx(taught.cog, abs=0.01)
    assert summarise([fallback])["recognised_as"] == {} and summarise([fallback])["unknown"] == 0


def test_a_bad_catalogue_is_named_before_any_trial(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    import softpad.trials

    def never(*args: object, **kwargs: object) -> None:
        raise AssertionError("the trials started before --catalogue was read")

    monkeypatch.setattr(softpad.trials, "compare", never)
    argv = ["compare", "--seeds", "0", "--pair", "catalogue:adaptive"]
    assert main([*argv, "--catalogue", str(tmp_path / "none.toml")]) == 2
    assert "not found" in capsys.readouterr().err


def test_learn_refuses_a_recording_that_is_no_trial(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["learn", str(tmp_path / "none.mcap"), "--out", str(tmp_path / "c.toml")]) == 2
    err = capsys.readouterr().err
    assert "none.mcap" in err and "Traceback" not in err
    assert main(["learn", "x.mcap", "--out", str(tmp_path / "c.txt")]) == 2
    assert "must name a .toml file" in capsys.readouterr().err


def test_compare_counts_the_catalogue_planners_decisions() -> None:
    """Each pair's summary counts the trials recognised (by name) and those handed on."""
    from softpad.trials import TrialResult
    from softpad.trials._compare import summarise

    def trial(rule: str | None, success: bool = True) -> TrialResult:
        cause = None if success else "jaws_hit_object"
        return TrialResult("object-5", 0, 0, (0.0, 0.0, 0.0), "10/4", success, cause, rule=rule)

    rules = ["catalogue: object-5 (d=0.31)", "catalogue: object 7 (d=0.10)"] * 2
    trials = [trial(r) for r in rules] + [trial("unknown -> centred (p=0.9)", False), trial(None)]
    s = summarise(trials)
    assert s["recognised_as"] == {"object-5": 2, "object 7": 2} and s["unknown"] == 1


def test_the_preregistered_report_parses_as_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """docs/planner.md's two report commands run through the real command line (the trials
    replaced): the catalogue pair alone, Table 6.1 at seeds 210-219 and ycb-eval's ten
    objects at 9401-9402, randomized, the catalogue read."""
    import re
    import shlex

    import softpad.trials
    from softpad.planning import LearnedTrial, learn_catalogue

    root = Path(__file__).resolve().parents[2]
    page = (root / "docs" / "planner.md").read_text(encoding="utf-8")
    section = page.split("Pre-registered report", 1)[1]
    block = re.search(r"```text\n(.*?)```", section, re.S)
    assert block is not None
    commands = [shlex.split(line) for line in block.group(1).splitlines() if line.strip()]
    (tmp_path / "catalogue.toml").write_text(
        learn_catalogue([LearnedTrial("toy", (1.0,) * 6, (1, 1, 0), True)], 1.0).to_toml()
    )
    seen: list[dict[str, Any]] = []

    def fake(specs: Any, seeds: Any, pairs: Any, **kwargs: Any) -> dict[str, Any]:
        seen.append({"specs": specs, "seeds": list(seeds), "pairs": list(pairs), **kwargs})
        return {"schema_version": 2, "seeds": list(seeds), "combinations": [], "contrasts": []}

    monkeypatch.setattr(softpad.trials, "compare", fake)
    monkeypatch.chdir(tmp_path)
    for argv in commands:
        assert argv[0] == "softpad" and argv[-2] == ">"
        args = [str(root / a) if a.startswith("src/") else a for a in argv[1:-2]]
        assert main(args) == 0, capsys.readouterr().err
    assert [s["seeds"] for s in seen] == [list(range(210, 220)), [9401, 9402]]
    assert all(s["pairs"] == [("catalogue", "adaptive")] for s in seen)
    assert [len(s["specs"]) for s in seen] == [11, 10]
    assert all(s["config"].randomize and s["config"].catalogue for s in seen)


def test_trials_takes_a_catalogue_only_for_the_catalogue_planner_and_reads_it_first(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    import softpad.trials

    def never(*args: object, **kwargs: object) -> None:
        raise AssertionError("the trials started before --catalogue was checked")

    monkeypatch.setattr(softpad.trials, "run_experiments", never)
    argv = ["trials", "--seeds", "0", "--trials", "1", "--objects", "object-5"]
    missing = str(tmp_path / "none.toml")
    assert main([*argv, "--planner", "catalogue", "--catalogue", missing]) == 2
    err = capsys.readouterr().err
    assert "none.toml" in err and "not found" in err and "Traceback" not in err
    bad = tmp_path / "bad.toml"
    bad.write_text('schema = "softpad-catalogue/3"\nmodules = 6\n')
    assert main([*argv, "--planner", "catalogue", "--catalogue", str(bad)]) == 2
    assert "malformed" in capsys.readouterr().err
    assert main([*argv, "--planner", "model-based", "--catalogue", str(bad)]) == 2
    assert "--catalogue is for --planner catalogue" in capsys.readouterr().err


@pytest.mark.mujoco
def test_trials_with_a_catalogue_recognise_its_object(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``softpad trials --planner catalogue``: without ``--catalogue`` object 5 is unknown
    (handed on); with a catalogue learned from that trial's own reading it is recognised and
    grasped by the catalogue's grasp, which the trial record carries."""
    import json

    from softpad.planning import LearnedTrial, learn_catalogue

    argv = ["trials", "--seeds", "0", "--trials", "1", "--objects", "object-5", "--workers", "1"]
    argv += ["--planner", "catalogue", "--detector", "thesis", "--no-progress", "--json"]
    assert main(argv) == 0
    (first,) = json.loads(capsys.readouterr().out)["trials"]
    assert first["rule"].startswith("unknown -> ")
    grasp = (first["cog"][0] + 0.05, first["cog"][1], first["theta"])
    taught = LearnedTrial("object-5", tuple(first["increments_pa"]), grasp, True)
    path = tmp_path / "c.toml"
    path.write_text(learn_catalogue([taught], 30.0).to_toml())
    assert main([*argv, "--catalogue", str(path)]) == 0
    (again,) = json.loads(capsys.readouterr().out)["trials"]
    assert again["rule"].startswith("catalogue: object-5 (d=0.00)")
    assert again["cog"] == pytest.approx(grasp[:2], abs=1e-5)


def test_learn_takes_a_stated_acceptance_alpha(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """``--acceptance-alpha`` reaches the learning's parameters (the catalogue's tolerances
    then narrow, tests/planning/test_catalogue_acceptance.py); outside 0.001..0.5 it is
    refused by name before any recording is read; without it, no narrowing."""
    import softpad.record
    from softpad.planning import LearnedTrial, learn_catalogue
    from softpad.record import Learned

    seen: list[Any] = []

    def fake(paths: Any, params: Any = None) -> Learned:
        seen.append(params)
        trial = LearnedTrial("toy", (1.0,) * 6, (1, 1, 0), True)
        return Learned(learn_catalogue([trial], 1.0, params), (trial,), 0, 1.0)

    monkeypatch.setattr(softpad.record, "learn_from_recordings", fake)
    out = str(tmp_path / "c.toml")
    assert main(["learn", "a.mcap", "--out", out, "--acceptance-alpha", "0.05"]) == 0
    assert main(["learn", "a.mcap", "--out", out, "--force"]) == 0
    assert [p.acceptance_alpha for p in seen] == [0.05, None]
    capsys.readouterr()
    for bad in ("0", "0.7", "nan", "x"):
        assert main(["learn", "a.mcap", "--out", out, "--force", "--acceptance-alpha", bad]) == 2
        err = capsys.readouterr().err
        assert "--acceptance-alpha" in err and "Traceback" not in err
    assert len(seen) == 2
