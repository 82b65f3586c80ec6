"""No function or method in ``src/softpad`` is longer than 60 lines (issue 36 item 4).

A function's length is ``end_lineno - lineno + 1`` of its ``def`` in the ast: signature,
docstring, body and nested functions included (decorators not counted). A nested function is
checked on its own as well.
"""

from __future__ import annotations

import ast
from pathlib import Path

import softpad

SRC = Path(softpad.__file__).parent
MAX_LINES = 60


def long_functions(root: Path, max_lines: int = MAX_LINES) -> list[str]:
    """``path:line name (N lines)`` for every function under ``root`` over ``max_lines``."""
    found = []
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                assert node.end_lineno is not None
                lines = node.end_lineno - node.lineno + 1
                if lines > max_lines:
                    where = path.relative_to(root.parent)
                    found.append(f"{where}:{node.lineno} {node.name} ({lines} lines)")
    return found


def test_no_function_over_60_lines() -> None:
    found = long_functions(SRC)
    assert not found, f"{len(found)} functions over {MAX_LINES} lines:\n" + "\n".join(found)


def test_the_check_finds_a_long_function(tmp_path: Path) -> None:
    def body(indent: str, n: int) -> str:
        return "".join(f"{indent}x{i} = {i}\n" for i in range(n))

    (tmp_path / "ok.py").write_text("def fits():\n" + body("    ", 59), encoding="utf-8")
    (tmp_path / "long.py").write_text(
        "class C:\n    async def too_long(self):\n" + body("        ", 60), encoding="utf-8"
    )
    assert long_functions(tmp_path) == [f"{tmp_path.name}/long.py:2 too_long (61 lines)"]
