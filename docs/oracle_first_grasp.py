"""The model-based planner's decision given the object's true outline instead of its estimate
(a development aid, docs/beat-the-thesis.md section 5c): is the estimate or the decision the
bottleneck?

    python docs/oracle_first_grasp.py TRIALS.json [--objects-file FILE.toml]

For each recorded trial the object as the trial drew it (parts, size, placement) gives one
footprint hypothesis: the smallest rectangle around its whole outline (1 degree steps). The
planner's candidates and score (``softpad.planning._model_based``, the trial's mounting, the
thesis detector's sensing ratio) choose a grasp from that certain posterior, and
``docs/replay_first_grasp.py``'s ``judge`` checks it against the true object.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

from softpad.cli._trials import select_objects
from softpad.layout import GripperSpec, PadLayout
from softpad.planning._model_based import (
    ModelBasedParams,
    Posterior,
    candidates,
    packaged_pad_model,
    predicted_success,
)
from softpad.planning._records import GraspPlan
from softpad.sim import LabVariation, Placement
from softpad.sim._footprint import part_outline, to_pad_frame

sys.path.insert(0, str(Path(__file__).parent))
from replay_first_grasp import judge, recorded_trials


def outline_m(spec: Any, placed: Placement) -> np.ndarray:
    """Points of the object's whole outline (what the jaws meet) in the pad frame, m."""
    return to_pad_frame(np.vstack([part_outline(p) for p in spec.parts]), placed)


def smallest_rectangle(pts: np.ndarray) -> tuple[np.ndarray, tuple[float, float], float]:
    """Centre, half sides and yaw of the smallest rectangle around ``pts`` (1 degree steps)."""
    best: tuple[float, Any, Any, float] | None = None
    for deg in range(180):
        a = math.radians(deg)
        u, n = np.array([math.cos(a), math.sin(a)]), np.array([-math.sin(a), math.cos(a)])
        pu, pn = pts @ u, pts @ n
        area = float(np.ptp(pu) * np.ptp(pn))
        if best is None or area < best[0]:
            centre = (pu.max() + pu.min()) / 2 * u + (pn.max() + pn.min()) / 2 * n
            best = (area, centre, (float(np.ptp(pu)) / 2, float(np.ptp(pn)) / 2), a)
    assert best is not None
    return best[1], best[2], best[3]


def oracle_plan(spec: Any, placed: Placement, gripper: GripperSpec, layout: PadLayout) -> GraspPlan:
    """The planner's choice when its posterior is the true smallest rectangle, for certain."""
    centre, halves, yaw = smallest_rectangle(outline_m(spec, placed))
    post = Posterior(
        np.array([centre]) / layout.pitch_m,
        np.array([halves]) / layout.pitch_m,
        np.array([yaw % math.pi]),
        np.array([1.0]),
    )
    params = ModelBasedParams()
    cg, tg = candidates(post, params)
    score = predicted_success(post, cg, tg, gripper, layout, packaged_pad_model(), params, 1.0)
    i = int(np.argmax(score))
    theta = float(tg[i]) - (math.pi if tg[i] > math.pi / 2 + 1e-12 else 0.0)
    return GraspPlan((1,), (0.0, 0.0), (float(cg[i, 0]), float(cg[i, 1])), theta, "oracle", (1,))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("trials", nargs="+")
    ap.add_argument("--objects-file")
    args = ap.parse_args()
    layout = PadLayout()
    specs = {s.name: s for s in select_objects(None, args.objects_file)}
    tally: dict[str, list[str]] = {}
    for t, spec in recorded_trials(args.trials, specs):
        obj = LabVariation.of(t["parameters"]).object(spec) if t["parameters"] else spec
        placed, gripper = Placement(*t["placement"]), GripperSpec.from_mounting(t["mounting"])
        plan = oracle_plan(obj, placed, gripper, layout)
        tally.setdefault(t["object"], []).append(judge(obj, placed, plan, gripper, layout.pitch_m))
    for name, verdicts in tally.items():
        ok = sum(v == "ok" for v in verdicts)
        kinds = sorted({v.rstrip("0123456789.") for v in verdicts if v != "ok"})
        print(f"{name:24s} oracle first grasp ok {ok}/{len(verdicts)} {' '.join(kinds)}")


if __name__ == "__main__":
    main()
