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


@pytest.mark.parametrize(
    ("seeds", "hold_s", "record", "message"),
    [
        (list(range(101)), 15.0, None, "--seeds '0-100' names 101 seeds; at most 100"),
        ([0], 601.0, None, "--hold-s must be from 0 to 600 s, got 601.0"),
        ([0, 1], 15.0, "run.mcap", "--record takes one seed at a time"),
    ],
    ids=["seeds", "hold", "record"],
)
def test_a_campaign_out_of_bounds_is_refused(seeds, hold_s, record, message) -> None:
    from softpad.trials import check_campaign

    with pytest.raises(InputError, match=message):
        check_campaign(seeds, "0-100", hold_s, record)


def test_comparisons_that_cannot_be_read_are_named(tmp_path) -> None:
    from softpad.trials import read_comparisons

    binary = tmp_path / "c.json"
    binary.write_bytes(b"\xff\xfe\x00")
    with pytest.raises(InputError, match="is not text"):
        read_comparisons([str(binary)])
    with pytest.raises(InputError, match="cannot read comparison"):
        read_comparisons([str(tmp_path / "missing.json")])


def test_the_object_fits_read_as_a_table() -> None:
    from softpad.trials import ObjectFit, object_fits_table

    fit = ObjectFit(
        "banana", "banana_curve", 0.0, 0.3, 0.1, (0.0, 0.15, 0.3), (0.9, 0.2, 0.4), 0.15
    )
    lines = object_fits_table([fit]).splitlines()
    assert lines[0] == "| object | parameter | range | nominal | fitted | best score |"
    assert lines[2] == "| banana | banana_curve | 0 .. 0.3 | 0.1 | 0.15 | 0.2 |"
