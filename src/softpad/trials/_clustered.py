"""Comparisons of two planner/detector pairs with the object as the unit.

Trials of one object are not independent of each other: a planner that fails on one object
fails on most of its trials, so a test that counts 100 trials of ten objects as 100 independent
draws overstates the evidence. Beside the trial-level test (Fisher's exact test on the pooled
counts), a comparison here reports two figures that treat the object as the unit, as grasping
benchmarks report per-object success:

- a paired sign-flip permutation test over objects: under the null hypothesis that the two
  pairs do equally well on every object, the sign of each object's difference in success rate
  is as likely + as -; the p-value is the share of the 2**n sign assignments whose mean
  difference is at least as far from zero as the observed one (exact while 2**n is at most
  ``EXACT_LIMIT``, else a seeded Monte Carlo of the same);
- a cluster bootstrap interval of the difference in success rate: objects resampled with
  replacement (each keeping all its trials under both pairs), the percentile interval of the
  difference in pooled success rate, seeded.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from softpad.errors import InputError

#: Bootstrap resamples of the objects and the seed of the resampling (fixed, so a comparison
#: and its merge give the same interval).
BOOTSTRAP_RESAMPLES = 10_000
BOOTSTRAP_SEED = 0

#: Sign assignments enumerated exactly up to this many (2**16: 16 objects); beyond, this many
#: seeded random ones.
EXACT_LIMIT = 2**16


def _counts(objects: Sequence[dict[str, Any]]) -> tuple[list[str], np.ndarray, np.ndarray]:
    names = [str(o["name"]) for o in objects]
    k = np.array([int(o["successes"]) for o in objects], dtype=float)
    n = np.array([int(o["trials"]) for o in objects], dtype=float)
    return names, k, n


def sign_flip_p_value(differences: Sequence[float], seed: int = BOOTSTRAP_SEED) -> float:
    """Two-sided p-value of a paired sign-flip permutation test of a zero mean difference.

    Parameters
    ----------
    differences
        One difference per object (pair B's success rate minus pair A's, 1).

    Returns
    -------
    float
        Share of sign assignments with ``|mean| >= |observed mean|`` (scipy.stats'
        ``permutation_test``, ``permutation_type='samples'``: exact for up to 16 objects).
    """
    from scipy.stats import permutation_test

    d = np.asarray(differences, dtype=float)
    if d.size == 0:
        raise InputError("a paired test needs at least one object")
    if not np.any(d) or d.size == 1:
        return 1.0  # one object: +d and -d have the same |mean|, so p is exactly 1
    res = permutation_test(
        (d, np.zeros_like(d)),
        lambda a, b, axis: np.mean(a - b, axis=axis),
        permutation_type="samples",
        vectorized=True,
        n_resamples=EXACT_LIMIT,
        alternative="two-sided",
        rng=np.random.default_rng(seed),
    )
    return float(min(1.0, res.pvalue))


def cluster_bootstrap_interval(
    k_a: np.ndarray,
    n_a: np.ndarray,
    k_b: np.ndarray,
    n_b: np.ndarray,
    resamples: int = BOOTSTRAP_RESAMPLES,
    seed: int = BOOTSTRAP_SEED,
    confidence: float = 0.95,
) -> tuple[float, float]:
    """Percentile interval of ``sum(k_b)/sum(n_b) - sum(k_a)/sum(n_a)`` over objects resampled
    with replacement (``k``: successes, ``n``: trials of each object under pairs A and B)."""
    arrays = [np.asarray(x, dtype=float) for x in (k_a, n_a, k_b, n_b)]
    m = arrays[0].size
    if m == 0 or any(a.shape != (m,) for a in arrays):
        raise InputError("a cluster bootstrap needs the same objects, at least one, under both")
    rng = np.random.default_rng(seed)
    idx = rng.integers(0, m, size=(resamples, m))
    ka, na, kb, nb = (a[idx].sum(axis=1) for a in arrays)
    diff = kb / np.maximum(nb, 1) - ka / np.maximum(na, 1)
    tail = 50 * (1 - confidence)
    lo, hi = np.percentile(diff, [tail, 100 - tail])
    return float(lo), float(hi)


def fisher_p_value(k_a: int, n_a: int, k_b: int, n_b: int) -> float:
    """Two-sided p of Fisher's exact test on the pooled counts (trials taken as independent)."""
    from scipy.stats import fisher_exact

    table = [[k_a, n_a - k_a], [k_b, n_b - k_b]]
    return float(fisher_exact(table, alternative="two-sided").pvalue)


def contrast(a: dict[str, Any], b: dict[str, Any]) -> dict[str, Any]:
    """Pair ``b`` against pair ``a`` (two combinations of a comparison over the same objects).

    Returns
    -------
    dict
        ``a`` and ``b`` (``planner:detector``), ``difference`` (b's success rate minus a's,
        pooled), ``trial_p_value`` (Fisher, trials as independent), ``objects`` (count),
        ``objects_better`` / ``objects_worse`` (objects on which b holds more / less often),
        ``object_p_value`` (paired sign-flip test over objects) and ``object_interval``
        (95 % cluster bootstrap interval of the difference, ``bootstrap_resamples`` resamples
        of seed ``bootstrap_seed``).
    """
    names_a, k_a, n_a = _counts(a["objects"])
    names_b, k_b, n_b = _counts(b["objects"])
    if names_a != names_b:
        raise InputError(f"pairs compared over other objects: {names_a} against {names_b}")
    d = k_b / np.maximum(n_b, 1) - k_a / np.maximum(n_a, 1)
    sa, sb = int(k_a.sum()), int(k_b.sum())
    ta, tb = int(n_a.sum()), int(n_b.sum())
    lo, hi = cluster_bootstrap_interval(k_a, n_a, k_b, n_b)
    return {
        "a": f"{a['planner']}:{a['detector']}",
        "b": f"{b['planner']}:{b['detector']}",
        "difference": round(sb / max(tb, 1) - sa / max(ta, 1), 4),
        "trial_p_value": float(f"{fisher_p_value(sa, ta, sb, tb):.4g}"),
        "objects": len(names_a),
        "objects_better": int(np.sum(d > 0)),
        "objects_worse": int(np.sum(d < 0)),
        "object_p_value": float(f"{sign_flip_p_value(d):.4g}"),
        "object_interval": [round(lo, 4), round(hi, 4)],
        "bootstrap_resamples": BOOTSTRAP_RESAMPLES,
        "bootstrap_seed": BOOTSTRAP_SEED,
    }


def contrasts(combinations: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """Every later pair against every earlier one, in the order the pairs are listed."""
    return [
        contrast(combinations[i], combinations[j])
        for i in range(len(combinations))
        for j in range(i + 1, len(combinations))
    ]


__all__ = [
    "BOOTSTRAP_RESAMPLES",
    "BOOTSTRAP_SEED",
    "EXACT_LIMIT",
    "cluster_bootstrap_interval",
    "contrast",
    "contrasts",
    "fisher_p_value",
    "sign_flip_p_value",
]
