"""The FEM response of the density study's pads: smaller modules against the 2 x 3 module
and against the scaling of an inflated layer (issue 47, item 5)."""

from __future__ import annotations

import itertools
import math

import pytest

from softpad.design import FemResponse, fem_response
from softpad.design._evaluate import channel_capacity_m3_pa, valve_scale

pytestmark = pytest.mark.fem

#: The study's pitches, m (2 x 3, 3 x 4, 3 x 5, 4 x 6 on about the same area).
PITCHES_M = (0.045, 0.034, 0.027, 0.0225)


@pytest.fixture(scope="module")
def responses() -> dict[float, FemResponse]:
    """Coarse-mesh (8-cell) responses, as the study's quick runs use."""
    return {w: fem_response(w, 0.0015, "neo-hookean", 1100.0, 8) for w in PITCHES_M}


def test_smaller_modules_are_stiffer(responses: dict[float, FemResponse]) -> None:
    """Lower, less compliant chambers and a stiffer centre patch, pitch by pitch."""
    rs = [responses[w] for w in PITCHES_M]
    for big, small in itertools.pairwise(rs):
        assert small.height_m < big.height_m
        assert small.compliance_m3_pa < big.compliance_m3_pa
        assert small.centre_stiffness_n_m > big.centre_stiffness_n_m


def test_height_and_compliance_scale_between_membrane_and_plate(
    responses: dict[float, FemResponse],
) -> None:
    """Height at a fixed pressure grows as a^(4/3) for a stretched membrane (Hencky) and as
    a^4 for a linear plate; compliance ~ area x height / p as a^(10/3) .. a^6. The FEM's
    exponents from 45 to 22.5 mm lie between."""
    big, small = responses[0.045], responses[0.0225]
    ratio = math.log(0.045 / 0.0225)
    height_exp = math.log(big.height_m / small.height_m) / ratio
    compliance_exp = math.log(big.compliance_m3_pa / small.compliance_m3_pa) / ratio
    assert 4 / 3 <= height_exp <= 4.0
    assert 10 / 3 <= compliance_exp <= 6.0


def test_rise_per_newton_scales_as_one_over_area(responses: dict[float, FemResponse]) -> None:
    """A load on a sealed chamber is carried by its pressure over the module's area: the
    centre's rise per newton times the area, with the gas's share of the capacity taken out
    (``rise x A x (C + G) / C``), is a shape factor of the inflated layer; it stays within
    15 % while the area changes fourfold. So the minimum detectable mass FALLS on smaller
    modules (the issue expected it to rise: the chamber is stiffer, but its area shrinks
    faster)."""
    factors = []
    for w, r in responses.items():
        gas = channel_capacity_m3_pa(r.characteristic(), r.p0_pa) - r.compliance_m3_pa
        factors.append(r.centre_rise_pa_n * w * w * (r.compliance_m3_pa + gas) / r.compliance_m3_pa)
    assert max(factors) / min(factors) < 1.15
    masses = [responses[w].compact_min_detectable_mass_kg for w in PITCHES_M]
    assert masses == sorted(masses, reverse=True)
    # the 1/area law between the ends within 25 % (the gas term and the shape factor)
    expected = (0.045 / 0.0225) ** 2
    assert masses[0] / masses[-1] == pytest.approx(expected, rel=0.25)


def test_compact_weight_on_the_45_mm_module_matches_the_packaged_map(
    responses: dict[float, FemResponse],
) -> None:
    """The 10 x 10 mm weight's rise on the 45 mm module against the packaged clamped map as
    the simulator reads it (``softpad pad sensitivity --pad-model clamped``: 830 Pa/N, a
    separate FEM run tabulated and interpolated): within 5 %."""
    from softpad.sim import PadResponse, pad_sensitivities

    probe = pad_sensitivities(PadResponse(pad_model="clamped"))
    packaged = probe["loads"]["centre: 10x10 mm weight on module 1"]["min_rise_pa_n"]
    assert responses[0.045].compact_rise_pa_n == pytest.approx(packaged, rel=0.05)


def test_sized_valves_keep_the_thesis_pads_and_shrink_with_the_channel(
    responses: dict[float, FemResponse],
) -> None:
    """The thesis pad's own response keeps its valves (scale 1 within 2 %: the 8-cell mesh);
    a 22.5 mm module's channel holds about a tenth of the air per pascal."""
    assert valve_scale(responses[0.045].characteristic(), 1100.0) == pytest.approx(1.0, abs=0.02)
    small = valve_scale(responses[0.0225].characteristic(), 1100.0)
    assert 0.05 < small < 0.15


def test_sized_valves_adjust_the_small_pad_the_thesis_valves_cannot() -> None:
    """The toy (catalogue) on 4 x 6 at 22.5 mm, 3 trials: with the thesis's
    orifices every trial ends in a box fault (a valve opening moves the small channel past the
    adjustment's tolerance); with orifices sized to the channel none does."""
    from softpad.design import PadDesign, TrialOptions, object_set_from_dict, run_design_trials
    from softpad.errors import InputError

    design = PadDesign(4, 6, 0.0225)
    response = fem_response(0.0225, 0.0015, "neo-hookean", 1100.0, 8)
    objects = object_set_from_dict(
        {"schema": "softpad-object-set/1", "name": "t",
         "object": [{"name": "toy", "catalogue": "toy", "placement": "centre"}]}
    )  # fmt: skip
    outcomes = {}
    for valves in ("thesis", "sized"):
        opts = TrialOptions(trials=3, hold_s=1.0, valves=valves)
        outcomes[valves] = [
            r["outcome"] for r in run_design_trials(design, response, objects, 7, opts)
        ]
    assert outcomes["thesis"] == ["box_fault"] * 3
    assert "box_fault" not in outcomes["sized"]
    with pytest.raises(InputError, match="valves must be one of thesis, sized"):
        TrialOptions(valves="tiny")
