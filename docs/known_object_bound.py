"""What knowing the object would buy: the first grasp of a planner that knows which object
lies on the pad and has seen many other placements of it (a development aid,
docs/beat-the-thesis.md section 5e).

    python docs/known_object_bound.py TRIALS.json [TRIALS.json ...] [--objects-file FILE.toml]

TRIALS.json: the output of ``softpad trials --randomize --json``. Every grasp of a fixed set
(centres on a 1/8-module grid over the pad, closing directions 15 degrees apart) is judged
against each recorded object as its trial drew it, with ``docs/replay_first_grasp.py``'s rule:
the centre inside the outline, the outline under a fingertip's width within the open jaws and
at least as wide as the closed ones. A trial's grasp is then chosen from the *other* trials of
the same object (leave one out): the grasp that works for the most of them, each weighted by
how close its recorded increments are to this trial's (Gaussian, the sensor's 5.5 Pa noise on
both readings and 10 % of each reading for the lab's varied physics). That is the Bayes
decision under a prior made of the object's own placements, so it bounds what any planner
reaches with these readings once it knows the object; a second grasp is chosen the same way
from the placements where the first would have failed.

With ``--other-objects`` the prior is every *other* object's placements instead: a planner
that has seen the rest of the set meets this object for the first time. With ``--ignore-readings`` every trial of the prior
weighs alike: what the object's identity and its usual place give without any sensing.
"""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

import numpy as np
from matplotlib.path import Path as MplPath

from softpad.cli._trials import select_objects
from softpad.layout import GripperSpec, PadLayout
from softpad.sensing import DEFAULT_OUTLINE_THRESHOLD_PA
from softpad.sim import LabVariation
from softpad.trials._geometry import _densify, object_outlines_m
from softpad.trials._loop import _Placed

#: Grasp centres per module side, and closing directions in [0, pi).
STEPS, DIRECTIONS = 8, 12
#: Relative spread of a module's increment between two trials of one placement.
SPREAD = 0.1


def grasps(layout: PadLayout) -> tuple[np.ndarray, np.ndarray]:
    """Grasp centres (G, 2), metres, and closing directions (D,), radians."""
    xs = (np.arange(layout.cols * STEPS) + 0.5) / STEPS
    ys = (np.arange(layout.rows * STEPS) + 0.5) / STEPS
    cx, cy = np.meshgrid(xs, ys, indexing="ij")
    centres = np.column_stack([cx.ravel(), cy.ravel()]) * layout.pitch_m
    return centres, np.arange(DIRECTIONS) * math.pi / DIRECTIONS


def works(spec: Any, placed: Any, gripper: GripperSpec, layout: PadLayout) -> np.ndarray:
    """Which grasps of :func:`grasps` pass the geometric judge on this object: (D * G,)."""
    centres, thetas = grasps(layout)
    polys = object_outlines_m(spec, placed)
    pts = np.vstack([_densify(p, 0.5e-3) for p in polys])
    inside = np.zeros(len(centres), dtype=bool)
    for p in polys:
        inside |= MplPath(p).contains_points(centres)
    out = []
    for th in thetas:
        u, n = np.array([math.cos(th), math.sin(th)]), np.array([-math.sin(th), math.cos(th)])
        under = np.abs((pts @ n)[None, :] - (centres @ n)[:, None]) <= gripper.tip_width_m / 2
        reach = np.abs((pts @ u)[None, :] - (centres @ u)[:, None])
        extent = np.where(under, reach, -1.0).max(axis=1)
        fits = (extent >= 0) & (extent <= gripper.max_width_m / 2)
        out.append(inside & fits & (2 * extent >= gripper.min_width_m))
    return np.concatenate(out)


def bayes_choices(
    readings: np.ndarray,
    ok: np.ndarray,
    prior: np.ndarray,
    judged: np.ndarray,
    use_readings: bool = True,
) -> tuple[int, int]:
    """First grasps and first-or-second grasps that work on the ``judged`` trials, each
    chosen from the trials its row of ``prior`` (bool, N x N) allows (see the docstring)."""
    noise = 2 * DEFAULT_OUTLINE_THRESHOLD_PA**2
    spread = SPREAD * (np.abs(readings)[:, None, :] + np.abs(readings)[None, :, :])
    var = noise + spread**2
    weight = np.exp(-0.5 * ((readings[:, None, :] - readings[None, :, :]) ** 2 / var).sum(-1))
    weight = prior * (weight if use_readings else 1.0)
    okf = ok.astype(float)
    first = second = 0
    for j in np.flatnonzero(judged):
        g1 = int(np.argmax(weight[j] @ okf))
        if ok[j, g1]:
            first += 1
            second += 1
            continue
        g2 = int(np.argmax((weight[j] * (1.0 - okf[:, g1])) @ okf))
        second += int(ok[j, g2])
    return first, second


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("trials", nargs="+")
    ap.add_argument("--objects-file")
    ap.add_argument(
        "--other-objects",
        action="store_true",
        help="choose each trial's grasp from the other objects' trials only (an unknown object)",
    )
    ap.add_argument(
        "--ignore-readings",
        action="store_true",
        help="weigh the prior's trials alike, whatever their increments (no sensing)",
    )
    args = ap.parse_args()
    layout = PadLayout()
    specs = {s.name: s for s in select_objects(None, args.objects_file)}
    rows: dict[str, list[tuple[list[float], np.ndarray]]] = {}
    for path in args.trials:
        with open(path, encoding="utf-8") as fh:
            for t in json.load(fh)["trials"]:
                if t["object"] not in specs or not t["increments_pa"]:
                    continue
                spec = specs[t["object"]]
                obj = LabVariation.of(t["parameters"]).object(spec) if t["parameters"] else spec
                gripper = GripperSpec.from_mounting(t["mounting"])
                ok = works(obj, _Placed(*t["placement"]), gripper, layout)
                rows.setdefault(t["object"], []).append((t["increments_pa"], ok))
    names = [name for name, rs in rows.items() for _ in rs]
    readings = np.array([r[0] for rs in rows.values() for r in rs], dtype=float)
    ok = np.array([r[1] for rs in rows.values() for r in rs])
    same = np.equal.outer(names, names)
    prior = ~same if args.other_objects else same & ~np.eye(len(names), dtype=bool)
    total = [0, 0, 0]
    for name, rs in rows.items():
        judged = np.array([n == name for n in names])
        first, second = bayes_choices(readings, ok, prior, judged, not args.ignore_readings)
        some = sum(bool(r[1].any()) for r in rs)
        print(
            f"{name:24s} trials {len(rs):4d}  some grasp works {some:4d}  "
            f"first grasp {first:4d}  first or second {second:4d}"
        )
        total = [total[0] + len(rs), total[1] + first, total[2] + second]
    n = max(total[0], 1)
    print(
        f"{'all':24s} trials {total[0]:4d}  first {total[1]} ({total[1] / n:.1%})  "
        f"first or second {total[2]} ({total[2] / n:.1%})"
    )


if __name__ == "__main__":
    main()
