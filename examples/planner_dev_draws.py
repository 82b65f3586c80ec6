"""Development draws of the model-based planner (issue 47): analytic-world readings of the
development half (ycb-dev) at seeds 1000 and up, the planner's grasp, and where the open
jaws come down on the object's true outline. Development only: never run it on an
evaluation set or on evaluation seeds.

    PYTHONPATH=src python examples/planner_dev_draws.py --seeds 10 [--mounting auto] [--planner NAME]

Per object: ``hit`` (a jaw's path crosses the object's outline within the fingertip's width:
the jaws would land on it), ``outside`` (the grasp centre over 3 mm off the object),
``narrow`` (the object narrower than the jaws' minimum opening there), ``ok``, ``none`` (no
object detected); ``unsensed`` counts plans whose better fingertip's mean response (the
planner's pad model) is under half the centre's. A geometric proxy of the MuJoCo trial: no
sensing, closing or holding is simulated.
"""

from __future__ import annotations

import argparse
import collections

import numpy as np

from softpad import thesis
from softpad.layout import GripperSpec, PadLayout
from softpad.planning import make_planner
from softpad.planning._model_based import packaged_pad_model, tip_response
from softpad.sim import Placement
from softpad.trials._config import TrialConfig
from softpad.trials._geometry import distance_to_object_m, half_extent_along_m
from softpad.trials._loop import configured_mounting, varied_lab
from softpad.trials._runner import perturbed_placement, trial_seed
from softpad.trials._survey import pad_reading

DEV_SET = "src/softpad/data/object_sets/ycb-dev.toml"
FIRST_SEED = 1000


def outcome(obj, placement, plan, gripper, layout) -> str:
    """What the jaws of ``plan`` meet on the object's true outline."""
    cog = (plan.cog[0] * layout.pitch_m, plan.cog[1] * layout.pitch_m)
    place = Placement(*placement)
    ext = half_extent_along_m(obj, place, cog, plan.theta, band_m=gripper.tip_width_m / 2)
    if distance_to_object_m(cog, obj, place) > 0.003:
        return "outside"
    if ext is None:
        return "nothing_between"
    if ext > gripper.max_width_m / 2:
        return "hit"
    return "narrow" if 2 * ext < gripper.min_width_m else "ok"


def main(argv: list[str] | None = None) -> collections.Counter[str]:
    """Print the draws' outcomes per object and in total; return the total counts."""
    from softpad.cli._trials import select_objects

    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--mounting", default=None)
    ap.add_argument("--planner", default="model-based")
    args = ap.parse_args(argv)
    layout, model = PadLayout(), packaged_pad_model()
    total: collections.Counter[str] = collections.Counter()
    for spec in select_objects(None, DEV_SET):
        c: collections.Counter[str] = collections.Counter()
        for seed in range(FIRST_SEED, FIRST_SEED + args.seeds):
            s = trial_seed(seed, spec.name, 0)
            cfg = TrialConfig(
                randomize=True, planner=args.planner, detector="adaptive", mounting=args.mounting
            )
            obj, cfg, lab = varied_lab(spec, s, cfg)
            placement = perturbed_placement(obj, s, cfg)
            reading = pad_reading(obj, placement, s, cfg, lab)
            mounting = configured_mounting(obj, placement, s, cfg, lab) or obj.gripper
            c["mounting " + mounting] += 1
            gripper = GripperSpec.from_mounting(mounting)
            t_o = thesis.OBJECT_THRESHOLD_PA
            objects = layout.connected_groups(tuple(k for k, v in enumerate(reading, 1) if v > t_o))
            if not objects:
                c["none"] += 1
                continue
            plans = make_planner(args.planner, gripper=gripper).plan(reading, objects, layout)
            plan = max(plans, key=lambda p: sum(reading[m - 1] for m in p.modules))
            c[outcome(obj, placement, plan, gripper, layout)] += 1
            tip = tip_response(np.array([plan.cog]), np.array([plan.theta]), gripper, layout, model)
            c["unsensed"] += int(tip[0] < 0.5)
        print(f"{spec.name:28s} " + " ".join(f"{k}={v}" for k, v in sorted(c.items())))
        total.update(c)
    print("total", " ".join(f"{k}={v}" for k, v in sorted(total.items())))
    return total


if __name__ == "__main__":
    main()
