"""Known objects as a mode of their own (issue 47 item 3): a catalogue learned from trials.

A lab knows its objects. :func:`learn_catalogue` keeps, for every object that was held in a
set of recorded trials, its reading signature (the increments of the trials, their mean and
their spread) and the grasps that held it. :class:`CataloguePlanner` recognises a known object
from its readings and grasps it where the nearest held trial did; an object it does not
recognise goes to the fallback planner (the model-based one when made by name).

Recognition criterion (stated): a reading is described by its load pattern (each module's
share of the total positive increment) and its total load. It matches a held reading of a
known object when the L1 distance of the patterns is at most the object's share tolerance and
the absolute log ratio of the totals at most its load tolerance; the normalised distance
``max(pattern / share_tolerance, load / load_tolerance)`` is at most 1. The object whose
nearest held reading is nearest (normalised) is recognised when that distance is at most 1;
else the object is unknown. Each object's tolerances are learned from its own held readings
(:class:`CatalogueParams`): a margin times the largest distance of one of them from the
nearest of the others (how far a new trial falls from those learned), never under a floor.
Nearest neighbours rather than a mean and covariance: an object's readings under the lab's
uncertain pose are not one Gaussian (a cylinder that rolls, a cluster of limes).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.planning._pcom import pcom
from softpad.planning._plan import Planner
from softpad.planning._records import GraspPlan

#: Schema tag of a catalogue file.
CATALOGUE_SCHEMA = "softpad-catalogue/2"
#: Start of the rule of a known object's plan (``"catalogue: NAME (d=...)"``).
KNOWN_RULE = "catalogue: "
#: Start of the rule of an unknown object's plan, the fallback's rule after it.
UNKNOWN_RULE = "unknown -> "


def known_name(rule: str | None) -> str | None:
    """The known object a catalogue plan's ``rule`` names; None for any other rule."""
    if rule is None or not rule.startswith(KNOWN_RULE):
        return None
    return rule[len(KNOWN_RULE) :].rsplit(" (d=", 1)[0]


@dataclass(frozen=True)
class LearnedTrial:
    """One recorded trial as the catalogue learns from it."""

    #: The object's name.
    object: str
    #: Increments the first plan was made from, pascals, one per module.
    increments_pa: tuple[float, ...]
    #: The grasp tried last: centre (x, y) in module units and direction, radians.
    grasp: tuple[float, float, float]
    #: Whether the object was held.
    held: bool


@dataclass(frozen=True)
class CatalogueParams:
    """How ``learn_catalogue`` sets each object's tolerances (every constant of the criterion).

    An object's tolerance on the load pattern (and on the total load) is ``margin`` times the
    largest distance of one of its held readings from the nearest of its other held readings
    (leave-one-out: how far a new trial of it falls from the ones learned), never under the
    floor; an object held once has the floors.
    """

    #: Factor on the largest leave-one-out distance.
    margin: float = 1.5
    #: Smallest tolerance on the load pattern (L1 distance of load shares, 0-2).
    share_floor: float = 0.1
    #: Smallest tolerance on the total load (absolute natural log of the ratio).
    load_floor: float = 0.1


def features(increments_pa: ArrayLike) -> tuple[np.ndarray, float] | None:
    """The reading's load pattern (each module's share of the total positive increment) and
    the natural log of that total; None for a reading with no positive increment."""
    p = np.clip(np.asarray(increments_pa, dtype=float), 0.0, None)
    total = float(p.sum())
    return (p / total, math.log(total)) if total > 0 else None


