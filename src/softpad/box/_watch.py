"""Watching a box: which box a command talks to in words, real-time pacing of a simulated
box opened by the watcher, stamped reads and the monitor's figures per period, and the
daemon's sampling statistics as text."""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

#: The box a monitor watches when told no other: the box daemon's default link.
LINK_DEFAULT = "zenoh://127.0.0.1:7447"


class Pacer:
    """Keeps a simulated box opened by a watcher at real time: each frame waits until the
    wall clock reaches its box time. A served box is paced by its daemon; ``sim://?realtime=0``
    asks for no pacing (as fast as the simulator computes).

    Parameters
    ----------
    url
        The box's URL.
    """

    def __init__(self, url: str) -> None:
        from softpad.box._registry import parse_url

        self.on = url.startswith("sim://") and parse_url(url)[2].get("realtime") != "0"
        self._start: tuple[float, float] | None = None  # (wall s, box s) of the first frame

    def wait(self, t_s: float) -> None:
        """Wait until the wall clock reaches box time ``t_s`` (s) after the first frame."""
        if not self.on:
            return
        if self._start is None:
            self._start = (time.monotonic(), t_s)
        delay = self._start[0] + (t_s - self._start[1]) - time.monotonic()
        if delay > 0:
            time.sleep(delay)


def describe_box(url: str, paced: bool | None = None) -> str:
    """Which box a command talks to, in words.

    Parameters
    ----------
    url
        The box's URL.
    paced
        Whether the command keeps a simulated box at real time; None says nothing of it.
    """
    if url.startswith("sim://"):
        pace = {True: " (paced at real time; sim://?realtime=0: unpaced)", False: " (unpaced)"}
        return f"the simulated box {url}{'' if paced is None else pace[paced]}"
    if url.startswith("zenoh://"):
        return f"the served box at {url}"
    return f"the box {url}"


def open_watched(url: str) -> Any:
    """The box at ``url`` opened for watching; when nothing serves at a zenoh:// link, the
    error says how to serve one or to watch a simulated box instead.

    Parameters
    ----------
    url
        The box's URL.
    """
    from softpad.box._base import ConnectionLost
    from softpad.box._registry import open_box

    try:
        return open_box(url)
    except ConnectionLost as exc:
        raise ConnectionLost(
            f"{exc} (is a box served there? 'softpad box serve --sim' serves the simulator; "
            "--box sim:// watches a simulated box of this command's own)"
        ) from None


def stamped_frames(box: Any, pacer: Pacer) -> Iterator[tuple[int, Any, float | None]]:
    """Frames of ``box`` without end as (seq, frame, latency s).

    A served box gives its daemon's sequence number and the latency from the daemon's
    sample to now (its monotonic clock is this machine's on loopback); a box opened here
    gives the frame's index from 1, paced by ``pacer``, and no latency.

    Parameters
    ----------
    box
        The box read.
    pacer
        The pacing of a box opened here.
    """
    from softpad.box._zenoh import ZenohBox

    i = 0
    while True:
        if isinstance(box, ZenohBox):
            s = box.read_stamped()
            yield s.seq, s.frame, time.monotonic() - s.mono_s
            continue
        f = box.read()
        pacer.wait(f.t_s)
        i += 1
        yield i, f, None


@dataclass(frozen=True)
class MonitorPeriod:
    """The monitor's figures over one period.

    Parameters
    ----------
    seq
        Sequence number of the period's last frame.
    frame
        The period's last :class:`~softpad.box.PressureFrame`.
    modules
        How many of its channels are the pad's modules.
    rate_hz
        Frames per wall-clock second in the period, Hz.
    latency_ms
        Median and 99th percentile of the latency, ms (None, None for a box opened here).
    lost
        Frames lost on the way so far (gaps in the sequence numbers).
    """

    seq: int
    frame: Any
    modules: int
    rate_hz: float
    latency_ms: tuple[float | None, float | None]
    lost: int

    def to_dict(self) -> dict[str, Any]:
        """The period as JSON (gauge pressures in kPa, latency in ms)."""
        d = self.frame.to_dict()
        d["pressures_kpa"] = d["pressures_kpa"][: self.modules]
        p50, p99 = self.latency_ms
        return {"seq": self.seq, **d, "rate_hz": round(self.rate_hz, 1), "latency_p50_ms": p50,
                "latency_p99_ms": p99, "lost": self.lost}  # fmt: skip

    def line(self) -> str:
        """The period as a line under :func:`monitor_header`."""
        f = self.frame
        vals = " ".join(f"{v / 1e3:8.3f}" for v in f.pressures_pa[: self.modules])
        ms = " ".join(f"{'-':>8s}" if v is None else f"{v:8.2f}" for v in self.latency_ms)
        return (
            f"{self.seq:9d} {f.t_s:9.3f} {vals} {f.supply_pa / 1e3:10.2f} {self.rate_hz:9.1f} "
            f"{ms} {self.lost:6d}"
        )


