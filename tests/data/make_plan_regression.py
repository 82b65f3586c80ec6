"""Generator of tests/data/plan_regression.json: fixed pad readings and every planner's plans.

    python tests/data/make_plan_regression.py              readings (simulated again) and plans
    python tests/data/make_plan_regression.py --plans-only  plans of the committed readings

Readings: Table 6.1's and Fig. 6.7's reference increments (softpad.planning.TABLE_6_1,
FIG_6_7: chosen by hand to give the thesis's PCOM) and simulated readings: two placements
(the trials' placement noise, seed 7) of every catalogue object (Table 6.1) and of every
object of the YCB evaluation set's two halves, each on the analytic world behind a noisy box
at p0 (:func:`softpad.trials._validate.static_draws`, as ``softpad validate``'s static rows).

Plans: each built-in planner (``BUILT_IN``) on each reading, told the reading's
mounting and the thesis detector's sensing ratio (1). ``--plans-only`` recomputes them after a
planner change that is meant to move plans; tests/planning/test_plan_regression.py lists the
plans a change moved until the file is regenerated.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

OUT = Path(__file__).with_name("plan_regression.json")


def reference_readings() -> list[dict[str, Any]]:
    """Table 6.1 and Fig. 6.7's hand-chosen increments, with the catalogue's mountings."""
    from softpad.planning import FIG_6_7, TABLE_6_1
    from softpad.sim import get_object, object_names

    known = set(object_names())
    out = []
    for case in TABLE_6_1 + FIG_6_7:
        mounting = get_object(case.name).gripper if case.name in known else "10/4"
        out.append(
            {
                "name": case.name,
                "source": case.source,
                "mounting": mounting,
                "increments_pa": list(case.delta_pa),
            }
        )
    return out


def simulated_readings(specs: list[Any], source: str) -> list[dict[str, Any]]:
    """Two static draws (seed 7) of every object of ``specs`` on the analytic world."""
    from softpad.trials._validate import static_draws

    out = []
    for spec in specs:
        for k, draw in enumerate(static_draws(spec, 2, seed=7)):
            out.append(
                {
                    "name": f"{spec.name}/draw{k}",
                    "source": source,
                    "mounting": spec.gripper,
                    "increments_pa": [round(v, 3) for v in draw.increments_pa],
                }
            )
    return out


def all_readings() -> list[dict[str, Any]]:
    """The reference readings, then the simulated ones (catalogue, YCB dev, YCB eval)."""
    from softpad.cli._trials import select_objects

    sets = Path(__file__).parents[2] / "src" / "softpad" / "data" / "object_sets"
    readings = reference_readings()
    readings += simulated_readings(select_objects(None), "analytic world, catalogue")
    for half in ("ycb-dev", "ycb-eval"):
        specs = select_objects(None, str(sets / f"{half}.toml"))
        readings += simulated_readings(specs, f"analytic world, {half}")
    return readings


#: The planners SoftPad registers itself (others may be installed: they have no fixed plans).
BUILT_IN = ("thesis", "gripper-aware", "model-based")


def plans_of(reading: dict[str, Any]) -> dict[str, list[dict[str, Any]]]:
    """Every planner's plans of one reading (2 x 3 pad), JSON-ready."""
    from softpad.layout import GripperSpec, PadLayout
    from softpad.planning import make_planner
    from softpad.sensing import detect_objects

    layout = PadLayout()
    d = [float(v) for v in reading["increments_pa"]]
    objects = detect_objects(d, layout)
    out = {}
    for name in BUILT_IN:
        planner = make_planner(name, gripper=GripperSpec.from_mounting(reading["mounting"]))
        plans = planner.plan(d, objects, layout)
        out[name] = [
            {
                "modules": list(p.modules),
                "cog": [round(p.cog[0], 9), round(p.cog[1], 9)],
                "theta": round(p.theta, 9),
                "rule": p.rule,
            }
            for p in plans
        ]
    return out


def main(argv: list[str]) -> None:
    if argv == ["--plans-only"]:
        readings = json.loads(OUT.read_text(encoding="utf-8"))["readings"]
    else:
        readings = all_readings()
    for r in readings:
        r["plans"] = plans_of(r)
    doc = {"schema": "softpad-plan-regression/1", "readings": readings}
    OUT.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    print(f"{len(readings)} readings written to {OUT}")


if __name__ == "__main__":
    main(sys.argv[1:])
