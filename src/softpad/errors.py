"""Exceptions shared by every sub-package.

Each subclasses a built-in so callers can catch either (``except ValueError`` still works).
The CLI turns any :class:`SoftPadError` into a one-line message and exit code 2.
"""

from __future__ import annotations


class SoftPadError(Exception):
    """Base class of every error SoftPad raises on purpose."""


class InputError(SoftPadError, ValueError):
    """A value given by the user is malformed or outside its allowed range."""


class LayoutError(InputError):
    """A pad layout string or a module number is invalid."""


class HardwareFault(SoftPadError, RuntimeError):
    """The pneumatic box reported or showed a fault (dropout, stuck valve, leak, supply loss).

    Raised only after the box has been put in a safe state (inflation valves closed).
    """


def check_finite(name: str, value: float) -> float:
    """Return ``value`` as float or raise :class:`InputError` naming it when it is NaN or infinite."""
    import math

    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise InputError(f"{name} must be a finite number, got {value!r}")
    return v
