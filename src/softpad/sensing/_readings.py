"""A pad's readings from text (a frame file): increments, or pressures with their reference.

Formats (kilopascals, module order)::

    {"delta_kpa": [...]}                              JSON: the increments
    {"pressures_kpa": [...], "reference_kpa": [...]}  JSON: readings and the saved reference
    delta_kpa            pressure_kpa,reference_kpa   CSV with a header, one row per module
    0,0.124,0.078,...                                 CSV: one line of increments

:func:`parse_readings` reads them into :class:`PadReadings` (pascals);
:meth:`PadReadings.increments_pa` checks them against the pad and the sensor's range.
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from softpad import thesis
from softpad.errors import InputError, parse_json
from softpad.layout import PadLayout
from softpad.sensing._filters import increments
from softpad.sensing._objects import SENSOR_FULL_SCALE_PA

#: The sensor's range for a reading, Pa (a gauge reading a little below ambient is noise).
READING_RANGE_PA = (-2e3, SENSOR_FULL_SCALE_PA)
#: A plain ASCII decimal number (no digit separators, no other scripts' digits).
_PLAIN = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?", re.ASCII)


@dataclass(frozen=True)
class PadReadings:
    """What a frame file holds, in pascals.

    Attributes
    ----------
    values_pa
        The increments (``reference_pa`` None) or the readings of every module, Pa.
    reference_pa
        The reference saved after inflation, Pa, or None.
    """

    values_pa: tuple[float, ...]
    reference_pa: tuple[float, ...] | None = None

    def increments_pa(self, layout: PadLayout, source: str) -> list[float]:
        """The increments of every module, checked against the pad's module count and the
        sensor's range.

        Parameters
        ----------
        layout
            The pad.
        source
            Where the readings came from, for messages.

        Returns
        -------
        list of float
            dP_i, Pa.
        """
        n, values, ref = layout.n_modules, list(self.values_pa), self.reference_pa
        if ref is None:
            if len(values) != n:
                raise InputError(
                    f"{source}: a {layout.name} pad needs {n} increments (modules 1..{n}), "
                    f"got {len(values)}"
                )
            check_increment_range(values, source)
            return values
        check_reading_range(values, f"{source}: pressures")
        check_reading_range(ref, f"{source}: reference")
        if len(values) != n or len(ref) != n:
            raise InputError(
                f"{source}: a {layout.name} pad needs {n} pressures and {n} reference values, "
                f"got {len(values)} and {len(ref)}"
            )
        return [float(v) for v in increments(values, ref)]


def check_increment_range(delta_pa: Sequence[float], source: str) -> None:
    """A module's pressure cannot fall below ambient, so its increment is at least -p0, and p0
    is at most 2.8 kPa (thesis Section 6.2); above, the sensor's 10 kPa full scale bounds it.

    Parameters
    ----------
    delta_pa
        Increments, Pa.
    source
        Where they came from, for messages.
    """
    lo = -thesis.P0_RANGE_PA[1]
    for k, d in enumerate(delta_pa, 1):
        if not lo <= d <= SENSOR_FULL_SCALE_PA:
            hint = ": were pascals given as kPa?" if d > SENSOR_FULL_SCALE_PA else ""
            raise InputError(
                f"{source}: increment of module {k} is {d / 1e3:g} kPa, outside "
                f"{lo / 1e3:g} to {SENSOR_FULL_SCALE_PA / 1e3:g} kPa (a module cannot fall "
                f"below ambient, nor read above the sensor's full scale){hint}"
            )


def check_reading_range(values_pa: Sequence[float], source: str) -> None:
    """Readings within :data:`READING_RANGE_PA`, else a message suggesting Pa given as kPa.

    Parameters
    ----------
    values_pa
        Gauge readings, Pa.
    source
        Where they came from, for messages.
    """
    lo, hi = READING_RANGE_PA
    for i, v in enumerate(values_pa, 1):
        if not lo <= v <= hi:
            hint = ": pascals given as kPa?" if v > hi else ""
            raise InputError(
                f"{source}: module {i} reads {v / 1e3:g} kPa, outside the sensor range "
                f"{lo / 1e3:g}..{hi / 1e3:g} kPa{hint}"
            )


def parse_readings(text: str, source: str) -> PadReadings:
    """Read a frame file's text (module docstring's formats).

    Parameters
    ----------
    text
        The file's text.
    source
        What the text is (``frame file 'f.csv'``), for messages.

    Returns
    -------
    PadReadings
        The values and the reference (None for increments), Pa.
    """
    stripped = text.strip()
    if not stripped:
        raise InputError(f"{source} is empty")
    if stripped.startswith("{"):
        return _json_readings(parse_json(stripped, source), source)
    return _csv_readings(stripped, source)


def _json_readings(data: Any, source: str) -> PadReadings:
    if not isinstance(data, dict):
        raise InputError(f"{source} must hold a JSON object")
    keys = [k for k in ("delta_kpa", "pressures_kpa", "reference_kpa") if k in data]
    if "delta_kpa" in keys and len(keys) > 1:
        raise InputError(
            f"{source} gives both delta_kpa and {keys[1]}: give one of delta_kpa, or "
            "pressures_kpa with reference_kpa"
        )
    if "delta_kpa" in data:
        return PadReadings(_json_kpa(data["delta_kpa"], "delta_kpa"))
    if "pressures_kpa" in data and "reference_kpa" in data:
        values = _json_kpa(data["pressures_kpa"], "pressures_kpa")
        return PadReadings(values, _json_kpa(data["reference_kpa"], "reference_kpa"))
    raise InputError(f"{source} needs key delta_kpa, or pressures_kpa and reference_kpa")


def _json_kpa(values: Any, key: str) -> tuple[float, ...]:
    if not isinstance(values, list):
        raise InputError(f"{key} must be a list of numbers in kPa, got {type(values).__name__}")
    return _kpa([str(v) for v in values], key)


def _kpa(items: Sequence[str], name: str) -> tuple[float, ...]:
    """Plain numbers in kPa as pascals, naming ``name`` and the bad item."""
    if not items or items == [""]:
        raise InputError(f"{name} needs comma-separated numbers, got an empty value")
    out = []
    for i, s in enumerate(items, 1):
        if not _PLAIN.fullmatch(s.strip()):
            raise InputError(
                f"{name}: item {i} {s.strip()!r} is not a number (ASCII digits like 0.12 or 1e-3)"
            )
        v = float(s) * 1e3
        if not math.isfinite(v):
            raise InputError(f"{name}: item {i} must be finite, got {s!r}")
        out.append(v)
    return tuple(out)


def _csv_readings(stripped: str, source: str) -> PadReadings:
    try:  # newline="" semantics: a lone \r ends a line as \n does
        rows = [
            r for r in csv.reader(io.StringIO(stripped, newline=None)) if any(c.strip() for c in r)
        ]
    except csv.Error as exc:
        raise InputError(f"{source} is not valid CSV: {exc}") from None
    if not rows:
        raise InputError(f"{source} has no values (CSV or JSON expected)")
    header = [c.strip().lower() for c in rows[0]]
    if all(_is_number(c) for c in header):  # a line of numbers (checked strictly below)
        if len(rows) != 1:
            raise InputError(f"{source}: without a header give one line of increments in kPa")
        return PadReadings(_kpa(rows[0], "frame"))
    if len(rows) == 1:
        raise InputError(f"{source} has a header but no data rows")
    return _csv_columns(header, rows[1:], source)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _csv_columns(header: list[str], body: list[list[str]], source: str) -> PadReadings:
    def column(name: str) -> tuple[float, ...]:
        i = header.index(name)
        if any(len(r) <= i for r in body):
            raise InputError(f"{source}: a row has no {name} column")
        return _kpa([r[i] for r in body], name)

    if "delta_kpa" in header:
        if "pressure_kpa" in header or "reference_kpa" in header:
            raise InputError(f"{source}: header names delta_kpa and pressures; give one of them")
        return PadReadings(column("delta_kpa"))
    if "pressure_kpa" in header and "reference_kpa" in header:
        return PadReadings(column("pressure_kpa"), column("reference_kpa"))
    raise InputError(
        f"{source}: header must name delta_kpa, or pressure_kpa and reference_kpa; "
        f"got {', '.join(header)}"
    )


def read_readings(path: str) -> PadReadings:
    """The readings of a frame file (CSV or JSON, see :func:`parse_readings`).

    Parameters
    ----------
    path
        The file.
    """
    from pathlib import Path

    try:
        text = Path(path).read_bytes().decode("utf-8")
    except OSError as exc:
        raise InputError(f"cannot read frame file {path!r}: {exc.strerror}") from None
    except UnicodeDecodeError:
        raise InputError(
            f"frame file {path!r} is not text (CSV or JSON expected; a binary file?)"
        ) from None
    return parse_readings(text, f"frame file {path!r}")


__all__ = [
    "READING_RANGE_PA",
    "PadReadings",
    "check_increment_range",
    "check_reading_range",
    "parse_readings",
    "read_readings",
]
