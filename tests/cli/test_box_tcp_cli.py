"""``softpad box serve``, and ``box read`` / ``box inflate`` / ``run`` against a tcp:// box."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
from collections.abc import Iterator

import pytest

from softpad.box import BoxServer, ConnectionLost, open_box
from softpad.cli.main import main


@pytest.fixture
def server() -> Iterator[BoxServer]:
    srv = BoxServer(open_box("sim://?seed=1&object=object-5&inflated_kpa=1.1"), "127.0.0.1", 0)
    thread = threading.Thread(target=srv.serve, daemon=True)
    thread.start()
    yield srv
    srv.stop()
    thread.join(timeout=5)
    srv.close()


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


def test_box_read_over_tcp(capsys, server: BoxServer) -> None:
    code, out, _ = run(capsys, "box", "read", "--box", server.url, "--count", "3", "--json")
    assert code == 0
    frames = [json.loads(line) for line in out.splitlines()]
    assert [f["t_s"] for f in frames] == [0.01, 0.02, 0.03]
    assert all(len(f["pressures_kpa"]) == 8 for f in frames)
    assert 1.0 < frames[0]["pressures_kpa"][2] < 1.4  # object 5 rests on module 3


def test_box_inflate_over_tcp(capsys, server: BoxServer) -> None:
    code, out, _ = run(capsys, "box", "inflate", "--box", server.url, "--json")
    assert code == 0
    d = json.loads(out)
    assert len(d["reference_pa"]) == 6 and d["reference_at_s"] > d["adjusted_at_s"]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["box", "read", "--box", "tcp://127.0.0.1"], "tcp:// needs host:port"),
        (["box", "serve", "--port", "70000"], "--port must be within 0..65535, got 70000"),
        (["box", "serve", "--host", "no.such.host.invalid"], "cannot resolve host"),
        (["box", "inflate", "--modules", "9"], "--modules must be within 1..8"),
    ],
    ids=["no-port", "port", "host", "modules"],
)
def test_errors_are_one_line_and_exit_2(capsys, argv, message) -> None:
    code, _, err = run(capsys, *argv)
    assert code == 2
    assert message in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_run_over_tcp_without_a_served_world_is_one_line(capsys, server: BoxServer) -> None:
    code, _, err = run(capsys, "run", "--box", server.url)
    assert code == 2 and "carries pressures and valves only" in err
    assert len(err.strip().splitlines()) == 1


def test_run_over_tcp_equals_the_run_in_process(capsys) -> None:
    """softpad run through a served simulator (world and robot served too): the same run."""
    from softpad.harness import simulation_extensions

    url = "sim://?seed=2"
    argv = ["run", "--object", "object-4", "--hold-s", "1", "--json"]
    code, out, _ = run(capsys, *argv, "--box", url)
    assert code == 0
    local = json.loads(out)
    box = open_box(url)
    with BoxServer(box, "127.0.0.1", 0, extensions=simulation_extensions(box)) as srv:
        thread = threading.Thread(target=srv.serve, daemon=True)
        thread.start()
        code, out, err = run(capsys, *argv, "--box", srv.url)
        srv.stop()
        thread.join(timeout=5)
    assert code == 0, err
    remote = json.loads(out)
    assert remote == local
    assert remote["outcome"] == "held" and remote["contact_detected"] is True


def test_box_read_when_nobody_listens_is_one_line(capsys) -> None:
    import socket

    s = socket.create_server(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    code, _, err = run(capsys, "box", "read", "--box", f"tcp://127.0.0.1:{port}")
    assert code == 3 and "cannot connect to the box at tcp://127.0.0.1" in err
    assert len(err.strip().splitlines()) == 1


def test_box_serve_prints_its_port_and_stops_when_the_client_leaves(capsys) -> None:
    """The real command in a subprocess: --once, port 0, loopback; softpad run as its client."""
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen(
        [sys.executable, "-m", "softpad.cli.main", "box", "serve", "--port", "0", "--once"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert line.startswith("serving sim:// on tcp://127.0.0.1:")
        url = line.split(" on ")[1].split()[0]
        # the served simulator offers its world and robot: the whole loop runs through it
        assert main(["run", "--box", url, "--object", "object-5", "--hold-s", "0", "--json"]) == 0
        assert proc.wait(timeout=20) == 0
        err = proc.stderr.read() if proc.stderr else ""
        assert "session ended (closed by the client); valves closed" in err
        assert json.loads(capsys.readouterr().out)["outcome"] == "held"
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=5)


@pytest.mark.parametrize("signame", ["SIGINT", "SIGTERM"], ids=["ctrl-c", "term"])
def test_box_serve_stops_cleanly_on_ctrl_c_and_term(signame: str) -> None:
    import signal

    proc = subprocess.Popen(
        [sys.executable, "-m", "softpad.cli.main", "box", "serve"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=dict(os.environ, PYTHONUNBUFFERED="1"),
    )
    try:
        assert proc.stdout is not None
        url = proc.stdout.readline().split(" on ")[1].split()[0]
        box = open_box(url)
        box.set_valve(2, "inflate")
        proc.send_signal(getattr(signal, signame))
        assert proc.wait(timeout=20) == 0
        err = proc.stderr.read() if proc.stderr else ""
        assert "session ended (server stopping); valves closed" in err
        assert "stopped; valves closed" in err and "Traceback" not in err
        with pytest.raises(ConnectionLost):
            box.read()
        box.close()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=5)
