"""Known objects as a mode of their own (issue 47 item 3): a catalogue learned from trials.

A lab knows its objects. :func:`learn_catalogue` keeps, for every object that was held in a
set of recorded trials, its reading signature (the increments of the trials, their mean and
their spread) and the grasps that held it. :class:`CataloguePlanner` recognises a known object
from its readings and grasps it where the nearest held trial did; an object it does not
recognise goes to the fallback planner (the model-based one when made by name).

Recognition criterion: the squared Mahalanobis distance of the increments ``r`` (pascals, one
per module) from an object's signature (the mean of its held trials' readings),

    d2 = (r - mean)^T (S + var I)^-1 (r - mean),

with ``S`` the pooled within-object covariance of the training readings (every known object's
readings about its own mean, summed, over the trials less the objects: how much one object's
reading moves from trial to trial with its pose and the lab's uncertain inputs; a covariance
per object from two or three trials is singular and called most of an object's own readings
unknown) and ``var`` the variance of a planning increment under the measured sensor noise (the
recordings' per-frame variance over 5: the increment is the mean of 10 reads minus a
reference of 10). The object is known when the
smallest ``d2`` is at most the chi-square quantile of ``recognition_quantile`` (0.999) with one
degree of freedom per module: a reading of that object (Gaussian with that covariance) is
called unknown 0.1 % of the time.
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
CATALOGUE_SCHEMA = "softpad-catalogue/1"
#: Start of the rule of a known object's plan (``"catalogue: NAME (d2=...)"``).
KNOWN_RULE = "catalogue: "
#: Start of the rule of an unknown object's plan, the fallback's rule after it.
UNKNOWN_RULE = "unknown -> "


def known_name(rule: str | None) -> str | None:
    """The known object a catalogue plan's ``rule`` names; None for any other rule."""
    if rule is None or not rule.startswith(KNOWN_RULE):
        return None
    return rule[len(KNOWN_RULE) :].rsplit(" (d2=", 1)[0]


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
class KnownObject:
    """One object of the catalogue: its training readings and the grasps that held it.

    Parameters
    ----------
    name
        The object's name in the recordings.
    readings_pa
        Readings of its held trials, pascals (trials x modules).
    grasps
        The grasp that held it in each of those trials: (x, y) module units, theta radians.
    """

    name: str
    #: Readings of its held trials, pascals (trials x modules).
    readings_pa: tuple[tuple[float, ...], ...]
    #: The grasp that held it in each of those trials: (x, y) module units, theta radians.
    grasps: tuple[tuple[float, float, float], ...]

    @property
    def signature_pa(self) -> np.ndarray:
        """Mean reading, pascals."""
        return np.mean(np.array(self.readings_pa), axis=0)

    def distance2(self, reading: np.ndarray, covariance_pa2: np.ndarray) -> float:
        """Squared Mahalanobis distance of ``reading`` from the signature under
        ``covariance_pa2`` (:meth:`Catalogue.covariance_pa2`)."""
        d = reading - self.signature_pa
        return float(d @ np.linalg.solve(covariance_pa2, d))

    def nearest_grasp(self, reading: np.ndarray) -> tuple[float, float, float]:
        """The grasp of the held trial whose reading is nearest ``reading``."""
        k = int(np.argmin(np.linalg.norm(np.array(self.readings_pa) - reading, axis=1)))
        return self.grasps[k]


