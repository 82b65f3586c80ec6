"""The box daemon (``softpad box serve``): one box served over zenoh to many clients.

A sampling thread reads the box at a fixed rate and publishes every frame (push); valve
commands arrive as queries and are acknowledged; any number of monitors subscribe read-only;
one client at a time controls the valves. Safety lives here, whatever the clients do:

* a channel above the trip level (``max_pressure_pa - trip_margin_pa``) is vented and an
  inflate command on it is refused;
* the controller holds a liveliness token and sends heartbeats; when the token vanishes
  (its process died, its link broke) or no heartbeat came for ``watchdog_s``, every inflation
  valve closes at once and each channel is held (sealed; a channel being vented keeps
  venting) or vented as configured; releasing control holds the same way;
* malformed or oversized payloads are counted and dropped; no input stops the daemon;
* frames are published from their own thread, so a slow link or monitor never delays the
  sampling and safety loop (frames it cannot take are counted as unsent).

The served box passes through :func:`guard_box`, the one place where a box-side safety
wrapper is applied.
"""

from __future__ import annotations

import math
import queue
import re
import threading
import time
import uuid
from collections.abc import Callable, Mapping
from typing import Any

from softpad import __version__
from softpad.box._auth import Verifier, new_key, seal_frame
from softpad.box._base import Box, PressureFrame, ValveCommand
from softpad.box._link import (
    DEFAULT_PREFIX,
    decode_request,
    encode_frame,
    encode_json,
    session_config,
)
from softpad.box._notes import ThrottledLog
from softpad.box._safety import SafetyTrip
from softpad.box._schedule import (
    CpuClock,
    GcPauses,
    PeriodRing,
    TickSchedule,
    set_realtime_priority,
)
from softpad.errors import HardwareFault, InputError, SoftPadError

Handler = Callable[[dict[str, Any]], dict[str, Any]]

#: Default maximum module pressure, pascals (thesis usable range ends at 2.8 kPa; 3 kPa max).
DEFAULT_MAX_PRESSURE_PA = 3000.0


def guard_box(box: Box, max_pressure_pa: float) -> Box:
    """The box the daemon serves: ``box`` with its box-side safety guard set to the limit.

    This is the one switch between the daemon and the safety layer
    (:class:`~softpad.box.SafetyGuard` in the :class:`~softpad.box.Box` base): its maximum is
    set to ``max_pressure_pa`` (release level kept below it). The daemon adds its own venting
    above the trip level, the watchdog and the refusal of commands from non-controllers.
    """
    import dataclasses

    limits = box.safety_limits
    release = min(limits.release_pa, max_pressure_pa - limits.trip_margin_pa - 100.0)
    box.safety_limits = dataclasses.replace(
        limits, max_pressure_pa=max_pressure_pa, release_pa=release
    )
    return box


class _Stats:
    """Running figures of the sampling loop (rate, jitter, dropped, malformed)."""

    def __init__(self, rate_hz: float) -> None:
        self.rate_hz = rate_hz
        self.frames = 0
        self.missed_ticks = 0
        self.malformed = 0
        self.refused = 0
        self.watchdog_trips = 0
        self.vents = 0
        self.faults = 0
        self.unsent = 0
        self.auth_failures = 0
        self.service_max_s = 0.0
        self.rt_priority: int | None = None
        self.started = time.monotonic()
        self.periods = PeriodRing(1.0 / rate_hz)
        self.gc = GcPauses()
        self.cpu = CpuClock()

    def sampled(self, mono: float) -> None:
        self.frames += 1
        self.periods.add(mono)

    def to_dict(self) -> dict[str, Any]:
        elapsed = max(time.monotonic() - self.started, 1e-9)
        periods = self.periods.summary()
        return {
            "target_rate_hz": self.rate_hz,
            "achieved_rate_hz": round(self.frames / elapsed, 2),
            "frames": self.frames,
            **periods,
            "jitter_std_s": periods["period_std_s"],
            "dropped_samples": self.missed_ticks,
            **self.gc.to_dict(),
            **self.cpu.to_dict(),
            "realtime_priority": self.rt_priority,
            "unsent_frames": self.unsent,
            "malformed_payloads": self.malformed,
            "refused_commands": self.refused,
            "auth_failures": self.auth_failures,
            "service_max_s": round(self.service_max_s, 6),
            "watchdog_trips": self.watchdog_trips,
            "safety_vents": self.vents,
            "box_faults": self.faults,
            "uptime_s": round(elapsed, 3),
        }


