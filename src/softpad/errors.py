"""Exceptions shared by every sub-package, and the exit code of each.

Each subclasses a built-in so callers can catch either (``except ValueError`` still works).
The ``softpad`` command turns every exception into a one-line message and the exit code of its
class (:func:`exit_code_for`):

====  ==========================================================================
code  meaning
====  ==========================================================================
0     success (every grasp held, every study done)
1     the job ran but failed (a grasp not held, a model that did not converge)
2     bad input (usage, values, files)
3     hardware or link fault (the box was put in a safe state)
4     internal error (a bug: please report it)
====  ==========================================================================
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable
from typing import Annotated, Any, ClassVar

EXIT_OK = 0
"""Success."""
EXIT_FAILED = 1
"""The job ran but failed (a grasp not held)."""
EXIT_INPUT = 2
"""Bad input: usage, values, files."""
EXIT_HARDWARE = 3
"""Hardware or link fault; the safe state was reached."""
EXIT_INTERNAL = 4
"""Internal error (a bug)."""


class SoftPadError(Exception):
    """Base class of every error SoftPad raises on purpose.

    ``exit_code`` is the ``softpad`` command's exit status for the class and ``kind`` the
    ``error.kind`` of its JSON output; ``partial`` may carry the results gathered before it.
    """

    exit_code: int = EXIT_FAILED
    kind: str = "failed"
    partial: dict | None = None


class JobFailed(SoftPadError, RuntimeError):
    """The job ran to its end but did not succeed (a grasp not held)."""


class InputError(SoftPadError, ValueError):
    """A value given by the user is malformed or outside its allowed range."""

    exit_code = EXIT_INPUT
    kind = "input"


class LayoutError(InputError):
    """A pad layout string or a module number is invalid."""


class HardwareFault(SoftPadError, RuntimeError):
    """The pneumatic box reported or showed a fault (dropout, stuck valve, leak, supply loss).

    Raised only after the box has been put in a safe state (inflation valves closed).
    """

    exit_code = EXIT_HARDWARE
    kind = "hardware"


def exit_code_for(exc: BaseException) -> int:
    """Exit status of the ``softpad`` command for ``exc`` (see the module's table)."""
    if isinstance(exc, SoftPadError):
        return int(exc.exit_code)
    return EXIT_INTERNAL


def check_finite(name: str, value: float) -> float:
    """Return ``value`` as float or raise :class:`InputError` naming it when it is NaN or infinite."""
    import math

    if isinstance(value, str | bytes):  # float("50.0") would pass: a number in text is a slip
        raise InputError(f"{name} must be a number, got the text {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise InputError(f"{name} must be a finite number, got {value!r}")
    return v


def check_range(
    name: str,
    value: object,
    lo: float,
    hi: float,
    unit: str = "",
    hint: str = "",
    low_hint: str = "",
) -> float:
    """Return ``value`` as a finite float within [lo, hi], or raise :class:`InputError` naming
    ``name``, the value, the limits and ``unit``.

    ``hint`` is added when the value lies above ``hi``, or below a negative ``lo`` of a range
    symmetric about zero (for example ``"millimetres given as metres?"``), the usual cause of a
    value a thousand times too large at the library's edge; ``low_hint`` when it lies below a
    positive ``lo`` (``"metres given as millimetres?"``).
    """
    v = check_finite(name, value)  # type: ignore[arg-type]
    if not lo <= v <= hi:
        u = f" {unit}" if unit else ""
        too_far = v > hi or (lo == -hi and v < lo)
        why = hint if too_far else low_hint if v < lo and lo > 0 else ""
        extra = f" ({why})" if why else ""
        raise InputError(f"{name} must be from {lo:g} to {hi:g}{u}, got {v:g}{u}{extra}")
    return v


def check_count(name: str, value: object, lo: int, hi: int) -> int:
    """Return ``value`` as an integer within [lo, hi] (bools refused), or raise
    :class:`InputError` naming it and the limits."""
    import numbers

    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InputError(f"{name} must be an integer from {lo} to {hi}, got {value!r}")
    if not lo <= int(value) <= hi:
        raise InputError(f"{name} must be from {lo} to {hi}, got {value}")
    return int(value)


#: Hint for a length a thousand times too large: millimetres given where metres are expected.
MM_AS_M = "millimetres given as metres?"
#: Hint for a pressure a thousand times too small: kilopascals given where pascals are expected.
KPA_AS_PA = "kilopascals given as pascals?"
#: Hint for a duration a thousand times too long: milliseconds given where seconds are expected.
MS_AS_S = "milliseconds given as seconds?"


def check_fields(
    owner: object,
    what: str,
    positive: Iterable[str] = (),
    non_negative: Iterable[str] = (),
    counts: Iterable[str] = (),
) -> None:
    """Check the named attributes of a parameters record, raising :class:`InputError` that
    names ``what`` (``"execution"``), the attribute and its value.

    Parameters
    ----------
    owner
        The record (usually ``self`` in a frozen dataclass's ``__post_init__``).
    positive, non_negative
        Attributes that must be finite numbers > 0, or >= 0.
    counts
        Attributes that must be integers >= 1.
    """
    import math

    def number(v: object) -> bool:
        return isinstance(v, int | float) and math.isfinite(v)

    for rule, ok, names in (
        ("a positive number", lambda v: number(v) and v > 0, positive),
        ("a number >= 0", lambda v: number(v) and v >= 0, non_negative),
        ("an integer >= 1", lambda v: isinstance(v, int) and v >= 1, counts),
    ):
        for n in names:
            v = getattr(owner, n)
            if not ok(v):
                raise InputError(f"{what} {n} must be {rule}, got {v!r}")


#: A field of a :class:`CheckedFields` record that must be a finite number > 0.
Positive = Annotated[float, "positive"]
#: A field of a :class:`CheckedFields` record that must be a finite number >= 0.
NonNegative = Annotated[float, "non_negative"]
#: A field of a :class:`CheckedFields` record that must be an integer >= 1.
Count = Annotated[int, "counts"]

_LIMIT_NAMES = {"Positive": "positive", "NonNegative": "non_negative", "Count": "counts"}


class CheckedFields:
    """Base of a frozen parameters dataclass whose field annotations state the fields' limits.

    A field annotated :data:`Positive`, :data:`NonNegative` or :data:`Count` is checked by
    :func:`check_fields` after ``__init__``, errors naming the ``what`` given in the class
    statement (``class ExecutionParams(CheckedFields, what="execution")``). A subclass with
    further checks defines ``__post_init__`` and calls ``super().__post_init__()`` in it.
    """

    _what: ClassVar[str] = ""
    _limits: ClassVar[dict[str, tuple[str, ...]] | None] = None

    def __init_subclass__(cls, what: str | None = None, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if what is not None:
            cls._what = what
        cls._limits = None

    def __post_init__(self) -> None:
        cls = type(self)
        if cls._limits is None:
            limits: dict[str, list[str]] = {"positive": [], "non_negative": [], "counts": []}
            for f in dataclasses.fields(self):  # type: ignore[arg-type]
                t = f.type if isinstance(f.type, str) else getattr(f.type, "__metadata__", ("",))[0]
                rule = _LIMIT_NAMES.get(str(t), str(t))
                if rule in limits:
                    limits[rule].append(f.name)
            cls._limits = {rule: tuple(names) for rule, names in limits.items()}
        check_fields(self, cls._what, **cls._limits)


def parse_json(text: str, what: str) -> Any:
    """``json.loads(text)``, or an :class:`InputError` saying that ``what`` (``"frame file
    'x.json'"``) is not valid JSON, with the reason and the line."""
    import json

    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"{what} is not valid JSON: {exc.msg} at line {exc.lineno}") from None
