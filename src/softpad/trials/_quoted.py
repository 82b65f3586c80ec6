"""The results README.md and docs/ quote, as commands to rerun (``softpad results``): each
result is a ``softpad`` command line with ``--json`` in three sizes, its figures read from
the JSON, and the page (docs/results.md) written with the commit, date and machine.

The default size fits about 30 minutes on 2 cores (seeds 0-1 for the trial-based results:
110 thesis-pair trials in ``validate``, 220 in ``compare``), ``full`` runs the seeds the docs
were measured on (hours), ``quick`` runs seconds-long versions for the test (the figures then
mean nothing).
"""

from __future__ import annotations

import platform
import subprocess
from collections.abc import Callable
from dataclasses import dataclass
from datetime import UTC, datetime
from typing import Any

#: ``run(argv) -> (exit code, its JSON or None, the end of its stderr, wall s)``: how a
#: command line is run (the command line's own ``main`` in process).
RunCommand = Callable[[list[str]], tuple[int, dict[str, Any] | None, str, float]]


@dataclass(frozen=True)
class ResultSpec:
    """One quoted result: the command of each size and how to read its figures.

    Attributes
    ----------
    name
        The result's title.
    full, quick
        The command in the full and quick sizes (``argv``: the default size).
    """

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


def _git(*args: str) -> str:
    """The standard output of ``git args``; raises where git fails or takes over 30 s."""
    return subprocess.run(
        ["git", *args], capture_output=True, text=True, check=True, timeout=30
    ).stdout


def commit_text() -> str:
    """The checkout's commit, ``(with uncommitted changes)`` where it has some."""
    try:
        head = _git("rev-parse", "--short", "HEAD").strip()
        dirty = _git("status", "--porcelain", "--untracked-files=no")
    except (OSError, subprocess.SubprocessError):
        return "unknown (not a git checkout)"
    return head + (" (with uncommitted changes)" if dirty.strip() else "")


def _cpus() -> int:
    import os

    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


_SIZES = {
    "default": "seeds 0-1 for the trial-based results, to fit about 30 min on 2 cores; "
    "the docs' seeds with --full",
    "full": "the seeds the docs quote",
    "quick": "a test of the machinery: the figures mean nothing",
}


def result_argv(spec: ResultSpec, size: str, workers: int | None = None) -> list[str]:
    """The command line of ``spec`` in ``size`` (``default``, ``full``, ``quick``), with
    ``--workers`` for the trial-based commands when ``workers`` is given.

    Parameters
    ----------
    spec
        The result.
    size
        ``"default"``, ``"full"`` or ``"quick"``.
    workers
        Worker processes of the trials, or None.
    """
    argv = list({"quick": spec.quick, "full": spec.full, "default": spec.argv}[size])
    if workers is not None and argv[0] in ("validate", "compare"):
        argv += ["--workers", str(workers)]
    return argv


def rerun_results(
    size: str,
    run: RunCommand,
    workers: int | None = None,
    say: Callable[[str], None] = lambda text: None,
) -> tuple[str, list[dict[str, Any]], int]:
    """Rerun every result of :data:`RESULTS` and compose the page.

    Parameters
    ----------
    size
        ``"default"``, ``"full"`` or ``"quick"``.
    run
        Runs one command line (:data:`RunCommand`).
    workers
        Worker processes of the trials, or None.
    say
        Told each command before it runs.

    Returns
    -------
    tuple
        The page (Markdown), what ran (name, command, exit, wall_s each) and how many
        failed.
    """
    started = datetime.now(UTC)
    sections: list[str] = []
    failed, ran = 0, []
    for spec in RESULTS:
        argv = result_argv(spec, size, workers)
        say(f"softpad results: {spec.name}: softpad {' '.join(argv)}")
        rc, doc, err, wall = run(argv)
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
    return "\n".join(_page_head(size, started) + sections), ran, failed


def _page_head(size: str, started: datetime) -> list[str]:
    """The page's title and what it was run on."""
    return [
        "# Results at one commit",
        "",
        "Written by `softpad results` (`make results`); every figure below comes from the "
        "command beside it, run at this commit. Do not edit by hand.",
        "",
        f"- commit: {commit_text()}",
        f"- date: {started:%Y-%m-%d %H:%M} UTC, {(datetime.now(UTC) - started).seconds} s in all",
        f"- machine: {platform.platform()}, {platform.machine()}, Python "
        f"{platform.python_version()}, {_cpus()} CPUs",
        f"- size: {size} ({_SIZES[size]})",
        "",
    ]


__all__ = ["RESULTS", "ResultSpec", "RunCommand", "commit_text", "rerun_results", "result_argv"]
