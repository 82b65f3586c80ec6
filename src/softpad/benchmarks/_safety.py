"""Randomised fault campaigns: the whole loop with random faults, the true pressure watched.

Each run places object 5 on the simulated box (analytic world), injects one or two faults of
random kind, channel and time (0..28 s: every phase of the loop), runs the loop and then leaves
the box alone for 30 s of box time. The simulator's true chamber pressure is read at every
frame, during the run and after; the campaign reports the peak, whether every run ended in a
verified safe state (or named the channel it could not make safe), and the detection delay of
each fault kind (fault event time minus the fault's start).
"""

from __future__ import annotations

import random
import statistics
from collections import defaultdict
from dataclasses import dataclass, field
from typing import Any

from softpad.benchmarks._common import BenchResult

#: Fault kinds of the campaign, with the argument drawn for each (a disconnect is left out:
#: after it the box cannot be read, the served box's watchdog covers it).
CAMPAIGN_KINDS = (
    "nan",
    "dropout",
    "stuck:inflate",
    "stuck:deflate",
    "stuck:closed",
    "leak",
    "supply_loss",
)
#: Stated margin of the true pressure over the maximum, Pa: the sensor's zero offset (3 x 20 Pa
#: rms) and noise (3 x 8 Pa) plus one frame of the fastest rise (530 Pa/s at 50 Hz: 11 Pa).
TRUE_MARGIN_PA = 100.0
#: Box time watched after each run, seconds.
AFTER_S = 30.0


@dataclass
class CampaignRun:
    """One run of the campaign."""

    seed: int
    faults: list[str]
    starts: dict[str, float]
    peak_true_pa: float = 0.0
    detected: list[tuple[str, float]] = field(default_factory=list)
    outcome: str = ""
    verified: bool | None = None
    channel_unsafe: int | None = None


def draw_faults(rng: random.Random, n_modules: int = 6, t_max_s: float = 28.0) -> list[str]:
    """One or two random fault specs (``KIND[:CHANNEL[:ARG]]@T``) for ``sim://?faults=``."""
    out = []
    for _ in range(rng.choice((1, 1, 2))):
        kind = rng.choice(CAMPAIGN_KINDS)
        ch = rng.randint(1, n_modules)
        t = round(rng.uniform(0.0, t_max_s), 2)
        if kind.startswith("stuck"):
            out.append(f"stuck:{ch}:{kind.split(':')[1]}@{t}")
        elif kind == "leak":
            out.append(f"leak:{ch}:{round(rng.uniform(0.005, 1.0), 3)}@{t}")
        elif kind == "supply_loss":
            out.append(f"supply_loss@{t}")
        else:
            out.append(f"{kind}:{ch}@{t}")
    return out


class _TrueWatch:
    """Recorder that keeps the peak of the simulator's true chamber pressure at every frame."""

    def __init__(self, box: Any) -> None:
        self.box = box
        self.peak = 0.0
        self.events: list[tuple[float, str, dict[str, Any]]] = []

    def frame(self, frame: Any, phase: str) -> None:
        self.peak = max(self.peak, float(self.box.true_pressures_pa.max()))

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        self.events.append((t_s, kind, data))


def run_one(seed: int, rate_hz: float = 50.0) -> CampaignRun:
    """Run the loop once with the faults drawn from ``seed``; watch the true pressure."""
    from softpad.box import open_box
    from softpad.control import ExecutionParams
    from softpad.errors import HardwareFault, SoftPadError
    from softpad.harness import run_simulated

    specs = draw_faults(random.Random(seed))
    run = CampaignRun(seed, specs, {s: float(s.rpartition("@")[2]) for s in specs})
    box = open_box(f"sim://?seed={seed}&rate_hz={rate_hz:g}&faults={','.join(specs)}")
    watch = _TrueWatch(box)
    try:
        res = run_simulated(["object-5"], box, ExecutionParams(hold_s=15.0), watch)
        run.outcome = res.outcome
    except HardwareFault as exc:
        run.outcome = "fault"
        safe = getattr(exc, "safe_state", None)
        if safe is not None:
            run.verified, run.channel_unsafe = safe.verified, safe.channel_unsafe
    except SoftPadError as exc:  # e.g. the object not seen: the loop stops, valves closed
        run.outcome = f"error: {type(exc).__name__}"
    run.detected = [(d.get("cause", "?"), t) for t, k, d in watch.events if k == "fault"]
    for _ in range(round(AFTER_S * rate_hz)):  # nobody commands anything: the box alone
        box.read()
        watch.frame(None, "after")
    run.peak_true_pa = watch.peak
    box.close()
    return run


def _kind(spec: str) -> str:
    head = spec.partition("@")[0].split(":")
    return f"stuck:{head[2]}" if head[0] == "stuck" else head[0]


def summarise(runs: list[CampaignRun]) -> dict[str, Any]:
    """Figures of a campaign: runs, faults, peak true pressure, detection delay per kind."""
    delays: dict[str, list[float]] = defaultdict(list)
    for r in runs:
        if r.detected:
            t_det = r.detected[0][1]
            first = min(r.starts.items(), key=lambda kv: kv[1])
            if t_det >= first[1]:
                delays[_kind(first[0])].append(t_det - first[1])
    return {
        "runs": len(runs),
        "faults": sum(len(r.faults) for r in runs),
        "faulted_runs": sum(r.outcome == "fault" for r in runs),
        "peak_true_pa": max(r.peak_true_pa for r in runs),
        "unverified": sum(r.verified is False for r in runs),
        "delay_s": {k: statistics.median(v) for k, v in sorted(delays.items())},
        "delay_max_s": {k: max(v) for k, v in sorted(delays.items())},
    }


def run(quick: bool) -> list[BenchResult]:
    """The campaign as benchmark figures (``softpad bench --only safety``)."""
    from softpad.box import RATED_MAX_PRESSURE_PA

    n = 12 if quick else 60
    runs = [run_one(1000 + s) for s in range(n)]
    s = summarise(runs)
    limit = RATED_MAX_PRESSURE_PA + TRUE_MARGIN_PA
    out = [
        BenchResult(
            "fault campaign: peak true chamber pressure, during runs and 30 s after",
            s["peak_true_pa"] / 1e3,
            "kPa",
            target=f"<= {limit / 1e3:g} kPa",
            met=s["peak_true_pa"] <= limit,
            detail=f"{s['runs']} runs, {s['faults']} faults (seeds 1000..{999 + n}), 50 Hz, object 5",
        ),
        BenchResult(
            "fault campaign: runs ended by a detected fault",
            s["faulted_runs"],
            "runs",
            detail=f"of {s['runs']}; {s['unverified']} ended unverified, naming the channel",
        ),
    ]
    for kind, d in s["delay_s"].items():
        out.append(
            BenchResult(
                f"fault campaign: detection delay, {kind}",
                d,
                "s (median)",
                detail=f"max {s['delay_max_s'][kind]:.2f} s; from the fault's start to its event",
            )
        )
    from softpad.benchmarks._attacks import run as run_attacks

    out.extend(run_attacks(quick))
    return out
