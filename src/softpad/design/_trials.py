"""``softpad trials`` on Dask: the MuJoCo trials of several experiment seeds as Dask tasks.

The same trials as :func:`softpad.trials.run_experiment` (trial ``k`` of an object gets
:func:`softpad.trials.trial_seed` of the experiment seed, the name and k), so the results do not
depend on where they ran; every (seed, object, trial) is one task on the client of
:func:`~softpad.design.dask_client`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from typing import Any

from softpad.errors import InputError


def _trial_task(spec: Any, k: int, seed: int, config: Any) -> Any:
    """One trial (a Dask task); the trial's own seed is derived as in ``run_experiment``, and a
    trial that raises is recorded as ``trial_error`` as there."""
    from softpad.trials import errored_trial, run_trial, trial_seed

    s = trial_seed(seed, spec.name, k)
    try:
        result, _ = run_trial(spec, k, s, config)
    except Exception as exc:
        return errored_trial(spec, k, s, config, exc)
    return result


def run_experiment_on_dask(
    specs: Sequence[Any],
    trials: int = 5,
    seeds: Sequence[int] = (0,),
    config: Any | None = None,
    scheduler: str | None = None,
    workers: int | None = None,
    on_trial: Callable[[Any], None] | None = None,
) -> list[Any]:
    """Experiments (one per seed) of ``trials`` trials of every object, on Dask.

    Parameters
    ----------
    specs
        Catalogue objects (:class:`softpad.sim.ObjectSpec`).
    trials
        Trials per object.
    seeds
        Experiment seeds.
    config
        :class:`softpad.trials.TrialConfig` (recording is not available on Dask).
    scheduler, workers
        As :func:`~softpad.design.dask_client`.
    on_trial
        Called with every finished :class:`softpad.trials.TrialResult`.

    Returns
    -------
    One :class:`softpad.trials.ExperimentResult` per seed, in seed order.
    """
    from softpad.trials import ExperimentResult, TrialConfig

    config = config or TrialConfig()
    _check_request(specs, trials, config)
    t0 = time.perf_counter()
    results, n_workers = _run_trial_tasks(
        specs, trials, seeds, config, scheduler, workers, on_trial
    )
    wall = time.perf_counter() - t0
    noise = {
        "position_sigma_mm": round(config.position_sigma_m * 1e3, 6),
        "yaw_sigma_deg": round(math.degrees(config.yaw_sigma_rad), 6),
    }
    return [
        ExperimentResult(
            trials=tuple(results[(s, spec.name, k)] for spec in specs for k in range(trials)),
            seed=s,
            masses_g={spec.name: spec.mass_kg * 1e3 for spec in specs},
            wall_time_s=wall / len(seeds),  # the seeds ran together: each its share
            workers=n_workers,
            seeds=(s,),
            placement_noise=noise,
        )
        for s in seeds
    ]


def _check_request(specs: Sequence[Any], trials: int, config: Any) -> None:
    """InputError for a trial count outside 1..1000, no objects, or a recording request."""
    if not isinstance(trials, int) or not 1 <= trials <= 1000:
        raise InputError(f"trials per object must be an integer from 1 to 1000, got {trials!r}")
    if not specs:
        raise InputError("no objects to try")
    if config.record_path is not None or config.record_trace:
        raise InputError(
            "recording trials is not available on Dask (--record needs --workers without --scheduler)"
        )


def _run_trial_tasks(
    specs: Sequence[Any],
    trials: int,
    seeds: Sequence[int],
    config: Any,
    scheduler: str | None,
    workers: int | None,
    on_trial: Callable[[Any], None] | None,
) -> tuple[dict[tuple[int, str, int], Any], int]:
    """Every (seed, object, trial) as a Dask task: the results by (seed, name, k) as they
    finish (``on_trial`` called with each) and the number of workers."""
    from softpad.design._dask import dask_client

    results: dict[tuple[int, str, int], Any] = {}
    with dask_client(scheduler, workers) as client:
        from distributed import as_completed

        n_workers = len(client.scheduler_info().get("workers", {})) or 1
        futures = {
            client.submit(
                _trial_task, spec, k, s, config, key=f"trial-{s}-{spec.name}-{k}-{time.time_ns()}"
            ): (s, spec.name, k)
            for s in seeds
            for spec in specs
            for k in range(trials)
        }
        for fut in as_completed(list(futures)):
            res = fut.result()
            results[futures[fut]] = res
            if on_trial is not None:
                on_trial(res)
    return results, n_workers