def monitor_header(n: int) -> str:
    """The header of :meth:`MonitorPeriod.line` for ``n`` modules.

    Parameters
    ----------
    n
        Modules shown.
    """
    modules = " ".join(f"{f'm{k + 1}_kpa':>8s}" for k in range(n))
    return (
        f"{'seq':>9s} {'t_s':>9s} {modules} {'supply_kpa':>10s} {'frames/s':>9s} "
        f"{'p50_ms':>8s} {'p99_ms':>8s} {'lost':>6s}"
    )


def monitor_periods(
    box: Any, pacer: Pacer, modules: int, period_s: float, count: int = 0
) -> Iterator[MonitorPeriod]:
    """The monitor's figures of ``box``, one :class:`MonitorPeriod` per ``period_s`` of box
    time (and one at the last of ``count`` frames).

    Parameters
    ----------
    box
        The box watched.
    pacer
        The pacing of a box opened by the watcher.
    modules
        How many channels are the pad's modules.
    period_s
        Box time between two periods, s.
    count
        Frames read, 0 for endless.
    """
    import numpy as np

    every = max(1, round(box.sample_rate_hz * period_s))
    i, lost, last, lat, t0, i0 = 0, 0, None, [], time.monotonic(), 0
    frames = stamped_frames(box, pacer)
    while count == 0 or i < count:
        seq, f, latency_s = next(frames)
        lost += 0 if last is None else max(0, seq - last - 1)
        last, i = seq, i + 1
        if latency_s is not None:
            lat.append(latency_s)
        if i % every == 0 or i == count:  # frames per wall second in the period
            now = time.monotonic()
            p50 = p99 = None
            if lat:
                p50, p99 = (round(float(v) * 1e3, 3) for v in np.percentile(lat, [50, 99]))
            rate = (i - i0) / max(now - t0, 1e-9)
            yield MonitorPeriod(seq, f, modules, rate, (p50, p99), lost)
            lat, t0, i0 = [], now, i


def stats_lines(d: dict[str, Any]) -> list[str]:
    """A box daemon's sampling statistics (its ``stats`` answer ``d``) as text.

    Parameters
    ----------
    d
        The answer: rates in Hz, times in s, counts.
    """

    def ms(v: float | None) -> str:
        return "-" if v is None else f"{v * 1e3:.3f} ms"

    lines = [
        f"rate      {d['achieved_rate_hz']:.1f} Hz achieved of {d['target_rate_hz']:g} Hz",
        f"period    p50 {ms(d.get('period_p50_s'))}, p99 {ms(d['period_p99_s'])}, "
        f"max {ms(d.get('period_max_s'))}, jitter (std) {ms(d['jitter_std_s'])}; "
        f"error p99 {ms(d.get('period_error_p99_s'))}",
        f"dropped   {d['dropped_samples']} ticks; malformed payloads {d['malformed_payloads']}",
    ]
    if "cpu_percent" in d:
        lines.append(
            f"cpu       daemon {d['cpu_percent']:.1f} % of a core, sampling thread "
            f"{d['sampler_cpu_percent']:.1f} %; gc {d['gc_collections']} collections, "
            f"longest {ms(d['gc_pause_max_s'])}; load average {d['load_average_1min']:g}"
        )
    lines.append(
        f"safety    {d['safety_vents']} vents, {d['watchdog_trips']} watchdog trips, "
        f"{d['refused_commands']} refused, {d.get('auth_failures', 0)} forged or replayed"
    )
    lines.append(f"control   {d['controller'] or 'nobody'}; frames {d['frames']}, seq {d['seq']}")
    return lines


__all__ = [
    "LINK_DEFAULT", "MonitorPeriod", "Pacer", "describe_box", "monitor_header",
    "monitor_periods", "open_watched", "stamped_frames", "stats_lines",
]  # fmt: skip
