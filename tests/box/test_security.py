"""Attacks on a served box, on loopback with scouting off: forged ids, releases, takes, tokens,
heartbeats and frames, replayed commands, unauthenticated clients against an authenticated
box, bad payloads and bounded services. Every wait is bounded by a frame count or a deadline.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from softpad.box import ConnectionLost, ControlRefused, ValveCommand, ZenohBox, open_box
from softpad.box._auth import seal_frame, split_frame
from softpad.box._base import PressureFrame
from softpad.box._link import decode_request, encode_frame, encode_json, session_config


class _Attacker:
    """A plain zenoh client on the daemon's endpoint: queries and publishes what it likes."""

    def __init__(self, url: str, prefix: str = "softpad/box") -> None:
        from urllib.parse import urlsplit

        import zenoh

        port = urlsplit(url).port
        self.s = zenoh.open(session_config("client", connect=(f"tcp/127.0.0.1:{port}",)))
        self.p = prefix

    def ask(self, key: str, msg: dict[str, Any] | bytes) -> dict[str, Any]:
        payload = msg if isinstance(msg, bytes) else encode_json(msg)
        for r in self.s.get(f"{self.p}/{key}", payload=payload, timeout=10.0):
            if r.ok is not None:
                return decode_request(r.ok.payload.to_bytes())
        raise AssertionError(f"no reply on {key}")

    def put(self, key: str, data: bytes) -> None:
        self.s.put(f"{self.p}/{key}", data)

    def close(self) -> None:
        self.s.close()


@pytest.fixture
def attack(served):
    """``with attack() as (daemon, url, controller, attacker)``: a served box, a client holding
    control of it and an attacker session."""
    from contextlib import contextmanager

    @contextmanager
    def make(*args: Any, **kwargs: Any):
        kwargs.setdefault("watchdog_s", 2.0)  # a busy test machine must not trip it
        with served(*args, **kwargs) as (daemon, url):
            a = open_box(url)
            assert isinstance(a, ZenohBox)
            a.take_control()
            bad = _Attacker(url)
            try:
                yield daemon, url, a, bad
            finally:
                bad.close()
                a.close()

    return make


def test_forged_client_id_cannot_command(attack) -> None:
    with attack() as (daemon, _url, a, bad):
        info = bad.ask("info", {})
        assert info["controller"] == a.client_id  # the id is public; it proves nothing
        before = daemon.stats.auth_failures
        for ch in range(1, 7):
            r = bad.ask(
                "valves", {"client": info["controller"], "channel": ch, "command": "inflate"}
            )
            assert r["ok"] is False and r["kind"] == "control", r
        assert set(daemon.box.valves) == {ValveCommand.CLOSED}
        assert daemon.stats.auth_failures - before == 6
        # with a made-up tag too
        r = bad.ask(
            "valves",
            {"client": a.client_id, "channel": 1, "command": "inflate", "n": 99, "mac": "00" * 32},
        )
        assert r["ok"] is False and "forged" in r["error"]
        a.set_valve(1, "deflate")  # the real controller still commands
        assert daemon.box.valves[0] is ValveCommand.DEFLATE


def test_forged_release_and_take_cannot_lock_out_the_controller(attack) -> None:
    with attack() as (daemon, _url, a, bad):
        r = bad.ask("control/release", {"client": a.client_id})
        assert r["ok"] is False and r["kind"] == "control"
        r = bad.ask("control/take", {"client": a.client_id})
        assert r["ok"] is False and "key" not in r
        r = bad.ask("control/take", {"client": "intruder"})
        assert r["ok"] is False and "controlled by client" in r["error"]
        assert daemon.controller == a.client_id
        a.set_valve(2, "deflate")
        a.close_valves()  # the safe-state commands of the real controller go through
        assert set(daemon.box.valves) == {ValveCommand.CLOSED}


