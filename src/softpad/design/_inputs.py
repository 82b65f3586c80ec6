"""A sweep's inputs as ``softpad design`` is given them: the design space from the options'
text, the trial options with the quick run's defaults, the object set, the cache folder, and
the outputs written. Every check raises :class:`~softpad.errors.InputError` naming the value,
its limit and the option it came from."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from softpad import thesis
from softpad.errors import InputError

#: Most designs one sweep spans.
MAX_DESIGNS = 500


def designs_from_text(
    grid: str | None = None,
    pitch_mm: str | None = None,
    thickness_mm: str | None = None,
    materials: Sequence[str] | None = None,
    p0_kpa: str | None = None,
    quick: bool = False,
) -> list[Any]:
    """The designs the options span (the quick set when none is given and ``quick``).

    Parameters
    ----------
    grid
        ``RxC`` grids, comma-separated (``2x3,3x4``); None: the thesis's.
    pitch_mm, thickness_mm, p0_kpa
        Values in mm, mm and kPa: ``1,1.5,2`` or ``1:2:0.5``; None: the thesis's.
    materials
        Material presets; None: the thesis's.
    quick
        With no option given, :data:`softpad.design.QUICK_DESIGNS`.

    Returns
    -------
    list of PadDesign
        The thesis's design first, then the space's (at most :data:`MAX_DESIGNS`).
    """
    from softpad.design._space import (
        LIMITS,
        QUICK_DESIGNS,
        THESIS_DESIGN,
        DesignSpace,
        parse_grids,
        parse_values,
    )

    if quick and all(v is None for v in (grid, pitch_mm, thickness_mm, materials, p0_kpa)):
        return list(QUICK_DESIGNS)
    base = THESIS_DESIGN

    def values(text: str | None, name: str, scale: float, key: str, default: float) -> Any:
        return (default,) if text is None else parse_values(text, name, scale, LIMITS[key])

    space = DesignSpace(
        grids=parse_grids(grid) if grid is not None else ((base.rows, base.cols),),
        pitches_m=values(pitch_mm, "--pitch-mm", 1e-3, "pitch_m", base.pitch_m),
        thicknesses_m=values(thickness_mm, "--thickness-mm", 1e-3, "thickness_m", base.thickness_m),
        materials=tuple(materials) if materials is not None else (base.material,),
        p0s_pa=values(p0_kpa, "--p0-kpa", 1e3, "p0_pa", base.p0_pa),
    )
    if space.size > MAX_DESIGNS:
        raise InputError(f"the options span {space.size} designs; at most {MAX_DESIGNS} per sweep")
    return space.designs()


def sweep_trial_options(
    trials: int | None,
    hold_s: float | None,
    quick: bool,
    planner: str,
    detector: str,
    randomize: bool = False,
    mounting: str | None = None,
    valves: str = "thesis",
) -> Any:
    """The :class:`~softpad.design.TrialOptions` of a sweep, checked.

    Parameters
    ----------
    trials
        Trials per object and seed, 1..100; None: 1 with ``quick``, else 5.
    hold_s
        Hold time, s, 0..60; None: 2 s with ``quick``, else the thesis's 15 s.
    quick
        The quick run's defaults.
    planner, detector
        Registered names.
    randomize
        Draw the uncertain inputs per trial.
    mounting
        The gripper's mounting (``auto``, ``10/4``, ...), or None (each object's).
    valves
        ``thesis`` (the thesis's orifices) or ``sized`` (orifices sized to each module).
    """
    from softpad.design._evaluate import TrialOptions

    trials = trials if trials is not None else (1 if quick else 5)
    if not 1 <= trials <= 100:
        raise InputError(f"--trials must be from 1 to 100, got {trials}")
    hold_s = hold_s if hold_s is not None else (2.0 if quick else thesis.HOLD_S)
    if not (math.isfinite(hold_s) and 0 <= hold_s <= 60):
        raise InputError(f"--hold-s must be from 0 to 60 s, got {hold_s!r}")
    return TrialOptions(
        trials, planner, detector, hold_s, randomize=randomize, mounting=mounting, valves=valves
    )


def choose_object_set(
    path: str | None, example: str | None, gripper: str | None, mounting: str | None
) -> Any:
    """The object set of a sweep: the file ``path``, else the example (default thesis-set),
    with one gripper mounting for all when ``gripper`` is given.

    Parameters
    ----------
    path
        An object-set file (TOML), or None.
    example
        A packaged example's name, or None.
    gripper
        One mounting for the set, or None.
    mounting
        The trials' mounting option (``gripper`` and ``mounting`` exclude each other).
    """
    from softpad.design._objects import example_object_set, load_object_set

    if gripper is not None and mounting is not None:
        raise InputError("give --gripper (one mounting for the set) or --mounting, not both")
    if path:
        s = load_object_set(path)
    else:
        s = example_object_set("thesis-set" if example is None else example)
    return s.with_gripper(gripper)


def cache_folder(text: str | None) -> Path:
    """The cache folder, created now so that an unusable one fails before any work.

    Parameters
    ----------
    text
        The folder's name; None: :func:`softpad.design.default_cache_dir`.
    """
    from softpad.design._cache import default_cache_dir

    path = default_cache_dir() if text is None else Path(text)
    if text is not None and not text.strip():
        raise InputError("--cache needs a folder name, got an empty value")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--cache {str(path)!r} cannot be used: {exc.strerror or exc}") from None
    return path


def cached_line(cached: int, computed: int, root: Path | None) -> str:
    """The first line of a design run answered, in part or whole, from the cache.

    Parameters
    ----------
    cached, computed
        Tasks answered from the cache and computed now.
    root
        The cache folder.
    """
    share = "all" if not computed else f"{cached} of {cached + computed}"
    return (
        f"softpad design: {share} tasks answered from the cache {root} (results of an "
        "earlier run of this code); --no-cache computes everything"
    )


def write_sweep(
    result: Any,
    outputs: dict[str, Path | None],
    write_text: Callable[[Path, str], Any] = lambda p, t: p.write_text(t),
) -> None:
    """Write a sweep's ranked table (``csv``, ``parquet``), Pareto plot (``png``) and report
    (``report``) to the files given.

    Parameters
    ----------
    result
        The :class:`~softpad.design.SweepResult`.
    outputs
        Files by kind; None writes none of that kind.
    write_text
        How the report's text is written (a command writes atomically).
    """
    if outputs["csv"] is not None:
        result.to_csv(outputs["csv"])
    if outputs["parquet"] is not None:
        result.to_parquet(outputs["parquet"])
    if outputs["png"] is not None:
        import matplotlib.pyplot as plt

        plt.close(result.plot(outputs["png"]))
    if outputs["report"] is not None:
        write_text(outputs["report"], result.report())


def trial_objects(names: Sequence[str] | None, objects_file: str | None = None) -> list[Any]:
    """The objects of a trial run: catalogue objects (all when ``names`` is None), or with
    ``objects_file`` that object set's objects (those named, all when None), each placed on
    the thesis's 2 x 3 pad with its mounting.

    Parameters
    ----------
    names
        Object names, or None for all.
    objects_file
        An object-set file (TOML, docs/design.md), or None for the catalogue.

    Returns
    -------
    list of ObjectSpec
        The objects, in the order named.
    """
    from softpad.sim import get_object, object_names

    if objects_file is not None:
        return _set_objects(objects_file, names)
    known = list(object_names())
    if names is None:
        return [get_object(n) for n in known]
    for n in names:
        if n not in known:
            raise InputError(f"unknown object {n!r}; known objects: {', '.join(known)}")
    return [get_object(n) for n in names]


def _set_objects(path: str, names: Sequence[str] | None) -> list[Any]:
    """The objects of the object-set file ``path`` as catalogue specs on the 2 x 3 pad."""
    from dataclasses import replace

    from softpad.design._objects import load_object_set

    objects = load_object_set(path)
    pad = (
        thesis.PROTOTYPE_COLS * thesis.MODULE_PITCH_M,
        thesis.PROTOTYPE_ROWS * thesis.MODULE_PITCH_M,
    )
    chosen = list(objects.objects)
    if names is not None:
        unknown = [n for n in names if n not in objects.names]
        if unknown:
            raise InputError(
                f"--objects: {', '.join(unknown)} not in {path!r}; its objects: "
                f"{', '.join(objects.names)}"
            )
        chosen = [o for o in chosen if o.name in names]
    return [replace(o.placed_on(pad), gripper=objects.mounting(o)) for o in chosen]


__all__ = [
    "MAX_DESIGNS", "cache_folder", "cached_line", "choose_object_set", "designs_from_text",
    "sweep_trial_options", "trial_objects", "write_sweep",
]  # fmt: skip
