"""Grasp trials of the thesis's Experiment 2 (thesis, Section 6.3) in the MuJoCo world.

One trial: a fresh MuJoCo world behind the simulated box (``sim://`` physics: chamber gas,
valves, sensor noise), the pad inflated to p0 and its reference saved, the object placed with a
seeded random pose perturbation, the pressure increments planned by the thesis planner, the
gripper moved over the centre of grasp, lowered at the approach speed until the pad senses the fingers
(running average of 10 samples above t_g), closed, lifted and held for 15 s. The outcome and,
for a failure, its cause are read from the physics.

Trials run in parallel processes; each trial's randomness comes from its own seed, derived
from the experiment seed, the object and the trial number, so results do not depend on the
number of workers.
"""

from __future__ import annotations

import atexit
import contextlib
import math
import os
import time
import traceback
import zlib
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from softpad.errors import InputError
from softpad.trials._config import TrialConfig
from softpad.trials._records import ExperimentResult, TrialResult


def trial_recording_path(base: str | Path, object_name: str, trial: int) -> Path:
    """File of one trial's recording for ``--record BASE.mcap``: ``BASE-OBJECT-tK.mcap``
    (K from 1)."""
    b = Path(base)
    return b.with_name(f"{b.stem}-{object_name}-t{trial + 1}{b.suffix}")


def trial_seed(seed: int, object_name: str, trial: int) -> int:
    """Seed of one trial, from the experiment seed, the object's name and the trial number.

    Independent of the worker count and of which other objects run alongside, so trial k of
    an object is the same trial in ``softpad demo`` and in ``softpad trials --objects NAME``.
    """
    for name, v in (("seed", seed), ("trial", trial)):
        if isinstance(v, bool) or not isinstance(v, int | np.integer) or v < 0:
            raise InputError(f"trial {name} must be an integer >= 0, got {v!r}")
    name_key = zlib.crc32(str(object_name).encode("utf-8"))
    ss = np.random.SeedSequence([int(seed), name_key, int(trial)])
    return int(ss.generate_state(1)[0])


def perturbed_placement(spec: Any, seed: int, config: TrialConfig) -> tuple[float, float, float]:
    """The catalogue placement of ``spec`` shifted and turned at random (normal, seeded); a
    placement ``anywhere_on_m`` a pad: anywhere the object fits on it, drawn from ``seed``
    (:func:`softpad.trials._geometry.anywhere_placement`)."""
    if spec.placement.anywhere_on_m is not None:
        from softpad.trials._geometry import anywhere_placement

        return anywhere_placement(spec, seed, spec.placement.anywhere_on_m)
    rng = np.random.default_rng(seed)
    dx, dy = rng.normal(0.0, config.position_sigma_m, 2)
    dyaw = rng.normal(0.0, config.yaw_sigma_rad)
    p = spec.placement
    return float(p.x_m + dx), float(p.y_m + dy), float(p.yaw_rad + dyaw)


def run_trial(
    spec: Any,
    trial: int = 0,
    seed: int = 0,
    config: TrialConfig | None = None,
    placement: tuple[float, float, float] | None = None,
    plan_override: Any | None = None,
    opening_m: float | None = None,
    mounting: str | None = None,
    truth: Any | None = None,
    recorder: Any | None = None,
    gripper: Any | None = None,
) -> tuple[TrialResult, Any | None]:
    """Run one grasp trial of ``spec`` in a fresh MuJoCo world.

    Parameters
    ----------
    spec
        Catalogue object (``softpad.sim.ObjectSpec``).
    trial
        Trial number (recorded only).
    seed
        Seed of the placement perturbation and of the box's sensor noise.
    config
        Trial parameters.
    placement
        Exact placement (x_m, y_m, yaw_rad) instead of a random one.
    plan_override
        A :class:`~softpad.planning.GraspPlan` to execute instead of the planner's (to provoke
        a failure on purpose, e.g. a COG outside the object).
    opening_m
        Jaw opening for the approach instead of the mounting's full width, metres (an
        experimenter's choice, to provoke a failure on purpose).
    mounting
        Gripper mounting (``"10/4"``, ``"6/2"``, ``"4/0"``) instead of the catalogue's.
    truth
        The object geometry the trial is scored with (``spec`` by default; the world always
        holds ``spec``). Nothing the loop does may depend on it: a test swaps it.
    recorder
        A :class:`softpad.control.Recorder` that also hears every frame and event of the loop
        (the robot's commands are ``robot`` events).
    gripper
        A :class:`softpad.layout.GripperSpec` (mounting widths and tips) instead of the
        mounting's with the Sawyer's tips: a design study, e.g. the thicker tips the thesis
        recommends.

    Returns
    -------
    The trial's result, and its :class:`softpad.record.RunLog` when ``config.record_trace``.
    """
    from softpad.trials._loop import TrialOverrides, execute_trial, varied_lab

    config = config or TrialConfig()
    if placement is None:  # with the drawn placement noise under config.randomize
        placement = perturbed_placement(spec, seed, varied_lab(spec, seed, config)[1])
    t0 = time.perf_counter()
    o = TrialOverrides(plan_override, opening_m, mounting, truth, recorder, gripper)
    result, trace = execute_trial(spec, placement, seed, config, o)
    result = replace(result, trial=trial, wall_time_s=time.perf_counter() - t0)
    return result, trace


