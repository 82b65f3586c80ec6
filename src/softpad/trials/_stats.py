"""Statistics of trial outcomes shared by the records, the comparison and the validation."""

from __future__ import annotations

from softpad.errors import InputError


def wilson_interval(successes: int, trials: int) -> tuple[float, float]:
    """95 % Wilson score interval of a success rate (scipy's binomial test)."""
    from scipy.stats import binomtest

    if isinstance(successes, bool) or isinstance(trials, bool):
        raise InputError(f"successes and trials must be counts, got {successes!r}, {trials!r}")
    if not (int(trials) == trials and int(successes) == successes and 0 <= successes <= trials):
        raise InputError(
            f"successes must be a whole number from 0 to trials = {trials!r}, got {successes!r}"
        )
    if trials == 0:
        return (0.0, 1.0)
    ci = binomtest(successes, trials).proportion_ci(confidence_level=0.95, method="wilson")
    return (round(float(ci.low), 4), round(float(ci.high), 4))


__all__ = ["wilson_interval"]
