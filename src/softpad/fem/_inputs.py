"""The studies' inputs checked where they are defined: ranges of a module's design values,
of study pressures, loads and masses, a load's footprint read from text, and the chamber
study's detection threshold.

Every check raises :class:`~softpad.errors.InputError` naming the value, its limit and the
input it came from (``name``: a command line passes its option, ``--masses-g``), so a unit
mix-up (pascals as kilopascals, kilograms as grams, metres as millimetres) is told apart
from a design. SI inside; the limits are stated in the unit the inputs are usually given in.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

from softpad import thesis
from softpad.errors import InputError
from softpad.fem._geometry import LoadPatch

#: Limits of the layer's thickness and the module's width, m: outside them a value is a unit
#: mix-up more likely than a design.
THICKNESS_RANGE_M = (0.1e-3, 20e-3)
WIDTH_RANGE_M = (5e-3, 0.5)
#: Limits of a study's mass on the module, kg.
MASS_RANGE_KG = (0.1e-3, 10.0)
#: Smallest side of a load's footprint, m.
MIN_FOOTPRINT_M = 0.5e-3


def check_design_values(parameter: str, values_m: Sequence[float], name: str = "values") -> None:
    """Refuse design values outside the parameter's range.

    Parameters
    ----------
    parameter
        ``"thickness"`` (the upper layer's) or ``"width"`` (the module's).
    values_m
        The values, m.
    name
        The input they came from, for the message.
    """
    ranges = {"thickness": THICKNESS_RANGE_M, "width": WIDTH_RANGE_M}
    if parameter not in ranges:
        raise InputError(f"{name}: parameter must be thickness or width, got {parameter!r}")
    lo, hi = ranges[parameter]
    for v in values_m:
        if not lo <= v <= hi:
            raise InputError(
                f"{name}: a {parameter} of {v * 1e3:g} mm is outside {lo * 1e3:g}..{hi * 1e3:g} mm"
            )


def check_study_pressures(pressures_pa: Sequence[float], name: str = "pressures") -> None:
    """Refuse study pressures above the module's maximum (500 kPa is usually pascals given as
    kilopascals).

    Parameters
    ----------
    pressures_pa
        Gauge pressures, Pa.
    name
        The input they came from, for the message.
    """
    top = max(pressures_pa)
    if top > thesis.MAX_PRESSURE_PA:
        raise InputError(
            f"{name}: {top / 1e3:g} kPa exceeds the module's maximum "
            f"{thesis.MAX_PRESSURE_PA / 1e3:g} kPa"
        )


def check_masses(masses_kg: Sequence[float], name: str = "masses") -> None:
    """Refuse masses outside :data:`MASS_RANGE_KG` (a light one: kilograms given as grams?).

    Parameters
    ----------
    masses_kg
        Masses put on the module, kg.
    name
        The input they came from, for the message.
    """
    lo, hi = MASS_RANGE_KG
    for m in masses_kg:
        if not lo <= m <= hi:
            hint = " (kilograms given as grams?)" if m < lo else ""
            raise InputError(
                f"{name}: {m * 1e3:g} g is outside {lo * 1e3:g}..{hi * 1e3:g} g" + hint
            )


def parse_footprint(text: str, module_width_m: float, name: str = "footprint") -> LoadPatch:
    """A load's footprint from ``"WxH"`` (a rectangle) or ``"dD"`` (a disc), in millimetres.

    Parameters
    ----------
    text
        ``"42x31"`` or ``"d30"``, mm.
    module_width_m
        The module's width, m: no side may be wider (a wider load rests on the frame).
    name
        The input it came from, for the message.

    Returns
    -------
    LoadPatch
        The footprint, centred on the module.
    """
    t = str(text).strip().lower()
    disc = t.startswith("d")
    parts = [t[1:]] if disc else t.split("x")
    if len(parts) != (1 if disc else 2) or any("," in s for s in parts):
        raise InputError(f"{name} must be WxH or dD in mm, got {text!r}")
    sides = [_millimetres(s, text, name) for s in parts]
    if max(sides) > module_width_m:
        raise InputError(
            f"{name} {text!r} is wider than the module ({module_width_m * 1e3:g} mm): "
            "a load wider than the module rests on its frame"
        )
    return LoadPatch("disc", sides[0], sides[0]) if disc else LoadPatch("rectangle", *sides)


#: A plain ASCII decimal number (no digit separators, no other scripts' digits).
_PLAIN = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?", re.ASCII)


def _millimetres(item: str, text: str, name: str) -> float:
    if not _PLAIN.fullmatch(item.strip()):
        raise InputError(f"{name} must be WxH or dD in mm, got {text!r}")
    side = float(item) * 1e-3
    if not math.isfinite(side) or side <= 0:
        raise InputError(f"{name} {text!r}: every side must be a positive number of mm")
    if side < MIN_FOOTPRINT_M:
        raise InputError(
            f"{name} {text!r}: a side of {side * 1e3:g} mm is under {MIN_FOOTPRINT_M * 1e3:g} mm "
            "(metres given as millimetres?)"
        )
    return side


def detection_threshold_pa(
    threshold_pa: float,
    noise_pa: float | None = None,
    n_sigma: float = 3.0,
    names: tuple[str, str] = ("threshold", "n_sigma x noise"),
) -> tuple[float, str]:
    """The chamber study's detection threshold: ``n_sigma`` times the sensor noise when the
    noise is given, else ``threshold_pa``; and which of the two it is.

    Parameters
    ----------
    threshold_pa
        A threshold on the sealed pressure's rise (t_o in the thesis), Pa.
    noise_pa
        The sensor's noise (standard deviation), Pa, or None.
    n_sigma
        Multiple of the noise that makes the threshold.
    names
        How the two sources are named in messages (a command line passes its options).

    Returns
    -------
    tuple
        The threshold, Pa, and the name of its source.
    """
    if noise_pa is None:
        threshold, source = threshold_pa, names[0]
    else:
        threshold, source = n_sigma * noise_pa, names[1]
    if not (math.isfinite(threshold) and threshold > 0):
        raise InputError(
            f"detection threshold ({source}) must be > 0 kPa, got {threshold * 1e-3:g} kPa"
        )
    return threshold, source


__all__ = [
    "MASS_RANGE_KG",
    "MIN_FOOTPRINT_M",
    "THICKNESS_RANGE_M",
    "WIDTH_RANGE_M",
    "check_design_values",
    "check_masses",
    "check_study_pressures",
    "detection_threshold_pa",
    "parse_footprint",
]
