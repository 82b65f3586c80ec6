"""The grasp loop with a robot reached by URL (``ros1://``) and a box reached by URL:
:func:`softpad.harness.run_with_robot`, under its old name here."""

from __future__ import annotations

from softpad.harness import run_with_robot

__all__ = ["run_with_robot"]