@dataclass(frozen=True)
class Catalogue:
    """Known objects of one pad and the noise they were learned under.

    Parameters
    ----------
    modules
        Modules of the pad the readings come from.
    variance_pa2
        Variance of a planning increment under the sensor noise, pascals squared.
    objects
        The known objects.
    recognition_quantile
        Chi-square quantile of the recognition threshold (0.999).
    """

    modules: int
    variance_pa2: float
    objects: tuple[KnownObject, ...] = ()
    recognition_quantile: float = 0.999

    def covariance_pa2(self) -> np.ndarray:
        """``S + var I``: the pooled within-object covariance of the readings plus the
        increment's noise variance, Pa^2 (see the module's docstring)."""
        scatter = np.zeros((self.modules, self.modules))
        dof = 0
        for obj in self.objects:
            x = np.array(obj.readings_pa)
            dev = x - x.mean(axis=0)
            scatter += dev.T @ dev
            dof += len(x) - 1
        return scatter / max(dof, 1) + self.variance_pa2 * np.eye(self.modules)

    @property
    def threshold(self) -> float:
        """Largest squared distance of a known object (chi-square, one dof per module)."""
        from scipy.stats import chi2

        return float(chi2.ppf(self.recognition_quantile, self.modules))

    def recognise(self, increments_pa: ArrayLike) -> tuple[KnownObject | None, float]:
        """The known object nearest the reading and its squared distance; None when no object
        lies within :attr:`threshold` (an unknown object)."""
        r = np.asarray(increments_pa, dtype=float)[: self.modules]
        cov = self.covariance_pa2()
        best: tuple[KnownObject | None, float] = (None, math.inf)
        for obj in self.objects:
            d2 = obj.distance2(r, cov)
            if d2 < best[1]:
                best = (obj, d2)
        return best if best[1] <= self.threshold else (None, best[1])

    def to_toml(self) -> str:
        """The catalogue as TOML (schema ``softpad-catalogue/1``)."""
        lines = [
            f'schema = "{CATALOGUE_SCHEMA}"',
            f"modules = {self.modules}",
            f"variance_pa2 = {self.variance_pa2!r}",
            f"recognition_quantile = {self.recognition_quantile!r}",
        ]
        for o in self.objects:
            lines += ["", "[[object]]", f"name = {_quote(o.name)}"]
            lines.append("readings_pa = [" + ", ".join(_floats(r) for r in o.readings_pa) + "]")
            lines.append("grasps = [" + ", ".join(_floats(g) for g in o.grasps) + "]")
        return "\n".join(lines) + "\n"


def _quote(text: str) -> str:
    import json

    return json.dumps(text)  # a TOML basic string is a JSON string


def _floats(values: Sequence[float]) -> str:
    return "[" + ", ".join(repr(float(v)) for v in values) + "]"


def learn_catalogue(
    trials: Sequence[LearnedTrial], variance_pa2: float, recognition_quantile: float = 0.999
) -> Catalogue:
    """A catalogue of every object held at least once in ``trials`` (objects never held have
    no grasp to reuse and stay unknown).

    Parameters
    ----------
    trials
        Recorded trials: each object's increments, the grasp tried and whether it held.
    variance_pa2
        Variance of the sensor noise on one increment, Pa^2, added to the readings' pooled
        within-object covariance.
    recognition_quantile
        Chi-square quantile of the Mahalanobis bound within which a reading is recognised.
    """
    if not trials:
        raise InputError("a catalogue needs at least one recorded trial")
    n = {len(t.increments_pa) for t in trials}
    if len(n) != 1:
        raise InputError(f"trials of pads with different module counts: {sorted(n)}")
    if not (math.isfinite(variance_pa2) and variance_pa2 > 0):
        raise InputError(f"variance_pa2 must be a positive number, got {variance_pa2!r}")
    objects = []
    for name in dict.fromkeys(t.object for t in trials):
        held = [t for t in trials if t.object == name and t.held]
        if held:
            readings = tuple(t.increments_pa for t in held)
            objects.append(KnownObject(name, readings, tuple(t.grasp for t in held)))
    return Catalogue(n.pop(), variance_pa2, tuple(objects), recognition_quantile)


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
            )
            for o in d.get("object", [])
        )
        return Catalogue(
            int(d["modules"]), float(d["variance_pa2"]), objects, float(d["recognition_quantile"])
        )
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
        known, d2 = (None, math.inf)
        if len(objects) == 1 and layout.n_modules == self.catalogue.modules:
            known, d2 = self.catalogue.recognise(r)
        self.last_known = None if known is None else known.name
        if known is None:
            plans = self.fallback.plan(increments_pa, objects, layout)
            return [replace(p, rule=UNKNOWN_RULE + p.rule) for p in plans]
        x, y, theta = known.nearest_grasp(r)
        mods = objects[0]
        return [
            GraspPlan(
                mods,
                pcom(r, mods, layout),
                (x, y),
                theta,
                f"{KNOWN_RULE}{known.name} (d2={d2:.1f})",
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
    "CataloguePlanner",
    "KnownObject",
    "LearnedTrial",
    "known_name",
    "learn_catalogue",
    "load_catalogue",
]
