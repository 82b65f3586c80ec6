"""``softpad learn``: a catalogue of known objects from recorded trials with their outcomes."""

from __future__ import annotations

import argparse
from typing import Any

from softpad.cli._args import add_command
from softpad.errors import InputError

_EPILOG = """examples:
  softpad trials --seeds 0-1 --record train.mcap        record 2 x 55 trials (one file each)
  softpad learn train-*.mcap --out catalogue.toml       learn the objects held in them
  softpad compare --pair catalogue:adaptive --catalogue catalogue.toml --seeds 2-3 --randomize

Each recording is one trial of one object (softpad trials --record; one without a plan of
one object or an outcome is skipped and counted): its first plan's
increments are the object's reading, its last grasp (after any retry) the grasp tried, and
its outcome says whether it held. An object held at least once is known: its readings and
the grasps that held it go into the catalogue, with tolerances learned from the spread of
its held readings. --planner catalogue recognises a known object when the reading's load
pattern (module shares) and total load lie within the object's tolerances of one of its held
readings, and grasps it as that trial did; any other object goes to the model-based planner
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
    p.set_defaults(handler=run)


def learned_trial(run: Any) -> tuple[Any, float] | None:
    """The :class:`~softpad.planning.LearnedTrial` of one recorded trial and the variance of
    a planning increment under its sensor noise, Pa^2 (per-frame variance / 5: the mean of 10
    reads minus a reference of 10); None for a trial that teaches nothing (no plan of one
    object or no outcome: the object was not detected, the box faulted)."""
    from softpad.planning import LearnedTrial

    name = f"recording {str(run.path)!r}"
    objects = run.metadata.get("objects")
    if not (isinstance(objects, list) and len(objects) == 1):
        raise InputError(f"{name}: not a trial of one object (objects {objects!r})")
    plans = [d for _, kind, d in run.events if kind == "plan"]
    outcomes = [d.get("outcome") for _, kind, d in run.events if kind == "outcome"]
    if not plans or not outcomes or len(plans[0].get("objects", [])) != 1:
        return None
    first = plans[0]["objects"][0]
    grasp = (float(first["cog"][0]), float(first["cog"][1]), float(first["theta"]))
    for _, kind, d in run.events:
        if kind == "retry":  # the grasp tried last
            grasp = (float(d["cog"][0]), float(d["cog"][1]), float(d["theta"]))
    increments = tuple(float(v) for v in plans[0]["increments_pa"])
    variance = float(run.metadata.get("pressure_variance_pa2", 0.0)) / 5
    return LearnedTrial(str(objects[0]), increments, grasp, outcomes[-1] == "held"), variance


def run(args: argparse.Namespace) -> int:
    import statistics

    from softpad.cli._output import emit, say
    from softpad.cli._paths import check_output
    from softpad.planning import learn_catalogue
    from softpad.record import load_recording

    out = check_output(args.out, "--out", force=args.force, suffix=".toml")
    assert out is not None
    learned = [learned_trial(load_recording(path)) for path in args.recordings]
    pairs = [x for x in learned if x is not None]
    if not pairs:
        raise InputError("no recording holds a plan of one object and its outcome")
    trials = [t for t, _ in pairs]
    variance = statistics.median(v for _, v in pairs)
    if not variance > 0:
        raise InputError("the recordings carry no sensor noise (pressure_variance_pa2)")
    catalogue = learn_catalogue(trials, variance)
    out.write_text(catalogue.to_toml(), encoding="utf-8")
    held = sum(t.held for t in trials)
    if args.json:
        emit(
            {
                "out": str(out),
                "objects": [o.name for o in catalogue.objects],
                "trials": len(trials),
                "skipped": len(learned) - len(pairs),
                "held": held,
                "increment_noise_pa": round(variance**0.5, 3),
                "tolerances": {
                    o.name: [round(o.share_tolerance, 3), round(o.load_tolerance, 3)]
                    for o in catalogue.objects
                },
            }
        )
        return 0
    say(
        f"{out}: {len(catalogue.objects)} known objects from {len(trials)} trials "
        f"({held} held; {len(learned) - len(pairs)} recordings without a plan of one object "
        f"skipped); increment noise {variance**0.5:.1f} Pa"
    )
    return 0
