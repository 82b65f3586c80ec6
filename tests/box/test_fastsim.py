"""The simulated box's compiled solve (src/softpad/box/_fastsim.c) gives the NumPy reference's
bits: every reading, true pressure and module height, on random valve schedules and loads."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from softpad.box import Box, PressureFrame, SafetyTrip, ValveCommand
from softpad.box import _sim as sim_module
from softpad.box._base import unchecked_frame
from softpad.box._sim import CompiledChambers, SimBox
from softpad.sim import (
    AnalyticWorld,
    ChamberBank,
    DisturbanceParams,
    TabulatedCharacteristic,
    default_characteristic,
)

fastsim = pytest.importorskip("softpad.box._fastsim", reason="not built (make ext)")

COMMANDS = (ValveCommand.CLOSED, ValveCommand.INFLATE, ValveCommand.DEFLATE)


def _box(seed: int, compiled: bool, monkeypatch: pytest.MonkeyPatch, **kw: object) -> SimBox:
    """A 1 kHz box on an analytic world; the reference built with the kernel hidden."""
    with monkeypatch.context() as m:
        if not compiled:
            m.setattr(sim_module, "_fastsim", None)
        box = SimBox(AnalyticWorld(), sample_rate_hz=1000.0, seed=seed, **kw)  # type: ignore[arg-type]
    assert isinstance(box.chambers, CompiledChambers)
    assert (box.chambers._tab is not None) is compiled
    assert (box.chambers._kernel is not None) is compiled
    return box


def _schedule(seed: int, frames: int) -> dict[int, tuple[str, object]]:
    """Random valve commands and presses (light to beyond the table's loads) by frame."""
    rng = np.random.default_rng(1000 + seed)
    events: dict[int, tuple[str, object]] = {}
    for f in rng.choice(frames, size=frames // 60, replace=False):
        if rng.random() < 0.7:
            events[int(f)] = ("valves", [COMMANDS[k] for k in rng.integers(0, 3, 8)])
        else:
            force = float(rng.choice([0.0, rng.uniform(0.05, 2.0), rng.uniform(2.0, 40.0)]))
            centre = (float(rng.uniform(0.0, 0.135)), float(rng.uniform(0.0, 0.09)))
            events[int(f)] = ("press", (centre, (0.04, 0.04), force))
    return events


KERNELS = ("solve", "interp", "relax", "ramp", "crosses", "readings")


def _counted(calls: dict[str, int], name: str) -> object:
    kernel = getattr(fastsim, name)

    def counted(*a: object) -> object:
        calls[name] += 1
        return kernel(*a)

    return counted


def _run(
    box: SimBox, events: dict[int, tuple[str, object]], frames: int, reader: Box | None = None
) -> list[bytes]:
    """Every frame's readings, time, supply reading, true pressures, heights and the guard's
    spans as bytes (read through ``reader``, a box around ``box``, where given)."""
    reader = box if reader is None else reader
    out = []
    for f in range(frames):
        ev = events.get(f)
        if ev is not None and ev[0] == "valves":
            for ch, cmd in enumerate(ev[1], start=1):  # type: ignore[arg-type]
                try:
                    reader.set_valve(ch, cmd)
                except SafetyTrip:  # a tripped channel keeps venting (in both boxes)
                    pass
        elif ev is not None:
            box.world.press(*ev[1])  # type: ignore[misc]
        frame = reader.read()
        heights = box.module_heights_m
        # the lowest and highest reading the guard is given, as numbers: the sign of a zero
        # among the readings' zeros (unconnected ports) is NumPy's reduction order's
        span = box.sensors.span
        spans = b"" if span is None else (np.array(span[1:]) + 0.0).tobytes()  # -0.0 -> 0.0
        out.append(
            frame.pressures_pa.tobytes()
            + np.array([frame.t_s, frame.supply_pa]).tobytes()
            + box.true_pressures_pa.tobytes()
            + heights.tobytes()
            + spans
        )
    return out


@pytest.mark.parametrize("seed", range(12))
def test_random_schedules_give_the_reference_bits(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    frames = 3000
    events = _schedule(seed, frames)
    kw = {"initial_pressure_pa": float(np.random.default_rng(seed).uniform(0, 3e3))}
    calls = dict.fromkeys(KERNELS, 0)
    ref = _run(_box(seed, False, monkeypatch, **kw), events, frames)
    for name in KERNELS:
        monkeypatch.setattr(sim_module._fastsim, name, _counted(calls, name))
    got = _run(_box(seed, True, monkeypatch, **kw), events, frames)
    assert min(calls.values()) > 50, calls  # the compiled path ran (a stretch every 20 ms)
    first = next((i for i, (a, b) in enumerate(zip(ref, got, strict=True)) if a != b), None)
    assert first is None, f"seed {seed}: first different frame {first}"


@pytest.mark.parametrize(("seed", "leak_m2"), [(0, 2e-9), (1, 2e-9), (2, 1e-6)])
def test_with_disturbances_and_a_leak(
    seed: int, leak_m2: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Creep (the volume the kernel adds) and a leak (stretches with every valve closed; a
    large one is stiff: sub-steps, the reference's)."""
    from softpad.box import Fault

    frames = 4000
    events = _schedule(seed, frames)
    runs = []
    for compiled in (False, True):
        box = _box(
            seed,
            compiled,
            monkeypatch,
            initial_pressure_pa=1100.0,
            disturbances=DisturbanceParams(update_s=0.05),
        )
        box.inject_fault(Fault("leak", channel=2, at_s=0.5, arg=leak_m2))
        runs.append(_run(box, events, frames))
    assert runs[0] == runs[1]


def test_the_kernel_on_random_states_including_fallbacks() -> None:
    """The kernel against ChamberBank._solve itself: random pressures, amounts, loads (beyond
    the table too) and creep; where it declines (not converged), the reference is what runs."""
    char = default_characteristic()
    rng = np.random.default_rng(7)
    declined = 0
    for trial in range(400):
        ref = ChamberBank(6, 6, char)
        fast = CompiledChambers(6, 6, char)
        loads = rng.choice([0.0, 1.0, 30.0]) * rng.random(6)
        p = rng.uniform(-500.0, 4000.0, 6)
        for bank in (ref, fast):
            bank.set_state(p, loads)
        amount = ref.amount * (1 + rng.normal(0, 10.0 ** rng.uniform(-6, -2), 6))
        creep = rng.uniform(0, 1e-7, 6) if trial % 2 else None
        for bank in (ref, fast):
            bank._amount = amount.copy()
            if creep is not None:
                bank._creep, bank._creeping = creep.copy(), True
        start = rng.uniform(-100.0, 3000.0, 6)
        out = np.empty(6)
        dn = np.empty(6)
        cols, slopes, drop = fast._columns("volume")
        if not fastsim.solve(
            start, amount, cols, slopes, char.pressure_pa, drop,
            creep, 101325.0, fast.params.tubing_volume_m3, out, dn,
        ):  # fmt: skip
            declined += 1
        a, b = ref._solve(start.copy()), fast._solve(start.copy())
        assert a.tobytes() == b.tobytes(), trial
        assert ref._dn_dp.tobytes() == fast._dn_dp.tobytes(), trial
        assert ref.heights_m().tobytes() == fast.heights_m().tobytes(), trial
    assert 0 < declined < 200  # both paths exercised


def test_crossings_and_readings_on_random_arrays() -> None:
    """The crossing test and the readings (with their rows' spans) against NumPy's."""
    rng = np.random.default_rng(3)
    hits = 0
    for _ in range(2000):
        p, start, eq = rng.normal(0, 50, (3, 6)).round(rng.integers(0, 3))
        want = bool(((p - eq) * (start - eq) < 0).any())
        hits += want
        assert fastsim.crosses(p, start, eq) is want
    assert 100 < hits < 1900
    for q, lo, hi in ((2.44, -2e3, 10e3), (0.0, -2e3, 10e3), (2.44, -5.0, 7.0)):
        true = rng.normal(0, 30, (40, 8))
        noise = rng.normal(0, 3, (60, 8))[10:50]
        out = np.empty((40, 8))
        lows, highs = fastsim.readings(true, noise, q, 1 / q if q else 0.0, lo, hi, out)
        x = true + noise
        if q:
            x = np.rint(x * (1 / q)) * q
        ref = np.minimum(np.maximum(x, lo), hi)
        assert out.tobytes() == ref.tobytes()
        assert lows == ref.min(axis=1).tolist() and highs == ref.max(axis=1).tolist()
    assert fastsim.readings(true, noise, 2.44, 1 / 2.44, 0.0, 1e4, out) is None  # a zero bound
    true[3, 2] = np.nan
    assert fastsim.readings(true, noise, 2.44, 1 / 2.44, -2e3, 1e4, out) is None


def test_one_reading_against_the_sensor_bank() -> None:
    """``reading`` (a changed box's sample) against SensorBank._quantise on random rows, and
    what it leaves to it (not finite, a zero bound, arrays not as expected)."""
    from softpad.sim import SensorBank, SensorParams

    rng = np.random.default_rng(4)
    for q, lo, hi in ((2.44, -2e3, 10e3), (0.0, -2e3, 10e3), (2.44, -5.0, 7.0)):
        bank = SensorBank(8, 0.01, SensorParams(quantization_pa=q, range_min_pa=lo,
                                                range_max_pa=hi), rng)  # fmt: skip
        noise = rng.normal(0, 3, (50, 8))
        for i in range(50):
            true = rng.normal(0, 30, 8).round(rng.integers(0, 3))
            out = np.empty(8)
            assert fastsim.reading(true, noise, i, bank._q, bank._inv_q, lo, hi, out)
            assert out.tobytes() == bank._quantise(true + noise[i]).tobytes()
    true, out = np.zeros(8), np.empty(8)
    assert not fastsim.reading(true, noise, 2, 2.44, 1 / 2.44, 0.0, 1e4, out)  # a zero bound
    assert not fastsim.reading(true, noise, 50, 2.44, 1 / 2.44, -2e3, 1e4, out)  # no row 50
    assert not fastsim.reading(true[:7], noise, 2, 2.44, 1 / 2.44, -2e3, 1e4, out)
    assert not fastsim.reading(true.astype(np.float32), noise, 2, 2.44, 0.4, -2e3, 1e4, out)
    true[3] = np.inf
    assert not fastsim.reading(true, noise, 2, 2.44, 1 / 2.44, -2e3, 1e4, out)


@pytest.mark.parametrize("seed", range(2))
def test_sealed_modules_under_changing_loads_give_the_reference_bits(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Every valve closed, presses changing every few frames (a held object's loads): each
    load change's reading from ``reading``, the reference's bits (as the trials' hold)."""
    frames = 500
    rng = np.random.default_rng(50 + seed)
    events: dict[int, tuple[str, object]] = {}
    for f in range(0, frames, int(rng.integers(1, 4))):
        centre = (float(rng.uniform(0.0, 0.135)), float(rng.uniform(0.0, 0.09)))
        events[f] = ("press", (centre, (0.04, 0.04), float(rng.uniform(0.0, 3.0))))
    calls = dict.fromkeys(["reading"], 0)
    ref = _run(_box(seed, False, monkeypatch, initial_pressure_pa=1100.0), events, frames)
    monkeypatch.setattr(sim_module._fastsim, "reading", _counted(calls, "reading"))
    got = _run(_box(seed, True, monkeypatch, initial_pressure_pa=1100.0), events, frames)
    assert calls["reading"] > 100, calls
    assert ref == got


def test_bad_arrays_are_refused() -> None:
    out = np.empty(2)
    with pytest.raises(TypeError, match="float64"):
        fastsim.interp(
            np.zeros(2, np.float32), np.zeros((2, 2)), np.zeros((1, 2)), np.zeros(2), None, out
        )
    with pytest.raises(ValueError, match="shape"):
        fastsim.interp(np.zeros(2), np.zeros((3, 2)), np.zeros((1, 2)), np.zeros(2), None, out)
    assert not fastsim.interp(
        np.array([np.nan, 0.0]), np.zeros((2, 2)), np.zeros((1, 2)), np.arange(2.0), None, out
    )


def test_the_span_rows_agree() -> None:
    from softpad.sim import _sensor

    assert sim_module.SPAN_ROWS == _sensor.SPAN_ROWS


class _General(SimBox):
    """The box with every frame on the general path (the world's step, then
    ``_step_physics`` and ``_sense``): the reference of :meth:`SimBox._read`'s hot path."""

    def _read(self) -> PressureFrame:
        dt = self._dt
        t = self._t + dt
        self._t = t
        if t >= self._faults.next_s:
            self._activate_faults()
        self.world.step(dt, self._heights)
        loads = self.world.module_loads_n()
        values, supply = self._sense(self._step_physics(t, dt, loads, loads.tobytes()))
        return unchecked_frame(t, values, supply)


@pytest.mark.parametrize(
    ("seed", "rate_hz"), [(0, 1000.0), (1, 1000.0), (2, 100.0), (3, 100.0), (4, 1000.0)]
)
def test_the_hot_path_of_a_frame_is_the_general_path(
    seed: int, rate_hz: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Every frame (readings, true pressures, heights, the guard's spans), every trip of the
    guard and the valves are those of the general path, through the layers of ``sim://``,
    with a leak, the disturbances and presses; the hot path takes most frames."""
    from softpad.box import Fault, compose_sim_box

    frames = 3000
    events = _schedule(seed, frames)
    events[0] = ("valves", [ValveCommand.INFLATE] * 8)  # up to the guard's trips
    runs: list[tuple[list[bytes], list[tuple[float, int, str]], tuple[ValveCommand, ...]]] = []
    general, fused = [0, 0], [0]
    for cls in (_General, SimBox):
        box = cls(
            AnalyticWorld(),
            sample_rate_hz=rate_hz,
            seed=seed,
            initial_pressure_pa=2500.0,
            disturbances=DisturbanceParams(update_s=0.5) if seed % 2 else None,
        )
        box.inject_fault(Fault("leak", channel=3, at_s=1.0, arg=2e-9))
        sense = box._sense

        def counted(changed: bool, sense: Callable[[bool], object] = sense) -> object:
            general[len(runs)] += 1
            return sense(changed)

        monkeypatch.setattr(box, "_sense", counted)
        monkeypatch.setattr(box, "_new_frames", _counting_frames(box, fused))
        layered = compose_sim_box(box)
        out = _run(box, events, frames, reader=layered)
        runs.append((out, box.safety.trips, box.valves))
    assert runs[0] == runs[1]
    assert len(runs[0][1]) > 0  # the guard tripped on the way
    assert general[0] == frames  # the reference: every frame on the general path
    assert general[1] < (0.2 if rate_hz == 1000.0 else 0.7) * frames  # ours: stretch starts
    # ours: most frames along a stretch in the one compiled call (the reference: none)
    if rate_hz == 1000.0 and not seed % 2:  # 100 Hz: ramps too short for the guard's spans;
        # the disturbances' zero-shift layer changes every frame, so it reads the plain box's
        assert fused[0] > 0.25 * frames, fused  # (before the guard trips; then the Python path)


class _Counted:
    """A compiled frame cursor counting the frames it gave (the Python path ran the rest)."""

    def __init__(self, frames: object, count: list[int]) -> None:
        self.frames, self.count = frames, count

    def next(self, *args: object) -> object:
        frame = self.frames.next(*args)  # type: ignore[attr-defined]
        self.count[0] += frame is not None
        return frame


def _counting_frames(box: SimBox, count: list[int]) -> Callable[[object], object]:
    make = box._new_frames

    def counting(guard: object) -> object:
        frames = make(guard)  # type: ignore[arg-type]
        return None if frames is None else _Counted(frames, count)

    return counting


def _on_a_stretch(
    frames: int = 45,
    level: float | None = None,
    fused: bool = True,
    what: str = "trip",
    held: int | None = None,
) -> SimBox:
    """A 1 kHz box with every valve open, ``frames`` frames read (the compiled cursor's usual
    frame next); then channel index ``held`` tripped (None: none) and the guard's ``what``
    level (trip or release) at ``level`` (None: as it is); the compiled cursor not made where
    not ``fused``."""
    box = SimBox(AnalyticWorld(), sample_rate_hz=1000.0, seed=0, initial_pressure_pa=500.0)
    if not fused:
        box._new_frames = lambda guard: None  # type: ignore[method-assign]
    box.set_valves(["inflate"] * 8)
    for _ in range(frames):
        box.read()
    guard = box.safety
    if held is not None:
        guard.tripped[held] = True
        guard._held = guard.tripped.tolist()
        guard._free = [not x for x in guard._held]
        guard._any_tripped = True
        guard._release_pa = 100.0 if what == "trip" else guard._release_pa  # stays tripped
    if level is not None:
        setattr(guard, f"_{what}_pa", level)
    return box


def _boundary(frames: int, exact: bool, what: str, held: int | None) -> tuple[float, float]:
    """The levels (lo, hi), adjacent doubles, between which the Python path's next frame
    changes from tripping a channel (``exact``: from running the guard's exact per-channel
    test) to not (trip levels: at lo, not at hi; release levels: at hi, not at lo)."""
    lo, hi = 0.0, 9000.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        box = _on_a_stretch(frames, mid, False, what, held)
        calls: list[int] = []
        full_test = box.safety._check_arrays

        def counted(
            *args: object, full_test: Callable[..., list[int]] = full_test, calls: list[int] = calls
        ) -> list[int]:
            calls.append(1)
            return full_test(*args)

        box.safety._check_arrays = counted  # type: ignore[method-assign]
        box.read()
        turned = bool(calls) if exact else bool(box.safety.trips)
        lo, hi = (mid, hi) if turned is (what == "trip") else (lo, mid)
    assert 0.0 < lo and hi < 9000.0 and np.nextafter(lo, hi) == hi
    return lo, hi


@pytest.mark.parametrize(
    ("frames", "what", "held"),
    [(3, "trip", None), (4, "trip", None), (6, "trip", None), (8, "trip", None),
     (18, "trip", None), (45, "trip", None), (45, "trip", 2), (6, "release", 2),
     (45, "release", 0)],
)  # fmt: skip
def test_the_compiled_frame_trips_where_the_guard_does(
    frames: int, what: str, held: int | None
) -> None:
    """Around the level where the guard's exact test trips (or releases) a channel, and where
    its quick bound (no tripped channel below the release level, the highest reading of an
    untripped one plus the window's rise below the trip level) gives way to that test (both
    found by bisection on the Python path), the compiled frame's box trips and releases the
    same channels with the same frames, and takes the frame itself exactly where nothing
    trips or is released; the window not yet full (3, 6 frames) and full (45), a channel
    tripped or not."""
    exact_lo, exact_hi = _boundary(frames, True, what, held)
    levels = [exact_lo, exact_hi, exact_hi + 1.0, exact_lo - 1.0]
    if what == "trip":
        trip_lo, trip_hi = _boundary(frames, False, what, held)
        assert trip_hi <= exact_hi
        levels += [trip_lo, trip_hi, trip_hi - 1.0]
    for level in levels:
        got, count = [], [0]
        for fused in (False, True):
            box = _on_a_stretch(frames, level, fused, what, held)
            box._frames_for = None  # made again by the next read, counted
            box._new_frames = _counting_frames(box, count)  # type: ignore[method-assign]
            frame = box.read()
            guard = box.safety
            got.append((guard.trips, guard._held, frame.pressures_pa.tobytes(), frame.supply_pa))
        assert got[0] == got[1], level
        # the compiled frame wherever the guard trips and releases nothing
        usual = level >= trip_hi if what == "trip" else level <= exact_lo
        assert count[0] == usual, level
        if what == "trip":
            assert bool(got[0][0]) is (level <= trip_lo)
        else:  # released at and above exact_hi (the held channel untripped)
            assert got[0][1][held] is (level <= exact_lo)  # type: ignore[index]


def test_the_exact_test_rounds_as_the_guard() -> None:
    """The exact per-channel test's rise (the window's change times 1 / (frames - 1), as
    SafetyGuard._check_arrays; its quick bound divides by frames - 1) puts the trip level
    where the guard's does: with the window's oldest readings all at a level c for which the
    two roundings differ in the frame's highest reading plus its rise, the compiled frame at
    that trip level, the Python path's trip one ulp below it."""
    box = _on_a_stretch(45)
    sensors = box.sensors
    v = sensors._ramp[sensors._i - sensors._ramp_start].tolist()
    top = max(v)
    c = next(x for x in np.linspace(-1900.0, -100.0, 1801).tolist()
             if top + (top - x) / 9 > top + (top - x) * (1.0 / 9))  # fmt: skip
    level = top + (top - c) * (1.0 / 9)
    for trip_pa, compiled in ((level, True), (np.nextafter(level, 0.0), False)):
        count = [0]
        b = _on_a_stretch(45, trip_pa)
        b.safety._history[1] = [c] * 8  # the window's oldest with the next frame
        b.safety._lows[1] = c
        b._frames_for = None
        b._new_frames = _counting_frames(b, count)  # type: ignore[method-assign]
        b.read()
        assert count[0] == compiled and bool(b.safety.trips) is not compiled, trip_pa


def _state(box: SimBox) -> bytes:
    """Everything the compiled frame reads or writes, as bytes (repr)."""
    ch, se, g = box.chambers, box.sensors, box.safety
    keys = ("_pos", "solved", "_valve_key", "_supply", "_stretch_dt", "solve_count")
    skeys = ("_i", "_ramp_next", "_ramp_key", "_ramp_end", "_ramp_start", "_same")
    return repr(
        [getattr(ch, k) for k in keys]
        + [getattr(se, k) for k in skeys]
        + [list(g._times), list(g._lows), len(g._history), g._any_tripped, box._t]
    ).encode()


@pytest.mark.parametrize(
    "change",
    ["supply", "valves", "dt", "time_again", "released", "over_range", "no_spans", "block_end"],
)
def test_the_compiled_frame_declines_what_is_not_its_usual_frame(change: str) -> None:
    """Frames.next returns None and changes nothing wherever the hold, the ramp or the
    guard's usual decision would not be taken; on its usual frame it changes what they
    change."""
    box = _on_a_stretch()
    frames = box._frames
    assert frames is not None
    t, dt = box._t + box._dt, box._dt
    args: list[object] = [t, dt, box._valve_count, box._supply_true]
    guard, sensors = box.safety, box.sensors
    if change == "supply":
        args[3] = box._supply_true - 1.0
    elif change == "valves":
        args[2] = box._valve_count + 1
    elif change == "dt":
        args[1] = dt * 2
    elif change == "time_again":
        args[0] = guard._times[-1]
    elif change == "released":  # a tripped channel reads below its release level
        guard._any_tripped, guard._held = True, [True] + [False] * 7
    elif change == "over_range":
        guard._max_pa = -1e9
    elif change == "no_spans":
        sensors._ramp_lo = None
    elif change == "block_end":
        sensors._ramp_end = sensors._i
    before = _state(box)
    assert frames.next(*args) is None
    assert _state(box) == before
    # the usual frame, from a fresh box: the steps' changes and the frame
    box = _on_a_stretch()
    t = box._t + box._dt
    want_row = box.sensors._ramp[box.sensors._i - box.sensors._ramp_start]
    frame = box._frames.next(t, box._dt, box._valve_count, box._supply_true)
    assert isinstance(frame, PressureFrame) and frame.t_s == t
    assert frame.pressures_pa.tobytes() == want_row.tobytes()
    assert box.safety._history[-1] is frame.pressures_pa and box.safety._times[-1] == t
    assert box.sensors.span is not None and box.sensors.span[0] is frame.pressures_pa


def test_the_compiled_frame_refuses_objects_it_cannot_read() -> None:
    box = _on_a_stretch()
    slots = [PressureFrame.__dict__[n] for n in ("t_s", "pressures_pa", "supply_pa")]
    with pytest.raises(TypeError):
        fastsim.Frames(box.chambers, box.sensors, box.safety, PressureFrame, 1, 2, 3)
    with pytest.raises(AttributeError):
        fastsim.Frames(box.chambers, 7, box.safety, PressureFrame, *slots)  # no __dict__
    with pytest.raises(TypeError):
        box._frames.next(1.0, 2.0)


def test_the_load_columns_on_random_loads() -> None:
    """The table's columns at the loads (and their slopes, and the pressure a load beyond
    the table takes off) against TabulatedCharacteristic._load_columns: loads on the grid,
    between, below and beyond it; a load not finite is declined."""
    char = default_characteristic()
    assert isinstance(char, TabulatedCharacteristic)
    bank = CompiledChambers(6, 6, char)
    grid = char.load_n
    rng = np.random.default_rng(11)
    beyond = 0
    for trial in range(300):
        kind = trial % 4
        f = (
            rng.choice(grid, 6)  # on the grid
            if kind == 0
            else rng.uniform(-1.0, 1.2 * grid[-1], 6)  # below, inside and beyond
            if kind == 1
            else rng.uniform(0.0, grid[-1], 6) * rng.integers(0, 2, 6)  # some unloaded
            if kind == 2
            else rng.exponential(grid[-1] / 4, 6)
        )
        for which in ("volume", "height"):
            key = f.tobytes()
            want = char._load_columns(which, f, key)
            got = bank._load_columns(char, which, f, key)
            assert want[0] == got[0] and (want[3] is None) is (got[3] is None), trial
            for a, b in zip(want[1:4], got[1:4], strict=True):
                assert a is None or a.tobytes() == b.tobytes(), (trial, which)
            assert want[4].tolist() == got[4].tolist()
        beyond += want[3] is not None
    assert 20 < beyond < 200
    out = [np.empty((char.pressure_pa.size, 2)), np.empty((char.pressure_pa.size - 1, 2))]
    args = (grid, char.volume_m3_table, char.pressure_pa, 9e-4, *out, np.empty(2))
    assert fastsim.columns(np.array([1.0, np.nan]), *args) == 0


def test_the_median_is_statistics_median() -> None:
    import statistics

    rng = np.random.default_rng(5)
    for n in range(1, 10):
        for _ in range(50):
            values = rng.normal(1000.0, 300.0, n).round(rng.integers(-2, 3)).tolist()
            want = statistics.median(values)
            assert np.float64(sim_module._median(values)).tobytes() == np.float64(want).tobytes()


def test_a_module_built_before_the_columns_kernel_runs_the_reference(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A ``_fastsim`` built from an older source (no ``columns``): the reference's columns."""
    import types

    old = types.SimpleNamespace(**{k: getattr(fastsim, k) for k in KERNELS})
    monkeypatch.setattr(sim_module, "_fastsim", old)
    char = default_characteristic()
    bank = CompiledChambers(6, 6, char)
    f = np.array([0.0, 0.5, 1.0, 2.0, 50.0, 3.0])
    want = char._load_columns("volume", f, f.tobytes())
    got = bank._load_columns(char, "volume", f, f.tobytes())  # type: ignore[arg-type]
    assert all(a.tobytes() == b.tobytes() for a, b in zip(want[1:4], got[1:4], strict=True))
