"""softpad.record.relay_frames: every frame handed on in order, at most ``count``, paced so
that the wall clock never runs behind the box's time."""

from __future__ import annotations

import time
from types import SimpleNamespace

from softpad.record import relay_frames


class _Box:
    def __init__(self, step_s: float) -> None:
        self.t, self.step = 0.0, step_s

    def read(self) -> SimpleNamespace:
        self.t += self.step
        return SimpleNamespace(t_s=self.t)


def test_frames_are_relayed_in_order_at_the_boxs_pace() -> None:
    seen: list[tuple[float, str]] = []
    live = SimpleNamespace(frame=lambda f, source: seen.append((f.t_s, source)))
    t0 = time.monotonic()
    assert relay_frames(_Box(0.02), live, count=6) == 6
    wall = time.monotonic() - t0
    assert [round(t, 2) for t, _ in seen] == [0.02, 0.04, 0.06, 0.08, 0.10, 0.12]
    assert {s for _, s in seen} == {"monitor"}
    assert wall >= 0.1 - 1e-3  # 5 steps of 20 ms after the first frame: never ahead of the box
