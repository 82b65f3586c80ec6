"""The misuse campaign of tests/fuzz_campaign.py (issue 35, last "Done when"): no traceback, no
clobbered file, no silently accepted unit mix-up, no input past its time bound.

A seeded slice (60 command lines, 20 API misuses) runs with the quick tests; the whole campaign
(600 and 180, about a minute on 2 cores) with ``make test-slow``. The classifier is checked
against inputs that must land in each bad class.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from fuzz_campaign import (
    BAD,
    SEED,
    Case,
    campaign,
    make_files,
    run_api,
    run_cli,
    stubbed,
    summary,
)


def _bad(results) -> list[str]:
    return [
        f"{r.outcome}: {r.case.label} {r.case.argv} -> {r.message}"
        for r in results
        if r.outcome in BAD
    ]


def test_a_seeded_slice_of_the_campaign_finds_nothing_bad() -> None:
    results = campaign(60, 20, SEED)
    s = summary(results)
    assert s["cli"]["inputs"] == 60 and s["api"]["inputs"] == 20
    assert _bad(results) == []
    # the slice exercises refusals and accepted inputs on both surfaces
    assert s["cli"]["refused"] > 20 and s["cli"]["accepted"] > 0
    assert s["api"]["refused"] > 5


@pytest.mark.slow  # 600 command lines and 180 API misuses: about a minute on 2 cores
def test_the_whole_campaign_finds_nothing_bad() -> None:
    results = campaign(600, 180, SEED)
    s = summary(results)
    assert s["cli"]["inputs"] == 600 and s["api"]["inputs"] == 180
    assert _bad(results) == []


def test_the_campaign_is_reproducible() -> None:
    import numpy as np

    from fuzz_campaign import cli_cases

    files = {"mcap": ["cut0.mcap", "empty.mcap", "garbage.mcap", "text.mcap"]}
    files |= {k: [f"{k}{i}.x" for i in range(6)] for k in ("toml", "frame", "csv", "set")}
    a = [c.argv for c in cli_cases(50, SEED, files)]
    assert a == [c.argv for c in cli_cases(50, SEED, files)]
    assert a != [c.argv for c in cli_cases(50, SEED + 1, files)]
    assert len({tuple(x) for x in a}) > 40  # varied inputs
    assert np.mean([c.invalid for c in cli_cases(200, SEED, files)]) > 0.5


def test_the_classifier_names_each_bad_outcome(tmp_path: Path, monkeypatch) -> None:
    import numpy as np

    import softpad.cli._plan

    monkeypatch.chdir(tmp_path)
    make_files(tmp_path, np.random.default_rng(0))

    def clobber() -> None:
        (tmp_path / "old.png").write_bytes(b"changed")

    def foreign() -> None:
        raise TypeError("not an InputError")

    assert run_api(Case("api", "type", "foreign", call=foreign), tmp_path).outcome == "traceback"
    assert run_api(Case("api", "unit", "x", call=lambda: None, mixup=True), tmp_path).outcome == (
        "mixup"
    )
    assert run_api(Case("api", "existing", "clobber", call=clobber), tmp_path).outcome == (
        "clobbered"
    )
    refused = Case("cli", "unit", "plan", ["plan", "--delta", "0,124,78,109,3,2"], names=("124",))
    assert run_cli(refused, tmp_path).outcome == "refused"
    (tmp_path / "old.png").write_bytes(b"kept")
    argv = ["plan", "--delta", "0,0.124,0.078,0.109,0,0", "--png", "old.png"]
    monkeypatch.setattr(softpad.cli._plan, "check_output", lambda path, *a, **k: Path(path))
    with stubbed():
        assert run_cli(Case("cli", "existing", "plan", argv), tmp_path).outcome == "clobbered"
