"""On-disk results of design sweeps, keyed by what they depend on and the code version.

Every finished task (a finite-element response, the trials of one design and seed) is written
at once as ``DIR/KIND/KEY.json`` (atomically: a temporary file renamed), so an interrupted
sweep resumes where it stopped and a repeated one costs nothing. The key is a hash of the
inputs and of :func:`code_version`, so changing the code invalidates the results.
"""

from __future__ import annotations

import json
import os
import tempfile
from functools import cache
from pathlib import Path
from typing import Any

from softpad.design._space import stable_hash
from softpad.errors import InputError


@cache
def code_version() -> str:
    """Hash of softpad's version and every Python source file of the package."""
    import softpad

    root = Path(softpad.__file__).parent
    parts = [softpad.__version__]
    for path in sorted(root.rglob("*.py")):
        parts.append(str(path.relative_to(root)))
        parts.append(stable_hash(path.read_text(encoding="utf-8")))
    return stable_hash(parts)


def default_cache_dir() -> Path:
    """``$XDG_CACHE_HOME/softpad/design`` (``~/.cache/softpad/design``)."""
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "softpad" / "design"


class ResultCache:
    """JSON results under ``root/KIND/KEY.json``; ``root=None`` keeps nothing.

    Parameters
    ----------
    root
        Directory (created on the first write), or None for no caching.
    """

    def __init__(self, root: str | Path | None) -> None:
        self.root = None if root is None else Path(root)
        if self.root is not None and self.root.exists() and not self.root.is_dir():
            raise InputError(f"cache directory {str(self.root)!r} is a file")

    @staticmethod
    def key(kind: str, payload: Any) -> str:
        """The key of a task: hash of its kind, inputs and the code version."""
        return stable_hash({"kind": kind, "inputs": payload, "code": code_version()})

    def _path(self, kind: str, key: str) -> Path | None:
        return None if self.root is None else self.root / kind / f"{key}.json"

    def get(self, kind: str, key: str) -> Any | None:
        """The stored result, or None (missing or unreadable: recomputed)."""
        path = self._path(kind, key)
        if path is None or not path.is_file():
            return None
        try:
            return json.loads(path.read_text(encoding="utf-8"))["result"]
        except (OSError, ValueError, KeyError):
            return None

    def put(self, kind: str, key: str, result: Any) -> None:
        """Store ``result`` (JSON-serialisable) atomically."""
        path = self._path(kind, key)
        if path is None:
            return
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            json.dump({"kind": kind, "key": key, "result": result}, f)
        os.replace(tmp, path)

    def count(self, kind: str) -> int:
        """Number of stored results of a kind."""
        if self.root is None or not (self.root / kind).is_dir():
            return 0
        return sum(1 for _ in (self.root / kind).glob("*.json"))
