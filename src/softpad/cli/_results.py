"""``softpad results``: rerun the results the docs quote, at one commit, into docs/results.md.

Each result is a ``softpad`` command line run in this process with ``--json``; its figures
are read from the JSON and written with the command, its wall time, and where the docs
quote it. Three sizes: the default fits about 30 minutes on 2 cores (seeds 0-1 for the
trial-based results: 110 thesis-pair trials in ``validate``, 220 in ``compare``), ``--full``
runs the seeds the docs were measured on (hours), ``--quick`` runs seconds-long versions for
the test (the figures then mean nothing).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import platform
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass
from datetime import UTC, datetime
from typing import Any

from softpad.cli._args import add_command
from softpad.cli._output import emit, say
from softpad.errors import InputError

_DESCRIPTION = """\
Rerun every result quoted in README.md and docs/ at the current commit and write them, with
the commit, date, machine and the command of each, to docs/results.md (or --out)."""

_EPILOG = """examples:
  softpad results --force                     about 30 min on 2 cores: seeds 0-1 for trials
  softpad results --full --force              the docs' seeds (validate 0-9, compare 0-19): hours
  softpad results --quick --out /tmp/r.md     seconds; for a test of the machinery
  make results                                the default size into docs/results.md
"""


@dataclass(frozen=True)
class ResultSpec:
    """One quoted result: the command of each size and how to read its figures."""

    name: str
    #: Where the docs quote it.
    quoted_in: str
    #: The command (without ``softpad``), in the default, full and quick sizes.
    argv: tuple[str, ...]
    full: tuple[str, ...]
    quick: tuple[str, ...]
    #: Markdown lines of the figures, from the command's JSON.
    figures: Callable[[dict[str, Any]], list[str]]


def _validation_lines(doc: dict[str, Any]) -> list[str]:
    lines = [
        f"{role}: {c['agree']} agree, {c['disagree']} disagree, {c['undecided']} undecided, "
        f"{c['not_run']} not run"
        for role, c in doc["counts"].items()
    ]
    lines += [
        f"(seeds {doc['seeds'] or 'none'}, {doc['placements']} placement draws)",
        "",
        "| role | observation | thesis | predicted | interval | agrees |",
        "|---|---|---|---|---|---|",
    ]
    for o in doc["observations"]:
        lines.append(
            f"| {o['role']} | {o['name']} | {_text(o['thesis'])} | {_text(o['predicted'])} | "
            f"{_text(o['interval'])} | {o['verdict']} |"
        )
    return lines


def _text(v: Any) -> str:
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.3g}"
    if isinstance(v, list):
        return "(" + ", ".join(_text(x) for x in v) + ")"
    return str(v)


def _compare_lines(doc: dict[str, Any]) -> list[str]:
    lines = ["| planner + detector | held | 95 % interval | failures |", "|---|---|---|---|"]
    for c in doc["combinations"]:
        lo, hi = c["success_interval"]
        fails = ", ".join(f"{k} {v}" for k, v in sorted(c["failures"].items())) or "-"
        lines.append(
            f"| {c['planner']} + {c['detector']} | {c['successes']}/{c['trials']} "
            f"({100 * c['success']:.1f} %) | {100 * lo:.1f}-{100 * hi:.1f} % | {fails} |"
        )
    return lines


def _probe_lines(doc: dict[str, Any]) -> list[str]:
    rise = max(doc["delta_kpa"])
    return [
        f"largest module rise {rise:.4f} kPa for {doc['force_n']:g} N on "
        f"{doc['footprint_mm'][0]:g} x {doc['footprint_mm'][1]:g} mm at {doc['at']}: "
        f"{rise / doc['force_n']:.3f} kPa/N (FEM linear: "
        f"{max(doc['fem_delta_kpa']) / doc['force_n']:.3f} kPa/N)"
    ]


_TRIALS = ("--no-progress",)
#: Issue 34's evaluation: the YCB set's evaluation half (never used to develop a planner), one
#: trial per object and seed, every uncertain input drawn per trial; seeds 5001 and up.
_EVAL = (
    "compare",
    "--objects-file",
    "src/softpad/data/object_sets/ycb-eval.toml",
    "--trials",
    "1",
    "--randomize",
)
_EVAL_PAIRS = (
    "--pair",
    "thesis:thesis",
    "--pair",
    "gripper-aware:adaptive",
    "--pair",
    "model-based:adaptive",
)


def _probe(at: str) -> tuple[str, ...]:
    """The pad probe's command at ``at`` (modules), 0.2 N on 10 x 10 mm: the same in each size."""
    return ("pad", "probe", "--at", at, "--force-n", "0.2", "--footprint-mm", "10,10", "--json")


