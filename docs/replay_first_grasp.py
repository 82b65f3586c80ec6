"""Re-plan the increments of recorded trials with today's model-based planner and judge its
first grasp against the true object, without MuJoCo (a development aid, docs/beat-the-thesis.md
section 5c).

    python docs/replay_first_grasp.py TRIALS.json [TRIALS.json ...] [--objects-file FILE.toml] [-v]

TRIALS.json: the output of ``softpad trials --randomize --json``. For each trial the planner
(``--planner model-based``, the trial's mounting, the thesis detector's sensing ratio) plans
the recorded increments; the plan is checked against the object as the trial drew it (size
unknowns from the trial's parameters, its placement): ``ok``, ``cog_out<mm>`` (the centre
off the footprint), ``jaw_hit<mm>`` (the footprint under a fingertip's width reaches past the
open jaws by that much: a jaw comes down on it), ``narrow`` (under the minimum width) or
``outside_jaws``. Only the first grasp: a retry, the jaws pushing the object, a round object
sliding off a jaw are not modelled, so it is a pessimistic proxy of the trial.
"""

from __future__ import annotations

import argparse
import json
import math
from collections.abc import Iterator
from typing import Any

import numpy as np

from softpad.cli._trials import select_objects
from softpad.layout import GripperSpec, PadLayout
from softpad.planning import make_planner
from softpad.sensing import detect_objects
from softpad.sim import LabVariation
from softpad.trials._geometry import distance_to_object_m, half_extent_along_m
from softpad.trials._loop import _Placed


def judge(spec: Any, placed: Any, plan: Any, gripper: GripperSpec, pitch_m: float) -> str:
    """The first grasp's geometric verdict (see the module's docstring)."""
    centre = (plan.cog[0] * pitch_m, plan.cog[1] * pitch_m)
    extent = half_extent_along_m(spec, placed, centre, plan.theta, band_m=gripper.tip_width_m / 2)
    off_mm = 1e3 * distance_to_object_m(centre, spec, placed)
    if extent is None:
        return "outside_jaws"
    if off_mm > 0.5:
        return f"cog_out{off_mm:.0f}"
    if extent > gripper.max_width_m / 2:
        return f"jaw_hit{1e3 * (extent - gripper.max_width_m / 2):.1f}"
    return "narrow" if 2 * extent < gripper.min_width_m else "ok"


def replay(trial: dict[str, Any], spec: Any, layout: PadLayout) -> tuple[str, Any]:
    """The verdict on one recorded trial and the plan judged."""
    obj = LabVariation.of(trial["parameters"]).object(spec) if trial["parameters"] else spec
    inc = np.asarray(trial["increments_pa"], dtype=float)
    gripper = GripperSpec.from_mounting(trial["mounting"])
    planner = make_planner("model-based", gripper=gripper)
    plans = planner.plan(list(inc), detect_objects(list(inc), layout), layout)
    if not plans:
        return "not_found", None
    plan = max(plans, key=lambda p: sum(inc[m - 1] for m in p.modules))
    return judge(obj, _Placed(*trial["placement"]), plan, gripper, layout.pitch_m), plan


def recorded_trials(
    paths: list[str], specs: dict[str, Any]
) -> Iterator[tuple[dict[str, Any], Any]]:
    """Each recorded trial of ``paths`` whose object is in ``specs`` and was found at t_o, with
    that object's spec."""
    for path in paths:
        with open(path, encoding="utf-8") as fh:
            trials = json.load(fh)["trials"]
        for t in trials:
            if t["object"] in specs and t["increments_pa"]:
                yield t, specs[t["object"]]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("trials", nargs="+")
    ap.add_argument("--objects-file")
    ap.add_argument("-v", action="store_true", help="one line per trial")
    args = ap.parse_args()
    layout = PadLayout()
    specs = {s.name: s for s in select_objects(None, args.objects_file)}
    tally: dict[str, list[tuple[str, bool]]] = {}
    for t, spec in recorded_trials(args.trials, specs):
        verdict, plan = replay(t, spec, layout)
        tally.setdefault(t["object"], []).append((verdict, t["success"]))
        if args.v and plan is not None:
            x, y, yaw = t["placement"]
            print(
                f"{t['object']:24s} {verdict:12s} held={t['success']!s:5s} plan=({plan.cog[0]:.2f}, "
                f"{plan.cog[1]:.2f}, {math.degrees(plan.theta):.0f} deg) object=({x / layout.pitch_m:.2f}, "
                f"{y / layout.pitch_m:.2f}, {math.degrees(yaw):.0f} deg) {plan.rule}"
            )
    for name, rows in tally.items():
        ok, held = sum(v == "ok" for v, _ in rows), sum(h for _, h in rows)
        print(f"{name:24s} first grasp ok {ok}/{len(rows)}, trials held {held}/{len(rows)}")


if __name__ == "__main__":
    main()
