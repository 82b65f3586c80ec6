"""One table of docs/validation.md from two ``softpad validate --json`` outputs: before and after.

    python examples/make_validation_table.py BEFORE.json AFTER.json

prints a Markdown table with one line per observation: its role (after issue 45: validation,
calibration, construction), the thesis's value with its 95 % interval, the prediction and
verdict before (the older JSON: Fisher's test and the 5 % theta share) and after (interval
overlap on >= 10x the thesis's trials; the modal plan within 0.1 module and 10 degrees), and
the smallest rate difference the count test detects with 80 % power (below/above the thesis's
rate, points). Rows are grouped by role, then the counts of each role.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any


def text(v: Any) -> str:
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.3g}"
    if isinstance(v, list):
        return "(" + ", ".join(text(x) for x in v) + ")"
    return str(v)


def old_verdict(o: dict[str, Any]) -> str:
    return {True: "yes", False: "**no**", None: "not run"}[o["agrees"]]


def detects(o: dict[str, Any]) -> str:
    d = o.get("detectable")
    if not d:
        return "-"
    down, up = (f"{v * 100:.0f}" if v is not None else "none" for v in d)
    return f"-{down}/+{up}"


def table(before: dict[str, Any], after: dict[str, Any]) -> str:
    old = {o["name"]: o for o in before["observations"]}
    marks = {"agree": "yes", "disagree": "**no**", "undecided": "undecided", "not run": "not run"}
    lines = [
        "| role | observation | thesis (95 % interval) | before: predicted | before | "
        "after: predicted (interval) | after | detects (pts) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for role in ("validation", "calibration", "construction"):
        for o in (o for o in after["observations"] if o["role"] == role):
            b = old.get(o["name"], {"predicted": None, "agrees": None})
            thesis = text(o["thesis"])
            if o.get("thesis_interval"):
                thesis += f" {text(o['thesis_interval'])}"
            got = text(o["predicted"])
            if o.get("interval") is not None and o.get("thesis_interval"):
                got += f" {text(o['interval'])}"
            lines.append(
                f"| {role} | {o['name']} | {thesis} | {text(b['predicted'])} | "
                f"{old_verdict(b)} | {got} | {marks[o['verdict']]} | {detects(o)} |"
            )
    lines.append("")
    c = before["counts"]
    lines.append(
        f"Before (all rows as one kind): {c['agree']} agree, {c['disagree']} disagree, "
        f"{c['not_run']} not run."
    )
    for role, c in after["counts"].items():
        lines.append(
            f"After, {role}: {c['agree']} agree, {c['disagree']} disagree, "
            f"{c['undecided']} undecided, {c['not_run']} not run."
        )
    return "\n".join(lines)


def main(before: Path, after: Path) -> str:
    """The table of two ``softpad validate --json`` files (paths), as Markdown text."""
    a, b = (json.loads(Path(p).read_text(encoding="utf-8")) for p in (before, after))
    return table(a, b)


if __name__ == "__main__":
    print(main(Path(sys.argv[1]), Path(sys.argv[2])))
