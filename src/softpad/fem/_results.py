"""Shared parts of the study result objects (the material field, CSV writing, lazy matplotlib)."""

from __future__ import annotations

import csv
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np


@dataclass(frozen=True)
class StudyResult:
    """Base of the results of one module's studies, each with ``.to_dict()``, ``.to_csv(path)``
    and ``.plot(ax=None)``.

    Attributes
    ----------
    model
        Material preset name.
    """

    model: str


def write_csv(path: str | Path, header: Sequence[str], rows: Sequence[Sequence[Any]]) -> Path:
    """Write ``rows`` under ``header`` to ``path`` (parent folders created); return the path."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(list(header))
        for row in rows:
            writer.writerow([_fmt(v) for v in row])
    return out


def _fmt(value: Any) -> Any:
    if isinstance(value, float | np.floating):
        return f"{float(value):.6g}"
    return value


def new_axes(ax: Any = None) -> Any:
    """Return ``ax`` or a fresh matplotlib axes (matplotlib imported lazily)."""
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, axes = plt.subplots(figsize=(6.0, 4.0))
    return axes


def label_axes(ax: Any, xlabel: str, ylabel: str, title: str | None = None, **legend: Any) -> Any:
    """Label ``ax``, add a light grid and a legend (``legend`` keywords); return ``ax``."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title is not None:
        ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(**legend)
    return ax


def save_figure(ax: Any, path: str | Path) -> Path:
    """Save the figure of ``ax`` as an image at ``path`` and close it."""
    import matplotlib.pyplot as plt

    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig = ax.figure
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    return out


def as_list(values: np.ndarray, scale: float = 1.0, digits: int = 6) -> list[float]:
    """Array times ``scale`` as a list of floats rounded to ``digits`` significant digits."""
    return [float(f"{v * scale:.{digits}g}") for v in np.asarray(values, dtype=float).ravel()]