def test_forged_token_and_heartbeats_do_not_hold_off_the_watchdog(attack) -> None:
    """The controller freezes (its heartbeats stop); an attacker declares a liveliness token
    under its id and publishes heartbeats naming it, with and without made-up tags."""
    with attack(watchdog_s=0.3) as (daemon, _url, a, bad):
        a.set_valve(1, "inflate")
        token = bad.s.liveliness().declare_token(f"softpad/box/control/holder/{a.client_id}")
        a._beat_stop.set()  # frozen controller
        n = 0
        while daemon.controller is not None and n < 2000:
            n += 1
            bad.put("control/heartbeat", encode_json({"client": a.client_id}))
            bad.put(
                "control/heartbeat",
                encode_json({"client": a.client_id, "n": 10**6 + n, "mac": "ab" * 32}),
            )
            time.sleep(0.005)
        token.undeclare()
        assert daemon.controller is None, "forged heartbeats kept the controller alive"
        assert daemon.last_trip is not None and "no heartbeat" in daemon.last_trip["reason"]
        assert daemon.box.valves[0] is not ValveCommand.INFLATE
        assert daemon.stats.auth_failures >= 2


def test_replayed_and_misdirected_commands_are_refused(attack, until) -> None:
    with attack() as (daemon, _url, a, bad):
        assert a._sealer is not None
        sealed = a._sealer.seal(
            "query", "valves", {"client": a.client_id, "channel": 3, "command": "deflate"}
        )
        assert bad.ask("valves", sealed)["ok"] is True  # the original, once
        again = bad.ask("valves", sealed)
        assert again["ok"] is False and "replayed" in daemon_log_reason(again)
        # a tag made for one key does not open another
        other = a._sealer.seal(
            "query", "valves", {"client": a.client_id, "channel": 3, "command": "closed"}
        )
        assert bad.ask("control/release", other)["ok"] is False
        assert daemon.controller == a.client_id
        beat = a._sealer.seal("heartbeat", "control/heartbeat", {"client": a.client_id})
        bad.put("control/heartbeat", encode_json(beat))
        bad.put("control/heartbeat", encode_json(beat))  # replayed heartbeat
        until(lambda: daemon.stats.auth_failures >= 3, "the replayed heartbeat refused")


def daemon_log_reason(reply: dict[str, Any]) -> str:
    return str(reply.get("error", ""))


def _forged_frames(seq: int, n: int = 8) -> list[bytes]:
    f = PressureFrame(0.0, np.full(n, np.nan), 10e3)
    over = PressureFrame(0.0, np.full(n, 9e3), 10e3)
    raw = encode_frame(seq, time.monotonic(), f)
    return [
        raw,  # untagged
        raw + bytes(32),  # zero tags
        seal_frame(encode_frame(seq + 1, time.monotonic(), over), b"k" * 32, b"k" * 32),
        b"garbage",
    ]


def test_forged_frames_are_ignored_by_monitors_and_the_controller(attack, caplog, until) -> None:
    with attack("sim://?seed=4&rate_hz=200") as (daemon, url, a, bad):
        m = open_box(url)
        assert isinstance(m, ZenohBox)
        try:
            captured: list[bytes] = []
            sub = bad.s.declare_subscriber(
                "softpad/box/frames", lambda s: captured.append(s.payload.to_bytes())
            )
            for _ in range(5):
                m.read(), a.read()
            until(lambda: len(captured) > 3, "a real frame captured")
            sub.undeclare()
            for _ in range(20):
                for data in [*_forged_frames(10**9), captured[0]]:  # forged, then a replay
                    bad.put("frames", data)
            seen = [(m.read_stamped(), a.read_stamped()) for _ in range(60)]
        finally:
            m.close()
        for fm, fa in seen:
            for f in (fm, fa):
                assert f.seq < 10**9 and np.isfinite(f.frame.pressures_pa).all()
                assert f.frame.pressures_pa.max() < 5e3
        assert m.forged_frames > 0 and a.forged_frames > 0
        assert "forged or replayed" in caplog.text
        assert daemon._acked <= daemon._seq  # lock-step was not switched off


def test_a_monitor_key_cannot_forge_frames_for_the_controller(attack, until) -> None:
    """A participant knowing the read key (anyone who asked ``info``) forges frames that a
    monitor believes, but the controller does not."""
    with attack() as (_daemon, _url, a, bad):
        read_key = bytes.fromhex(bad.ask("info", {})["read_key"])
        data = encode_frame(10**6, time.monotonic(), PressureFrame(0.0, np.full(8, 9e3), 1e4))
        before = a.forged_frames
        for _ in range(10):
            bad.put("frames", seal_frame(data, read_key, None))
        until(lambda: a.forged_frames >= before + 10, "the controller refusing them")
        assert all(a.read_stamped().seq < 10**6 for _ in range(20))
        assert split_frame(seal_frame(data, read_key, None))[0] == data


