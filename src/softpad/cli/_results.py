"""``softpad results``: rerun the results the docs quote, at one commit, into docs/results.md
(:func:`softpad.trials.rerun_results`).

Each result is a ``softpad`` command line run in this process with ``--json``; its figures
are read from the JSON and written with the command, its wall time, and where the docs
quote it.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import time
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
    from softpad.trials import commit_text, rerun_results

    out = check_output(args.out, "--out", force=args.force, suffix=".md")
    assert out is not None
    if args.workers is not None and not 1 <= args.workers <= 256:
        raise InputError(f"--workers must be from 1 to 256, got {args.workers}")
    size = "quick" if args.quick else "full" if args.full else "default"
    page, ran, failed = rerun_results(
        size, run_result, args.workers, lambda text: say(text, args.json)
    )
    write_text_atomic(out, page)
    say(f"softpad results: written to {out}", args.json)
    if args.json:
        emit({"commit": commit_text(), "size": size, "out": str(out), "results": ran})
    return 1 if failed else 0


__all__ = ["run_result"]
