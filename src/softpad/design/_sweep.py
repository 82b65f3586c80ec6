"""A design sweep: the FEM response and the trials of every design, on Dask, cached.

Tasks: one finite-element response per distinct module (width, thickness, material, p0;
designs that differ only in the grid share it), then one trial batch per design and seed (the
whole object set), which depends on its module's response. They run on a Dask ``distributed``
client (:func:`~softpad.design.dask_client`); each finished task is stored in the
:class:`~softpad.design.ResultCache` as it arrives, so an interrupted sweep resumes.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from softpad.design._cache import ResultCache
from softpad.design._evaluate import TrialOptions, run_design_trials
from softpad.design._objects import ObjectSet
from softpad.design._response import fem_response
from softpad.design._space import THESIS_DESIGN, PadDesign
from softpad.errors import InputError

#: Cells along the quarter's side of the finite-element mesh: full and quick sweeps.
FEM_CELLS = {False: 12, True: 8}

#: ``progress(done, total, what)``: called as each task finishes.
Progress = Callable[[int, int, str], None]


@dataclass(frozen=True)
class SweepTask:
    """One task of a sweep: its kind (``fem``/``trials``), cache key and inputs."""

    kind: str
    key: str
    design: PadDesign
    seed: int | None = None


@dataclass(frozen=True)
class _SweepJob:
    """What every task of one sweep shares: objects, trial options, mesh, cache, progress."""

    object_set: ObjectSet
    options: TrialOptions
    quick: bool
    cache: ResultCache
    progress: Progress | None

    def fem_key(self, design: PadDesign) -> str:
        """Cache key of the finite-element response of ``design``'s module."""
        return self.cache.key("fem", {**design.fem_variables(), "cells": FEM_CELLS[self.quick]})

    def keep(self, done: dict[str, Any], task: SweepTask, result: Any) -> None:
        """Store ``result`` of ``task`` in ``done`` and in the cache."""
        done[task.key] = result
        self.cache.put(task.kind, task.key, result)


def _fem_task(design: PadDesign, cells: int) -> dict[str, Any]:
    """The FEM response of ``design``'s module as a dict (a Dask task)."""
    v = design.fem_variables()
    return fem_response(v["width_m"], v["thickness_m"], v["material"], v["p0_pa"], cells).to_dict()


def _trials_task(
    design: PadDesign,
    response: dict[str, Any],
    object_set: ObjectSet,
    seed: int,
    options: TrialOptions,
) -> list[dict[str, Any]]:
    """The trials of one design and seed (a Dask task)."""
    return run_design_trials(design, response, object_set, seed, options)


@dataclass(frozen=True)
class SweepRaw:
    """What a sweep computed: responses by FEM key, trial records by (design name, seed)."""

    #: The designs, baseline first.
    designs: tuple[PadDesign, ...]
    #: FEM response dict of each design, by design name.
    responses: dict[str, dict[str, Any]]
    #: Trial records of each design, by design name (every seed).
    trials: dict[str, list[dict[str, Any]]]
    #: Tasks run now and tasks read from the cache.
    computed: int
    #: Tasks run now and tasks read from the cache.
    cached: int
    #: Wall time of the sweep, seconds.
    wall_time_s: float
    #: Dask workers used (0: nothing needed computing).
    workers: int


def run_sweep(
    designs: Sequence[PadDesign],
    object_set: ObjectSet,
    options: TrialOptions | None = None,
    seeds: Sequence[int] = (0,),
    quick: bool = False,
    scheduler: str | None = None,
    workers: int | None = None,
    cache: ResultCache | None = None,
    progress: Progress | None = None,
) -> SweepRaw:
    """Evaluate ``designs`` (the thesis's pad is added first when missing) on ``object_set``.

    Parameters
    ----------
    designs
        Designs to evaluate (unique names).
    object_set
        The objects to grasp.
    options
        How trials run.
    seeds
        Experiment seeds (each gives every object ``options.trials`` trials).
    quick
        Coarser finite-element mesh (:data:`FEM_CELLS`).
    scheduler
        ``tcp://127.0.0.1:PORT`` of a running Dask scheduler; None starts a local cluster.
    workers
        Worker processes of the local cluster (default: the CPUs; 1: in this process).
    cache
        Where finished tasks are kept (None: nothing kept).
    progress
        Called as each task finishes.
    """
    t0 = time.perf_counter()
    options = options or TrialOptions()
    cache = cache or ResultCache(None)
    designs = _with_baseline(designs)
    if not seeds or len(set(seeds)) != len(seeds):
        raise InputError(f"seeds must be distinct and at least one, got {list(seeds)}")
    job = _SweepJob(object_set, options, quick, cache, progress)
    fem_keys = {d.name: job.fem_key(d) for d in designs}
    tasks = _sweep_tasks(job, designs, seeds, fem_keys)
    done = _cached_results(cache, tasks)
    missing = [t for t in tasks if t.key not in done]
    missing = list({t.key: t for t in missing}.values())  # FEM shared by designs: once
    n_cached = len({t.key for t in tasks}) - len(missing)
    used = _compute(job, missing, done, scheduler, workers, n_cached) if missing else 0
    if not missing and scheduler is not None:  # the cache answered; the scheduler must too
        used = _reach(scheduler)
    responses = {d.name: done[fem_keys[d.name]] for d in designs}
    trials = {
        d.name: [
            r for t in tasks if t.kind == "trials" and t.design.name == d.name for r in done[t.key]
        ]
        for d in designs
    }
    return SweepRaw(
        tuple(designs), responses, trials, len(missing), n_cached, time.perf_counter() - t0, used
    )


