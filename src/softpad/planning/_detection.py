"""Object detection at the noise of the increments (issue 47: light objects).

The thesis finds an object where a module's increment exceeds t_o = 50 Pa (it "detects a
12.6 g Duplo brick"). Light objects on a module's edge, a seam or spread over several modules
stay under it: the project's FEM (``softpad.sim.PadResponse``, cast pad at p0) gives a
16 mm cube 7.6 Pa/g on a module's centre, 1.2 Pa/g on each module of a seam and 0.24 Pa/g on
each of four at a corner, so a 5 g die on a centre (38 Pa) or a 25 g ball on a seam (30 Pa)
is never seen (docs/planner.md, "Light objects: detection at the noise").

:class:`NoiseObjectDetector` puts the threshold where the noise of the increment puts it
instead: ``k`` standard deviations of the increment, ``k`` from a family-wise false-alarm
probability over the pad's modules (Bonferroni, one-sided; Student's t since the spread is
estimated, with nu degrees of freedom)::

    k = t_nu^-1(1 - alpha / N)
    sigma_inc^2 = s^2 (1 / n_ref + 1 / n_judged + 2 r^2)
    threshold = k sigma_inc

with ``s`` the spread of one reading, measured on the box's own reference reads (pooled over
the channels, before anything is placed), ``n_ref`` and ``n_judged`` the reads averaged into
the reference and into the judged increment, and ``r`` the sensor's slow drift as a share of
its white noise: consecutive reads do not show a drift correlated over seconds, and between
the reference and the judged reads it may have moved (bounded by its full decorrelation,
hence the factor 2). The model-based planner's loop finds its objects with it
(:meth:`softpad.planning.ModelBasedPlanner.object_detector`); the thesis's pair keeps t_o.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from statistics import NormalDist
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sensing import ObjectDetector, detect_objects


@dataclass(frozen=True)
class NoiseDetectionParams:
    """Parameters of :class:`NoiseObjectDetector` (SI units)."""

    #: Family-wise false-alarm probability of one detection (one judged increment of every
    #: module of the pad) on an empty pad: 1e-3, one phantom object in a thousand empty-pad
    #: decisions, whatever the pad's size (a choice: a planner that grasps at nothing once in
    #: a thousand looks costs a retreat; an object never seen costs the trial).
    false_alarm: float = 1e-3
    #: Reads averaged into the reference (thesis, Section 6.2.1.1: 10).
    reference_reads: int = thesis.REFERENCE_READS
    #: Reads averaged into a judged increment: the loop's planning reads and its watch's
    #: running average (thesis: the 10-sample filter; ``ExecutionParams.planning_reads``).
    judged_reads: int = thesis.FILTER_WINDOW
    #: The sensor's slow drift as a share of its white noise (3 Pa / 8 Pa: the box sensor's
    #: figures, :data:`softpad.thesis.SENSOR_DRIFT_STD_PA` over
    #: :data:`softpad.thesis.SENSOR_NOISE_STD_PA`); the spread of consecutive reads does not
    #: show it.
    drift_ratio: float = thesis.SENSOR_DRIFT_STD_PA / thesis.SENSOR_NOISE_STD_PA
    #: Spread of one reading assumed until the box's own reads are seen, Pa rms (the box's
    #: published reading variance, :data:`softpad.thesis.SENSOR_VARIANCE_PA2`).
    nominal_spread_pa: float = math.sqrt(thesis.SENSOR_VARIANCE_PA2)
    #: The threshold is never under the converter's resolution, Pa (2.44 Pa, a 12-bit
    #: converter over 10 kPa: :data:`softpad.thesis.SENSOR_QUANTIZATION_PA`): a noiseless
    #: (simulated ideal) sensor would otherwise find objects in rounding.
    floor_pa: float = thesis.SENSOR_QUANTIZATION_PA

    def __post_init__(self) -> None:
        if not (isinstance(self.false_alarm, int | float) and 0 < self.false_alarm < 1):
            raise InputError(f"false-alarm probability must be in (0, 1), got {self.false_alarm!r}")
        for name in ("reference_reads", "judged_reads"):
            v = getattr(self, name)
            if not (isinstance(v, int) and v >= 1):
                raise InputError(f"{name} must be an integer >= 1, got {v!r}")
        for name in ("drift_ratio", "nominal_spread_pa", "floor_pa"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v >= 0):
                raise InputError(f"{name} must be a number >= 0, got {v!r}")

    def sigmas(self, n_modules: int, dof: int | None = None) -> float:
        """k: the one-sided quantile at ``false_alarm / n_modules`` (Bonferroni) of a
        Gaussian increment over its standard deviation, known (``dof`` None) or estimated
        with ``dof`` degrees of freedom (Student's t, :func:`student_quantile`)."""
        if not (isinstance(n_modules, int) and n_modules >= 1):
            raise InputError(f"module count must be an integer >= 1, got {n_modules!r}")
        return student_quantile(1.0 - self.false_alarm / n_modules, dof)

    def increment_std_pa(self, spread_pa: float) -> float:
        """sigma_inc, Pa rms: the increment's noise for a reading spread ``spread_pa``."""
        share = 1.0 / self.reference_reads + 1.0 / self.judged_reads + 2.0 * self.drift_ratio**2
        return spread_pa * math.sqrt(share)


def student_quantile(p: float, dof: int | None) -> float:
    """The ``p`` quantile of Student's t with ``dof`` degrees of freedom (None: the
    Gaussian's), by the Cornish-Fisher expansion about the Gaussian quantile ``x``
    (Abramowitz and Stegun, Eq. 26.7.5)::

        t = x + g1 / v + g2 / v^2 + g3 / v^3 + g4 / v^4

    Within 0.1 % of the exact quantile for ``dof`` >= 18 down to ``1 - p`` = 2.5e-8 (the
    pad's pooled reference reads have 54: 6 channels x 9); 2 % low at 9.

    Parameters
    ----------
    p
        Probability in (0, 1).
    dof
        Degrees of freedom (>= 1), or None for the Gaussian.
    """
    x = NormalDist().inv_cdf(p)
    if dof is None:
        return x
    if not (isinstance(dof, int) and dof >= 1):
        raise InputError(f"degrees of freedom must be an integer >= 1, got {dof!r}")
    x2 = x * x
    g = (
        x * (x2 + 1) / 4,
        x * ((5 * x2 + 16) * x2 + 3) / 96,
        x * (((3 * x2 + 19) * x2 + 17) * x2 - 15) / 384,
        x * ((((79 * x2 + 776) * x2 + 1482) * x2 - 1920) * x2 - 945) / 92160,
    )
    return x + sum(gi / dof ** (i + 1) for i, gi in enumerate(g))


def reading_spread_pa(reads_pa: ArrayLike) -> float:
    """Spread of one reading, Pa rms: the within-channel standard deviation of repeated
    reads, pooled over the channels (the mean of their variances, ``ddof`` 1 each).

    Parameters
    ----------
    reads_pa
        Repeated reads, pascals: shape (n_reads >= 2, n_channels), one row a read.
    """
    a = np.asarray(reads_pa, dtype=float)
    if a.ndim != 2 or a.shape[0] < 2 or a.shape[1] < 1:
        raise InputError(f"reads must have shape (n_reads >= 2, n_channels), got {a.shape}")
    if not np.isfinite(a).all():
        raise InputError("reads for the noise estimate contain NaN or infinite values")
    return float(math.sqrt(float(np.mean(a.var(axis=0, ddof=1)))))


class NoiseObjectDetector:
    """Modules whose increment exceeds ``k`` standard deviations of its noise, 8-connected
    groups (the thesis's grouping, Section 6.2.1.2, at a threshold from the noise).

    Parameters
    ----------
    params
        False-alarm probability, reads averaged, drift share, nominal spread.
    """

    def __init__(self, params: NoiseDetectionParams | None = None) -> None:
        self.params = params or NoiseDetectionParams()
        #: Spread of one reading, Pa rms: nominal until :meth:`calibrate`.
        self.spread_pa = self.params.nominal_spread_pa
        #: Degrees of freedom of the measured spread (None: the nominal, taken as known).
        self.dof: int | None = None

    def calibrate(self, reference_reads_pa: ArrayLike) -> None:
        """Measure the spread of one reading on the box's reference reads (the empty pad's,
        one row a read, one column a module; (reads - 1) x modules degrees of freedom)."""
        self.spread_pa = reading_spread_pa(reference_reads_pa)
        rows, cols = np.shape(reference_reads_pa)
        self.dof = (rows - 1) * cols

    def threshold_pa(self, n_modules: int) -> float:
        """The detection threshold on a pad of ``n_modules``, Pa."""
        p = self.params
        return p.sigmas(n_modules, self.dof) * p.increment_std_pa(self.spread_pa)

    def objects(self, increments_pa: ArrayLike, layout: PadLayout) -> list[tuple[int, ...]]:
        """One sorted tuple of 1-based modules per object; empty when nothing lies there."""
        t = max(self.threshold_pa(layout.n_modules), self.params.floor_pa)
        return detect_objects(increments_pa, layout, t)


def planner_detector(planner: Any) -> ObjectDetector | None:
    """The object detector a planner finds its objects with (its ``object_detector()``: a
    fresh one for each run of the loop, which calibrates it on the run's reference reads),
    or None for a planner without one (the loop's t_o detector then).

    Parameters
    ----------
    planner
        Any planner; one with an ``object_detector()`` method brings its own detector.
    """
    make = getattr(planner, "object_detector", None)
    return make() if callable(make) else None


__all__ = [
    "NoiseDetectionParams",
    "NoiseObjectDetector",
    "planner_detector",
    "reading_spread_pa",
    "student_quantile",
]
