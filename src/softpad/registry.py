"""Parts chosen by name: one registry per kind of part, with an entry-point group each.

A :class:`Registry` maps names (``--planner gripper-aware``, ``--detector cusum``) to factories.
Its parts come from three places, in this order of precedence:

1. :meth:`Registry.register` (a factory object, at run time);
2. :meth:`Registry.register_lazy` (a ``"module:attribute"`` string, imported only when the
   part is made: how SoftPad's own parts in higher layers are offered without importing them);
3. the registry's entry-point group (``softpad.planners``, ``softpad.contact_detectors``,
   ``softpad.object_detectors``, ``softpad.robots``), read through :mod:`importlib.metadata`
   when a name is not found otherwise or the names are listed: how another installed package
   adds a part (pytest's ``pytest11``, Gymnasium's ``register``).

The command line builds its choices and help from :meth:`Registry.names` and
:meth:`Registry.summary`; an unknown name is an :class:`~softpad.errors.InputError` that names
the value and the registered ones.
"""

from __future__ import annotations

import importlib
import os
import sys
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from softpad.errors import InputError

F = TypeVar("F", bound=Callable[..., Any])


@dataclass(frozen=True)
class _Entry:
    target: Any  # a factory, or a "module:attribute" string not imported yet
    summary: str


def _load(target: str) -> Any:
    module, _, attribute = target.partition(":")
    obj: Any = importlib.import_module(module)
    for part in attribute.split("."):
        obj = getattr(obj, part)
    return obj


def _first_line(obj: Any) -> str:
    doc = (getattr(obj, "__doc__", None) or "").strip()
    return " ".join(doc.split("\n\n")[0].split())


def _path_state() -> tuple[tuple[str, int | None], ...]:
    """``sys.path``'s folders (absolute: ``""`` is the working folder) with their modification
    times (None: not a readable folder)."""
    state: list[tuple[str, int | None]] = []
    for entry in map(os.path.abspath, sys.path):
        try:
            state.append((entry, os.stat(entry).st_mtime_ns))
        except OSError:
            state.append((entry, None))
    return tuple(state)


_installed: list[Any] = [None, None]  # [path state, its entry points]


def _installed_entry_points() -> Any:
    """Every installed distribution's entry points, read again only when ``sys.path`` or one of
    its folders changed (installing or removing a distribution changes its folder's time):
    building the command's parser asks 20 times, and each read of all the ``entry_points.txt``
    files took about 5 ms (issue 38)."""
    from importlib.metadata import entry_points

    state = _path_state()
    if _installed[0] != state:
        _installed[:] = [state, entry_points()]
        _by_group.clear()
    return _installed[1]


_by_group: dict[str, dict[str, Any]] = {}  # group: {name: entry point} of _installed[1]


def _group_entry_points(group: str) -> dict[str, Any]:
    """The entry points of ``group`` by name (not to be changed: shared until the installed
    ones change); building the parser asks about 20 times, and each ``select`` over every
    installed entry point took about 0.2 ms (issue 50)."""
    installed = _installed_entry_points()
    found = _by_group.get(group)
    if found is None:
        found = _by_group[group] = {ep.name: ep for ep in installed.select(group=group)}
    return found


class Registry(Generic[F]):
    """Factories of one kind of part by name.

    Parameters
    ----------
    kind
        What the parts are, for messages (``"planner"``).
    group
        The entry-point group through which installed packages offer parts.
    """

    def __init__(self, kind: str, group: str) -> None:
        self.kind = kind
        self.group = group
        self._entries: dict[str, _Entry] = {}

    def register(self, name: str, factory: F, summary: str | None = None) -> None:
        """Offer ``factory`` under ``name`` (replacing a part of that name); ``summary``: one
        line for the command's help (default: the first paragraph of its docstring)."""
        self._check_name(name)
        self._entries[name] = _Entry(factory, _first_line(factory) if summary is None else summary)

    def register_lazy(self, name: str, target: str, summary: str) -> None:
        """Offer the factory at ``target`` (``"package.module:attribute"``) under ``name``,
        imported only when the part is made."""
        self._check_name(name)
        if ":" not in target:
            raise InputError(f"lazy {self.kind} target must be 'module:attribute', got {target!r}")
        self._entries[name] = _Entry(target, summary)

    def unregister(self, name: str) -> None:
        """Forget ``name`` (a test's temporary part); entry points come back on the next look."""
        self._entries.pop(name, None)

    def _check_name(self, name: str) -> None:
        if not (isinstance(name, str) and name and name.strip() == name and ":" not in name):
            raise InputError(f"a {self.kind} name must be a non-empty word, got {name!r}")

    def _entry_points(self) -> dict[str, Any]:
        return _group_entry_points(self.group)

    def names(self) -> tuple[str, ...]:
        """Every name offered, registered first (in registration order), then entry points."""
        extra = [n for n in sorted(self._entry_points()) if n not in self._entries]
        return (*self._entries, *extra)

    def _entry(self, name: str) -> _Entry:
        entry = self._entries.get(name)
        if entry is None:
            ep = self._entry_points().get(name)
            if ep is None:
                raise InputError(
                    f"unknown {self.kind} {name!r}; available: {', '.join(self.names())}"
                )
            factory = ep.load()
            self.register(name, factory)
            entry = self._entries[name]
        return entry

    def factory(self, name: str) -> F:
        """The factory registered as ``name`` (imported now when it was lazy)."""
        entry = self._entry(name)
        if isinstance(entry.target, str):
            entry = _Entry(_load(entry.target), entry.summary)
            self._entries[name] = entry
        f: F = entry.target
        return f

    def summary(self, name: str) -> str:
        """One line on the part ``name`` (for help texts)."""
        return self._entry(name).summary

    def help(self) -> str:
        """``name: summary`` of every part, ``;``-separated (a command's ``--help``)."""
        return "; ".join(f"{n}: {self.summary(n)}" if self.summary(n) else n for n in self.names())

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and name in self.names()
