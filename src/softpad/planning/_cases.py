"""Reference cases: Table 6.1, Fig. 6.7 and one case per planning rule.

Increments are chosen by hand (pascals) so that Eq. (6.1) gives the PCOM the thesis implies,
with every touched module above t_o; the expected plans are the thesis's numbers (Table 6.1,
Fig. 6.7) or, for the rule cases, worked out by hand in docs/planner.md. They are data, used
by the tests, the demo and the documentation; the planner never reads them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class PlanCase:
    """One reference pattern on the 2 x 3 pad."""

    #: Case name (Table 6.1 object, figure panel or rule).
    name: str
    #: Increments of modules 1..6, pascals.
    delta_pa: tuple[float, ...]
    #: Expected centre of grasp, module units.
    cog: tuple[float, float]
    #: Expected direction of grasp, radians.
    theta: float
    #: Expected rule name (empty when not pinned).
    rule: str = ""
    #: Where the expected plan comes from.
    source: str = ""
    #: Object weight from Table 6.1 / Fig. 6.7, grams (0 when not given).
    weight_g: float = 0.0


def _d(**modules: float) -> tuple[float, ...]:
    v = [0.0] * 6
    for key, value in modules.items():
        v[int(key[1:]) - 1] = float(value)
    return tuple(v)


PI = math.pi

#: Table 6.1 of the thesis: one representative planned grasp per object.
TABLE_6_1: tuple[PlanCase, ...] = (
    PlanCase("object-1", _d(m3=62, m6=62), (2.5, 1.0), 0.0, "n2-vertical", "Table 6.1", 23.8),
    PlanCase(
        "object-2", _d(m1=60, m5=70.4348), (1.04, 0.96), PI / 4, "n2-diagonal", "Table 6.1", 25.3
    ),
    PlanCase("object-3", _d(m1=77, m2=77, m3=77), (1.5, 1.5), PI / 2, "n3-row", "Table 6.1", 44.4),
    PlanCase("object-4", _d(m1=189, m4=81), (0.5, 1.2), 0.0, "n2-vertical", "Table 6.1", 52.0),
    PlanCase(
        "object-5",
        _d(m1=114.75, m2=155.25, m3=67.5),
        (1.36, 1.5),
        PI / 2,
        "n3-row",
        "Table 6.1",
        64.9,
    ),
    PlanCase(
        "object-6", _d(m4=190, m5=222, m6=222), (1.55, 0.5), PI / 2, "n3-row", "Table 6.1", 122.0
    ),
    PlanCase(
        "banana",
        _d(m2=124, m3=78, m4=109),
        (1.0, 1.0),
        -PI / 4,
        "n3-diagonal-corner",
        "Table 6.1",
        59.8,
    ),
    PlanCase(
        "toy",
        _d(m1=205, m3=274, m5=205),
        (2.0, 1.0),
        -PI / 4,
        "n3-diagonal-corner",
        "Table 6.1",
        131.6,
    ),
    PlanCase(
        "limes",
        _d(m2=97, m4=194, m5=408, m6=272),
        (1.5, 0.8),
        0.0,
        "n4-drop-farthest > n3-corner-shift",
        "Table 6.1",
        187.0,
    ),
    PlanCase(
        "cylinder",
        _d(m1=253, m2=242, m3=55, m4=253, m5=242, m6=55),
        (1.14, 1.0),
        PI / 2,
        "n6-major-axis",
        "Table 6.1",
        88.9,
    ),
    PlanCase(
        "charger",
        _d(m1=380, m2=323.404, m3=105.106, m4=380, m5=323.404, m6=105.106),
        (1.16, 1.0),
        PI / 2,
        "n6-major-axis",
        "Table 6.1",
        312.3,
    ),
)

#: Fig. 6.7 of the thesis: objects on modules 1 and 4.
FIG_6_7: tuple[PlanCase, ...] = (
    PlanCase("fig6.7a", _d(m1=92, m4=108), (0.5, 0.96), 0.0, "n2-vertical", "Fig. 6.7a", 38.0),
    PlanCase("fig6.7b-left", _d(m1=136, m4=64), (0.5, 1.18), 0.0, "n2-vertical", "Fig. 6.7b left"),
    PlanCase(
        "fig6.7b-right",
        _d(m1=199, m4=81.2676),
        (0.5, 1.21),
        0.0,
        "n2-vertical",
        "Fig. 6.7b right",
        54.0,
    ),
)

#: One case per rule of the 2 x 3 planner (expected values worked out by hand).
RULE_CASES: tuple[PlanCase, ...] = (
    PlanCase("n1-module-centre", _d(m3=100), (2.5, 1.5), 0.0, "n1-module-centre", "N = 1"),
    PlanCase("n2-horizontal", _d(m4=100, m5=300), (1.25, 0.5), PI / 2, "n2-horizontal", "N = 2"),
    PlanCase("n2-vertical", _d(m2=300, m5=100), (1.5, 1.25), 0.0, "n2-vertical", "N = 2"),
    PlanCase("n2-diagonal", _d(m2=100, m4=100), (1.0, 1.0), -PI / 4, "n2-diagonal", "N = 2"),
    PlanCase(
        "n3-row", _d(m4=100, m5=100, m6=200), (1.75, 0.5), PI / 2, "n3-row", "N = 3, Fig. 6.4d-(1)"
    ),
    PlanCase(
        "n3-corner-side",
        _d(m1=600, m2=300, m5=100),
        (0.9, 1.5),
        PI / 2,
        "n3-corner-side",
        "Fig. 6.4d-(2)",
    ),
    PlanCase(
        "n3-corner-shift",
        _d(m1=250, m2=600, m5=150),
        (1.05, 1.5),
        PI / 2,
        "n3-corner-shift",
        "Fig. 6.4d-(3)",
    ),
    PlanCase(
        "n3-diagonal-side",
        _d(m2=200, m3=100, m4=700),
        (0.85, 0.85),
        -PI / 4,
        "n3-diagonal-side",
        "Fig. 6.4d-(4)",
    ),
    PlanCase(
        "n3-diagonal-corner",
        _d(m2=400, m3=250, m4=350),
        (1.0, 1.0),
        -PI / 4,
        "n3-diagonal-corner",
        "Fig. 6.4d-(5)",
    ),
    PlanCase(
        "n3-diagonal-shift",
        _d(m2=500, m3=300, m4=200),
        (1.8, 1.5),
        PI / 2,
        "n3-diagonal-shift",
        "Fig. 6.4d-(4)(5), straight link",
    ),
    PlanCase(
        "n4-square-centre",
        _d(m1=100, m2=300, m4=100, m5=100),
        (1.0, 1.0),
        0.0,
        "n4-square-centre",
        "N = 4",
    ),
    PlanCase(
        "n4-drop-farthest",
        _d(m2=100, m4=200, m5=420, m6=280),
        (1.5, 0.8),
        0.0,
        "n4-drop-farthest > n3-corner-shift",
        "Fig. 6.4e",
    ),
    PlanCase(
        "n5-horseshoe-central",
        _d(m1=100, m3=100, m4=100, m5=100, m6=100),
        (1.5, 0.5),
        PI / 2,
        "n5-horseshoe-central",
        "Fig. 6.4f-(1)",
    ),
    PlanCase(
        "n5-horseshoe-reduce",
        _d(m1=400, m3=50.01, m4=400, m5=100, m6=50.01),
        (0.5, 1.15),
        0.0,
        "n5-horseshoe-reduce > n3-corner-shift",
        "Fig. 6.4f-(2)",
    ),
    PlanCase(
        "n5-square-plus-one/in-square",
        _d(m2=100, m3=100, m4=100, m5=100, m6=100),
        (1.7, 1.0),
        PI / 2,
        "n5-square-plus-one/in-square",
        "N = 5",
    ),
    PlanCase(
        "n5-square-plus-one/single",
        _d(m2=60, m3=60, m4=960, m5=60, m6=60),
        (0.8, 0.5),
        PI / 2,
        "n5-square-plus-one/single",
        "Fig. 6.4f-(3)",
    ),
    PlanCase(
        "n6-major-axis",
        _d(m1=100, m2=100, m3=200, m4=100, m5=100, m6=200),
        (1.75, 1.0),
        PI / 2,
        "n6-major-axis",
        "N = 6",
    ),
)
