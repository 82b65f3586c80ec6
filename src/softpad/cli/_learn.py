"""``softpad learn``: a catalogue of known objects from recorded trials with their outcomes."""

from __future__ import annotations

import argparse
from typing import Any

from softpad.cli._args import add_command, add_number

_EPILOG = """examples:
  softpad trials --seeds 0 --record train.mcap          record 55 trials (one file each)
  softpad learn train-*.mcap --out catalogue.toml       learn the objects held in them
  softpad compare --pair catalogue:adaptive --catalogue catalogue.toml --seeds 2-3 --randomize
  softpad trials --planner catalogue --detector adaptive --catalogue catalogue.toml --seeds 2 --json

Each recording is one trial of one object (softpad trials --record; one without a plan of
one object or an outcome is skipped and counted): its first plan's
increments are the object's reading, its last grasp (after any retry) the grasp tried, and
its outcome says whether it held. An object held at least once is known: its held readings
go into the catalogue with the stated tolerances, and a grasp rule learnt from all its
trials (the closing direction that held most often; the mean centre of its held grasps, moved
with the reading's load centre). --planner catalogue recognises a known object when the
reading's load pattern (module shares) and total load lie within the tolerances of one of its
held readings, and grasps it by its rule; any other object goes to the model-based planner
(docs/planner.md).
"""


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "learn",
        "learn known objects (readings, grasps that held) from recorded trials",
        "Learn a catalogue of known objects for --planner catalogue from trial recordings.",
        _EPILOG,
        json="print what was learned as one JSON object",
        force=True,
    )
    p.add_argument("recordings", nargs="+", metavar="REC.mcap", help="trial recordings")
    p.add_argument("--out", required=True, metavar="FILE.toml", help="catalogue to write")
    add_number(
        p,
        "--acceptance-alpha",
        "narrow each object's tolerances to the conformal 1-ALPHA quantile of its own held "
        "readings' spread, 0.001..0.5 (default: the shared tolerances for every object; "
        "docs/planner.md)",
        None,
        lo=0.001,
        hi=0.5,
    )
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from softpad.cli._output import emit, say
    from softpad.cli._paths import check_output
    from softpad.planning import CatalogueParams
    from softpad.record import learn_from_recordings

    out = check_output(args.out, "--out", force=args.force, suffix=".toml")
    assert out is not None
    params = CatalogueParams(acceptance_alpha=args.acceptance_alpha)
    learned = learn_from_recordings(args.recordings, params)
    catalogue, trials = learned.catalogue, learned.trials
    out.write_text(catalogue.to_toml(), encoding="utf-8")
    held = sum(t.held for t in trials)
    noise = learned.variance_pa2**0.5
    if args.json:
        emit(
            {
                "out": str(out),
                "objects": [o.name for o in catalogue.objects],
                "trials": len(trials),
                "skipped": learned.skipped,
                "held": held,
                "increment_noise_pa": round(noise, 3),
                "tolerances": {
                    o.name: [round(o.share_tolerance, 3), round(o.load_tolerance, 3)]
                    for o in catalogue.objects
                },
            }
        )
        return 0
    say(
        f"{out}: {len(catalogue.objects)} known objects from {len(trials)} trials "
        f"({held} held; {learned.skipped} recordings without a plan of one object "
        f"skipped); increment noise {noise:.1f} Pa"
    )
    return 0