def test_deep_and_oversized_payloads_get_a_clear_reply(attack) -> None:
    with attack() as (daemon, _url, _a, bad):
        deep = b"[" * 2000 + b"]" * 2000
        r = bad.ask("valves", deep)
        assert r["ok"] is False and r["kind"] == "input" and "deep" in r["error"]
        r = bad.ask("info", b'{"a":' * 100 + b"1" + b"}" * 100)
        assert r["ok"] is False and "limit is 8" in r["error"]
        r = bad.ask("valves", b" " * 5000)
        assert r["ok"] is False and "exceeds the limit" in r["error"]
        assert daemon.stats.malformed >= 3


def test_services_are_bounded_and_refused_on_a_hardware_box(
    attack, served, tmp_path, until
) -> None:
    from softpad.box import BoxDaemon, BoxWrapper
    from softpad.errors import InputError
    from softpad.harness import simulation_extensions

    with attack() as (daemon, _url, a, _bad):
        frames = daemon.stats.frames
        with pytest.raises(InputError, match="limit is 8"):
            a.request("ext/sim.place", objects=["object-5"] * 300)
        with pytest.raises(InputError, match="64 characters"):
            a.request("ext/sim.place", objects=["x" * 100])
        until(lambda: daemon.stats.frames > frames + 10, "sampling going on")
    # a hardware box (fake IIO tree, in-memory valve lines), alone and seen through a view,
    # refuses the simulator's services; a view of a simulator is still a simulator
    sim = open_box("sim://")
    hw = _hardware_box(tmp_path)
    try:
        for box in (hw, BoxWrapper(hw, owns_inner=False)):
            with pytest.raises(InputError, match="simulated box only"):
                BoxDaemon(box, services=simulation_extensions(sim))
        view = BoxDaemon(BoxWrapper(sim, owns_inner=False), services=simulation_extensions(sim))
        view.close()
    finally:
        hw.close()
        sim.close()


def _hardware_box(root: Path):
    """A HardwareBox of 2 channels on a fake sysfs IIO tree and in-memory GPIO lines."""
    from softpad.box import FakeValveLines, HardwareBox
    from softpad.config import parse_installation

    dev = root / "iio:device0"
    dev.mkdir(parents=True)
    for k in range(2):
        (dev / f"in_voltage{k}_raw").write_text("1100\n")
    (dev / "in_voltage_scale").write_text("0.439453125\n")
    chans = [
        {"gpiochip": "/dev/gpiochip9", "inflate_line": 2 * k, "deflate_line": 2 * k + 1,
         "iio_device": 0, "iio_channel": k, "pa_per_count": 0.5}
        for k in range(2)
    ]  # fmt: skip
    kinds = {"inflate_valves": "normally_closed", "deflate_valves": "normally_open"}
    box = {"channel": chans, "iio_root": str(root), **kinds}
    settings = parse_installation({"box": box, "pad": {"rows": 1, "cols": 2}}).box
    lines = FakeValveLines(
        (w.gpiochip, o) for w in settings.channels for o in (w.inflate_line, w.deflate_line)
    )
    return HardwareBox(settings, lines=lines)


def test_box_fault_is_logged_once_not_every_frame(free_port, until) -> None:
    from softpad.box import BoxDaemon, BoxWrapper
    from softpad.errors import HardwareFault

    class Broken(BoxWrapper):
        def _read(self) -> PressureFrame:
            raise HardwareFault("sensor bus timed out")

    lines: list[str] = []
    sim = open_box("sim://?rate_hz=200")
    d = BoxDaemon(Broken(sim), (f"tcp/127.0.0.1:{free_port()}",), log=lines.append)
    with d:
        until(lambda: d.stats.faults >= 60, "60 box faults")
    faults = [ln for ln in lines if "box fault" in ln]
    assert 1 <= len(faults) <= 2, faults


def _openssl(*args: str, cwd: Path) -> None:
    subprocess.run(["openssl", *args], cwd=cwd, check=True, capture_output=True, timeout=60)