def errored_trial(
    spec: Any, trial: int, seed: int, config: TrialConfig, exc: Exception
) -> TrialResult:
    """The record of a trial that raised ``exc``: failed, cause ``trial_error``, the traceback
    in ``detail`` with the call that runs the trial again alone."""
    text = "".join(traceback.format_exception(exc)).rstrip()
    rerun = f"run_trial(get_object({spec.name!r}), {trial}, {seed}, config) runs it again"
    return TrialResult(
        object=spec.name,
        trial=trial,
        seed=seed,
        placement=perturbed_placement(spec, seed, config),
        mounting=spec.gripper,
        success=False,
        cause="trial_error",
        detail=f"{rerun}\n{text}",
    )


def _worker(args: tuple[Any, int, int, TrialConfig]) -> tuple[TrialResult, Any | None]:
    """One trial of a sweep; a trial that raises is recorded (``trial_error``) so that one
    defect does not lose the sweep's other trials."""
    spec, trial, seed, config = args
    try:
        return run_trial(spec, trial, seed, config)
    except Exception as exc:
        return errored_trial(spec, trial, seed, config, exc), None


def run_experiment(
    specs: Sequence[Any],
    trials: int = 5,
    seed: int = 0,
    workers: int | None = None,
    config: TrialConfig | None = None,
    on_trial: Callable[[TrialResult], None] | None = None,
    trace_object: str | None = None,
    record: str | Path | None = None,
) -> tuple[ExperimentResult, Any | None]:
    """Run ``trials`` trials of every object, in parallel processes.

    Parameters
    ----------
    specs
        Catalogue objects.
    trials
        Trials per object (5 in the thesis).
    seed
        Experiment seed.
    workers
        Worker processes (default: the CPUs available, at most the number of trials); 1 runs
        in this process.
    config
        Trial parameters.
    on_trial
        Called with every finished trial (progress bars, logs), in completion order.
    trace_object
        Record the pressure trace of trial 0 of this object.
    record
        Record every trial as MCAP, into :func:`trial_recording_path` files of this base name.

    Returns
    -------
    The experiment and the trace of ``trace_object`` (or None).
    """
    if not isinstance(trials, int) or not 1 <= trials <= 1000:
        raise InputError(f"trials per object must be an integer from 1 to 1000, got {trials!r}")
    if not specs:
        raise InputError("no objects to try")
    config = config or TrialConfig()
    tasks = _experiment_tasks(specs, trials, seed, config, trace_object, record)
    workers = _worker_count(workers, len(tasks))
    t0 = time.perf_counter()
    results: list[Any] = [None] * len(tasks)
    trace: list[Any] = []

    def done(i: int, res: TrialResult, tr: Any | None) -> None:
        results[i] = res
        if tr is not None:
            trace.append(tr)
        if on_trial:
            on_trial(res)

    _run_tasks(tasks, workers, done)
    exp = _experiment(specs, seed, config, results, workers, time.perf_counter() - t0)
    return exp, trace[0] if trace else None


def run_experiments(
    specs: Sequence[Any],
    trials: int,
    seeds: Sequence[int],
    workers: int | None = None,
    config: TrialConfig | None = None,
    on_trial: Callable[[TrialResult], None] | None = None,
    on_seed: Callable[[ExperimentResult], None] | None = None,
) -> list[ExperimentResult]:
    """:func:`run_experiment` for every seed of ``seeds``, all their trials queued at once on
    the same workers (the next seed's trials start while the last of the one before still
    run: both cores stay busy to the end of the campaign); the same results as one
    :func:`run_experiment` per seed.

    Parameters
    ----------
    specs, trials, workers, config, on_trial
        As in :func:`run_experiment`.
    seeds
        Experiment seeds, one experiment each.
    on_seed
        Called with each seed's experiment as soon as all its trials have finished.

    Returns
    -------
    The experiments in the order of ``seeds``; each one's ``wall_time_s`` is the campaign's
    wall time over the number of seeds (their sum is the campaign's).
    """
    if not isinstance(trials, int) or not 1 <= trials <= 1000:
        raise InputError(f"trials per object must be an integer from 1 to 1000, got {trials!r}")
    if not specs:
        raise InputError("no objects to try")
    config = config or TrialConfig()
    per_seed = [_experiment_tasks(specs, trials, s, config, None, None) for s in seeds]
    tasks = [t for ts in per_seed for t in ts]
    workers = _worker_count(workers, len(tasks))
    n = len(specs) * trials
    results: list[Any] = [None] * len(tasks)
    left = [n] * len(seeds)
    exps: list[Any] = [None] * len(seeds)
    t0 = time.perf_counter()

    def done(i: int, res: TrialResult, tr: Any | None) -> None:
        results[i] = res
        if on_trial:
            on_trial(res)
        j = i // n
        left[j] -= 1
        if left[j] == 0:
            wall = (time.perf_counter() - t0) / len(seeds)
            exps[j] = _experiment(
                specs, seeds[j], config, results[j * n : (j + 1) * n], workers, wall
            )
            if on_seed:
                on_seed(exps[j])

    _run_tasks(tasks, workers, done)
    wall = (time.perf_counter() - t0) / max(len(seeds), 1)
    return [replace(e, wall_time_s=wall) for e in exps]


