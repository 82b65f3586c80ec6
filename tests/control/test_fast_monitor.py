"""The fault monitor's steady-rise rates in compiled code (src/softpad/control/_fastmonitor.c)
give the NumPy reference's bits, frame by frame, on random runs; what the kernel does not
decide (times out of order, an edge before the kept times) it leaves to the reference."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray

from softpad.control import _safety
from softpad.control._safety import _SteadyRise

fastmonitor = pytest.importorskip("softpad.control._fastmonitor", reason="not built (make ext)")

Rates = tuple[NDArray[np.float64], NDArray[np.float64]] | None


def _bits(r: Rates) -> bytes | None:
    return None if r is None else r[0].tobytes() + b"|" + r[1].tobytes()


def _random_run(
    seed: int, compiled: bool, window_s: float, count: int, n: int, frames: int = 1500
) -> tuple[list[bytes | None], list[int]]:
    """Random readings (steady rises, steps, noise), irregular frame times (a lost frame, a
    jitter, now and then the same time again; in even seeds once back), channels sealed and
    unsealed; the rates of every frame, and how the kernel answered (1, 0, -1)."""
    rng = np.random.default_rng(seed)
    steady = _SteadyRise(n, window_s, count)
    answers: list[int] = []
    if compiled:
        kernel = steady._kernel
        assert kernel is not None

        def counted(*args: object) -> int:
            answers.append(kernel(*args))
            return answers[-1]

        steady._kernel = counted
    else:
        steady._kernel = None
    out: list[bytes | None] = []
    t, p = 0.0, rng.normal(1000.0, 50.0, n)
    slope = rng.choice([0.0, 2.0, 5.0], n)
    sealed = rng.random(n) < 0.8
    for k in range(frames):
        r = rng.random()
        t += 0.01 if r < 0.9 else 0.02 if r < 0.95 else 0.0 if r < 0.97 else 0.013
        t -= 0.015 if k == frames // 2 and seed % 2 == 0 else 0.0  # once back (a new box)
        t += rng.normal(0.0, 1e-4) if r < 0.5 else 0.0
        p = p + slope + rng.normal(0.0, 8.0, n)
        if rng.random() < 0.01:
            p = p + rng.normal(0.0, 300.0, n)  # a load step
        if rng.random() < 0.004:
            sealed = rng.random(n) < 0.7
        out.append(_bits(steady.update(t, p, sealed, rates=rng.random() < 0.95)))
    return out, answers


@pytest.mark.parametrize(
    ("seed", "window_s", "count", "n"),
    [(0, 0.25, 3, 6), (1, 0.25, 3, 6), (2, 0.5, 2, 4), (3, 0.1, 5, 16), (4, 0.3, 1, 1)],
)
def test_random_runs_give_the_reference_bits(
    seed: int, window_s: float, count: int, n: int
) -> None:
    want, _ = _random_run(seed, False, window_s, count, n)
    got, answers = _random_run(seed, True, window_s, count, n)
    first = next((i for i, (a, b) in enumerate(zip(want, got, strict=True)) if a != b), None)
    assert first is None, f"first different frame {first}"
    assert answers.count(1) > 200, answers.count(1)  # the kernel gave most rates
    assert (-1 in answers) is (seed % 2 == 0)  # time back: the reference's, for a while


def _state(m: int, n: int, seed: int = 0) -> tuple[object, ...]:
    rng = np.random.default_rng(seed)
    times = np.cumsum(np.full(m, 0.01))
    sums = np.cumsum(rng.normal(1000.0, 10.0, (m, n)), axis=0)
    offsets = 0.5 * 0.25 * np.arange(2 * 3 + 3)
    return times, sums, offsets, np.zeros(n)


def test_what_the_kernel_leaves_to_the_reference() -> None:
    times, sums, offsets, sealed_from = _state(200, 6)
    out = (np.empty((3, 6)), np.empty((4, 6)))
    t = float(times[-1])
    assert fastmonitor.rates(times, sums, 0, 200, t, offsets, sealed_from, 0.25, *out) == 1
    back = times.copy()
    back[150] = back[149] - 1e-3  # out of order: numpy's search is the reference
    assert fastmonitor.rates(back, sums, 0, 200, t, offsets, sealed_from, 0.25, *out) == -1
    # the oldest edge before the kept times: the reference's kept[-1]
    assert fastmonitor.rates(times, sums, 150, 200, t, offsets, sealed_from, 0.25, *out) == -1
    # no channel sealed throughout, a half window without a sample: no rates
    late = np.full(6, t)
    assert fastmonitor.rates(times, sums, 0, 200, t, offsets, late, 0.25, *out) == 0
    sparse = times[::20].copy()
    assert fastmonitor.rates(sparse, sums[::20].copy(), 0, 10, float(sparse[-1]), offsets,
                             sealed_from, 0.25, *out) == 0  # fmt: skip


def test_bad_arrays_are_refused() -> None:
    times, sums, offsets, sealed_from = _state(50, 6)
    out = (np.empty((3, 6)), np.empty((4, 6)))
    with pytest.raises(ValueError, match="rates"):
        fastmonitor.rates(times, sums, 0, 51, 0.4, offsets, sealed_from, 0.25, *out)
    with pytest.raises(ValueError, match="rates"):
        fastmonitor.rates(times, sums, 0, 50, 0.4, offsets[:-1], sealed_from, 0.25, *out)
    with pytest.raises(ValueError, match="rates"):
        fastmonitor.rates(times, sums, 0, 50, 0.4, offsets, sealed_from, 0.25, out[1], out[0])
    with pytest.raises(TypeError, match="float64"):
        fastmonitor.rates(times.astype(np.float32), sums, 0, 50, 0.4, offsets, sealed_from,
                          0.25, *out)  # fmt: skip


def test_without_the_module_the_reference_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_safety, "_fastmonitor", None)
    assert _SteadyRise(6, 0.25, 3)._kernel is None
