"""Side-by-side comparison of planner/detector pairs on Experiment 2 over many seeds."""

from __future__ import annotations

import statistics
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

import softpad
from softpad.errors import InputError
from softpad.planning import UNKNOWN_RULE, known_name
from softpad.trials._clustered import contrasts
from softpad.trials._config import TrialConfig
from softpad.trials._records import TrialResult, errored_records
from softpad.trials._runner import run_experiments
from softpad.trials._stats import wilson_interval

#: The pairs ``softpad compare`` runs by default: the thesis's and the best found here.
DEFAULT_PAIRS = (("thesis", "thesis"), ("gripper-aware", "adaptive"))


#: The idle pad of the false-alarm counts: inflated to p0, sensor noise and drift and the slow
#: disturbances of a real pad on (docs/box-and-simulator.md); seed 8, not the seed 7 the CUSUM
#: was calibrated on.
IDLE_BOX = "sim://?rate_hz={rate:g}&inflated_kpa=1.1&disturbances=1&seed={seed}"


def idle_false_alarms_per_hour(
    detectors: Sequence[str], hours: float, rate_hz: float = 100.0, seed: int = 8
) -> dict[str, float]:
    """False contact alarms per hour of an idle pad for each named detector, all fed the same
    frames; each detector is re-armed with the same reference after every alarm."""
    from softpad.box import open_box
    from softpad.layout import PadLayout
    from softpad.sensing import capture_reference, count_alarms, make_contact_detector

    alarms = dict.fromkeys(detectors, 0)
    with open_box(IDLE_BOX.format(rate=rate_hz, seed=seed)) as box:
        layout = PadLayout()  # the simulated box's default pad, the thesis's 2 x 3
        n = layout.n_modules
        reference = capture_reference([f.pressures_pa[:n] for f in box.read_many(10)])
        dets = {d: make_contact_detector(d, box.sample_rate_hz, layout) for d in detectors}
        for det in dets.values():
            det.reset(reference)
        left = round(hours * 3600 * box.sample_rate_hz)
        while left > 0:  # blocks of frames, every detector keeping its state between them
            block = [box.read().pressures_pa[:n] for _ in range(min(left, 100_000))]
            left -= len(block)
            for name, det in dets.items():
                alarms[name] += count_alarms(det, reference, block, rearm_only=True)
    return {d: n / hours for d, n in alarms.items()}


def _quantiles(values: list[float]) -> tuple[float | None, float | None]:
    if not values:
        return None, None
    return round(statistics.median(values), 5), round(float(np.percentile(values, 95)), 5)


def summarise(trials: Sequence[TrialResult]) -> dict[str, Any]:
    """Success, its interval, failures by cause, detection delay and finger travel."""
    ok = sum(t.success for t in trials)
    delays = [t.contact_delay_s for t in trials if t.contact_delay_s is not None]
    travels = [1e-3 * t.finger_travel_mm for t in trials if t.finger_travel_mm is not None]
    d50, d95 = _quantiles(delays)
    f50, f95 = _quantiles(travels)
    return {
        "trials": len(trials),
        "successes": ok,
        "success": round(ok / len(trials), 4) if trials else None,
        "success_interval": list(wilson_interval(ok, len(trials))),
        "failures": dict(Counter(t.cause for t in trials if not t.success and t.cause)),
        "retried": sum(t.attempts > 1 for t in trials),
        # the catalogue planner's decision (planning._catalogue): trials of a known object by
        # the name recognised, and trials handed on as unknown (0 and {} for other planners)
        "recognised_as": dict(Counter(n for t in trials if (n := known_name(t.rule)))),
        "unknown": sum((t.rule or "").startswith(UNKNOWN_RULE) for t in trials),
        "delay_s_median": d50,
        "delay_s_p95": d95,
        "finger_travel_m_median": f50,
        "finger_travel_m_p95": f95,
    }


def compare(
    specs: Sequence[Any],
    seeds: Sequence[int],
    pairs: Sequence[tuple[str, str]] = DEFAULT_PAIRS,
    config: TrialConfig | None = None,
    trials: int = 5,
    workers: int | None = None,
    idle_hours: float = 1.0,
    on_trial: Callable[[TrialResult], None] | None = None,
) -> dict[str, Any]:
    """Experiment 2 for every (planner, detector) pair over ``seeds``; one result per pair.

    Returns the ``softpad compare --json`` document: ``combinations``, each with ``planner``,
    ``detector``, overall ``success``, ``success_interval``, delays, finger travel,
    ``false_alarms_per_hour`` (idle pad, ``idle_hours`` at 100 Hz), ``objects``, ``failed_trials``
    (object, trial, seed, cause) and ``errored`` (trials that raised); ``contrasts``: each pair
    against every earlier one, trials and objects as the unit (``trials._clustered.contrast``).
    """
    if not seeds:
        raise InputError("compare needs at least one seed")
    config = config or TrialConfig()
    combos = []
    for planner, detector in pairs:
        cfg = replace(config, planner=planner, detector=detector)
        results: list[TrialResult] = []
        trial_seeds: list[int] = []  # the experiment seed of each result
        # every seed's trials queued at once on the same workers
        for exp in run_experiments(specs, trials, list(seeds), workers, cfg, on_trial):
            results += exp.trials
            trial_seeds += [exp.seed] * len(exp.trials)
        by_object = {s.name: [t for t in results if t.object == s.name] for s in specs}
        combos.append(
            {
                "planner": planner,
                "detector": detector,
                # uncertain inputs drawn per trial (each failed trial carries its values)
                "randomize": config.randomize,
                **summarise(results),
                "false_alarms_per_hour": idle_false_alarms_per_hour([detector], idle_hours)[
                    detector
                ],
                "idle_hours": idle_hours,
                "objects": [{"name": n, **summarise(ts)} for n, ts in by_object.items()],
                # every failed trial, to run it again alone (trial_seed of seed, object, trial)
                "failed_trials": _failed_trials(trial_seeds, results),
                # trials that raised (a bug, not a grasp outcome): their records, tracebacks
                "errored": errored_records(results),
            }
        )
    return _document(list(seeds), combos)