def _make_pki(d: Path, ca: str, names: tuple[str, ...]) -> None:
    """A CA and certificates for 127.0.0.1 signed by it (openssl CLI, EC P-256)."""
    ec = ("-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes")
    _openssl(
        "req",
        "-x509",
        *ec,
        "-keyout",
        f"{ca}.key",
        "-out",
        f"{ca}.pem",
        "-days",
        "1",
        "-subj",
        f"/CN={ca}",
        cwd=d,
    )
    ext = d / "ext.cnf"
    ext.write_text(
        "subjectAltName=DNS:localhost,IP:127.0.0.1\nbasicConstraints=CA:FALSE\n"
        "extendedKeyUsage=serverAuth,clientAuth\n"
    )
    for n in names:
        _openssl("req", *ec, "-keyout", f"{n}.key", "-out", f"{n}.csr", "-subj", f"/CN={n}", cwd=d)
        _openssl(
            "x509",
            "-req",
            "-in",
            f"{n}.csr",
            "-CA",
            f"{ca}.pem",
            "-CAkey",
            f"{ca}.key",
            "-CAcreateserial",
            "-out",
            f"{n}.pem",
            "-days",
            "1",
            "-extfile",
            "ext.cnf",
            cwd=d,
        )


def _site(path: Path, **link: Any) -> Path:
    lines = ["[link]"] + [f"{k} = {json.dumps(v)}" for k, v in link.items()]
    path.write_text("\n".join(lines) + "\n")
    return path


def _refusal(url: str) -> ConnectionLost | None:
    """The ``ConnectionLost`` that opening ``url`` raises, or None when it opened (closed
    again); any other error propagates."""
    try:
        open_box(url).close()
    except ConnectionLost as exc:
        return exc
    return None


@pytest.mark.skipif(shutil.which("openssl") is None, reason="needs the openssl command")
def test_mutual_tls_box_refuses_clients_without_a_certificate(tmp_path: Path, free_port) -> None:
    from softpad.box import BoxDaemon
    from softpad.box._credentials import daemon_auth
    from softpad.config import load_installation

    _make_pki(tmp_path, "ca", ("daemon", "client"))
    _make_pki(tmp_path, "rogue-ca", ("rogue",))
    port = free_port()
    t = str(tmp_path)
    daemon_site = _site(
        tmp_path / "daemon.toml",
        listen=[f"tls/127.0.0.1:{port}"],
        tls_certificate=f"{t}/daemon.pem",
        tls_private_key=f"{t}/daemon.key",
        tls_root_ca=f"{t}/ca.pem",
    )
    link = load_installation(daemon_site).link
    good = _site(
        tmp_path / "client.toml",
        tls_certificate=f"{t}/client.pem",
        tls_private_key=f"{t}/client.key",
        tls_root_ca=f"{t}/ca.pem",
    )
    no_cert = _site(tmp_path / "nocert.toml", tls_root_ca=f"{t}/ca.pem")
    rogue = _site(
        tmp_path / "rogue.toml",
        tls_certificate=f"{t}/rogue.pem",
        tls_private_key=f"{t}/rogue.key",
        tls_root_ca=f"{t}/ca.pem",
    )
    url = f"zenoh://127.0.0.1:{port}?timeout_s=3&config="
    with BoxDaemon(open_box("sim://?seed=4"), link.listen, auth=daemon_auth(link)) as daemon:
        with open_box(url + str(good)) as box:
            assert box.endpoint.startswith("tls/")  # type: ignore[attr-defined]
            box.set_valve(1, "deflate")
            assert daemon.box.valves[0] is ValveCommand.DEFLATE
        # no certificate, a rogue CA's, plain tcp on the TLS port: each client waits out its
        # connect timeout (1 s: a loopback handshake takes milliseconds), side by side
        short = url.replace("timeout_s=3", "timeout_s=1")
        refused = [
            short + str(no_cert),
            short + str(rogue),
            f"zenoh://127.0.0.1:{port}?timeout_s=1",
        ]
        with ThreadPoolExecutor(len(refused)) as pool:
            errors = list(pool.map(_refusal, refused))
        assert all(isinstance(e, ConnectionLost) for e in errors), errors


