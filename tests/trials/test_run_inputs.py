"""softpad.trials' run checks and messages (what ``softpad trials``, ``compare``, ``demo``
and ``results`` call): counts' ranges, the message naming raising trials, the quoted
results' command lines."""

from __future__ import annotations

import pytest

from softpad.errors import InputError
from softpad.trials import RESULTS, check_counts, result_argv, trial_errors_text


@pytest.mark.parametrize(
    ("trials", "workers", "message"),
    [(0, None, "--trials must be from 1 to 1000, got 0"), (5, 300, "--workers must be from 1")],
    ids=["trials", "workers"],
)
def test_counts_out_of_range(trials: int, workers: int | None, message: str) -> None:
    with pytest.raises(InputError, match=message):
        check_counts(trials, workers)


def test_raising_trials_are_named_with_the_last_line_of_the_first_traceback() -> None:
    assert trial_errors_text([], "trials") is None
    errored = [
        {"object": f"o{i}", "trial": i, "seed": 7, "detail": "Traceback\n  ...\nKeyError: 'x'"}
        for i in range(7)
    ]
    text = trial_errors_text(errored, "demo")
    assert text is not None
    assert text.startswith("softpad demo: error: 7 trial(s) raised and count as failed: o0 trial 0")
    assert "o4 trial 4 (seed 7) and 2 more; first: KeyError: 'x'." in text


def test_the_trial_commands_get_the_workers_the_others_not() -> None:
    sizes = {spec.argv[0] for spec in RESULTS}
    assert {"validate", "compare", "pad"} <= sizes
    for spec in RESULTS:
        argv = result_argv(spec, "quick", workers=2)
        assert argv[: len(spec.quick)] == list(spec.quick)
        assert (argv[-2:] == ["--workers", "2"]) == (spec.quick[0] in ("validate", "compare"))
