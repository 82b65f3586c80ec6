"""The whole loop on every thesis object (analytic world, sensor noise), over many seeds.

A single seed proves little: object 1's fingertips come down near the seam between rows and
are sensed in some noise draws and not in others. Each object therefore runs on ten sensor-noise
seeds (0-9) and its held count is compared with a reference rate measured on 40 other seeds
(100-139; ``python tests/control/test_table_6_1_loop.py NAME`` prints them) by Fisher's exact
test: the test fails when the two counts are unlikely to share one rate (two-sided p < 0.001),
i.e. when the loop's behaviour changed, not when one draw was unlucky. The reference rates are
the simulator's own predictions (e.g. the cylinder is seen on two modules and missed, the
thesis's own cylinder failure; the banana is seen on the thesis's modules 2, 3 and 4, but with
module 3 the strongest it is planned by another rule than the thesis's and missed); how they
compare with Table 6.1 is in docs/trials.md.
"""

from __future__ import annotations

import sys

import pytest
from scipy.stats import fisher_exact

from softpad.control import ExecutionParams
from softpad.harness import run_simulated
from softpad.sim import object_names

NAMES = list(object_names())
SEEDS = range(10)
#: Held runs out of 40 on seeds 100-139 (default FEM characteristic and module response,
#: hold 0.5 s; re-measured when the pad physics changes).
REFERENCE_HELD_OF_40 = {
    "object-1": 20,
    "object-2": 40,
    "object-3": 40,
    "object-4": 40,
    "object-5": 40,
    "object-6": 40,
    "banana": 2,
    # 0 since issue 33: the loop's held comes from the gripper's own jaw reading, and the
    # analytic world latches its grasp of the toy's diagonal arm at the 6/2 mounting's 20 mm
    # stop (its point-set jaws close through the arm's footprint to 20.5 mm), so the gripper
    # reads "closed on nothing" while the world carries the toy (40 of 40 by the world's
    # contacts before); a limit of the analytic world's grasp model, not of the loop
    "toy": 0,
    "limes": 39,
    "cylinder": 0,
    "charger": 40,
}
#: Two-sided p-value below which the held counts are taken to differ.
ALPHA = 1e-3
#: Objects whose test runs in ``make test`` (about 2.5 CPU s each): those with a reference
#: rate strictly between 0 and 40 of 40 (the seam case, the banana's rule, the limes), where a
#: changed loop shows first; the others run in ``make test-slow`` (issue 50).
FAST = {"object-1", "banana", "limes"}


def outcome(name: str, seed: int) -> str:
    """The loop's outcome for ``name`` on the analytic world with sensor-noise seed ``seed``."""
    return run_simulated([name], f"sim://?seed={seed}", ExecutionParams(hold_s=0.5)).outcome


@pytest.mark.parametrize(
    "name", [n if n in FAST else pytest.param(n, marks=pytest.mark.slow) for n in NAMES], ids=NAMES
)
def test_held_rate_over_seeds_agrees_with_the_reference(name: str) -> None:
    outcomes = [outcome(name, s) for s in SEEDS]
    held = outcomes.count("held")
    ref = REFERENCE_HELD_OF_40[name]
    table = [[held, len(SEEDS) - held], [ref, 40 - ref]]
    p = float(fisher_exact(table).pvalue)
    assert p >= ALPHA, (
        f"{name}: held {held}/{len(SEEDS)} against {ref}/40 (p = {p:.2g}): {outcomes}"
    )


def test_fisher_test_has_the_power_to_fail() -> None:
    """The tolerance is not vacuous: 10 held of 10 against 16 of 40 is rejected, and so is
    3 of 10 against 40 of 40."""
    assert fisher_exact([[10, 0], [16, 24]]).pvalue < ALPHA
    assert fisher_exact([[3, 7], [40, 0]]).pvalue < ALPHA


if __name__ == "__main__":  # reference counts: python tests/control/test_table_6_1_loop.py NAME
    for name in sys.argv[1:] or NAMES:
        held = sum(outcome(name, s) == "held" for s in range(100, 140))
        print(f"{name}: {held} of 40 held")
