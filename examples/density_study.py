"""How dense must a pad be? (issue 47, item 5; docs/design.md, "Pad density").

Four pads on about the thesis's area (2x3 at 45 mm, 3x4 at 34 mm, 3x5 at 27 mm, 4x6 at
22.5 mm), each with its own FEM response, under the thesis, gripper-aware and model-based
planners, on the YCB development half and the held-out evaluation half, with --randomize and
placements anywhere on the pad (the sets' own). Each (set, pair) is a `softpad design` sweep
of the four pads (quick mesh, 2 s hold, one worker, the design cache).

    nice -n 10 python examples/density_study.py --dev-seeds 1000-1001 --eval-seeds 9301-9302 \\
        --png docs/figures/design_density.png --json density.json

prints the Markdown table, the mesh convergence and the answer (the pad with the fewest
modules on which the model-based planner holds 85 % of the held-out objects).
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any


def _seeds(text: str) -> list[int]:
    from softpad.cli._args import int_ranges

    return list(int_ranges(text, "--seeds", lo=0, hi=2**32 - 1))


def parse(argv: list[str] | None = None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--dev-set", default="ycb-dev")
    p.add_argument("--eval-set", default="ycb-eval")
    p.add_argument("--dev-seeds", default="1000")
    p.add_argument("--eval-seeds", default="9301")
    p.add_argument("--only", choices=("dev", "eval"), default=None, help="one of the two sets")
    p.add_argument("--trials", type=int, default=1, help="trials per object and seed")
    p.add_argument("--objects", type=int, default=None, help="the first N objects of each set")
    p.add_argument("--pads", default=None, help="pads by index into DENSITY_PADS, e.g. 0,3")
    p.add_argument("--valves", default="sized", choices=("thesis", "sized"))
    p.add_argument("--cache", default=None, help="cache folder (default ~/.cache/softpad/design)")
    p.add_argument("--png", default=None, help="write the Pareto figure")
    p.add_argument("--json", default=None, help="write the study as JSON")
    return p.parse_args(argv)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    from softpad.design import (
        DENSITY_PADS,
        ResultCache,
        default_cache_dir,
        density_study,
        example_object_set,
    )
    from softpad.design._density import subset

    args = parse(argv)
    pads = DENSITY_PADS
    if args.pads is not None:
        pads = tuple(DENSITY_PADS[int(i)] for i in args.pads.split(","))
    names = {"dev": args.dev_set, "eval": args.eval_set}
    chosen = [names[args.only]] if args.only else list(names.values())
    sets = [subset(example_object_set(n), args.objects) for n in chosen]
    seeds = {args.dev_set: _seeds(args.dev_seeds), args.eval_set: _seeds(args.eval_seeds)}
    cache = ResultCache(args.cache if args.cache is not None else default_cache_dir())
    study = density_study(
        sets, seeds, args.trials, pads, valves=args.valves, cache=cache,
        progress=lambda line: print(line, file=sys.stderr, flush=True),
    )  # fmt: skip
    held = chosen[-1]
    answer = study.smallest_pad("model-based:adaptive", held, 0.85)
    print(study.table_markdown())
    for pad, figures in study.convergence.items():
        diffs = ", ".join(
            f"{k} {100 * v['relative_difference']:+.1f} %" for k, v in figures.items()
        )
        print(f"{pad}: coarse vs medium mesh: {diffs}")
    verb = "holds 85 % first on" if answer["reached"] else "does not reach 85 %; best"
    print(f"model-based:adaptive on {held} {verb} {answer['pad']} "
          f"({answer['successes']}/{answer['trials']})")  # fmt: skip
    if args.png:
        import matplotlib.pyplot as plt

        plt.close(study.plot(args.png, held))
    out = {**study.to_dict(), "answer": answer}
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(out, f, indent=1)
    return out


if __name__ == "__main__":
    main()