def _gaps(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pattern (L1 of shares) and log-load distances of every reading of ``a`` from every
    one of ``b`` (readings x modules each, pascals): two arrays len(a) x len(b)."""
    fa = [features(r) for r in a]
    fb = [features(r) for r in b]
    big = np.inf
    ds = np.full((len(a), len(b)), big)
    dl = np.full((len(a), len(b)), big)
    for i, x in enumerate(fa):
        for j, y in enumerate(fb):
            if x is not None and y is not None:
                ds[i, j] = float(np.abs(x[0] - y[0]).sum())
                dl[i, j] = abs(x[1] - y[1])
    return ds, dl


@dataclass(frozen=True)
class KnownObject:
    """One object of the catalogue: its training readings, the grasps that held it and its
    tolerances.

    Parameters
    ----------
    name
        The object's name in the recordings.
    readings_pa
        Readings of its held trials, pascals (trials x modules).
    grasps
        The grasp that held it in each of those trials: (x, y) module units, theta radians.
    share_tolerance
        Largest L1 distance of a reading's load shares from one of ``readings_pa``'s.
    load_tolerance
        Largest absolute log ratio of a reading's total load to that same reading's.
    """

    name: str
    #: Readings of its held trials, pascals (trials x modules).
    readings_pa: tuple[tuple[float, ...], ...]
    #: The grasp that held it in each of those trials: (x, y) module units, theta radians.
    grasps: tuple[tuple[float, float, float], ...]
    #: Tolerance on the load pattern (L1 distance of the load shares).
    share_tolerance: float = 0.1
    #: Tolerance on the total load (absolute natural log of the ratio).
    load_tolerance: float = 0.1

    def distance(self, reading: ArrayLike) -> tuple[float, int, bool]:
        """The distance of ``reading`` from the nearest held reading (pattern L1 plus the
        absolute log load ratio), that reading's index, and whether some held reading lies
        within both tolerances (the nearest such one is then the index)."""
        ds, dl = _gaps(np.atleast_2d(np.asarray(reading, dtype=float)), np.array(self.readings_pa))
        d = ds[0] + dl[0]
        within = (ds[0] <= self.share_tolerance) & (dl[0] <= self.load_tolerance)
        k = int(np.argmin(np.where(within, d, np.inf))) if within.any() else int(np.argmin(d))
        return float(np.min(d)), k, bool(within.any())


@dataclass(frozen=True)
class Catalogue:
    """Known objects of one pad and the noise they were learned under.

    Parameters
    ----------
    modules
        Modules of the pad the readings come from.
    variance_pa2
        Variance of a planning increment under the sensor noise, pascals squared (recorded).
    objects
        The known objects.
    """

    modules: int
    variance_pa2: float
    objects: tuple[KnownObject, ...] = ()

    def recognise(self, increments_pa: ArrayLike) -> tuple[KnownObject | None, float, int]:
        """The known object nearest the reading (:meth:`KnownObject.distance`), the distance
        and the index of the held reading whose grasp to use; the object is None (unknown)
        when the nearest object has no held reading within its tolerances of this one."""
        r = np.asarray(increments_pa, dtype=float)[: self.modules]
        best: tuple[KnownObject | None, float, int, bool] = (None, math.inf, -1, False)
        for obj in self.objects:
            d, k, within = obj.distance(r)
            if d < best[1]:
                best = (obj, d, k, within)
        return best[:3] if best[3] else (None, best[1], -1)

    def to_toml(self) -> str:
        """The catalogue as TOML (schema ``softpad-catalogue/2``)."""
        lines = [
            f'schema = "{CATALOGUE_SCHEMA}"',
            f"modules = {self.modules}",
            f"variance_pa2 = {self.variance_pa2!r}",
        ]
        for o in self.objects:
            lines += ["", "[[object]]", f"name = {_quote(o.name)}"]
            lines.append(f"share_tolerance = {o.share_tolerance!r}")
            lines.append(f"load_tolerance = {o.load_tolerance!r}")
            lines.append("readings_pa = [" + ", ".join(_floats(r) for r in o.readings_pa) + "]")
            lines.append("grasps = [" + ", ".join(_floats(g) for g in o.grasps) + "]")
        return "\n".join(lines) + "\n"


def _quote(text: str) -> str:
    import json

    return json.dumps(text)  # a TOML basic string is a JSON string


def _floats(values: Sequence[float]) -> str:
    return "[" + ", ".join(repr(float(v)) for v in values) + "]"


def _tolerances(readings: np.ndarray, params: CatalogueParams) -> tuple[float, float]:
    """``params.margin`` times the largest leave-one-out distance of ``readings`` (pattern,
    load), each at least its floor."""
    if len(readings) < 2:
        return params.share_floor, params.load_floor
    ds, dl = _gaps(readings, readings)
    np.fill_diagonal(ds, np.inf)
    np.fill_diagonal(dl, np.inf)
    share = params.margin * float(np.max(np.min(ds, axis=1)))
    load = params.margin * float(np.max(np.min(dl, axis=1)))
    return max(share, params.share_floor), max(load, params.load_floor)


def learn_catalogue(
    trials: Sequence[LearnedTrial], variance_pa2: float, params: CatalogueParams | None = None
) -> Catalogue:
    """A catalogue of every object held at least once in ``trials`` (objects never held have
    no grasp to reuse and stay unknown).

    Parameters
    ----------
    trials
        Recorded trials: each object's increments, the grasp tried and whether it held.
    variance_pa2
        Variance of the sensor noise on one increment, Pa^2 (kept in the catalogue).
    params
        How each object's tolerances are set (:class:`CatalogueParams`).
    """
    params = params or CatalogueParams()
    if not trials:
        raise InputError("a catalogue needs at least one recorded trial")
    n = {len(t.increments_pa) for t in trials}
    if len(n) != 1:
        raise InputError(f"trials of pads with different module counts: {sorted(n)}")
    if not (math.isfinite(variance_pa2) and variance_pa2 > 0):
        raise InputError(f"variance_pa2 must be a positive number, got {variance_pa2!r}")
    objects = []
    for name in dict.fromkeys(t.object for t in trials):
        held = [t for t in trials if t.object == name and t.held and features(t.increments_pa)]
        if held:
            readings = tuple(t.increments_pa for t in held)
            share, load = _tolerances(np.array(readings), params)
            grasps = tuple(t.grasp for t in held)
            objects.append(KnownObject(name, readings, grasps, share, load))
    return Catalogue(n.pop(), variance_pa2, tuple(objects))


def load_catalogue(path: str | Path) -> Catalogue:
    """Read a catalogue written by ``softpad learn`` (InputError names what is wrong).

    Parameters
    ----------
    path
        The catalogue file (TOML).
    """
    import tomllib

    p = Path(path)
    try:
        d = tomllib.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"catalogue {str(p)!r} not found") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"catalogue {str(p)!r} is not valid TOML: {exc}") from None
    if d.get("schema") != CATALOGUE_SCHEMA:
        raise InputError(f"catalogue {str(p)!r}: schema must be {CATALOGUE_SCHEMA!r}")
    try:
        objects = tuple(
            KnownObject(
                str(o["name"]),
                tuple(tuple(float(v) for v in r) for r in o["readings_pa"]),
                tuple((float(g[0]), float(g[1]), float(g[2])) for g in o["grasps"]),
                float(o["share_tolerance"]),
                float(o["load_tolerance"]),
            )
            for o in d.get("object", [])
        )
        return Catalogue(int(d["modules"]), float(d["variance_pa2"]), objects)
    except (KeyError, TypeError, ValueError, IndexError) as exc:
        raise InputError(f"catalogue {str(p)!r} is malformed: {exc!r}") from None


class CataloguePlanner:
    """Known objects grasped where they were held; unknown ones planned by ``fallback``.

    Parameters
    ----------
    catalogue
        The known objects (an empty one: every object is unknown).
    fallback
        The planner of unknown objects (and of pads with more than one object on them).
    """

    def __init__(self, catalogue: Catalogue, fallback: Planner) -> None:
        self.catalogue = catalogue
        self.fallback = fallback
        #: Name of the object recognised in the last plan, None for an unknown one.
        self.last_known: str | None = None

    def plan(
        self, increments_pa: ArrayLike, objects: list[tuple[int, ...]], layout: PadLayout
    ) -> list[GraspPlan]:
        """One plan per object (see :class:`~softpad.planning.Planner`)."""
        r = np.asarray(increments_pa, dtype=float)
        known, d, k = (None, math.inf, -1)
        if len(objects) == 1 and layout.n_modules == self.catalogue.modules:
            known, d, k = self.catalogue.recognise(r)
        self.last_known = None if known is None else known.name
        if known is None:
            plans = self.fallback.plan(increments_pa, objects, layout)
            return [replace(p, rule=UNKNOWN_RULE + p.rule) for p in plans]
        x, y, theta = known.grasps[k]
        mods = objects[0]
        return [
            GraspPlan(
                mods,
                pcom(r, mods, layout),
                (x, y),
                theta,
                f"{KNOWN_RULE}{known.name} (d={d:.2f})",
                mods,
            )
        ]

    def retry(self, plan: GraspPlan, *args: Any, **kwargs: Any) -> GraspPlan | None:
        """A known object's grasp is not retried; an unknown one's is the fallback's retry."""
        if plan.rule.startswith(KNOWN_RULE) or not hasattr(self.fallback, "retry"):
            return None
        handed = replace(plan, rule=plan.rule.removeprefix(UNKNOWN_RULE))
        result: GraspPlan | None = self.fallback.retry(handed, *args, **kwargs)
        return result


__all__ = [
    "CATALOGUE_SCHEMA",
    "KNOWN_RULE",
    "UNKNOWN_RULE",
    "Catalogue",
    "CatalogueParams",
    "CataloguePlanner",
    "KnownObject",
    "LearnedTrial",
    "features",
    "known_name",
    "learn_catalogue",
    "load_catalogue",
]
