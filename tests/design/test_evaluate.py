"""Trials of an object set on a design (analytic world, simulated box)."""

from __future__ import annotations

import pytest

from softpad.design import (
    THESIS_DESIGN,
    PadDesign,
    TrialOptions,
    fem_response,
    object_set_from_dict,
    run_design_trials,
)
from softpad.errors import InputError

pytestmark = pytest.mark.fem


def _set(*names: str) -> object:
    return object_set_from_dict(
        {
            "schema": "softpad-object-set/1",
            "name": "t",
            "object": [{"name": n, "catalogue": n} for n in names],
        }
    )


@pytest.fixture(scope="module")
def response() -> dict:
    return fem_response(**_fem(THESIS_DESIGN), cells_in_plane=8).to_dict()


def _fem(d: PadDesign) -> dict:
    v = d.fem_variables()
    return dict(
        width_m=v["width_m"], thickness_m=v["thickness_m"], material=v["material"], p0_pa=v["p0_pa"]
    )


def test_thesis_pad_holds_the_banana_and_detects_contact(response: dict) -> None:
    rows = run_design_trials(
        THESIS_DESIGN, response, _set("banana", "charger"), 0, TrialOptions(hold_s=1.0)
    )
    assert [r["object"] for r in rows] == ["banana", "charger"]
    for r in rows:
        assert r["success"] and r["outcome"] == "held"
        # the thesis detector: running average of 10 samples at 100 Hz, 0.05 m/s approach
        assert 0.0 < r["contact_delay_s"] < 0.3


def test_same_seed_same_trials_other_seed_other_noise(response: dict) -> None:
    opts = TrialOptions(hold_s=0.5, trials=2)
    s = _set("banana")
    a = run_design_trials(THESIS_DESIGN, response, s, 3, opts)
    b = run_design_trials(THESIS_DESIGN, response, s, 3, opts)
    c = run_design_trials(THESIS_DESIGN, response, s, 4, opts)
    assert a == b
    assert [r["sim_time_s"] for r in a] != [r["sim_time_s"] for r in c] or a != c


def test_trials_run_on_another_grid(response: dict) -> None:
    big = PadDesign(3, 4, 0.045)  # same module: the same response
    rows = run_design_trials(big, response, _set("banana"), 0, TrialOptions(hold_s=0.5))
    assert rows[0]["outcome"] in ("held", "missed", "dropped", "contact_not_detected")
    assert rows[0]["sim_time_s"] > 1.0


@pytest.mark.parametrize(
    ("changes", "named"),
    [
        ({"trials": 0}, "trials"),
        ({"planner": "x"}, "planner"),
        ({"detector": "x"}, "detector"),
        ({"hold_s": -1.0}, "hold"),
    ],
    ids=["trials", "planner", "detector", "hold"],
)
def test_bad_options(changes: dict, named: str) -> None:
    with pytest.raises(InputError, match=named):
        TrialOptions(**changes)
