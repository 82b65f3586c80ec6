"""Regenerate the regression recordings in tests/data/ (``softpad replay`` cases).

Run from the repository root::

    .venv/bin/python tests/data/make_recordings.py

Each is ``softpad run --record`` on the simulated box at 100 Hz with 6 channels and a 0.5 s hold
(about 200 kB). ``tests/record/test_replay.py`` replays every ``*.mcap`` here and requires today's
code to reproduce the recorded plan and contact sample; regenerate them only on purpose (a
deliberate change of the sensing or planning), and say so in the commit.
"""

from __future__ import annotations

from pathlib import Path

from softpad.cli.main import main

HERE = Path(__file__).parent

#: name -> (objects, box URL)
CASES = {
    "banana": (["banana"], "sim://?seed=1&channels=6&rate_hz=100"),
    "object-1_object-4": (["object-1", "object-4"], "sim://?seed=2&channels=6&rate_hz=100"),
    "cylinder": (["cylinder"], "sim://?seed=3&channels=6&rate_hz=100"),
}


def make(name: str) -> Path:
    """Record case ``name`` into tests/data/NAME.mcap (overwriting it)."""
    objects, url = CASES[name]
    path = HERE / f"{name}.mcap"
    argv = ["run", "--box", url, "--hold-s", "0.5", "--record", str(path), "--force"]
    for o in objects:
        argv += ["--object", o]
    if main(argv) != 0:
        raise SystemExit(f"recording {name} failed")
    return path


if __name__ == "__main__":
    for case in CASES:
        print(make(case), f"{make.__name__}: done")