def _experiment(
    specs: Sequence[Any],
    seed: int,
    config: TrialConfig,
    results: list[TrialResult],
    workers: int,
    wall_s: float,
) -> ExperimentResult:
    """The experiment of ``seed`` from its trials' results (object by object, in task order)."""
    return ExperimentResult(
        trials=tuple(results),
        seed=seed,
        masses_g={s.name: s.mass_kg * 1e3 for s in specs},
        wall_time_s=wall_s,
        workers=workers,
        seeds=(seed,),
        placement_noise={
            "position_sigma_mm": round(config.position_sigma_m * 1e3, 6),
            "yaw_sigma_deg": round(math.degrees(config.yaw_sigma_rad), 6),
        },
    )


def _experiment_tasks(
    specs: Sequence[Any],
    trials: int,
    seed: int,
    config: TrialConfig,
    trace_object: str | None,
    record: str | Path | None,
) -> list[tuple[Any, int, int, TrialConfig]]:
    """``(spec, k, trial seed, config)`` of every trial, object by object; trial 0 of
    ``trace_object`` records its trace, and each trial its MCAP file under ``record``."""
    tasks = []
    for spec in specs:
        for k in range(trials):
            cfg = replace(config, record_trace=(spec.name == trace_object and k == 0))
            if record is not None:
                cfg = replace(cfg, record_path=str(trial_recording_path(record, spec.name, k)))
            tasks.append((spec, k, trial_seed(seed, spec.name, k), cfg))
    return tasks


def _worker_count(workers: int | None, n_tasks: int) -> int:
    """Worker processes to use: ``workers`` (checked) or the CPUs available, at most
    ``n_tasks``."""
    n_cpu = (
        len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    )
    workers = n_cpu if workers is None else workers
    if not isinstance(workers, int) or not 1 <= workers <= 256:
        raise InputError(f"workers must be an integer from 1 to 256, got {workers!r}")
    return min(workers, n_tasks)


def _run_tasks(
    tasks: list[Any], workers: int, done: Callable[[int, TrialResult, Any | None], None]
) -> None:
    """Run ``tasks`` in this process (one worker) or on the shared pool; ``done`` sees each
    task's index, result and recorded trace as it completes."""
    if workers == 1:
        for i, task in enumerate(tasks):
            done(i, *_worker(task))
        return
    pool = _shared_pool(workers)
    try:
        futures = {pool.submit(_worker, task): i for i, task in enumerate(tasks)}
        for fut in as_completed(futures):
            done(futures[fut], *fut.result())
    except BaseException:  # Ctrl-C, a broken pool, a failing hook: no worker left running
        _close_shared_pool(cancel=True)
        raise


#: The worker processes of this process's experiments, and their count: they live across
#: seeds, pairs and arms (``softpad trials --seeds 0-9``, ``compare``, ``validate``), so that a
#: campaign pays the start-up (interpreter, imports: about a second a process) once.
_POOL: tuple[int, ProcessPoolExecutor] | None = None


def _shared_pool(workers: int) -> ProcessPoolExecutor:
    """A pool of ``workers`` processes, the one of the last experiment when it has as many."""
    global _POOL
    if _POOL is not None and _POOL[0] == workers:
        return _POOL[1]
    _close_shared_pool()
    _POOL = (workers, ProcessPoolExecutor(max_workers=workers))
    return _POOL[1]


def _close_shared_pool(cancel: bool = False) -> None:
    """Shut the shared pool down (``cancel``: drop its queued trials, do not wait)."""
    global _POOL
    pool, _POOL = _POOL, None
    if pool is not None:
        with contextlib.suppress(BrokenProcessPool):
            pool[1].shutdown(wait=not cancel, cancel_futures=cancel)


atexit.register(_close_shared_pool)
