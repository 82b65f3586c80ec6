"""The line gain's range: what the thesis's own observations bracket (issue 45, item 1)."""

from __future__ import annotations

import pytest

from softpad.sim import UNCERTAIN_PARAMETERS, PadResponse, pad_sensitivities
from softpad.sim._response import DEFAULT_LINE_GAIN, LINE_GAIN_RANGE
from softpad.trials._line import line_gain_bracket


@pytest.fixture(scope="module")
def bracket() -> dict[str, float]:
    return line_gain_bracket()


def test_the_cast_fem_alone_falls_short_of_the_thesis(bracket: dict[str, float]) -> None:
    """Gain 1 (the cast-pad FEM): the can's line below the 269 Pa/N its observation needs, and
    the Duplo face's minimum detectable mass above the thesis's 7 g."""
    assert bracket["fem_line_pa_n"] < bracket["s_needed_pa_n"]
    assert bracket["fem_duplo_g"] > 7.0


def test_the_shipped_range_reaches_the_bracket(bracket: dict[str, float]) -> None:
    """``line_response_gain`` runs from the FEM as it is (1, the nominal, which PadResponse
    uses by default) to the 5 g end of the bracket (to the two decimals it is written with),
    and holds the can's end."""
    low, high, nominal = LINE_GAIN_RANGE
    assert low == nominal == 1.0
    assert high == pytest.approx(bracket["high"], abs=0.006)
    assert low < bracket["low"] < high
    entry = next(p for p in UNCERTAIN_PARAMETERS if p.name == "line_response_gain")
    assert (entry.low, entry.high, entry.nominal) == (low, high, nominal)
    assert "3.26" in entry.source and f"{bracket['low']:.2f}" == "3.26"
    assert PadResponse().line_gain == DEFAULT_LINE_GAIN == nominal


@pytest.mark.parametrize("end", ["low", "high"])
def test_the_ends_meet_the_observations(end: str, bracket: dict[str, float]) -> None:
    """At the low end the can's lightest column reaches t_o on its two modules (the line rise
    meets 269 Pa/N, 0.5 %); at the high end the Duplo face's minimum detectable mass is 5 g."""
    figures = pad_sensitivities(PadResponse(line_gain=bracket[end]))
    if end == "low":
        assert figures["line_pa_n"] == pytest.approx(bracket["s_needed_pa_n"], rel=0.005)
    else:
        assert figures["min_detectable_mass_g"]["Duplo face 42x31 mm"] == pytest.approx(
            5.0, rel=0.005
        )


def test_a_drawn_gain_reaches_the_trials_pad() -> None:
    """LabVariation builds the trials' pad with the drawn gain and seam; a draw is in range."""
    from softpad.sim import LabVariation, draw_uncertain

    lab = LabVariation.of({"line_response_gain": 4.0, "seam_width_m": 0.002})
    pad = lab.pad_response()
    assert pad.line_gain == 4.0 and pad.seam_width_m == pytest.approx(0.002)
    drawn = [draw_uncertain(seed)["line_response_gain"] for seed in range(200)]
    assert min(drawn) >= LINE_GAIN_RANGE[0] and max(drawn) <= LINE_GAIN_RANGE[1]
    # uniform over the range: about (5.95 - 3.26) / 4.95 = 54 % of draws see the can
    share = sum(g >= 3.26 for g in drawn) / len(drawn)
    assert 0.44 < share < 0.64
