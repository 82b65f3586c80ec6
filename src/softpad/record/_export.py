"""Export a recording as one table (CSV, Parquet): frames and events, time-ordered."""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from softpad.errors import InputError

if TYPE_CHECKING:  # the methods of RecordedRun call these (no import circle)
    from softpad.record._read import RecordedRun


def table(run: RecordedRun) -> dict[str, list[Any]]:
    """Columns ``t_s, wall_ns, phase, p1_pa .. pN_pa, supply_pa, event, event_json``.

    One row per frame (event columns empty) and one per event (pressure columns empty, NaN
    readings too), in box-time order; an event follows the frames of the same time stamp.
    """
    n = run.channels
    phases = run.phases
    rows: list[tuple[float, int, list[Any]]] = []
    for i, t in enumerate(run.t_s):
        p = [None if not np.isfinite(v) else float(v) for v in run.pressures_pa[i]]
        rows.append((float(t), 0, [float(t), int(run.wall_ns[i]), phases[i], *p]))
        rows[-1][2].extend([float(run.supply_pa[i]), "", ""])
    for t, kind, d in run.events:
        row = [t, None, d.get("phase", ""), *([None] * n), None, kind, json.dumps(d)]
        rows.append((t, 1, row))
    rows.sort(key=lambda r: (r[0], r[1]))
    names = ["t_s", "wall_ns", "phase", *[f"p{k + 1}_pa" for k in range(n)], "supply_pa"]
    names += ["event", "event_json"]
    return {name: [r[2][j] for r in rows] for j, name in enumerate(names)}


def to_csv(run: RecordedRun, path: str | Path) -> Path:
    """Write :func:`table` as CSV (empty fields for missing values)."""
    cols = table(run)
    p = Path(path)
    with open(p, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for row in zip(*cols.values(), strict=True):
            w.writerow(["" if v is None else v for v in row])
    return p


def to_parquet(run: RecordedRun, path: str | Path) -> Path:
    """Write :func:`table` as Parquet; InputError when ``pyarrow`` is not installed."""
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise InputError(
            "Parquet export needs pyarrow (pip install 'softpad[parquet]'); use .csv instead"
        ) from None
    pq.write_table(pa.table(table(run)), str(path))
    return Path(path)
