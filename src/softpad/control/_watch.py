"""The loop's own object watch and planning step, for whoever watches a pad.

:class:`GraspExecution <softpad.control.GraspExecution>` waits for an object with
:class:`ObjectWatch` (its ``wait_object`` phase) and plans with :func:`plan_from_reads` (its
``plan`` phase); a ROS node that only watches the pad uses the same two, with the same parts,
so the same object gives the same plan on its topics as the grasp loop (issue 48: a node with
its own running average and settling published a COG 1.9 mm away from the loop's).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from softpad.layout import PadLayout
from softpad.planning import GraspPlan, Planner
from softpad.sensing import ObjectDetector, RunningAverage, measured_change


class ObjectWatch:
    """Watch the filtered increments until an object has lain still for the settle time.

    Every frame: the increments over ``reference_pa`` go through a running average of
    ``filter_length`` samples; once it is full, ``object_detector`` looks for objects in them
    (:func:`~softpad.sensing.measured_change`). The first frame with an object is *seen*;
    ``settle_s`` of box time later the watch has *settled* (the loop plans then) if the
    detector still finds an object; if not (a noise peak under a threshold set near the
    noise, an object put down and taken away), the watch waits on as before the sighting.

    Parameters
    ----------
    reference_pa
        The pad's reference pressures (empty pad, after the adjustment), Pa.
    object_detector
        Finds objects in the filtered increments.
    layout
        The pad.
    filter_length
        Samples of the running average (thesis: 10).
    settle_s
        Box time from the first sight of an object to planning, s.
    """

    def __init__(
        self,
        reference_pa: NDArray[np.float64],
        object_detector: ObjectDetector,
        layout: PadLayout,
        filter_length: int,
        settle_s: float,
    ) -> None:
        self.reference_pa = np.asarray(reference_pa, dtype=float)
        self.object_detector, self.layout = object_detector, layout
        self.settle_s = float(settle_s)
        self._filter = RunningAverage(filter_length)
        #: Box time of the first frame with an object, s (None until then).
        self.seen_at: float | None = None
        #: Objects (modules of each) in the filtered increments of the last frame judged (the
        #: first sighting, then the settle time's); empty until the filter is full.
        self.objects: list[tuple[int, ...]] = []
        self._last = np.zeros_like(self.reference_pa)
        self._settled = False

    def update(self, pressures_pa: NDArray[np.float64], t_s: float) -> str | None:
        """One frame's pressures at box time ``t_s``: ``"seen"`` on the first frame with an
        object, ``"settled"`` on every frame from ``settle_s`` after it (once an object is
        still there then), else None."""
        d = self._filter.update(np.asarray(pressures_pa, dtype=float) - self.reference_pa)
        self._last = d
        if self.seen_at is not None:
            if t_s - self.seen_at < self.settle_s:
                return None
            if not self._settled and not self._find(d):
                self.seen_at = None  # gone by the settle time (noise, a passing touch): wait on
                return None
            self._settled = True
            return "settled"
        if not self._filter.full:
            return None
        if self._find(d):
            self.seen_at = t_s
            return "seen"
        return None

    def _find(self, d: NDArray[np.float64]) -> bool:
        """Whether the detector finds objects in the filtered increments ``d`` (kept in
        :attr:`objects`)."""
        self.objects = [tuple(o) for o in self.object_detector.objects(measured_change(d),
                                                                       self.layout)]  # fmt: skip
        return bool(self.objects)

    def filtered(self) -> NDArray[np.float64]:
        """The current filtered increments, Pa (as the detector sees them)."""
        return measured_change(self._last)


def plan_from_reads(
    reads_pa: Sequence[NDArray[np.float64]],
    reference_pa: NDArray[np.float64],
    object_detector: ObjectDetector,
    planner: Planner,
    layout: PadLayout,
) -> tuple[NDArray[np.float64], tuple[GraspPlan, ...]]:
    """The loop's planning step: increments = the mean of ``reads_pa`` (the loop takes
    ``planning_reads`` of them after settling) minus the reference, the objects in them, one
    plan per object. Returns ``(increments_pa, plans)``."""
    delta = measured_change(np.mean(np.asarray(reads_pa, dtype=float), axis=0) - reference_pa)
    objects = object_detector.objects(delta, layout)
    return delta, tuple(planner.plan(delta, objects, layout))
