"""Contact and object detectors by name (``--detector``): registries with entry points.

A factory takes a :class:`DetectorContext` (the pad's layout, the box's sample rate, the
gripper and the loop's thresholds) and returns a :class:`ContactDetector` or an
:class:`ObjectDetector`. Installed packages add detectors through the entry-point groups
``softpad.contact_detectors`` and ``softpad.object_detectors`` (docs/architecture.md).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from softpad.layout import GripperSpec, PadLayout
from softpad.registry import Registry
from softpad.sensing._contact import ContactDetector, ThesisContactDetector
from softpad.sensing._filters import DEFAULT_FILTER_LENGTH
from softpad.sensing._objects import (
    DEFAULT_CONTACT_THRESHOLD_PA,
    DEFAULT_OBJECT_THRESHOLD_PA,
    ObjectDetector,
    ThesisObjectDetector,
)


@dataclass(frozen=True)
class DetectorContext:
    """What a detector factory is told about the pad it watches.

    Parameters
    ----------
    layout
        The pad (its module count sizes per-module and per-pair statistics).
    sample_rate_hz
        Frames per second of the box, hertz.
    gripper
        The gripper's geometry, None when not known.
    contact_threshold_pa
        t_g, pascals (the thesis detector's threshold).
    object_threshold_pa
        t_o, pascals (the thesis object detector's threshold).
    window
        Running-average length, samples.
    """

    layout: PadLayout = field(default_factory=PadLayout)
    sample_rate_hz: float = 100.0
    gripper: GripperSpec | None = None
    contact_threshold_pa: float = DEFAULT_CONTACT_THRESHOLD_PA
    object_threshold_pa: float = DEFAULT_OBJECT_THRESHOLD_PA
    window: int = DEFAULT_FILTER_LENGTH

    @property
    def modules(self) -> int:
        """Number of modules of the pad."""
        return self.layout.n_modules


ContactDetectorFactory = Callable[[DetectorContext], ContactDetector]
ObjectDetectorFactory = Callable[[DetectorContext], ObjectDetector]

#: Contact detectors by name; entry-point group ``softpad.contact_detectors``.
CONTACT_DETECTOR_REGISTRY: Registry[ContactDetectorFactory] = Registry(
    "contact detector", "softpad.contact_detectors"
)
#: Object detectors by name; entry-point group ``softpad.object_detectors``.
OBJECT_DETECTOR_REGISTRY: Registry[ObjectDetectorFactory] = Registry(
    "object detector", "softpad.object_detectors"
)


def register_contact_detector(
    name: str, factory: ContactDetectorFactory, summary: str | None = None
) -> None:
    """Offer ``factory(context) -> ContactDetector`` as ``--detector name`` everywhere."""
    CONTACT_DETECTOR_REGISTRY.register(name, factory, summary)


def register_object_detector(
    name: str, factory: ObjectDetectorFactory, summary: str | None = None
) -> None:
    """Offer ``factory(context) -> ObjectDetector`` under ``name``."""
    OBJECT_DETECTOR_REGISTRY.register(name, factory, summary)


def available_contact_detectors() -> tuple[str, ...]:
    """Names of the contact detectors (built in, registered, and from entry points)."""
    return CONTACT_DETECTOR_REGISTRY.names()


def available_object_detectors() -> tuple[str, ...]:
    """Names of the object detectors (built in, registered, and from entry points)."""
    return OBJECT_DETECTOR_REGISTRY.names()


def _context(
    sample_rate_hz: float, layout: PadLayout | None, fields: dict[str, Any]
) -> DetectorContext:
    return DetectorContext(layout or PadLayout(), sample_rate_hz, **fields)


def make_contact_detector(
    name: str, sample_rate_hz: float = 100.0, layout: PadLayout | None = None, **fields: Any
) -> ContactDetector:
    """The contact detector registered as ``name`` for a box sampling at ``sample_rate_hz``
    and the pad ``layout`` (the thesis's 2 x 3 when None); ``fields``: the other fields of
    :class:`DetectorContext` (``gripper``, thresholds, ``window``). InputError names an
    unknown detector and the known ones."""
    return CONTACT_DETECTOR_REGISTRY.factory(name)(_context(sample_rate_hz, layout, fields))


def make_object_detector(
    name: str, sample_rate_hz: float = 100.0, layout: PadLayout | None = None, **fields: Any
) -> ObjectDetector:
    """The object detector registered as ``name`` (arguments as :func:`make_contact_detector`)."""
    return OBJECT_DETECTOR_REGISTRY.factory(name)(_context(sample_rate_hz, layout, fields))


def _thesis_contact(context: DetectorContext) -> ContactDetector:
    """the thesis's running average above t_g (Section 6.2.3)"""
    return ThesisContactDetector(context.contact_threshold_pa, context.window)


def _cusum(context: DetectorContext) -> ContactDetector:
    """a two-family CUSUM calibrated for the box's sample rate and the pad's size"""
    from softpad.sensing._cusum import cusum_for_rate

    return cusum_for_rate(context.sample_rate_hz, context.modules)


def _adaptive(context: DetectorContext) -> ContactDetector:
    """a CUSUM whose allowance follows each module's own motion (objects rocking on the pad)"""
    from softpad.sensing._adaptive import adaptive_for_rate

    return adaptive_for_rate(context.sample_rate_hz, context.modules)


def _thesis_objects(context: DetectorContext) -> ObjectDetector:
    """modules above t_o, 8-connected groups (Section 6.2.1.2)"""
    return ThesisObjectDetector(context.object_threshold_pa)


register_contact_detector("thesis", _thesis_contact)
register_contact_detector("cusum", _cusum)
register_contact_detector("adaptive", _adaptive)
register_object_detector("thesis", _thesis_objects)
