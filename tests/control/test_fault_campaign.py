"""Fault campaigns (issues 17 and 35): the whole loop with faults, the true pressure watched.

* the phase campaign: a stuck inflation valve, a stuck deflation valve and a leak started at a
  random time inside each phase of the loop (inflation and adjustment, waiting for the
  object, the hold, the valve check), at 100 Hz and 1 kHz: every one detected within
  ``MAX_DELAY_S`` (2 s), the run ends in a verified safe state or names the channel, the
  true pressure never above the maximum plus ``TRUE_MARGIN_PA``, and closing the box never
  seals a vented channel again (its physics watched 30 s after the close);
* the random campaign: random kinds, channels and times.

``make test`` runs the phases missed before (adjustment, valve check) at 100 Hz and a few random
seeds; ``make test-slow`` the rest (the 1 kHz case included) and the campaign-wide figures;
``softpad bench --only safety`` the bigger campaigns. The simulator's true chamber pressure is checked at every frame during
each run, 30 s after it and 30 s after closing the box.
"""

from __future__ import annotations

import random

import pytest

from softpad.benchmarks._safety import (
    MAX_DELAY_S,
    PHASE_KINDS,
    PHASES,
    TRUE_MARGIN_PA,
    draw_faults,
    run_case,
    run_one,
    summarise,
)
from softpad.box import RATED_MAX_PRESSURE_PA

#: (kind, phase, rate): every kind in every phase at 100 Hz; at 1 kHz a stuck inflation valve
#: in the valve check (every kind and phase at 1 kHz runs in ``softpad bench --only safety``).
CASES = [(k, ph, 100.0) for ph in PHASES for k in PHASE_KINDS] + [
    ("stuck:inflate", "valve_check", 1000.0)
]
#: Cases run by ``make test`` (the phases where faults were missed or named only at the
#: adjustment's timeout), at 100 Hz; the others by ``make test-slow``. The 1 kHz case is the
#: 100 Hz valve-check case's check on ten times the frames (16 of the suite's 480 CPU-s and
#: its longest test, issue 38): make test-slow runs it; make test keeps faults at 1 kHz in
#: tests/control/test_inflation.py (named within 2 s during the adjustment) and
#: tests/box/test_safe_state_kept.py (the guard's venting kept).
QUICK_PHASES = ("adjust", "valve_check")
QUICK_RATE_HZ = 100.0
SEED = 2000


class _Runs(dict):
    """Runs by key, each run once, when a test first asks for it."""

    def __init__(self, run) -> None:  # type: ignore[no-untyped-def]
        super().__init__()
        self._run = run

    def __missing__(self, key):  # type: ignore[no-untyped-def]
        self[key] = r = self._run(key)
        return r


@pytest.fixture(scope="module")
def phase_runs() -> dict:
    return _Runs(lambda c: run_case(c[0], c[1], SEED, c[2]))


@pytest.mark.parametrize(
    "case",
    [
        c
        if c[1] in QUICK_PHASES and c[2] == QUICK_RATE_HZ
        else pytest.param(c, marks=pytest.mark.slow)
        for c in CASES
    ],
    ids=lambda c: f"{c[0]}-{c[1]}-{c[2]:g}Hz",
)
def test_fault_in_every_phase_is_detected_within_2_s_and_ends_safe(phase_runs, case) -> None:
    r = phase_runs[case]
    assert r.outcome == "fault", r
    assert r.delay_s is not None and 0.0 <= r.delay_s <= MAX_DELAY_S, (r.faults, r.detected)
    assert r.verified or r.channel_unsafe is not None, r
    assert not r.resealed, r
    assert r.peak_true_pa <= RATED_MAX_PRESSURE_PA + TRUE_MARGIN_PA, (r.faults, r.peak_true_pa)


@pytest.mark.slow
def test_phase_campaign_summary(phase_runs) -> None:
    s = summarise([phase_runs[c] for c in CASES])
    assert s["faulted_runs"] == s["runs"] and s["resealed"] == 0
    assert s["delay_p95_s"] <= MAX_DELAY_S


SEEDS = range(24)
#: Seeds run by ``make test``; the others, and the campaign-wide figures, by ``make test-slow``
#: (issue 38: the whole campaign took 27 s of the suite's time).
QUICK_SEEDS = range(6)


@pytest.fixture(scope="module")
def campaign() -> dict:
    return _Runs(run_one)


@pytest.mark.parametrize(
    "seed",
    [s if s in QUICK_SEEDS else pytest.param(s, marks=pytest.mark.slow) for s in SEEDS],
    ids=lambda s: f"seed{s}",
)
def test_true_pressure_never_above_max_and_run_ends_safe(campaign, seed: int) -> None:
    r = campaign[seed]
    assert r.peak_true_pa <= RATED_MAX_PRESSURE_PA + TRUE_MARGIN_PA, (r.faults, r.peak_true_pa)
    assert not r.resealed, r
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


#: Seeds of the loop-level checks below, apart from the campaign's (2000-2004): the
#: judgements were developed on these and the campaign then run once.
DEV_SEEDS = (3000, 3001, 3002)


@pytest.mark.parametrize(
    ("kind", "phase"),
    [("stuck:inflate", "wait_object"), ("stuck:deflate", "adjust")],
    ids=["stuck-inflate-wait-object", "stuck-deflate-adjust"],
)
@pytest.mark.parametrize(
    "rate_hz", [100.0, pytest.param(1000.0, marks=pytest.mark.slow)], ids=["100Hz", "1kHz"]
)
def test_the_slowest_cases_are_named_within_2_s(kind: str, phase: str, rate_hz: float) -> None:
    """The cases the campaign named last (issue 35): a stuck inflation valve while the object
    is placed (3.6, 3.8, 5.4 s on these seeds at 100 Hz: three whole windows, then not
    judged while the robot pressed) and a deflation valve stuck open while the modules fill
    (2.1, 1.0, 2.7 s: named only once sealed at p0). Now the steady-rise and fill-rate
    judgements name them within 2 s (about 1 s and 0.3-0.4 s)."""
    for seed in DEV_SEEDS:
        r = run_case(kind, phase, seed, rate_hz)
        assert r.outcome == "fault", r
        assert r.delay_s is not None and 0.0 <= r.delay_s <= MAX_DELAY_S, (r.faults, r.detected)
        assert r.verified or r.channel_unsafe is not None, r
        assert r.peak_true_pa <= RATED_MAX_PRESSURE_PA + TRUE_MARGIN_PA, r
