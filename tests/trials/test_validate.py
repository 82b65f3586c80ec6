"""softpad.trials._validate: each row's computation against its stated criterion, and the
command on a tiny seed range."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.stats import fisher_exact

from softpad import thesis
from softpad.trials import TrialResult
from softpad.trials._validate import (
    COG_TOLERANCE_UNITS,
    GRAVITY_M_S2,
    cylinder_modules_row,
    duplo_row,
    experiment_rows,
    fisher_agreement,
    landed,
    min_detectable_mass_row,
    noise_row,
    plan_row,
    rate_row,
    static_draws,
)

PI = math.pi


def test_fisher_agreement_is_scipys_two_sided_test() -> None:
    """docs/trials.md's 431/550 against the thesis's 52/55: p = 0.002, a disagreement."""
    p = fisher_agreement(431, 550, 52, 55)
    ref = fisher_exact([[431, 119], [52, 3]]).pvalue
    assert p == pytest.approx(ref)
    assert p == pytest.approx(0.002, abs=0.001)
    assert rate_row("x", "s", 431, 550, 52, 55).agrees is False


@pytest.mark.parametrize(
    ("k", "n", "agrees"), [(50, 50, True), (40, 50, True), (0, 50, False)], ids=["50", "40", "0"]
)
def test_rate_row_agrees_by_p_above_alpha(k: int, n: int, agrees: bool) -> None:
    row = rate_row("x", "s", k, n, 4, 5)
    assert row.agrees is agrees
    assert (row.p_value > 0.05) is agrees
    lo, hi = row.interval
    assert lo <= k / n <= hi


def test_rate_row_without_trials_is_not_run() -> None:
    row = rate_row("x", "s", 0, 0, 4, 5)
    assert row.agrees is None and row.predicted is None


def _plans(cog: tuple[float, float], theta: float, n: int, spread: float, seed: int = 0):
    rng = np.random.default_rng(seed)
    return [
        (cog[0] + rng.normal(0, spread), cog[1] + rng.normal(0, spread), theta) for _ in range(n)
    ]


def test_plan_row_agrees_when_the_thesis_plan_is_among_the_predicted() -> None:
    row = plan_row("p", "T", (0.5, 0.96, 0.0), _plans((0.5, 1.0), 0.0, 200, 0.02), "static")
    assert row.agrees is True
    assert row.predicted[2] == 0.0
    assert row.predicted[1] == pytest.approx(1.0, abs=0.01)


def test_plan_row_cog_outside_range_plus_tolerance_disagrees() -> None:
    far = 1.0 + 0.05 + COG_TOLERANCE_UNITS + 0.05  # beyond ~2.5 sigma + the tolerance
    row = plan_row("p", "T", (0.5, far, 0.0), _plans((0.5, 1.0), 0.0, 200, 0.02), "static")
    assert row.agrees is False


def test_plan_row_theta_needs_five_percent_share_modulo_pi() -> None:
    plans = _plans((1.0, 1.0), PI / 4, 97, 0.0) + _plans((1.0, 1.0), -PI / 4, 3, 0.0)
    assert plan_row("p", "T", (1.0, 1.0, -PI / 4), plans, "static").agrees is False  # 3 %
    plans = _plans((1.0, 1.0), PI / 4, 90, 0.0) + _plans((1.0, 1.0), 3 * PI / 4, 10, 0.0)
    row = plan_row("p", "T", (1.0, 1.0, -PI / 4), plans, "static")
    assert row.agrees is True  # 3 pi / 4 is -pi / 4 for parallel jaws, 10 %
    assert row.predicted[2] == pytest.approx(PI / 4, abs=1e-4)


def test_plan_row_without_plans_disagrees() -> None:
    assert plan_row("p", "T", (1.0, 1.0, 0.0), [None, None], "static").agrees is False


@pytest.mark.parametrize(
    ("counts", "agrees"),
    [((6, 6, 6, 6, 4), True), ((2,) * 20, False), ((6,) * 20, True)],
    ids=["thesis", "two-modules", "always-six"],
)
def test_cylinder_modules_row(counts: tuple[int, ...], agrees: bool) -> None:
    row = cylinder_modules_row(counts, "static")
    assert row.agrees is agrees
    assert row.predicted == f"{sum(c == 6 for c in counts)}/{len(counts)}"


def test_min_detectable_mass_from_an_independent_rise_map() -> None:
    """The row's 42 x 31 mm figure against the probe's vectorised sealed rise map (the gas
    law on the module characteristic, not the response's linear formula), within 3 %."""
    from softpad.sim import PadResponse, default_characteristic
    from softpad.sim._probe import sealed_rise_map

    row = min_detectable_mass_row()
    r = PadResponse()
    c = r.module_centers_m()[0]
    rise = (
        sealed_rise_map(
            r,
            default_characteristic(),
            thesis.P0_PA,
            0.1,
            (0.042, 0.031),
            np.array([c[0]]),
            np.array([c[1]]),
        )[0, 0, 0]
        / 0.1
    )
    m_g = thesis.OBJECT_THRESHOLD_PA / (GRAVITY_M_S2 * rise) * 1e3
    assert row.predicted == pytest.approx(m_g, rel=0.03)
    lo, hi = row.interval
    assert lo <= row.predicted <= hi
    assert row.agrees is (lo <= 7.0 and hi >= 5.0)


def test_duplo_rise_is_linear_in_mass_and_above_t_o() -> None:
    row = duplo_row()
    m_min_g = min_detectable_mass_row().predicted  # the same 42 x 31 mm face, centred
    assert row.predicted == pytest.approx(thesis.OBJECT_THRESHOLD_PA * 12.6 / m_min_g, rel=1e-3)
    assert row.agrees is (row.interval[0] > thesis.OBJECT_THRESHOLD_PA)


def test_noise_row_on_a_short_idle() -> None:
    """Single-sample rms of the box's sensor (8 Pa white, 3 Pa drift, disturbances) within
    30 % of their root sum of squares; the filtered peak far below t_g."""
    row = noise_row(idle_s=5.0)
    rms, peak = row.predicted
    assert rms == pytest.approx(math.hypot(8.0, 3.0), rel=0.3)
    assert peak < thesis.CONTACT_THRESHOLD_PA
    assert row.agrees is True


def test_static_draws_see_object_6_on_the_bottom_row() -> None:
    """Object 6 (122 g, 214 Pa a module) is seen on modules 4-6 in every draw and planned
    across the row near its centre (placement noise 3 mm: within 0.1 module units)."""
    from softpad.sim import get_object

    draws = static_draws(get_object("object-6"), 3)
    assert [d.modules for d in draws] == [(4, 5, 6)] * 3
    for d in draws:
        assert d.plan is not None and d.plan[2] == pytest.approx(PI / 2)
        np.testing.assert_allclose(d.plan[:2], (1.5, 0.5), atol=0.1)


def _trial(obj: str, ok: bool, cause: str | None = None, attempts: int = 1) -> TrialResult:
    return TrialResult(obj, 0, 0, (0.0, 0.0, 0.0), "6/2", ok, cause, attempts=attempts)


def test_experiment_rows_count_causes_and_landings() -> None:
    from softpad.trials import THESIS_TABLE_6_1

    trials = [_trial(n, True) for n in THESIS_TABLE_6_1 for _ in range(5)]
    trials[-1] = _trial("charger", False, "jaws_hit_object")
    trials[0] = _trial("object-1", True, attempts=2)
    rows = {r.name: r for r in experiment_rows(trials)}
    assert rows["Experiment 2 held, all objects"].predicted == "54/55"
    assert rows["Experiment 2 held: charger"].predicted == "4/5"
    assert rows["jaws landing on an object"].predicted == "2/55"
    assert rows["seam miss (contact not detected): charger"].predicted == "0/5"
    assert landed(trials[0]) and not landed(trials[1])


@pytest.mark.slow
@pytest.mark.mujoco
def test_validate_command_on_one_seed(capsys: pytest.CaptureFixture[str]) -> None:
    """``softpad validate --seeds 0 --trials 1 --json``: every row present with the JSON fields,
    the trial rows run (11 trials)."""
    from softpad.cli.main import main

    rc = main(
        [
            "validate",
            "--seeds",
            "0",
            "--trials",
            "1",
            "--placements",
            "2",
            "--json",
            "--workers",
            "1",
        ]
    )
    assert rc == 0
    out = json.loads(capsys.readouterr().out)
    obs = out["observations"]
    assert {"name", "source", "thesis", "predicted", "interval", "agrees", "test"} <= set(obs[0])
    exp = next(o for o in obs if o["name"] == "Experiment 2 held, all objects")
    assert exp["predicted"].endswith("/11") and exp["agrees"] is not None
    assert len(out["trials"]) == 11
    assert out["counts"]["not_run"] == 0


def test_randomized_static_draws_differ_and_repeat() -> None:
    """--randomize: each draw its own uncertain parameters (here the can's heavy part, seam,
    noise), reproducible from the seed; nominal draws unchanged by it."""
    from softpad.sim import get_object

    spec = get_object("cylinder")
    a = static_draws(spec, 3, 0, randomize=True)
    assert a == static_draws(spec, 3, 0, randomize=True)
    assert a != static_draws(spec, 3, 0, randomize=False)


def test_cylinder_line_budget_is_short_of_six_modules() -> None:
    """docs/validation.md's argument, regenerated: the lightest column's share under the
    planned x_COG = 1.14 is (1.14 - 0.5) / 3 (hand-worked: 0.2133), so the needed S is
    t_o / (0.2133 x 0.8718 N) = 268.8 Pa/N; the clamped-edge FEM's strip gives less than that
    and less than a homogeneous can's 172 Pa/N; the point response falls towards the line."""
    from softpad.trials._validate import cylinder_line_budget

    b = cylinder_line_budget()
    assert b["s_needed_pa_n"] == pytest.approx(50.0 / (0.64 / 3 * 0.0889 * 9.80665), rel=1e-6)
    assert b["s_needed_even_pa_n"] == pytest.approx(172.1, abs=0.1)
    assert b["s_fem_pa_n"] < b["s_needed_even_pa_n"] < b["s_needed_pa_n"]
    points = [b[f"point_{d:g}_mm_pa_n"] for d in (0.0, 2.5, 5.0, 10.0, 15.0, 22.5)]
    assert points == sorted(points)
