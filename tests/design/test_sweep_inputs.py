"""softpad.design's sweep inputs (what ``softpad design`` and ``softpad trials`` call): the
design space from text, the trial options' quick defaults and ranges, the objects of a
trial run, the cache folder."""

from __future__ import annotations

from pathlib import Path

import pytest

from softpad import thesis
from softpad.design import (
    MAX_DESIGNS,
    QUICK_DESIGNS,
    THESIS_DESIGN,
    cache_folder,
    cached_line,
    designs_from_text,
    sweep_trial_options,
    trial_objects,
)
from softpad.errors import InputError


def test_no_option_with_quick_is_the_quick_set() -> None:
    assert designs_from_text(quick=True) == list(QUICK_DESIGNS)
    assert designs_from_text() == [THESIS_DESIGN]


def test_the_options_span_their_product_after_the_baseline() -> None:
    designs = designs_from_text("2x3,3x4", "35,45", None, ["yeoh"], "1:2:0.5")
    assert designs[0] == THESIS_DESIGN
    assert len(designs) == 1 + 2 * 2 * 1 * 3
    assert {d.pitch_m for d in designs[1:]} == {0.035, 0.045}
    assert {d.p0_pa for d in designs[1:]} == {1000.0, 1500.0, 2000.0}


def test_too_many_designs_are_refused_naming_the_limit() -> None:
    with pytest.raises(InputError, match=f"at most {MAX_DESIGNS} per sweep"):
        designs_from_text("2x3,3x4,4x6", "20:60:1", "1:2:0.1")


@pytest.mark.parametrize(
    ("trials", "hold_s", "message"),
    [(0, None, "--trials must be from 1 to 100, got 0"), (1, 61.0, "--hold-s must be from 0")],
    ids=["trials", "hold"],
)
def test_trial_options_out_of_range(trials: int, hold_s: float | None, message: str) -> None:
    with pytest.raises(InputError, match=message):
        sweep_trial_options(trials, hold_s, False, "thesis", "thesis")


def test_quick_trial_options_are_shorter() -> None:
    quick = sweep_trial_options(None, None, True, "thesis", "thesis")
    full = sweep_trial_options(None, None, False, "thesis", "thesis")
    assert (quick.trials, quick.hold_s) == (1, 2.0)
    assert (full.trials, full.hold_s) == (5, thesis.HOLD_S)


def test_trial_objects_of_the_catalogue_by_name() -> None:
    assert [o.name for o in trial_objects(["banana", "object-1"])] == ["banana", "object-1"]
    with pytest.raises(InputError, match="unknown object 'pear'; known objects: object-1"):
        trial_objects(["pear"])


def test_cache_folder_is_created_or_refused(tmp_path: Path) -> None:
    assert cache_folder(str(tmp_path / "a" / "b")).is_dir()
    with pytest.raises(InputError, match="--cache needs a folder name"):
        cache_folder("  ")
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(InputError, match="cannot be used"):
        cache_folder(str(blocker / "sub"))
    assert cached_line(3, 0, tmp_path).startswith("softpad design: all tasks answered")
    assert "3 of 5 tasks" in cached_line(3, 2, tmp_path)