RESULTS: tuple[ResultSpec, ...] = (
    ResultSpec(
        "Validation against the thesis's observations",
        "README.md, docs/validation.md",
        ("validate", "--seeds", "0-1", "--json", *_TRIALS),
        ("validate", "--seeds", "0-9", "--json", *_TRIALS),
        ("validate", "--placements", "2", "--json", *_TRIALS),
        _validation_lines,
    ),
    ResultSpec(
        "Experiment 2, the thesis pair and gripper-aware + adaptive",
        "README.md, docs/trials.md, docs/beat-the-thesis.md",
        ("compare", "--seeds", "0-1", "--idle-hours", "0.1", "--json", *_TRIALS),
        ("compare", "--seeds", "0-19", "--idle-hours", "10", "--json", *_TRIALS),
        (
            "compare",
            "--seeds",
            "0",
            "--trials",
            "1",
            "--objects",
            "object-3",
            "--idle-hours",
            "0.001",
            "--json",
            *_TRIALS,
        ),
        _compare_lines,
    ),
    ResultSpec(
        "The model-based planner on the YCB evaluation half, every uncertain input drawn",
        "README.md, docs/beat-the-thesis.md (section 5), docs/planner.md",
        (*_EVAL, "--seeds", "5001-5002", *_EVAL_PAIRS, "--idle-hours", "0.1", "--json", *_TRIALS),
        (*_EVAL, "--seeds", "5001-5010", *_EVAL_PAIRS, "--idle-hours", "0.5", "--json", *_TRIALS),
        (
            *_EVAL,
            "--seeds",
            "5001",
            "--objects",
            "ycb-077-rubiks-cube",
            "--pair",
            "model-based:adaptive",
            "--idle-hours",
            "0.001",
            "--json",
            *_TRIALS,
        ),
        _compare_lines,
    ),
    ResultSpec(
        "Module sensitivity at its centre (pad probe, 0.2 N on 10 x 10 mm)",
        "README.md, docs/design.md, docs/box-and-simulator.md",
        _probe("1.5,1.5"),
        _probe("1.5,1.5"),
        _probe("1.5,1.5"),
        _probe_lines,
    ),
    ResultSpec(
        "Module sensitivity on the line between modules 2 and 3 (pad probe)",
        "README.md, docs/box-and-simulator.md",
        _probe("2,1.5"),
        _probe("2,1.5"),
        _probe("2,1.5"),
        _probe_lines,
    ),
)


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "results",
        "rerun every result the docs quote at this commit into docs/results.md",
        _DESCRIPTION,
        _EPILOG,
        json="print what was run (commit, size, file, each command's exit code and wall time)",
        force=True,
    )
    size = p.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="seconds-long versions (a test)")
    size.add_argument("--full", action="store_true", help="the docs' seeds (hours)")
    p.add_argument("--out", default="docs/results.md", metavar="FILE.md", help="output file")
    p.add_argument("--workers", type=int, default=None, help="worker processes of the trials")
    p.set_defaults(handler=run)


def _git(*args: str) -> str:
    """The standard output of ``git args``; raises where git fails or takes over 30 s."""
    return subprocess.run(
        ["git", *args], capture_output=True, text=True, check=True, timeout=30
    ).stdout


def _commit() -> str:
    try:
        head = _git("rev-parse", "--short", "HEAD").strip()
        dirty = _git("status", "--porcelain", "--untracked-files=no")
    except (OSError, subprocess.SubprocessError):
        return "unknown (not a git checkout)"
    return head + (" (with uncommitted changes)" if dirty.strip() else "")


def run_result(argv: list[str]) -> tuple[int, dict[str, Any] | None, str, float]:
    """Run one ``softpad`` command line in this process: exit code, its JSON, the end of its
    stderr, wall seconds."""
    from softpad.cli.main import main

    out, err = io.StringIO(), io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(argv)
    wall = time.perf_counter() - t0
    lines = [ln for ln in out.getvalue().splitlines() if ln.startswith("{")]
    doc = json.loads(lines[-1]) if lines else None
    return rc, doc, err.getvalue()[-500:], wall


def run(args: argparse.Namespace) -> int:
    from softpad.cli._paths import check_output, write_text_atomic

    out = check_output(args.out, "--out", force=args.force, suffix=".md")
    assert out is not None
    if args.workers is not None and not 1 <= args.workers <= 256:
        raise InputError(f"--workers must be from 1 to 256, got {args.workers}")
    size = "quick" if args.quick else "full" if args.full else "default"
    started = datetime.now(UTC)
    sections, failed, ran = [], 0, []
    for spec in RESULTS:
        argv = list({"quick": spec.quick, "full": spec.full, "default": spec.argv}[size])
        if args.workers is not None and argv[0] in ("validate", "compare"):
            argv += ["--workers", str(args.workers)]
        say(f"softpad results: {spec.name}: softpad {' '.join(argv)}", args.json)
        rc, doc, err, wall = run_result(argv)
        failed += rc != 0 or doc is None
        ran.append(
            {"name": spec.name, "command": ["softpad", *argv], "exit": rc, "wall_s": round(wall, 1)}
        )
        body = spec.figures(doc) if rc == 0 and doc else [f"**failed (exit {rc})**: `{err}`"]
        sections += [
            f"## {spec.name}",
            "",
            f"Command: `softpad {' '.join(argv)}` ({wall:.0f} s). Quoted in: {spec.quoted_in}.",
            "",
            *body,
            "",
        ]
    head = [
        "# Results at one commit",
        "",
        "Written by `softpad results` (`make results`); every figure below comes from the "
        "command beside it, run at this commit. Do not edit by hand.",
        "",
        f"- commit: {_commit()}",
        f"- date: {started:%Y-%m-%d %H:%M} UTC, {(datetime.now(UTC) - started).seconds} s in all",
        f"- machine: {platform.platform()}, {platform.machine()}, Python "
        f"{platform.python_version()}, {_cpus()} CPUs",
        f"- size: {size} ("
        + {
            "default": "seeds 0-1 for the trial-based results, to fit about 30 min on 2 cores; "
            "the docs' seeds with --full",
            "full": "the seeds the docs quote",
            "quick": "a test of the machinery: the figures mean nothing",
        }[size]
        + ")",
        "",
    ]
    write_text_atomic(out, "\n".join(head + sections))
    say(f"softpad results: written to {out}", args.json)
    if args.json:
        emit({"commit": _commit(), "size": size, "out": str(out), "results": ran})
    return 1 if failed else 0


def _cpus() -> int:
    import os

    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


__all__ = ["RESULTS", "ResultSpec", "run_result"]
