"""The context-manager protocol of the recording sinks."""

from __future__ import annotations

from typing import Self


class ClosedOnExit:
    """Base of the sinks that hold a resource (a file, a server): ``with sink:`` gives the
    sink and calls its :meth:`close` on leaving, also on an error."""

    def close(self) -> None:
        """Release the resource. Idempotent."""

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
