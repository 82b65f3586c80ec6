"""Sensing primitives: filters, reference capture, increments, objects, contact.

Pure functions and small state classes; every pressure is a gauge pressure in pascals.
Thesis symbols (values in :mod:`softpad.thesis`): t_o (object threshold), t_g (contact threshold),
running average of 10 samples, reference = mean of 10 reads (seed, Sections 6.2.1.1 and 6.3).
"""

from softpad.sensing._adaptive import (
    ADAPTIVE_CALIBRATIONS,
    AdaptiveCusumDetector,
    AdaptiveParams,
    adaptive_for_rate,
    calibrate_adaptive,
)
from softpad.sensing._contact import (
    ContactDetector,
    LatchingContactDetector,
    ThesisContactDetector,
    count_alarms,
)
from softpad.sensing._cusum import (
    CUSUM_CALIBRATIONS,
    DEFAULT_BASELINE_TIME_S,
    CusumCalibration,
    CusumContactDetector,
    CusumLimit,
    calibrate_cusum,
    cusum_for_rate,
    cusum_statistics,
    excursion_peaks,
    fit_limit,
)
from softpad.sensing._filters import RunningAverage, capture_reference, increments
from softpad.sensing._floor import sensing_ratio, step_floor_pa
from softpad.sensing._objects import (
    DEFAULT_CONTACT_THRESHOLD_PA,
    DEFAULT_OBJECT_THRESHOLD_PA,
    DEFAULT_OUTLINE_THRESHOLD_PA,
    SENSOR_FULL_SCALE_PA,
    SMALLEST_PLAUSIBLE_INCREMENT_PA,
    ObjectDetector,
    ThesisObjectDetector,
    detect_objects,
    measured_change,
    outline_objects,
)
from softpad.sensing._registry import (
    CONTACT_DETECTOR_REGISTRY,
    OBJECT_DETECTOR_REGISTRY,
    ContactDetectorFactory,
    DetectorContext,
    ObjectDetectorFactory,
    available_contact_detectors,
    available_object_detectors,
    make_contact_detector,
    make_object_detector,
    register_contact_detector,
    register_object_detector,
)

__all__ = [
    "ADAPTIVE_CALIBRATIONS",
    "CONTACT_DETECTOR_REGISTRY",
    "CUSUM_CALIBRATIONS",
    "DEFAULT_BASELINE_TIME_S",
    "DEFAULT_CONTACT_THRESHOLD_PA",
    "DEFAULT_OBJECT_THRESHOLD_PA",
    "DEFAULT_OUTLINE_THRESHOLD_PA",
    "OBJECT_DETECTOR_REGISTRY",
    "SENSOR_FULL_SCALE_PA",
    "SMALLEST_PLAUSIBLE_INCREMENT_PA",
    "AdaptiveCusumDetector",
    "AdaptiveParams",
    "ContactDetector",
    "ContactDetectorFactory",
    "CusumCalibration",
    "CusumContactDetector",
    "CusumLimit",
    "DetectorContext",
    "LatchingContactDetector",
    "ObjectDetector",
    "ObjectDetectorFactory",
    "RunningAverage",
    "ThesisContactDetector",
    "ThesisObjectDetector",
    "adaptive_for_rate",
    "available_contact_detectors",
    "available_object_detectors",
    "calibrate_adaptive",
    "calibrate_cusum",
    "capture_reference",
    "count_alarms",
    "cusum_for_rate",
    "cusum_statistics",
    "detect_objects",
    "excursion_peaks",
    "fit_limit",
    "increments",
    "make_contact_detector",
    "make_object_detector",
    "measured_change",
    "outline_objects",
    "register_contact_detector",
    "register_object_detector",
    "sensing_ratio",
    "step_floor_pa",
]
