"""The plans of a fixed set of pad readings, each planner's, against the committed ones.

A change to a planner that moves a plan fails here with the list of moved plans (reading,
planner, committed -> new); when the move is intended, regenerate the file with
``python tests/data/make_plan_regression.py --plans-only`` and commit it with the change.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from softpad.planning import available_planners

DATA = Path(__file__).parents[1] / "data"
#: The built-in planners (tests/data/make_plan_regression.py's BUILT_IN), all registered.
PLANNERS = ("thesis", "gripper-aware", "model-based")
assert set(PLANNERS) <= set(available_planners())
DOC = json.loads((DATA / "plan_regression.json").read_text(encoding="utf-8"))


def _moved(old: list[dict], new: list[dict]) -> bool:
    if len(old) != len(new):
        return True
    for a, b in zip(old, new, strict=True):
        if a["modules"] != b["modules"] or a["rule"] != b["rule"]:
            return True
        if math.dist(a["cog"], b["cog"]) > 1e-6 or abs(a["theta"] - b["theta"]) > 1e-6:
            return True
    return False


def test_the_set_covers_the_reference_cases_and_simulated_readings() -> None:
    sources = {r["source"] for r in DOC["readings"]}
    assert {"Table 6.1", "Fig. 6.7a"} <= sources
    assert {"analytic world, catalogue", "analytic world, ycb-eval"} <= sources
    for r in DOC["readings"]:
        assert set(r["plans"]) == set(PLANNERS)


@pytest.mark.parametrize("planner", PLANNERS)
def test_no_plan_moved(planner: str) -> None:
    import runpy

    maker = runpy.run_path(str(DATA / "make_plan_regression.py"), run_name="not_main")
    moved = []
    for r in DOC["readings"]:
        new = maker["plans_of"](r)[planner]
        if _moved(r["plans"][planner], new):
            moved.append(f"{r['name']}: {r['plans'][planner]} -> {new}")
    assert not moved, f"{len(moved)} {planner} plan(s) moved:\n" + "\n".join(moved)
