"""Pressure-based centre of mass (PCOM), Eq. (6.1) of the thesis."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from softpad.errors import InputError
from softpad.layout import PadLayout


def pcom(delta_pa: ArrayLike, modules: Sequence[int], layout: PadLayout) -> tuple[float, float]:
    """Weighted mean of the module centres, weights dP_i (Eq. 6.1).

    ``x_PCOM = sum(dP_i x_i) / sum(dP_i)`` over the object's modules, likewise y.

    Parameters
    ----------
    delta_pa
        Increments of every module of the layout, pascals (module order 1..N).
    modules
        1-based module numbers of the object.
    layout
        Pad geometry.

    Returns
    -------
    (x, y) in module units.
    """
    if isinstance(delta_pa, list):
        d = delta_pa
    elif isinstance(delta_pa, np.ndarray):
        d = delta_pa.tolist()
    else:
        d = list(np.asarray(delta_pa, float))
    if not modules:
        raise InputError("an object needs at least one module to compute its PCOM")
    centres = layout.center_table
    total = sx = sy = 0.0
    for m in modules:
        w = float(d[layout.check_module(m) - 1])
        x, y = centres[m - 1]
        total += w
        sx += w * x
        sy += w * y
    if not math.isfinite(total) or total <= 0:
        raise InputError(f"increments of modules {list(modules)} must sum to > 0 Pa, got {total:g}")
    return sx / total, sy / total
