"""A trial that raises (a bug) is recorded as failed, the sweep goes on, the command exits 4.

``run_trial`` is replaced so that one chosen trial raises and the others return a made-up
held result at once: what is tested is the sweep around the trials, not the physics.
"""

from __future__ import annotations

import contextlib
import io
import json
from dataclasses import replace
from typing import Any

import pytest

import softpad.trials
import softpad.trials._runner as runner
from softpad.cli.main import main
from softpad.errors import EXIT_INTERNAL
from softpad.sim import get_object
from softpad.trials import TrialResult, run_experiment

BAD = ("banana", 1)  # the trial that raises: object and trial number


def _fake_run_trial(spec: Any, trial: int = 0, seed: int = 0, config: Any = None, **_: Any):
    if (spec.name, trial) == BAD:
        raise ZeroDivisionError("a planted defect")
    held = TrialResult(spec.name, trial, seed, (0.0, 0.0, 0.0), spec.gripper, True, None)
    return replace(held, detail="fake"), None


@pytest.fixture
def planted(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(runner, "run_trial", _fake_run_trial)
    monkeypatch.setattr(softpad.trials, "run_trial", _fake_run_trial)


def _run(argv: list[str]) -> tuple[int, dict[str, Any], str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, json.loads(out.getvalue()), err.getvalue()


@pytest.mark.usefixtures("planted")
def test_the_sweep_keeps_every_other_trial_and_records_the_error() -> None:
    specs = [get_object("object-1"), get_object("banana")]
    exp, _ = run_experiment(specs, trials=3, seed=4, workers=1)
    assert [(t.object, t.trial) for t in exp.trials] == [
        (s.name, k) for s in specs for k in range(3)
    ]
    bad = [t for t in exp.trials if not t.success]
    assert [(t.object, t.trial, t.cause) for t in bad] == [(*BAD, "trial_error")]
    # the record can rerun it: its own seed, the traceback with the exception's message
    assert bad[0].seed == runner.trial_seed(4, "banana", 1)
    assert "ZeroDivisionError: a planted defect" in bad[0].detail
    assert "run_trial(get_object('banana'), 1," in bad[0].detail
    assert sum(t.success for t in exp.trials) == 5


@pytest.mark.usefixtures("planted")
def test_trials_prints_every_trial_and_exits_with_the_internal_error_code() -> None:
    argv = ["trials", "--objects", "object-1,banana", "--trials", "2", "--seeds", "0-1"]
    code, doc, err = _run([*argv, "--workers", "1", "--json", "--no-progress"])
    assert code == EXIT_INTERNAL
    assert doc["overall"]["trials"] == 8 and doc["overall"]["successes"] == 6
    assert doc["overall"]["failures"] == {"trial_error": 2}
    assert "2 trial(s) raised" in err and "banana trial 1" in err and "Traceback" not in err


@pytest.mark.mujoco  # the idle pad of the false-alarm count runs the simulated box
@pytest.mark.usefixtures("planted")
def test_compare_keeps_the_comparison_and_names_the_errored_trials() -> None:
    argv = ["compare", "--objects", "object-1,banana", "--trials", "2", "--seeds", "3"]
    argv += ["--pair", "thesis:thesis", "--idle-hours", "0.01"]
    code, doc, err = _run([*argv, "--workers", "1", "--json", "--no-progress"])
    assert code == EXIT_INTERNAL
    (c,) = doc["combinations"]
    assert c["successes"] == 3 and c["failures"] == {"trial_error": 1}
    assert [(t["object"], t["trial"]) for t in c["errored"]] == [BAD]
    # every failed trial is listed with its experiment seed, to be run again alone
    assert c["failed_trials"] == [
        {
            "object": "banana",
            "trial": 1,
            "seed": 3,
            "cause": "trial_error",
            "rule": None,
            "parameters": None,
        }
    ]  # rule: the first plan's (none: the trial errored); parameters: the drawn uncertain
    # inputs under --randomize, None without
    assert "a planted defect" in c["errored"][0]["detail"]
    assert "banana trial 1 (seed" in err


@pytest.mark.usefixtures("planted")
def test_a_sweep_without_errors_exits_zero() -> None:
    argv = ["trials", "--objects", "object-1", "--trials", "2", "--seeds", "0"]
    code, doc, err = _run([*argv, "--workers", "1", "--json", "--no-progress"])
    assert code == 0 and doc["overall"]["successes"] == 2 and "raised" not in err


def test_a_dask_trial_that_raises_is_recorded_the_same(monkeypatch: pytest.MonkeyPatch) -> None:
    from softpad.design._trials import _trial_task

    monkeypatch.setattr(softpad.trials, "run_trial", _fake_run_trial)
    r = _trial_task(get_object("banana"), 1, 9, softpad.trials.TrialConfig())
    assert (r.cause, r.seed) == ("trial_error", runner.trial_seed(9, "banana", 1))
    assert _trial_task(get_object("banana"), 0, 9, softpad.trials.TrialConfig()).success