def test_user_password_box_refuses_clients_without_credentials(
    tmp_path: Path, free_port, monkeypatch: pytest.MonkeyPatch
) -> None:
    from softpad.box import BoxDaemon
    from softpad.box._credentials import daemon_auth
    from softpad.config import load_installation

    (tmp_path / "users").write_text("robot:s3cret-pw\n")
    port = free_port()
    link = load_installation(
        _site(
            tmp_path / "d.toml",
            listen=[f"tcp/127.0.0.1:{port}"],
            user="robot",
            password_file=str(tmp_path / "users"),
        )
    ).link
    client = _site(tmp_path / "c.toml", user="robot", password_file=str(tmp_path / "users"))
    url = f"zenoh://127.0.0.1:{port}?timeout_s=3"
    with BoxDaemon(open_box("sim://?seed=4"), link.listen, auth=daemon_auth(link)):
        with open_box(f"{url}&config={client}") as box:
            box.read()
        monkeypatch.setenv("SOFTPAD_BOX_USER", "robot")
        monkeypatch.setenv("SOFTPAD_BOX_PASSWORD", "s3cret-pw")
        with open_box(url) as box:
            box.read()
        refused = url.replace("timeout_s=3", "timeout_s=1")  # waits out its connect timeout
        monkeypatch.setenv("SOFTPAD_BOX_PASSWORD", "wrong")
        with pytest.raises(ConnectionLost):
            open_box(refused)
        monkeypatch.delenv("SOFTPAD_BOX_USER")
        monkeypatch.delenv("SOFTPAD_BOX_PASSWORD")
        with pytest.raises(ConnectionLost):
            open_box(refused)
    from softpad.errors import InputError

    with pytest.raises(InputError, match="never carries credentials"):
        open_box(f"zenoh://robot:s3cret-pw@127.0.0.1:{port}")


def test_cli_serves_with_user_password_from_the_installation_file(
    tmp_path: Path, free_port
) -> None:
    """The issue's 'Predicate rejected value for usrpwd': the daemon starts and serves."""
    (tmp_path / "users").write_text("robot:pw\n")
    port = free_port()
    site = _site(
        tmp_path / "site.toml",
        listen=[f"tcp/127.0.0.1:{port}"],
        user="robot",
        password_file=str(tmp_path / "users"),
    )
    serve = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "softpad",
            "box",
            "serve",
            "--sim",
            "--config",
            str(site),
            "--duration-s",
            "60",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        line = serve.stdout.readline()  # type: ignore[union-attr]
        assert "serving" in line, serve.stderr.read() if serve.poll() is not None else line  # type: ignore[union-attr]
        with open_box(f"zenoh://127.0.0.1:{port}?config={site}") as box:
            box.read()
    finally:
        serve.kill()
        serve.wait(timeout=10)


def test_tcp_beyond_loopback_is_refused_whatever_else_is_set(tmp_path: Path) -> None:
    from softpad.config import ConfigError, parse_installation
    from softpad.errors import InputError

    full = {
        "allow_remote": True,
        "user": "u",
        "password_file": "/x",
        "tls_certificate": "/c",
        "tls_private_key": "/k",
        "tls_root_ca": "/ca",
    }
    with pytest.raises(ConfigError, match="plain tcp"):
        parse_installation({"link": {"listen": ["tcp/192.168.7.2:7447"], **full}})
    tls_only = {k: v for k, v in full.items() if k not in ("user", "password_file", "tls_root_ca")}
    with pytest.raises(ConfigError, match="no authentication"):  # TLS without client checks
        parse_installation({"link": {"listen": ["tls/192.168.7.2:7447"], **tls_only}})
    assert parse_installation({"link": {"listen": ["tls/192.168.7.2:7447"], **full}}).link.has_auth
    with pytest.raises(InputError, match="beyond loopback"):
        open_box("zenoh://192.168.7.2:7447")


def test_a_script_that_never_closes_its_box_exits(served) -> None:
    """Issue 35 item 11: interpreter exit closed nothing and hung on the open session."""
    with served() as (_daemon, url):
        code = f"from softpad.box import open_box; b = open_box({url!r}); print(b.read().t_s)"
        done = subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, timeout=120
        )
    assert done.returncode == 0, done.stderr
    assert float(done.stdout) >= 0


