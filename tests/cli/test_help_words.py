"""Words a newcomer knows (issue 51): "thesis", never "the seed", in every help; examples in
every group's help; every command in docs/quickstart.md; --config's help says what it sets."""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import pytest

from softpad.cli._installation import leaf_parsers
from softpad.cli.main import build_parser

ROOT = Path(__file__).resolve().parents[2]
#: "seed" used for the thesis (random seeds, --seeds, seed 0 are another thing).
SEED_FOR_THESIS = re.compile(
    r"\(seed, |\bseed(, | )(Section|Table|Fig\.|Eq\.)|\bthe seed(?:'s)?\b(?! (of|for|\d))"
)


def _groups() -> dict[str, argparse.ArgumentParser]:
    """The top-level commands that have actions of their own (box, ros, ...)."""
    root = build_parser()
    (sub,) = (a for a in root._actions if isinstance(a, argparse._SubParsersAction))
    return {
        name: p
        for name, p in sub.choices.items()
        if any(isinstance(a, argparse._SubParsersAction) for a in p._actions)
    }


def _all_parsers() -> list[argparse.ArgumentParser]:
    root = build_parser()
    out, todo = [], [root]
    while todo:
        p = todo.pop()
        out.append(p)
        for a in p._actions:
            if isinstance(a, argparse._SubParsersAction):
                todo.extend(dict.fromkeys(a.choices.values()))
    return out


def test_no_help_calls_the_thesis_the_seed() -> None:
    found = [
        f"{p.prog}: {m.group(0)!r}"
        for p in _all_parsers()
        for m in SEED_FOR_THESIS.finditer(p.format_help())
    ]
    assert not found, found


@pytest.mark.parametrize("group", sorted(_groups()))
def test_every_group_help_has_examples(group: str) -> None:
    text = _groups()[group].format_help()
    examples = text.split("examples:", 1)[-1] if "examples:" in text else ""
    assert f"softpad {group} " in examples, f"softpad {group} --help shows no example"


def test_every_command_is_in_the_quickstart() -> None:
    text = (ROOT / "docs" / "quickstart.md").read_text()
    shell = "\n".join(re.findall(r"```bash\n(.*?)```", text, flags=re.S))
    missing = [
        p.prog
        for p in leaf_parsers(build_parser())
        if p.prog != "softpad" and not re.search(re.escape(p.prog) + r"(\s|$)", shell)
    ]
    assert not missing, f"not in docs/quickstart.md's shell blocks: {missing}"


def test_config_help_names_what_the_file_sets() -> None:
    helps = {
        p.prog: p._option_string_actions["--config"].help for p in leaf_parsers(build_parser())
    }
    assert "takes nothing from it" in helps["softpad completion"]
    assert "--threshold-kpa" in helps["softpad plan"] and "--gripper" in helps["softpad plan"]
    assert "--box" in helps["softpad box monitor"]