def _failed_trials(seeds: list[int], results: list[TrialResult]) -> list[dict[str, Any]]:
    """Every failed trial with its experiment seed (to run it again alone), cause, first
    plan's rule and drawn inputs."""
    return [
        {
            "object": t.object,
            "trial": t.trial,
            "seed": s,
            "cause": t.cause,
            "rule": t.rule,
            "parameters": t.parameters,
        }
        for s, t in zip(seeds, results, strict=True)
        if not t.success
    ]


def _document(seeds: list[int], combos: list[dict[str, Any]]) -> dict[str, Any]:
    """The comparison document: its pairs and every pair against each one listed before it
    (``contrasts``: trial-level and object-clustered tests, softpad.trials._clustered)."""
    return {
        "schema_version": softpad.SCHEMA_VERSION,
        "seeds": seeds,
        "combinations": combos,
        "contrasts": contrasts(combos),
    }


def read_comparisons(paths: Sequence[str]) -> dict[str, Any]:
    """One comparison from the saved ``softpad compare --json`` files ``paths``
    (:func:`merge_comparisons`).

    Parameters
    ----------
    paths
        The files (JSON), in order.
    """
    from pathlib import Path

    from softpad.errors import parse_json

    docs = []
    for path in paths:
        try:
            text = Path(path).read_bytes().decode("utf-8")
        except OSError as exc:
            raise InputError(f"cannot read comparison {path!r}: {exc.strerror}") from None
        except UnicodeDecodeError:
            raise InputError(f"comparison {path!r} is not text (JSON expected)") from None
        docs.append((repr(path), parse_json(text, f"comparison {path!r}")))
    return merge_comparisons(docs)


def merge_comparisons(documents: Sequence[tuple[str, Any]]) -> dict[str, Any]:
    """One comparison from several ``softpad compare --json`` documents of the same seeds and
    objects (pairs run separately, on other days or machines), in the order given.

    ``documents`` holds (name, parsed JSON) pairs; the name (a file name) is quoted in errors.
    A document of another schema, other seeds or objects, or a pair already present is refused.
    """
    if not documents:
        raise InputError("nothing to merge: give at least one comparison")
    seeds: list[int] | None = None
    objects: list[str] | None = None
    combos: list[dict[str, Any]] = []
    for name, doc in documents:
        doc_seeds, doc_combos = _comparison_parts(name, doc)
        for c in doc_combos:
            names = [o["name"] for o in c["objects"]]
            objects = names if objects is None else objects
            if names != objects:
                raise InputError(f"{name}: objects {names} differ from the first's {objects}")
            if any((c["planner"], c["detector"]) == (o["planner"], o["detector"]) for o in combos):
                raise InputError(f"{name}: the pair {c['planner']}:{c['detector']} is given twice")
        seeds = doc_seeds if seeds is None else seeds
        if doc_seeds != seeds:
            raise InputError(
                f"{name}: seeds {_span(doc_seeds)} differ from the first's {_span(seeds)}"
            )
        combos += doc_combos
    assert seeds is not None  # at least one document
    return _document(seeds, combos)


def _comparison_parts(name: str, doc: Any) -> tuple[list[int], list[dict[str, Any]]]:
    """The seeds and combinations of one comparison document, checked."""
    if not isinstance(doc, dict) or doc.get("schema_version") != softpad.SCHEMA_VERSION:
        version = doc.get("schema_version") if isinstance(doc, dict) else None
        raise InputError(
            f"{name}: not a softpad comparison of schema {softpad.SCHEMA_VERSION} "
            f"(schema_version {version!r})"
        )
    seeds, combos = doc.get("seeds"), doc.get("combinations")
    if not isinstance(seeds, list) or not all(isinstance(s, int) for s in seeds) or not seeds:
        raise InputError(f"{name}: 'seeds' must be a non-empty list of integers")
    # every key the table and the figure read
    keys = (
        "planner",
        "detector",
        "trials",
        "successes",
        "success",
        "success_interval",
        "delay_s_median",
        "delay_s_p95",
        "finger_travel_m_median",
        "false_alarms_per_hour",
        "failures",
        "objects",
    )
    if not isinstance(combos, list) or not combos:
        raise InputError(f"{name}: 'combinations' must be a non-empty list")
    for c in combos:
        if not isinstance(c, dict) or any(k not in c for k in keys):
            raise InputError(f"{name}: every combination needs {', '.join(keys)}")
        if not isinstance(c["objects"], list) or not all(
            isinstance(o, dict) and all(k in o for k in ("name", "success", "successes", "trials"))
            for o in c["objects"]
        ):
            raise InputError(
                f"{name}: every object of a combination needs name, success, successes and trials"
            )
    return seeds, combos


def _span(seeds: list[int]) -> str:
    return f"{seeds[0]}..{seeds[-1]} ({len(seeds)})"