def test_fuzzed_payloads_never_break_the_daemon(attack, until) -> None:
    """Hypothesis: random JSON and bytes on every key; each query is answered, nothing
    un-authenticated moves a valve, the daemon goes on sampling (bounded: 120 examples)."""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    keys = [
        "info",
        "stats",
        "valves",
        "control/take",
        "control/release",
        "ext/sim.place",
        "ext/robot.move_to",
    ]
    scalars = (
        st.none()
        | st.booleans()
        | st.integers(-(2**70), 2**70)
        | st.floats(allow_nan=False, allow_infinity=False)
        | st.text(max_size=20)
    )
    values = st.recursive(
        scalars,
        lambda c: st.lists(c, max_size=4) | st.dictionaries(st.text(max_size=8), c, max_size=4),
        max_leaves=12,
    )
    fields = st.fixed_dictionaries(
        {},
        optional={
            "client": st.text(max_size=20) | scalars,
            "channel": values,
            "command": values,
            "n": values,
            "mac": values,
            "objects": values,
        },
    )
    payloads = (
        fields.map(encode_json)
        | st.binary(max_size=300)
        | values.map(lambda v: json.dumps(v).encode())
    )

    with attack() as (daemon, _url, a, bad):
        valves = daemon.box.valves

        @settings(
            max_examples=120, deadline=None, suppress_health_check=list(HealthCheck), database=None
        )
        @given(key=st.sampled_from(keys), payload=payloads)
        def one(key: str, payload: bytes) -> None:
            r = bad.ask(key, payload)
            assert isinstance(r.get("ok"), bool)
            if key not in ("info", "stats"):
                assert r["ok"] is False, (key, payload, r)

        one()
        assert daemon.box.valves == valves
        assert daemon.controller == a.client_id
        frames = daemon.stats.frames
        until(lambda: daemon.stats.frames > frames + 5, "sampling going on")


def test_tls_keys_on_a_tcp_endpoint_are_refused(tmp_path: Path, cli) -> None:
    """Issue 35 item 5: TLS settings on a tcp/ endpoint looked like authentication."""
    site = _site(
        tmp_path / "s.toml",
        listen=["tcp/127.0.0.1:7447"],
        tls_certificate="/c.pem",
        tls_private_key="/k.pem",
        tls_root_ca="/ca.pem",
    )
    code, _out, err = cli("box", "serve", "--sim", "--config", str(site), "--duration-s", "1")
    assert code == 2 and "protect nothing" in err


def test_a_controller_that_lost_control_reads_on_after_another_takes(attack, until) -> None:
    with attack(watchdog_s=0.3) as (daemon, url, a, _bad):
        a._beat_stop.set()  # frozen: the watchdog withdraws control
        until(lambda: daemon.controller is None, "the watchdog trip")
        with open_box(url) as b:
            b.set_valve(1, "deflate")  # another client takes control
            with pytest.raises(ControlRefused, match="does not control"):
                a.set_valve(1, "inflate")
            forged = a.forged_frames
            seqs = [a.read_stamped().seq for _ in range(30)]
            assert np.all(np.diff(seqs) > 0)
            assert a.forged_frames - forged <= 2  # at most the frames in flight


def test_an_impostor_queryable_neither_takes_commands_nor_fakes_answers(attack, until) -> None:
    """zenoh's default query target picks one queryable: an impostor answering ``valves``
    would have swallowed the controller's commands. Every queryable now gets each query and
    only the box pinned at connection is believed; two boxes at connection is refused."""
    from softpad.errors import HardwareFault

    def command_heard_by_the_impostor() -> bool:  # once its queryable reached the client
        a.set_valve(2, "deflate")
        return a.impostor_replies >= 1

    with attack() as (daemon, url, a, bad):
        fake = {"ok": True, "valves": ["closed"] * 8}
        queryables = [
            bad.s.declare_queryable(
                f"softpad/box/{k}", lambda q: q.reply(q.key_expr, encode_json(fake))
            )
            for k in ("valves", "info")
        ]
        try:
            # the impostor's declaration reaches the client's session a moment later (on a busy
            # machine the first command went before it: 0 impostor replies); repeating the
            # same command is harmless
            until(command_heard_by_the_impostor, "a command the impostor also answers", 30.0)
            assert daemon.box.valves[1] is ValveCommand.DEFLATE  # the box took it, not the impostor
            assert a.impostor_replies >= 1
            with pytest.raises(HardwareFault, match="impostor"):
                open_box(url)
        finally:
            for q in queryables:
                q.undeclare()


def test_config_option_carries_the_link_credentials_to_the_box_url(tmp_path: Path) -> None:
    from softpad.cli._installation import _defaults
    from softpad.config import load_installation

    site = _site(
        tmp_path / "ws.toml", connect=["tcp/127.0.0.1:7447"], user="robot", password_file="/p"
    )
    assert _defaults(load_installation(site))["box"] == (
        f"zenoh://127.0.0.1:7447/softpad/box?config={site}"
    )
