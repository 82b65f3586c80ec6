"""The ``softpad`` command. Each sub-command lives in its own private module."""

from softpad.cli.main import main

__all__ = ["main"]
