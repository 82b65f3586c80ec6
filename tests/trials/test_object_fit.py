"""softpad.trials._object_fit: the objects' unknowns fitted to Table 6.1's plans."""

from __future__ import annotations

import json
import math

import pytest

from softpad.errors import InputError
from softpad.trials._object_fit import fit_object_unknowns, plan_score

PI = math.pi


@pytest.mark.parametrize(
    ("plans", "score"),
    [
        ([(1.0, 1.0, 0.0)] * 3, 0.0),
        ([(1.3, 1.4, 0.0)] * 3, 0.5),  # a 3-4-5 triangle of 0.5 module
        ([(1.0, 1.0, PI / 4)] * 3, 1.0),  # one 45-degree step
        ([(1.0, 1.0, PI)] * 3, 0.0),  # the same grasp modulo pi
        ([(1.0, 1.0, PI / 2)] * 2 + [(1.0, 1.0, 0.0)], 2.0),  # the modal plan counts
        ([None, None], math.inf),
    ],
    ids=["same", "cog", "theta", "modulo-pi", "modal", "no-plan"],
)
def test_plan_score(plans: list, score: float) -> None:
    assert plan_score(plans, (1.0, 1.0, 0.0)) == pytest.approx(score)


def test_the_toy_fit_picks_the_split_whose_plan_is_the_thesiss() -> None:
    """On the grid 0.2, 0.5, 0.8 of the right hand's share only 0.8 gives the thesis's
    (2, 1, -pi/4) (an even toy plans its middle): the fit picks it, with score 0."""
    (fit,) = fit_object_unknowns(("toy",), draws=4, grid=3)
    assert fit.grid == pytest.approx((0.2, 0.5, 0.8))
    assert fit.scores[2] == pytest.approx(0.0, abs=1e-9)
    assert min(fit.scores[:2]) > 0.5
    assert fit.fitted == pytest.approx(0.8)
    assert json.dumps(fit.to_dict())


def test_bad_fit_input_is_refused() -> None:
    with pytest.raises(InputError, match="has no fitted unknown"):
        fit_object_unknowns(("object-1",), draws=2, grid=2)
    with pytest.raises(InputError, match="draws per value"):
        fit_object_unknowns(draws=1)


def test_calibrate_needs_recordings_or_objects(capsys: pytest.CaptureFixture[str]) -> None:
    from softpad.cli.main import main

    assert main(["calibrate"]) == 2
    assert "--objects" in capsys.readouterr().err
    assert main(["calibrate", "--objects", "a.mcap"]) == 2
    assert "takes no recordings" in capsys.readouterr().err