def _check_options(
    box: Box,
    watchdog_s: float,
    watchdog_action: str,
    rt_priority: int | None,
    services: Mapping[str, Handler] | None,
) -> None:
    """InputError for a daemon option out of range, or services for a box not simulated."""
    if watchdog_action not in ("hold", "vent"):
        raise InputError(f"watchdog action must be hold or vent, got {watchdog_action!r}")
    from softpad.config import WATCHDOG_RANGE_S

    lo, hi = WATCHDOG_RANGE_S  # the installation file's range (issue 49: 60 s was accepted)
    if not (math.isfinite(watchdog_s) and lo <= watchdog_s <= hi):
        raise InputError(f"watchdog time must be within {lo:g}..{hi:g} s, got {watchdog_s!r}")
    if rt_priority is not None and (
        isinstance(rt_priority, bool)
        or not isinstance(rt_priority, int)
        or not 1 <= rt_priority <= 99
    ):
        raise InputError(f"real-time priority must be an integer from 1 to 99, got {rt_priority!r}")
    if services and not box.simulated:
        raise InputError(
            f"services ({', '.join(sorted(services))}) are for a simulated box only, "
            f"not {type(box).__name__}"
        )


class BoxDaemon:
    """Serve ``box`` over zenoh (see the module docstring and :mod:`softpad.box._link`).

    Parameters
    ----------
    box
        The box to serve; closed by :meth:`close`.
    listen
        Zenoh endpoints to listen on (``tcp/127.0.0.1:7447``); the caller checked the policy
        (:func:`softpad.config.check_remote_policy`).
    key_prefix
        Zenoh key prefix of every key of this box.
    max_pressure_pa
        Hard maximum gauge pressure of every channel, pascals.
    trip_margin_pa
        Venting starts this far below the maximum, pascals.
    watchdog_s
        A controller silent (no heartbeat) this long, seconds, loses control: valves close.
    watchdog_action
        ``"hold"`` (every valve closed) or ``"vent"`` (every channel deflated).
    lockstep_frames
        For a simulated box: while a client controls it, sample at most this many frames
        ahead of the last frame the controller acknowledged reading (``PREFIX/control/ack``),
        so the simulated world runs on the controller's time, never ahead of what it has seen.
        None (hardware): free-running.
    services
        Extra queryables ``PREFIX/ext/OP`` (the served simulator's world and robot); a handler
        takes the request and returns the reply's fields. Only the controller may call them,
        and only a simulated box offers them (bounded: :mod:`softpad.harness._remote`).
    auth
        Keyword arguments of :func:`softpad.box._link.session_config` (user/password, TLS).
    log
        Called with one line per event; None: silent.
    spin_s
        The last this many seconds before each tick's deadline are busy-waited rather than
        slept (sleep's wake-up latency, for a tighter period at the cost of CPU); 0: sleep.
    rt_priority
        Run the daemon's threads under ``SCHED_FIFO`` at this priority (1..99; Linux, root or
        ``CAP_SYS_NICE``): the 1 kHz schedule then holds on a loaded machine. None: the
        ordinary scheduler.
    """

    def __init__(
        self,
        box: Box,
        listen: tuple[str, ...] = ("tcp/127.0.0.1:7447",),
        key_prefix: str = DEFAULT_PREFIX,
        *,
        max_pressure_pa: float = DEFAULT_MAX_PRESSURE_PA,
        trip_margin_pa: float = 50.0,
        watchdog_s: float = 0.5,
        watchdog_action: str = "hold",
        services: Mapping[str, Handler] | None = None,
        auth: Mapping[str, Any] | None = None,
        log: Callable[[str], None] | None = None,
        lockstep_frames: int | None = None,
        spin_s: float = 0.0,
        rt_priority: int | None = None,
    ) -> None:
        _check_options(box, watchdog_s, watchdog_action, rt_priority, services)
        self.box = guard_box(box, max_pressure_pa)
        self.listen = tuple(listen)
        self.prefix = key_prefix.rstrip("/")
        self.max_pressure_pa = float(max_pressure_pa)
        self.trip_pa = float(max_pressure_pa - trip_margin_pa)
        self.watchdog_s = float(watchdog_s)
        self.watchdog_action = watchdog_action
        self.services = dict(services or {})
        self.lockstep_frames = lockstep_frames
        self.spin_s = float(spin_s)
        self.rt_priority = rt_priority
        self._auth = dict(auth or {})
        self._log = log
        #: Repeating lines (a box fault every frame, a flood of forged messages) said once,
        #: then at most every 10 s with their count.
        self._note = ThrottledLog(log)
        self.stats = _Stats(float(box.sample_rate_hz))
        self.stats.rt_priority = rt_priority
        self._init_state()

    def _init_state(self) -> None:
        """Nobody in control, nothing sampled or sent yet, no session or threads."""
        #: Drawn at start: tags every frame for monitors (handed on ``info``).
        self._read_key = new_key()
        #: The controller's key and counters (None: nobody controls).
        self._verifier: Verifier | None = None
        #: The key of the current or the last controller: frames keep its tag after a
        #: release or a trip, so a client that lost control still reads them.
        self._frame_key: bytes | None = None
        self._lock = threading.RLock()
        self._stop = threading.Event()
        self.controller: str | None = None
        self._heartbeat = 0.0
        self._taken_at = 0.0
        self._live: set[str] = set()
        self._venting: set[int] = set()
        self.last_trip: dict[str, Any] | None = None
        self._last: PressureFrame | None = None
        self._seq = 0
        self._session: Any = None
        self._thread: threading.Thread | None = None
        self._decls: list[Any] = []
        self._outbox: queue.Queue[bytes] = queue.Queue(maxsize=2000)
        self._acked = 0
        self._ack_event = threading.Event()

    # --- life cycle -------------------------------------------------------------------
    def start(self) -> BoxDaemon:
        """Open the zenoh session, declare every key and start sampling."""
        config = session_config("peer", self.listen, **self._auth)  # names a missing zenoh
        if self.rt_priority is not None:  # before any thread starts: they all inherit it
            set_realtime_priority(self.rt_priority)
        import zenoh

        try:
            self._session = zenoh.open(config)
        except zenoh.ZError as exc:
            raise InputError(f"cannot listen on {', '.join(self.listen)}: {exc}") from None
        s, p = self._session, self.prefix
        self._pub = s.declare_publisher(
            f"{p}/frames", express=True, congestion_control=zenoh.CongestionControl.BLOCK
        )
        for key, fn in (
            ("info", self._on_info),
            ("stats", self._on_stats),
            ("valves", self._on_valves),
            ("control/take", self._on_take),
            ("control/release", self._on_release),
            ("ext/*", self._on_service),
        ):
            self._decls.append(s.declare_queryable(f"{p}/{key}", self._guarded(fn)))
        self._decls.append(s.declare_subscriber(f"{p}/control/heartbeat", self._on_heartbeat))
        self._decls.append(s.declare_subscriber(f"{p}/control/ack", self._on_ack))
        self._decls.append(
            s.liveliness().declare_subscriber(
                f"{p}/control/holder/*", self._on_liveliness, history=True
            )
        )
        self._start_compiled_guard()
        self.stats.gc.start()  # start-up's objects never scanned again; collections between ticks
        self._sender = threading.Thread(target=self._send_loop, name="softpad-sender", daemon=True)
        self._sender.start()
        self._thread = threading.Thread(
            target=self._sample_loop, name="softpad-sampler", daemon=True
        )
        self._thread.start()
        self._say(f"serving {type(self.box).__name__} on {', '.join(self.listen)} key {p}")
        return self

    def _start_compiled_guard(self) -> None:
        """A hardware box's over-pressure guard in compiled code, off the interpreter lock
        (issue 49: a stall of this process no longer holds the guard up); the guard below
        keeps running too."""
        start = getattr(self.box, "start_guard", None)
        if start is None:
            return
        if start(self.trip_pa, self.trip_pa - 200.0):
            self._say(f"compiled guard: venting above {self.trip_pa:.0f} Pa, off the GIL")
        else:
            self._say("compiled guard not available: the over-pressure guard runs in Python only")

    def wait(self, timeout_s: float | None = None) -> bool:
        """Block until :meth:`stop` (True) or ``timeout_s`` passed (False)."""
        return self._stop.wait(timeout_s)

    def stop(self) -> None:
        """Stop sampling (thread-safe)."""
        self._stop.set()

    def close(self) -> None:
        """Stop, close every valve, close the box and the session. Idempotent."""
        self._stop.set()
        try:
            if self._thread is not None:
                self._thread.join(timeout=5.0)
                self._sender.join(timeout=5.0)
            with self._lock:
                try:
                    self.box.close()
                except SoftPadError as exc:
                    self._say(f"closing the box: {exc}")
        finally:
            self.stats.gc.stop()
            if self._session is not None:
                self._session.close()
                self._session = None

    def __enter__(self) -> BoxDaemon:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _say(self, text: str) -> None:
        if self._log is not None:
            self._log(text)

    # --- sampling ---------------------------------------------------------------------
    def _sample_loop(self) -> None:
        """Sample, check the limits and run the watchdog on the fixed schedule
        (:mod:`softpad.box._schedule`); frames go to the sender thread, never out from here."""
        stats = self.stats
        period = 1.0 / stats.rate_hz
        paced = bool(getattr(self.box, "self_paced", False))
        schedule = TickSchedule(stats.rate_hz, self.spin_s)
        between_ticks = _between_ticks(self.box)
        while not self._stop.is_set():
            if self._wait_for_controller():
                schedule.restart()  # the simulated clock waited: not a missed tick
                stats.periods.restart()
            if not paced:
                stats.missed_ticks += schedule.wait()
            try:
                with self._lock:
                    frame = self.box.read()
                    mono = time.monotonic()
                    self._last = frame
                    self._safety(frame, mono)
            except SoftPadError as exc:
                self.stats.faults += 1
                self._note(f"box fault: {exc}; valves closed", key="box fault")
                self._safe_state("hold")
                time.sleep(period)
                continue
            if paced:  # the box keeps its own schedule and counts its dropped ticks
                stats.missed_ticks = int(getattr(self.box, "missed_ticks", 0))
            else:
                stats.missed_ticks += schedule.late(mono)
            self._seq += 1
            try:
                self._outbox.put_nowait(encode_frame(self._seq, mono, frame))
            except queue.Full:
                stats.unsent += 1
            stats.sampled(mono)
            stats.cpu.sampled_by_this_thread()
            if between_ticks is not None:
                between_ticks()  # the simulator's bulk work (noise blocks), off the tick
            stats.gc.collect_if_due()  # right after the tick's work, never in the middle of it

    def _wait_for_controller(self) -> bool:
        """Lock-step: hold sampling while the controller is behind; True when it waited."""
        waited = False
        while (
            self.lockstep_frames is not None
            and self.controller is not None
            and self._seq - self._acked >= self.lockstep_frames
            and not self._stop.is_set()
        ):
            waited = True
            self.stats.gc.collect_if_due()
            self._ack_event.wait(0.01)
            self._ack_event.clear()
            self._check_controller(time.monotonic())
        return waited

    def _on_ack(self, sample: Any) -> None:
        try:
            msg = decode_request(sample.payload.to_bytes())
            seq = msg.get("seq")
            if self._authentic("ack", "control/ack", msg) and type(seq) is int:
                self._acked = max(self._acked, min(seq, self._seq))
                self._ack_event.set()
        except Exception:
            self.stats.malformed += 1

    def _send_loop(self) -> None:
        """Publish queued frames. A slow link may block here, never the sampling and safety
        loop: when the queue is full, frames are counted as unsent and skipped."""
        while not self._stop.is_set():
            try:
                data = self._outbox.get(timeout=0.1)
            except queue.Empty:
                continue
            try:
                self._pub.put(seal_frame(data, self._read_key, self._frame_key))
            except Exception as exc:  # the session is closing
                self._say(f"publishing: {exc}")
                return

    def _safety(self, frame: PressureFrame, mono: float) -> None:
        """Vent channels above the trip level; trip the watchdog on a silent controller."""
        p = frame.pressures_pa
        for k in range(frame.channels):
            ch = k + 1
            if math.isfinite(p[k]) and p[k] > self.trip_pa:
                if ch not in self._venting:
                    self._venting.add(ch)
                    self.stats.vents += 1
                    self._say(f"channel {ch} at {p[k]:.0f} Pa > {self.trip_pa:.0f} Pa: venting")
                self.box.set_valve(ch, ValveCommand.DEFLATE)
            elif ch in self._venting and (not math.isfinite(p[k]) or p[k] < self.trip_pa - 200):
                # back under the limit: the controller may command it again, but it keeps
                # venting until then (sealing it would let a stuck inflation valve refill it)
                self._venting.discard(ch)
        if not math.isfinite(frame.supply_pa):
            self._close_inflation()
        self._check_controller(mono)

    def _check_controller(self, mono: float) -> None:
        """Withdraw control from a controller without heartbeats, or whose liveliness token
        has not appeared within the watchdog time of taking control."""
        c = self.controller
        if c is None:
            return
        if mono - self._heartbeat > self.watchdog_s:
            self._trip(f"no heartbeat for {mono - self._heartbeat:.3f} s")
        elif c not in self._live and mono - self._taken_at > self.watchdog_s:
            self._trip("its liveliness token never appeared")

    def _close_inflation(self) -> None:
        for ch, cmd in enumerate(self.box.valves, 1):
            if cmd is ValveCommand.INFLATE:
                self.box.set_valve(ch, ValveCommand.CLOSED)

    def _safe_state(self, action: str) -> None:
        with self._lock:
            try:
                # "hold" closes inflation only: a channel being vented keeps venting (issue 35:
                # closing it again re-sealed a stuck inflation valve); "vent" vents every channel
                self._close_inflation()
                if action == "vent":
                    for ch in range(1, self.box.channels + 1):
                        self.box.set_valve(ch, ValveCommand.DEFLATE)
            except SoftPadError as exc:
                self._say(f"could not reach the safe state: {exc}")

    def _trip(self, why: str) -> None:
        """Watchdog: the controller is gone; close inflation, hold or vent, free control."""
        with self._lock:
            who, self.controller = self.controller, None
            self._verifier = None
            if who is None:
                return
            self.stats.watchdog_trips += 1
            #: The last watchdog trip: client, reason, seconds since its last heartbeat.
            self.last_trip = {
                "client": who,
                "reason": why,
                "silent_s": time.monotonic() - self._heartbeat,
            }
            self._safe_state(self.watchdog_action)
        self._say(
            f"watchdog: controller {who} lost ({why}); inflation closed, {self.watchdog_action}"
        )

    # --- requests ---------------------------------------------------------------------
    def _guarded(self, fn: Handler) -> Callable[[Any], None]:
        """Wrap a handler: decode, count malformed input, always reply, never raise."""

        def on_query(query: Any) -> None:
            try:
                payload = query.payload.to_bytes() if query.payload is not None else None
                try:
                    msg = decode_request(payload)
                except InputError as exc:
                    self.stats.malformed += 1
                    reply = {"ok": False, "kind": "input", "error": str(exc)}
                else:
                    msg["_key"] = str(query.key_expr)
                    reply = self._answer(fn, msg)
                query.reply(query.key_expr, encode_json(reply))
            except Exception as exc:
                self.stats.malformed += 1
                self._say(f"dropped a query: {type(exc).__name__}: {exc}")

        return on_query

    def _answer(self, fn: Handler, msg: dict[str, Any]) -> dict[str, Any]:
        try:
            return {"ok": True, **fn(msg)}
        except _Refused as exc:
            self.stats.refused += 1
            return {"ok": False, "kind": exc.kind, "error": str(exc)}
        except SafetyTrip as exc:  # the Box base's guard refused (over the trip level)
            self.stats.refused += 1
            return {"ok": False, "kind": "safety", "error": str(exc)}
        except HardwareFault as exc:
            return {"ok": False, "kind": "hardware", "error": str(exc)}
        except InputError as exc:
            self.stats.malformed += 1
            return {"ok": False, "kind": "input", "error": str(exc)}
        except Exception as exc:
            self._say(f"error answering {msg.get('_key')}: {type(exc).__name__}: {exc}")
            return {"ok": False, "kind": "hardware", "error": f"daemon error: {exc}"}

    def _client(self, msg: dict[str, Any]) -> str:
        c = msg.get("client")
        # ids are printed in the log and name a liveliness key: letters, digits, "_", "-", "."
        # only (a newline or an escape code would forge log lines; a lone surrogate cannot be
        # printed at all)
        if not isinstance(c, str) or _CLIENT_ID.fullmatch(c) is None:
            shown = ascii(c)[:80]
            raise InputError(
                f"client must be an id of 1..64 letters, digits, '_', '-' or '.', got {shown}"
            )
        return c

    def _require_control(self, msg: dict[str, Any]) -> str:
        """The controller's id when ``msg`` is its authentic, fresh query; else refused."""
        c = self._client(msg)
        if self.controller != c:
            holder = self.controller or "nobody"
            raise _Refused(
                "control",
                f"client {c} does not control the box (controller: {holder}); take control first",
            )
        key = str(msg.get("_key", "")).removeprefix(self.prefix + "/")
        if not self._authentic("query", key, msg):
            raise _Refused(
                "control",
                f"{key} refused: not authenticated as controller {c} (forged or replayed)",
            )
        return c

    def _authentic(self, stream: str, key: str, msg: dict[str, Any]) -> bool:
        """True when ``msg`` on ``key`` carries the controller's valid tag and a fresh counter;
        a failure is counted and logged (throttled)."""
        v = self._verifier
        why = "nobody controls the box" if v is None else v.check(stream, key, msg)
        if why is None:
            return True
        if v is not None and msg.get("client") == v.client:  # claims to be the controller
            self.stats.auth_failures += 1
            self._note(f"refused {key} claiming client {v.client}: {why}", key=f"auth {key}")
        return False

    def info(self) -> dict[str, Any]:
        """What the daemon advertises on ``PREFIX/info``."""
        return {
            "channels": self.box.channels,
            "sample_rate_hz": float(self.box.sample_rate_hz),
            "max_pressure_pa": self.max_pressure_pa,
            "trip_pressure_pa": self.trip_pa,
            "watchdog_s": self.watchdog_s,
            "watchdog_action": self.watchdog_action,
            "box": type(self.box).__name__,
            "controller": self.controller,
            "services": sorted(self.services),
            "supply_sensor": bool(getattr(self.box, "supply_sensor", True)),
            "read_key": self._read_key.hex(),
            "seq": self._seq,
            "version": f"softpad {__version__}",
        }

    def _on_info(self, msg: dict[str, Any]) -> dict[str, Any]:
        return self.info()

    def _on_stats(self, msg: dict[str, Any]) -> dict[str, Any]:
        guard = getattr(self.box, "guard_stats", None)  # the compiled guard; None: not running
        return {
            **self.stats.to_dict(),
            "controller": self.controller,
            "seq": self._seq,
            "compiled_guard": guard() if guard is not None else None,
        }

    def _on_take(self, msg: dict[str, Any]) -> dict[str, Any]:
        c = self._client(msg)
        with self._lock:
            if self.controller not in (None, c):
                raise _Refused(
                    "control",
                    f"box is controlled by client {self.controller}; it must release control "
                    "or vanish (watchdog) first",
                )
            if self.controller == c:  # the same id again: only its holder, proven by its key
                self._require_control(msg)
            # granted now; the liveliness token (declared before the request, on the same
            # link) must be seen within the watchdog time or control is withdrawn. The key
            # goes in this reply only (to the querier), never published.
            secret = new_key()
            self._verifier = Verifier(c, secret)
            self._frame_key = secret
            self.controller = c
            self._heartbeat = self._taken_at = time.monotonic()
            self._acked = self._seq
        self._say(f"client {c} took control")
        return {
            "controller": c,
            "watchdog_s": self.watchdog_s,
            "seq": self._seq,
            "key": secret.hex(),
        }

    def _on_release(self, msg: dict[str, Any]) -> dict[str, Any]:
        with self._lock:  # checked under the lock: no take or trip in between
            c = self._require_control(msg)
            self._safe_state("hold")
            self.controller = None
            self._verifier = None
        self._say(f"client {c} released control; inflation closed, vented channels venting")
        return {}

    def _on_heartbeat(self, sample: Any) -> None:
        try:
            msg = decode_request(sample.payload.to_bytes())
            if self._authentic("heartbeat", "control/heartbeat", msg):
                self._heartbeat = time.monotonic()
        except Exception:
            self.stats.malformed += 1

    def _on_liveliness(self, sample: Any) -> None:
        try:
            import zenoh

            client = str(sample.key_expr).rsplit("/", 1)[-1]
            if sample.kind == zenoh.SampleKind.PUT:
                self._live.add(client)
            else:
                self._live.discard(client)
                if client == self.controller:
                    self._trip("its liveliness token vanished")
        except Exception as exc:
            self._say(f"liveliness: {exc}")

    def _on_valves(self, msg: dict[str, Any]) -> dict[str, Any]:
        ch = msg.get("channel")
        if isinstance(ch, float) and ch.is_integer():
            ch = int(ch)
        with self._lock:  # checked under the lock: the watchdog cannot trip in between
            self._require_control(msg)
            ch = self.box.check_channel(ch)  # type: ignore[arg-type]
            cmd = ValveCommand.parse(msg.get("command"))  # type: ignore[arg-type]
            if cmd is ValveCommand.INFLATE:
                self._check_inflate(ch)
            if ch in self._venting and cmd is not ValveCommand.DEFLATE:
                raise _Refused("safety", f"channel {ch} is being vented above the maximum")
            self.box.set_valve(ch, cmd)
            last = self._last  # frames sampled after this one show the command
            return {
                "valves": [v.value for v in self.box.valves],
                "t_s": None if last is None else last.t_s,
            }

    def _check_inflate(self, ch: int) -> None:
        last = self._last
        if last is None:
            return
        p = float(last.pressures_pa[ch - 1])
        if not math.isfinite(p):
            raise _Refused(
                "safety", f"channel {ch} has no valid pressure reading: inflation refused"
            )
        if p >= self.trip_pa:
            raise _Refused(
                "safety",
                f"channel {ch} at {p:.0f} Pa: inflation refused at or above "
                f"{self.trip_pa:.0f} Pa (maximum {self.max_pressure_pa:.0f} Pa)",
            )

    def _on_service(self, msg: dict[str, Any]) -> dict[str, Any]:
        op = str(msg.pop("_key")).rsplit("/", 1)[-1]
        handler = self.services.get(op)
        if handler is None:
            raise InputError(f"unknown service {op!r}; offered: {', '.join(sorted(self.services))}")
        request = {k: v for k, v in msg.items() if k not in ("mac", "n", "client")}
        with self._lock:
            self._require_control({**msg, "_key": f"{self.prefix}/ext/{op}"})
            t0 = time.monotonic()
            try:
                return handler({**request, "op": op})
            finally:
                self.stats.service_max_s = max(self.stats.service_max_s, time.monotonic() - t0)


class _Refused(SoftPadError):
    """A request refused by policy (control held by another client, safety limit)."""

    def __init__(self, kind: str, message: str) -> None:
        super().__init__(message)
        self.kind = kind


def _between_ticks(box: Box) -> Callable[[], object] | None:
    """The simulator's hook for work it can do between two ticks rather than inside a read
    (drawing the next block of sensor noise), seen through any wrappers; None for hardware."""
    from softpad.box._sim_layers import simulator_of

    return getattr(simulator_of(box), "between_ticks", None)


#: A client id: printable, no key-expression or log-line specials.
_CLIENT_ID = re.compile(r"[A-Za-z0-9_.\-]{1,64}")


def new_client_id() -> str:
    """A random client id (the liveliness token's last key chunk)."""
    return uuid.uuid4().hex[:16]
