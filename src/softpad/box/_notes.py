"""Log lines that repeat at the sampling rate, said once and then summarised."""

from __future__ import annotations

import time
from collections.abc import Callable


class ThrottledLog:
    """Say a line the first time; while the same line repeats, say it again at most every
    ``interval_s`` with how many times it came (a fault at 1 kHz is one line, not 1000 a
    second).

    Parameters
    ----------
    say
        Where lines go (None: nowhere).
    interval_s
        Shortest time between two lines of the same text, seconds.
    """

    def __init__(self, say: Callable[[str], None] | None, interval_s: float = 10.0) -> None:
        self._say = say
        self.interval_s = float(interval_s)
        self._last: dict[str, tuple[float, int]] = {}

    def __call__(self, text: str, key: str | None = None) -> None:
        """Note ``text`` (grouped under ``key``, default the text itself)."""
        k = text if key is None else key
        now = time.monotonic()
        said, held = self._last.get(k, (-1e18, 0))
        if now - said >= self.interval_s:
            more = f" (and {held} more like it in {now - said:.0f} s)" if held else ""
            if self._say is not None:
                self._say(text + more)
            self._last[k] = (now, 0)
            if len(self._last) > 256:  # bounded: forget the oldest groups
                for old in sorted(self._last, key=lambda g: self._last[g][0])[:128]:
                    del self._last[old]
        else:
            self._last[k] = (said, held + 1)