def _sweep_tasks(
    job: _SweepJob, designs: list[PadDesign], seeds: Sequence[int], fem_keys: dict[str, str]
) -> list[SweepTask]:
    """Each design's FEM task, then its trial task for each seed (keyed by objects, options,
    design variables, seed and FEM key)."""
    common = {"objects": job.object_set.fingerprint(), "options": job.options.to_dict()}
    tasks: list[SweepTask] = []
    for d in designs:
        tasks.append(SweepTask("fem", fem_keys[d.name], d))
        for s in seeds:
            payload = {**common, "design": d.variables(), "seed": int(s), "fem": fem_keys[d.name]}
            tasks.append(SweepTask("trials", job.cache.key("trials", payload), d, int(s)))
    return tasks


def _cached_results(cache: ResultCache, tasks: list[SweepTask]) -> dict[str, Any]:
    """The results of ``tasks`` already in ``cache``, by key."""
    done: dict[str, Any] = {}
    for t in tasks:
        hit = cache.get(t.kind, t.key)
        if hit is not None:
            done[t.key] = hit
    return done


def _with_baseline(designs: Sequence[PadDesign]) -> list[PadDesign]:
    """The thesis's design first (added when missing), then the others; names unique."""
    out = list(designs)
    if not any(d.is_thesis for d in out):
        out.insert(0, THESIS_DESIGN)
    else:
        out.sort(key=lambda d: not d.is_thesis)
    names = [d.name for d in out]
    if len(set(names)) != len(names):
        raise InputError(f"design names must be unique, got {names}")
    return out


def _reach(scheduler: str) -> int:
    """Connect to ``scheduler`` (an :class:`InputError` when nothing answers); its workers."""
    from softpad.design._dask import dask_client

    with dask_client(scheduler, None) as client:
        return len(client.scheduler_info().get("workers", {})) or 1


def _compute(
    job: _SweepJob,
    missing: list[SweepTask],
    done: dict[str, Any],
    scheduler: str | None,
    workers: int | None,
    n_cached: int,
) -> int:
    """Run the missing tasks on Dask (FEM first, trials depending on it); store each result
    as it arrives. Returns the number of workers."""
    from softpad.design._dask import dask_client, has_dask

    total = len(missing) + n_cached
    # one worker and no scheduler: this process is that worker (a cluster of one would only
    # add its start-up, seconds); without Dask installed, likewise
    if scheduler is None and (workers == 1 or not has_dask()):
        _compute_here(job, missing, done, n_cached)
        return 1
    with dask_client(scheduler, workers) as client:
        from distributed import as_completed

        n_workers = len(client.scheduler_info().get("workers", {})) or 1
        fem_futures: dict[str, Any] = {}
        futures: dict[Any, SweepTask] = {}
        for t in missing:
            if t.kind == "fem":
                fut = client.submit(
                    _fem_task, t.design, FEM_CELLS[job.quick], key=f"fem-{t.key}", pure=False
                )
                fem_futures[t.key] = fut
                futures[fut] = t
        ordered = {t.key: t for t in missing}
        for t in ordered.values():
            if t.kind != "trials":
                continue
            fkey = job.fem_key(t.design)
            response = fem_futures.get(fkey, done.get(fkey))
            fut = client.submit(
                _trials_task,
                t.design,
                response,
                job.object_set,
                t.seed,
                job.options,
                key=f"trials-{t.key}",
                pure=False,
            )
            futures[fut] = t
        count = n_cached
        for fut in as_completed(list(futures)):
            t = futures[fut]
            job.keep(done, t, fut.result())
            count += 1
            if job.progress is not None:
                job.progress(
                    count,
                    total,
                    f"{t.kind} {t.design.name}" + ("" if t.seed is None else f" seed {t.seed}"),
                )
    return n_workers


def _compute_here(
    job: _SweepJob, missing: list[SweepTask], done: dict[str, Any], n_cached: int
) -> None:
    """The missing tasks in this process, FEM first (one worker, or Dask not installed)."""
    count, total = n_cached, len(missing) + n_cached
    for t in sorted(missing, key=lambda t: t.kind != "fem"):
        if t.kind == "fem":
            result: Any = _fem_task(t.design, FEM_CELLS[job.quick])
        else:
            response = done[job.fem_key(t.design)]
            result = _trials_task(t.design, response, job.object_set, t.seed or 0, job.options)
        job.keep(done, t, result)
        count += 1
        if job.progress is not None:
            seed = "" if t.seed is None else f" seed {t.seed}"
            job.progress(count, total, f"{t.kind} {t.design.name}{seed}")


def design_sweep(
    designs: Sequence[PadDesign],
    object_set: ObjectSet,
    options: TrialOptions | None = None,
    seeds: Sequence[int] = (0,),
    **kwargs: Any,
) -> Any:
    """Run :func:`run_sweep` and rank the designs: a :class:`~softpad.design.SweepResult`.

    ``kwargs`` go to :func:`run_sweep` (``quick``, ``scheduler``, ``workers``, ``cache``,
    ``progress``).
    """
    from softpad.design._results import SweepResult, design_row, rank_rows

    options = options or TrialOptions()
    raw = run_sweep(designs, object_set, options, seeds, **kwargs)
    rows = [design_row(d, raw.responses[d.name], raw.trials[d.name]) for d in raw.designs]
    meta = {
        "seeds": list(seeds),
        "objects": len(object_set.objects),
        "trials_per_object": options.trials,
        "planner": options.planner,
        "detector": options.detector,
        "hold_s": options.hold_s,
        "world": "analytic",
        "fem_cells_in_plane": FEM_CELLS[bool(kwargs.get("quick", False))],
        "computed": raw.computed,
        "cached": raw.cached,
        "wall_time_s": round(raw.wall_time_s, 3),
        "workers": raw.workers,
    }
    return SweepResult(tuple(rank_rows(rows)), object_set.name, meta, raw.trials)
