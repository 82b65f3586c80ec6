"""Every public function and class (the ``__all__`` of each sub-package) documents its
parameters in a NumPy-style ``Parameters`` (or, for records, ``Attributes``) section
(issue 46; python-control's ``tests/docstrings_test.py`` is the model).

A dataclass field may instead carry a ``#:`` comment above it (what Sphinx's autodoc reads).
``*args``/``**kwargs`` and private parameters (``_name``) are not checked. Names documented
before this test existed and still lacking are listed in :data:`UNDOCUMENTED` with what they
lack; the list may only shrink: a listed name that is now documented fails the test until it
is taken off the list.
"""

from __future__ import annotations

import dataclasses
import enum
import importlib
import inspect
import pkgutil
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

import softpad

_SECTION = re.compile(r"^([ \t]*)(Parameters|Attributes|Other Parameters)\n[ \t]*-{3,}\n", re.M)


def documented_names(doc: str) -> set[str]:
    """Names given at the top indentation of the docstring's Parameters/Attributes sections
    (``name``, ``name : type`` or ``a, b, c``)."""
    names: set[str] = set()
    for m in _SECTION.finditer(doc):
        indent = m.group(1)
        lines = doc[m.end() :].splitlines()
        for i, line in enumerate(lines):
            if not line.strip():
                continue
            if not line.startswith(indent) or line[len(indent)] in " \t":
                continue  # a description line
            if i + 1 < len(lines) and re.fullmatch(r"[ \t]*-{3,}", lines[i + 1]):
                break  # the next section's header
            spec = line.strip().split(" : ")[0]
            names |= {n.strip().lstrip("*") for n in spec.split(",")}
    return names


def _commented_fields(cls: type) -> set[str]:
    """Dataclass fields with a ``#:`` comment on the line(s) just above them."""
    try:
        lines = inspect.getsource(cls).splitlines()
    except (OSError, TypeError):
        return set()
    out = set()
    for i, line in enumerate(lines):
        m = re.match(r"\s+(\w+)\s*:", line)
        if m and i > 0 and lines[i - 1].strip().startswith("#:"):
            out.add(m.group(1))
    return out


def _parameters(obj: Callable[..., Any]) -> list[str]:
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    skip = (inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD)
    return [
        p.name
        for p in sig.parameters.values()
        if p.kind not in skip and p.name not in ("self", "cls") and not p.name.startswith("_")
    ]


def missing_documentation(obj: Any) -> list[str]:
    """What ``obj`` (a public function or class) leaves undocumented: ``["docstring"]`` or
    its undocumented parameters."""
    doc = inspect.getdoc(obj) or ""
    if not doc.strip():
        return ["docstring"]
    if inspect.isclass(obj) and (
        issubclass(obj, BaseException | enum.Enum) or getattr(obj, "_is_protocol", False)
    ):
        return []
    known = documented_names(doc)
    if dataclasses.is_dataclass(obj):
        known |= _commented_fields(obj)
    return [p for p in _parameters(obj) if p not in known]


def public_callables() -> list[tuple[str, Any]]:
    """``(softpad.pkg.Name, object)`` of every function and class in a sub-package's
    ``__all__``."""
    out = []
    for info in sorted(pkgutil.iter_modules(softpad.__path__), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"softpad.{info.name}")
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if inspect.isfunction(obj) or inspect.isclass(obj):
                out.append((f"softpad.{info.name}.{name}", obj))
    return out


def _debt() -> dict[str, str]:
    path = Path(__file__).with_name("docstring_debt.txt")
    out = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            name, _, lacking = line.partition(" ")
            out[name] = lacking
    return out


#: Public names that lacked parameter documentation when this test was written.
UNDOCUMENTED = _debt()


def test_every_public_callable_documents_its_parameters() -> None:
    new = {
        name: lacking
        for name, obj in public_callables()
        if (lacking := missing_documentation(obj)) and name not in UNDOCUMENTED
    }
    assert not new, "undocumented parameters (NumPy 'Parameters' section):\n" + "\n".join(
        f"{n}: {', '.join(v)}" for n, v in sorted(new.items())
    )


def test_the_list_of_undocumented_names_only_shrinks() -> None:
    public = dict(public_callables())
    fixed = [n for n in UNDOCUMENTED if n not in public or not missing_documentation(public[n])]
    assert not fixed, "documented now (or gone): take off tests/docstring_debt.txt:\n" + "\n".join(
        fixed
    )


def _example(a: int, b: float, *args: Any, c: str = "", **kw: Any) -> None:
    """An example.

    Parameters
    ----------
    a, b
        Numbers.

    Returns
    -------
    c
        Not a parameter section.
    """


@pytest.mark.parametrize(
    ("doc_names", "expected"), [(("a", "b"), []), (("a",), ["b"])], ids=["all", "one-missing"]
)
def test_the_check_reads_numpy_sections(doc_names: tuple[str, ...], expected: list[str]) -> None:
    def f(a: int, b: int, *args: Any, **kw: Any) -> None:
        pass

    f.__doc__ = "F.\n\nParameters\n----------\n" + "".join(f"{n}\n    x\n" for n in doc_names)
    assert missing_documentation(f) == expected
    # names in a Returns section do not count as documented parameters
    assert missing_documentation(_example) == ["c"]
