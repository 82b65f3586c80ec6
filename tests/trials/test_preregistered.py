"""The pre-registered evaluation of docs/planner.md is a valid command as written.

The commands are run once, by hand, at the closing commit; here they are parsed by the real
command line with the trials replaced, so that a typo, an unknown pair or a renamed object set
is found before that run and not by it.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path
from typing import Any

import pytest

from softpad.cli.main import main
from softpad.design import load_object_set

ROOT = Path(__file__).resolve().parents[2]
PAIRS = [("thesis", "thesis"), ("gripper-aware", "adaptive"), ("model-based", "adaptive")]


def _registered() -> list[list[str]]:
    page = (ROOT / "docs" / "planner.md").read_text(encoding="utf-8")
    section = page.split("### Pre-registered evaluation (issue 47)", 1)[1]
    block = re.search(r"```text\n(.*?)```", section, re.S)
    assert block is not None
    return [shlex.split(line) for line in block.group(1).splitlines() if line.strip()]


def test_two_commands_are_registered_one_per_set() -> None:
    commands = _registered()
    files = [c[c.index("--objects-file") + 1] for c in commands]
    assert files == [
        "src/softpad/data/object_sets/ycb-eval.toml",
        "src/softpad/data/object_sets/datasheet-eval.toml",
    ]
    seeds = [c[c.index("--seeds") + 1] for c in commands]
    assert len(set(seeds)) == 2  # each set its own seeds


@pytest.mark.parametrize("index", [0, 1], ids=["ycb-eval", "datasheet-eval"])
def test_the_registered_command_runs_every_object_randomized_anywhere(
    index: int, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import softpad.trials

    argv = _registered()[index]
    assert argv[0] == "softpad" and argv[-2] == ">"
    seen: dict[str, Any] = {}

    def fake(specs: Any, seeds: Any, pairs: Any, **kwargs: Any) -> dict[str, Any]:
        seen.update(specs=specs, seeds=list(seeds), pairs=list(pairs), **kwargs)
        return {"schema_version": 2, "seeds": list(seeds), "combinations": [], "contrasts": []}

    monkeypatch.setattr(softpad.trials, "compare", fake)
    monkeypatch.chdir(ROOT)
    assert main(argv[1:-2]) == 0
    capsys.readouterr()
    objects = load_object_set(ROOT / argv[argv.index("--objects-file") + 1])
    assert [s.name for s in seen["specs"]] == [o.name for o in objects.objects]
    assert all(o.placement == "anywhere" for o in objects.objects)
    assert seen["config"].randomize and seen["pairs"] == PAIRS
    assert len(seen["seeds"]) * seen["trials"] * len(objects.objects) == 100
