"""Example SoftPad plug-in: one planner and one contact detector, offered by entry points.

Installed (``pip install ./examples/plugin``), its ``pyproject.toml`` declares

- ``softpad.planners``: ``pcom-centre`` -> :func:`pcom_centre_planner`;
- ``softpad.contact_detectors``: ``median-rise`` -> :func:`median_rise_detector`;

and every SoftPad command that takes ``--planner`` or ``--detector`` lists them. Each factory
receives the registry's context (pad layout, sample rate, gripper, thresholds) and returns the
protocol type (:class:`softpad.planning.Planner`, :class:`softpad.sensing.ContactDetector`).
Only SoftPad's public API is used.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.layout import PadLayout
from softpad.planning import GraspPlan, Planner, PlannerContext, ThesisPlanner
from softpad.sensing import ContactDetector, DetectorContext, LatchingContactDetector

__all__ = ["MedianRiseDetector", "PcomCentrePlanner", "median_rise_detector", "pcom_centre_planner"]


class PcomCentrePlanner:
    """The thesis's grasp direction, centred on the pressure-based centre of mass (PCOM)
    instead of the thesis's centre of grasp: a planner for objects whose weight sits where
    their middle is. ``rule`` of each plan is ``pcom-centre`` (after the thesis's rule)."""

    def __init__(self, inner: Planner) -> None:
        self.inner = inner

    def plan(
        self, increments_pa: ArrayLike, objects: list[tuple[int, ...]], layout: PadLayout
    ) -> list[GraspPlan]:
        return [
            dataclasses.replace(p, cog=p.pcom, rule=f"pcom-centre ({p.rule})")
            for p in self.inner.plan(increments_pa, objects, layout)
        ]


class MedianRiseDetector(LatchingContactDetector):
    """Contact when the median of the last ``window`` rises of any module exceeds
    ``threshold_pa`` (a median ignores single spikes, a mean does not).

    Parameters
    ----------
    threshold_pa
        Rise over the reference that declares contact, pascals.
    window
        Samples in the median, samples (odd counts give a sample of the rise).
    """

    def __init__(self, threshold_pa: float, window: int) -> None:
        super().__init__()
        self.threshold_pa, self.window = float(threshold_pa), int(window)
        self._recent = np.zeros((0, 0))

    @property
    def floor_key(self) -> tuple[object, ...]:
        return ("median-rise", self.threshold_pa, self.window)

    def _restart(self, modules: int) -> None:
        self._recent = np.zeros((self.window, modules))  # primed with the reference

    def _exceeds(self, rise_pa: NDArray[np.float64]) -> NDArray[np.bool_]:
        self._recent = np.vstack([self._recent[1:], rise_pa])
        out: NDArray[np.bool_] = np.median(self._recent, axis=0) > self.threshold_pa
        return out


def pcom_centre_planner(context: PlannerContext) -> Planner:
    """the thesis's direction, centred on the PCOM (example plug-in)"""
    return PcomCentrePlanner(ThesisPlanner(context.params))


def median_rise_detector(context: DetectorContext) -> ContactDetector:
    """median of the last 5 rises above t_g (example plug-in)"""
    return MedianRiseDetector(context.contact_threshold_pa, 5)
