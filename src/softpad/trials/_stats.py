"""Statistics of trial outcomes shared by the records, the comparison and the validation."""

from __future__ import annotations

from math import sqrt

from softpad.errors import InputError

#: The standard normal's 97.5 % quantile, ``scipy.special.ndtri(0.975)`` to the last bit (the
#: two-sided 95 % level of the Wilson interval).
_Z_95 = 1.959963984540054


def wilson_interval(successes: int, trials: int) -> tuple[float, float]:
    """95 % Wilson score interval of a success rate, rounded to 4 decimals.

    The same arithmetic, in the same order, as scipy's
    ``binomtest(successes, trials).proportion_ci(0.95, method="wilson")`` (Newcombe 1998,
    without continuity correction), so the same bits; written out here because importing
    ``scipy.stats`` for it costs about a second of CPU in every process that prints a trial
    table (a test compares the two).
    """
    if isinstance(successes, bool) or isinstance(trials, bool):
        raise InputError(f"successes and trials must be counts, got {successes!r}, {trials!r}")
    if not (int(trials) == trials and int(successes) == successes and 0 <= successes <= trials):
        raise InputError(
            f"successes must be a whole number from 0 to trials = {trials!r}, got {successes!r}"
        )
    if trials == 0:
        return (0.0, 1.0)
    lo, hi = wilson_bounds_95(int(successes), int(trials))
    return (round(lo, 4), round(hi, 4))


def wilson_bounds_95(k: int, n: int) -> tuple[float, float]:
    """The unrounded 95 % Wilson interval of ``k`` successes in ``n >= 1`` trials (unchecked):
    scipy's ``_binom_wilson_conf_int`` step by step."""
    z = _Z_95
    p = k / n
    denom = 2 * (n + z**2)
    center = (2 * n * p + z**2) / denom
    delta = z / denom * sqrt(4 * n * p * (1 - p) + z**2)
    lo = 0.0 if k == 0 else center - delta
    hi = 1.0 if k == n else center + delta
    return (float(lo), float(hi))


__all__ = ["wilson_interval"]
