"""Randomised fault campaign (issue 17): random fault kinds, channels and times over every phase.

The simulator's true chamber pressure is checked at every frame during each run and for 30 s
of box time after it: never above the maximum plus the stated margin (sensor offset and noise
plus one frame of the fastest rise, ``TRUE_MARGIN_PA``); every run that ends on a fault ends in
a verified safe state or names the channel it could not make safe.
"""

from __future__ import annotations

import random

import pytest

from softpad.benchmarks._safety import TRUE_MARGIN_PA, draw_faults, run_one, summarise
from softpad.box import RATED_MAX_PRESSURE_PA

SEEDS = range(24)
#: Seeds run by ``make test``; the others, and the campaign-wide figures, by ``make test-slow``
#: (issue 38: the whole campaign took 27 s of the suite's time).
QUICK_SEEDS = range(6)


class _Campaign(dict):
    """Runs of the campaign by seed, each run once, when a test first asks for it."""

    def __missing__(self, seed: int):
        self[seed] = r = run_one(seed)
        return r


@pytest.fixture(scope="module")
def campaign() -> dict:
    return _Campaign()


@pytest.mark.parametrize(
    "seed",
    [s if s in QUICK_SEEDS else pytest.param(s, marks=pytest.mark.slow) for s in SEEDS],
    ids=lambda s: f"seed{s}",
)
def test_true_pressure_never_above_max_and_run_ends_safe(campaign, seed: int) -> None:
    r = campaign[seed]
    assert r.peak_true_pa <= RATED_MAX_PRESSURE_PA + TRUE_MARGIN_PA, (r.faults, r.peak_true_pa)
    if r.outcome == "fault":
        assert r.verified or r.channel_unsafe is not None, r


@pytest.mark.slow
def test_campaign_covers_every_kind_and_detects_most(campaign) -> None:
    runs = [campaign[s] for s in SEEDS]
    kinds = {f.partition("@")[0].split(":")[0] for r in runs for f in r.faults}
    assert {"nan", "dropout", "stuck", "leak", "supply_loss"} <= kinds
    s = summarise(runs)
    # faults drawn after the loop's end (about 26 s) cannot be seen; the rest must be
    assert s["faulted_runs"] >= 0.75 * s["runs"]


def test_draw_faults_is_seeded() -> None:
    assert draw_faults(random.Random(5)) == draw_faults(random.Random(5))
