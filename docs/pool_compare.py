"""Pool ``softpad compare --json`` outputs of one trial per object (one file per pair and
seed) into one table per object set: success with 95 % Wilson intervals, Fisher's exact
test of each pair against the first, per-object counts, contact delay (median over trials)
and false alarms per hour (mean over the files' idle runs).

    python docs/pool_compare.py OUT_DIR/eval_*_50??.json

File names: ``{set}_{planner}_{seed}.json`` (as written by the commands in
docs/beat-the-thesis.md, section 5). Prints Markdown.
"""

from __future__ import annotations

import json
import statistics
import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

from scipy.stats import fisher_exact

from softpad.trials import wilson_interval


def pooled(paths: list[str]) -> dict[str, dict[str, Any]]:
    """Per pair (planner:detector): trials, successes, per-object counts, delays, alarms."""
    out: dict[str, dict[str, Any]] = {}
    for path in sorted(paths):
        doc = json.loads(Path(path).read_text(encoding="utf-8"))
        for c in doc["combinations"]:
            key = f"{c['planner']}:{c['detector']}"
            p = out.setdefault(
                key,
                {
                    "n": 0,
                    "k": 0,
                    "objects": defaultdict(lambda: [0, 0]),
                    "delays": [],
                    "alarms": [],
                    "seeds": [],
                    "failures": defaultdict(int),
                },
            )
            p["n"] += c["trials"]
            p["k"] += c["successes"]
            p["alarms"].append(c["false_alarms_per_hour"])
            p["seeds"] += doc["seeds"]
            for cause, count in c["failures"].items():
                p["failures"][cause] += count
            for o in c["objects"]:
                p["objects"][o["name"]][0] += o["successes"]
                p["objects"][o["name"]][1] += o["trials"]
                if o["delay_s_median"] is not None:
                    p["delays"].append(o["delay_s_median"])  # one trial per object and file
    return out


def fisher(a: dict[str, Any], b: dict[str, Any]) -> str:
    """Two-sided Fisher's exact p of a's success count against b's."""
    if a is b:
        return "-"
    _, pv = fisher_exact([[a["k"], a["n"] - a["k"]], [b["k"], b["n"] - b["k"]]])
    return f"{pv:.3g}"


def table(pairs: dict[str, dict[str, Any]]) -> str:
    order = ("thesis:thesis", "gripper-aware:adaptive")
    names = [n for n in order if n in pairs] + sorted(n for n in pairs if n not in order)
    ref, aware = pairs.get(order[0]), pairs.get(order[1])
    lines = [
        "| pair | success | 95 % Wilson | Fisher p vs thesis pair | vs gripper-aware pair "
        "| delay median (ms) | false alarms/h | failures |",
        "|---|---:|---|---:|---:|---:|---:|---|",
    ]
    for name in names:
        p = pairs[name]
        lo, hi = wilson_interval(p["k"], p["n"])
        p_ref = fisher(p, ref) if ref else "-"
        p_aware = fisher(p, aware) if aware else "-"
        delay = f"{1e3 * statistics.median(p['delays']):.0f}" if p["delays"] else "-"
        alarms = statistics.fmean(p["alarms"]) if p["alarms"] else float("nan")
        fails = ", ".join(f"{c} {n}" for c, n in sorted(p["failures"].items())) or "-"
        lines.append(
            f"| {name} | {p['k']}/{p['n']} = {100 * p['k'] / p['n']:.0f} % | "
            f"{100 * lo:.0f}-{100 * hi:.0f} % | {p_ref} | {p_aware} | {delay} | {alarms:g} | "
            f"{fails} |"
        )
    objects = sorted({o for p in pairs.values() for o in p["objects"]})
    lines += ["", "| object | " + " | ".join(names) + " |", "|---|" + "---:|" * len(names)]
    for o in objects:
        cells = [f"{pairs[n]['objects'][o][0]}/{pairs[n]['objects'][o][1]}" for n in names]
        lines.append(f"| {o} | " + " | ".join(cells) + " |")
    seeds = sorted({s for p in pairs.values() for s in p["seeds"]})
    lines.append(f"\nseeds {seeds}")
    return "\n".join(lines)


if __name__ == "__main__":
    print(table(pooled(sys.argv[1:])))
