"""A seeded misuse campaign of the ``softpad`` command and the Python API (issue 35, last
"Done when": 600 CLI inputs and 180 API misuses, no traceback, no clobbered file, no silently
accepted unit mix-up).

Run it (about 2 minutes on 2 cores)::

    PYTHONPATH=src MPLBACKEND=Agg python tests/fuzz_campaign.py [--cli 600] [--api 180]
        [--seed 35] [--json] [--show OUTCOME]

Each CLI input runs in process through :func:`softpad.cli.main.main`, stdout and stderr
captured, in a temporary folder that holds valid and corrupt input files and existing output
files (their hashes are taken before and after every input). The commands that would run for
long (trials, FEM solves, design sweeps, daemons, nodes) are stubbed where their work would
start: reaching a stub means the command line was accepted. Boxes are opened for real only for
``sim://`` and ``replay://``; other URLs are parsed, never connected. Every input runs under a
time bound (:data:`TIME_BOUND_S`).

Outcomes (:data:`OUTCOMES`):

* ``refused``: exit 2 (an :class:`~softpad.errors.InputError` for the API) with a message that
  names the option, the value, a file or the parameter;
* ``vague``: refused, but the message names none of them;
* ``accepted``: exit 0 or the work reached, for an input that may be valid;
* ``failed``: exit 1 or 3 (a job that ran and failed, a link fault);
* ``traceback``: a traceback, exit 4, an exception escaping ``main`` or a foreign exception
  from the API;
* ``clobbered``: a file that existed before the input changed or vanished without ``--force``;
* ``mixup``: a value a thousand times off (a unit mix-up) accepted without error or warning;
* ``accepted_invalid``: another invalid value (NaN, a wrong type or length) accepted;
* ``timeout``: the input ran past the time bound.
"""

from __future__ import annotations

import argparse
import contextlib
import hashlib
import io
import json
import math
import os
import re
import shutil
import signal
import sys
import tempfile
import threading
import time
import types
import warnings
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from softpad.errors import SoftPadError

#: Seed of the campaign (issue 35). Other seeds give other inputs of the same kinds.
SEED = 35
#: Longest time one input may run, seconds (the stubs end every long job far sooner).
TIME_BOUND_S = 20.0
OUTCOMES = (
    "refused",
    "vague",
    "accepted",
    "failed",
    "traceback",
    "clobbered",
    "mixup",
    "accepted_invalid",
    "timeout",
)
#: Outcomes the campaign must never produce.
BAD = ("traceback", "clobbered", "mixup", "timeout")
DATA = Path(__file__).resolve().parent / "data"


@dataclass
class Case:
    """One input: a command line (``argv``) or an API call (``call``)."""

    surface: str
    kind: str
    label: str
    argv: list[str] = field(default_factory=list)
    call: Callable[[], Any] | None = None
    #: Words one of which a clean refusal's message contains (the option, the value...).
    names: tuple[str, ...] = ()
    #: The input is surely invalid (refusal expected); ``mixup``: invalid by a unit mix-up.
    invalid: bool = True
    mixup: bool = False


@dataclass
class Result:
    case: Case
    outcome: str
    code: int | None
    message: str
    seconds: float


# ----------------------------------------------------------------------------- running


class _Started(SoftPadError):
    """A stubbed long job was reached: the input was accepted (exit 0)."""

    exit_code = 0
    kind = "started"


class _TimeBound(BaseException):
    """The input ran past :data:`TIME_BOUND_S` (a BaseException: ``main`` does not catch it)."""


def _started(*args: Any, **kwargs: Any) -> Any:
    raise _Started("the work would start here")


#: Frames a command may read from a box opened by the campaign before it is stopped.
MAX_READS = 1000


def _open_box_checked(real: Callable[[str], Any]) -> Callable[..., Any]:
    """``open_box`` that opens ``sim://`` and ``replay://`` boxes for real, stopping the
    command after :data:`MAX_READS` frames; a ``zenoh://`` URL is checked but never
    connects (:class:`_ZenohBox`)."""

    def open_box(url: str = "sim://") -> Any:
        box = real(url)  # a zenoh:// URL is checked, then stops at the stubbed ZenohBox
        read, count = box.read, [0]

        def limited() -> Any:
            count[0] += 1
            if count[0] > MAX_READS:
                raise _Started(f"box {url!r} read {MAX_READS} frames")
            return read()

        box.read = limited
        return box

    return open_box


class _ZenohBox:
    """The client of a checked ``zenoh://`` URL: it would connect here. A class, so that
    ``isinstance(box, ZenohBox)`` in the code under test still works (it is False)."""

    def __init__(self, host: str, port: int, *args: Any, **kwargs: Any) -> None:
        raise _Started(f"box zenoh://{host}:{port} would be used here")


def _arm_node(box_url: str = "sim://", *args: Any, **kwargs: Any) -> Any:
    """``SimArmNode`` up to its box (opened as the campaign opens boxes): no ROS, no server."""
    import softpad.box

    softpad.box.open_box(box_url).close()
    raise _Started("the work would start here")


#: The long FEM jobs of ``softpad.fem`` that the stubs replace (also tests/cli/test_fuzz.py).
FEM_LONG_JOBS = (
    "ModuleModel",
    "inflation_sweep",
    "design_sweep",
    "stiffness_study",
    "sensitive_area_study",
    "sealed_chamber_study",
    "fit_material",
    "compare_models",
    "module_characteristic",
)


def _stub_targets() -> list[tuple[Any, str, Any]]:
    """(object, attribute, replacement) of every stubbed long job."""
    import softpad.box
    import softpad.box._daemon
    import softpad.box._zenoh
    import softpad.cli._bench
    import softpad.cli._box
    import softpad.cli._demo
    import softpad.cli._results
    import softpad.cli._trials
    import softpad.control
    import softpad.design
    import softpad.fem
    import softpad.fem._response
    import softpad.harness
    import softpad.record
    import softpad.ros
    import softpad.sim
    import softpad.sim._probe
    import softpad.trials

    targets: list[tuple[Any, str, Any]] = [
        (softpad.harness, "run_simulated", _started),
        (softpad.harness, "run_objects", _started),
        (softpad.cli._trials, "run_with_progress", _started),
        (softpad.cli._trials, "run_seeds_with_progress", _started),
        (softpad.cli._demo, "_reference_plans", _started),
        (softpad.cli._results, "run_result", _started),
        (softpad.cli._box, "_monitor_foxglove", _started),
        (softpad.control, "inflate_and_adjust", _started),
        (softpad.box, "BoxDaemon", _started),
        (softpad.box._daemon, "BoxDaemon", _started),  # ServeOptions.daemon's
        (softpad.box, "open_watched", _open_box_checked(softpad.box.open_watched)),
        (softpad.box, "open_box", _open_box_checked(softpad.box.open_box)),
        (softpad.record, "FoxgloveLive", _started),
        (softpad.design, "design_sweep", _started),
        (softpad.design, "run_experiment_on_dask", _started),
        (softpad.trials, "compare", _started),
        (softpad.trials, "validate", _started),
        (softpad.ros, "PadNode", _started),
        (softpad.ros, "SimArmNode", _arm_node),
        (softpad.box._zenoh, "ZenohBox", _ZenohBox),
        (softpad.cli._bench, "importlib", types.SimpleNamespace(import_module=_started)),
        (softpad.sim, "sealed_rise_map", _started),
        (softpad.sim._probe, "sealed_rise_map", _started),  # softpad.sim.pad_map's
        (softpad.fem._response, "module_response", _started),
        (softpad.fem.ModuleSetup, "model", _started),
    ]
    targets.extend((softpad.fem, name, _started) for name in FEM_LONG_JOBS)
    # where softpad.fem's study runs (softpad.fem.run_sweep, ...) find them
    targets.extend(
        (sys.modules[getattr(softpad.fem, name).__module__], name, _started)
        for name in FEM_LONG_JOBS
    )
    return targets


@contextlib.contextmanager
def stubbed() -> Iterator[None]:
    """The long jobs of every command replaced by :func:`_started` (undone on exit)."""
    targets = _stub_targets()
    saved = [(obj, name, getattr(obj, name)) for obj, name, _ in targets]
    try:
        for obj, name, new in targets:
            setattr(obj, name, new)
        yield
    finally:
        for obj, name, old in reversed(saved):
            setattr(obj, name, old)


@contextlib.contextmanager
def _time_bound(seconds: float) -> Iterator[None]:
    """Raise :class:`_TimeBound` in the main thread after ``seconds`` (no bound elsewhere)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def expire(signum: int, frame: Any) -> None:
        raise _TimeBound(f"ran past {seconds:g} s")

    old = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def _hashes(folder: Path) -> dict[str, str]:
    out = {}
    for p in sorted(folder.rglob("*")):
        if p.is_file() and not p.is_symlink():
            out[str(p.relative_to(folder))] = hashlib.sha256(p.read_bytes()).hexdigest()
    return out


def _names_it(message: str, names: tuple[str, ...]) -> bool:
    """The message names one of ``names``, or else an option or a quoted value (a refusal
    of another option than the one misused, a default output that exists)."""
    low = message.lower()
    if any(n and (n.lower() in low or repr(n).lower() in low) for n in names):
        return True
    return bool(re.search(r"--[a-z]|'[^']+'", message))


_WARNED = re.compile(r"warning|given as|were .* given", re.IGNORECASE)


def run_cli(case: Case, folder: Path) -> Result:
    """Run one command line in process in ``folder``; classify it."""
    from softpad.cli.main import main

    before = _hashes(folder)
    out, err = io.StringIO(), io.StringIO()
    code: int | None = None
    escaped = ""
    t0 = time.perf_counter()
    try:
        with (
            _time_bound(TIME_BOUND_S),
            contextlib.redirect_stdout(out),
            contextlib.redirect_stderr(err),
        ):
            code = main(list(case.argv))
    except _TimeBound:
        return Result(case, "timeout", None, "", time.perf_counter() - t0)
    except SystemExit as exc:  # --help, --version
        code = exc.code if isinstance(exc.code, int) else 2
    except BaseException as exc:
        escaped = f"{type(exc).__name__}: {exc}"
    seconds = time.perf_counter() - t0
    text = err.getvalue()
    message = escaped or (text.strip().splitlines() or [""])[-1]
    after = _hashes(folder)
    if "--force" not in case.argv:
        lost = [k for k, h in before.items() if after.get(k) != h]
        if lost:
            return Result(case, "clobbered", code, f"changed: {lost}", seconds)
    if escaped or "Traceback" in text or code == 4:
        return Result(case, "traceback", code, message, seconds)
    started = re.search(r"the work would start here|would be used here|read \d+ frames", text)
    if code == 0 or started:
        return Result(case, _accepted(case, text), code, message, seconds)
    if code == 2:
        ok = _names_it(message, case.names) or "usage:" in text
        return Result(case, "refused" if ok else "vague", code, message, seconds)
    return Result(case, "failed", code, message, seconds)


def _accepted(case: Case, warned_text: str) -> str:
    if case.mixup and not _WARNED.search(warned_text):
        return "mixup"
    if case.invalid and not case.mixup:
        return "accepted_invalid"
    return "accepted"


def run_api(case: Case, folder: Path) -> Result:
    """Call one API misuse in ``folder``; classify it."""
    before = _hashes(folder)
    result = _api_outcome(case)
    after = _hashes(folder)
    lost = [k for k, h in before.items() if after.get(k) != h]
    if lost:
        return Result(case, "clobbered", result.code, f"changed: {lost}", result.seconds)
    return result


def _api_outcome(case: Case) -> Result:
    from softpad.errors import InputError

    assert case.call is not None
    t0 = time.perf_counter()
    try:
        with _time_bound(TIME_BOUND_S), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            value = case.call()
            _close(value)
    except _TimeBound:
        return Result(case, "timeout", None, "", time.perf_counter() - t0)
    except InputError as exc:
        ok = _names_it(str(exc), case.names)
        return Result(case, "refused" if ok else "vague", 2, str(exc), time.perf_counter() - t0)
    except Exception as exc:
        msg = f"{type(exc).__name__}: {exc}"
        return Result(case, "traceback", None, msg, time.perf_counter() - t0)
    text = " ".join(str(w.message) for w in caught)
    return Result(case, _accepted(case, text), 0, text, time.perf_counter() - t0)


def _close(value: Any) -> None:
    close = getattr(value, "close", None)
    if callable(close) and not isinstance(value, type):
        close()


# ----------------------------------------------------------------------------- files


#: Files that exist before every input (outputs must not be clobbered without --force).
EXISTING = (
    "old.png",
    "old.csv",
    "old.npz",
    "old.md",
    "old.mcap",
    "old.parquet",
    "old.vtu",
    "old.html",
    "characteristic.npz",
    "module_response.npz",
    "report/index.html",
    "docs/results.md",
    "out/kept.txt",
)


def make_files(folder: Path, rng: np.random.Generator) -> dict[str, list[str]]:
    """Write the campaign's input files into ``folder``; return them by kind."""
    rec = (DATA / "banana.mcap").read_bytes()
    for name in EXISTING:
        p = folder / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_bytes(f"kept {name}".encode())
    shutil.copy(DATA / "banana.mcap", folder / "rec.mcap")
    shutil.copy(DATA / "banana.mcap", folder / "old.mcap")
    corrupt = {
        "empty.mcap": b"",
        "garbage.mcap": rng.bytes(2000),
        "text.mcap": b"pressure,1,2,3\n",
        "head.mcap": rec[:8],
    }
    for k, cut in enumerate(sorted(rng.integers(20, len(rec) - 1, size=6))):
        corrupt[f"cut{k}.mcap"] = rec[: int(cut)]
    for name, data in corrupt.items():
        (folder / name).write_bytes(data)
    files = {"mcap": sorted(corrupt), "toml": [], "frame": [], "csv": [], "set": []}
    for kind, texts in _text_files().items():
        for i, text in enumerate(texts):
            name = f"{kind}{i}.{ {'frame': 'json', 'set': 'toml'}.get(kind, kind) }"
            (folder / name).write_text(text)
            files[kind].append(name)
    return files


def _text_files() -> dict[str, list[str]]:
    """Corrupt, mistyped and unit-mixed installation, frame, measurement and object-set files
    (the first of each kind is valid)."""
    blocks = Path(__file__).resolve().parents[1] / "src/softpad/data/object_sets/blocks.toml"
    valid_set = blocks.read_text()
    return {
        "toml": [
            "[thresholds]\np0_kpa = 1.1\n",
            "[thresholds]\np0_kpa = 1100\n",  # Pa given as kPa
            "[pad]\npitch_mm = 0.045\n",  # m given as mm
            "[thresholds]\np0_kpa = '1.1'\n",
            "[thresholds\np0_kpa = 1.1\n",
            "[thresholds]\np0_kpa = nan\n",
            "[box]\nsample_rate_hz = -1\n",
            "[link]\nwatchdog_s = 500\n",  # ms given as s
            "[thresholds]\nt_g_kpa = 90\n",  # Pa given as kPa
            "\x00\x01\x02",
            "[pad]\nrows = 2.5\n",
            "[thresholds]\np0_pa = 1100\n",  # a key in SI units: unknown
            "[pad.pose]\nz_mm = 0.02\n",  # m given as mm? a pose may be that close: valid
        ],
        "frame": [
            '{"delta_kpa": [0, 0.124, 0.078, 0.109, 0, 0]}',
            '{"delta_kpa": [0, 124, 78, 109, 3, 2]}',  # Pa given as kPa
            '{"delta_kpa": [0, 0.124, 0.078',
            '{"delta_kpa": [0, NaN, 0, 0, 0, 0]}',
            '{"pressures_kpa": [1.2, 1.1, 1.1, 1.1, 1.1, 1.1]}',
            '{"pressures_kpa": [1200, 1100, 1100, 1100, 1100, 1100],'
            ' "reference_kpa": [1100, 1100, 1100, 1100, 1100, 1100]}',  # Pa given as kPa
            "delta_kpa\n0\n0.1\n",
            '{"delta_kpa": [[0, 1], [2, 3]]}',
            '{"delta_kpa": {"a": 1}}',
            "",
        ],
        "csv": [
            "pressure_kpa,height_mm\n0,0\n1,8\n2,11\n",
            "pressure_kpa,height_mm\n0,0\n1000,8\n2000,11\n",  # Pa given as kPa
            "pressure_kpa,height_mm\n0,0\n1,0.008\n2,0.011\n",  # m given as mm
            "pressure_kpa,height_mm\n0,0\n1,",
            "height_mm,pressure_kpa\nx,y\n",
            "pressure_kpa,height_mm\nnan,1\n1,2\n",
        ],
        "set": [
            valid_set,
            valid_set.replace("size_mm = [31, 31, 23]", "size_mm = [0.031, 0.031, 0.023]"),
            valid_set.replace("mass_g = 12.6", "mass_g = 0.0126"),  # kg given as g
            valid_set[: len(valid_set) // 2],
            valid_set.replace("12.6", "nan"),
            'schema = "softpad-object-set/1"\nname = "x"\n',
        ],
    }


# ----------------------------------------------------------------------------- CLI inputs

BANANA = "0,0.124,0.078,0.109,0,0"
SIX = "1.1,1.1,1.1,1.1,1.1,1.1"
#: (command words, option, a valid value, tag). The tag says how to misuse the value: a unit
#: (kPa, mm, s, g, m/s; N, Hz, h, ml, frac without a thousandfold mix-up), ``int``, a list
#: (``kPa*6``: six values, ``mm*``: any number), a pair (``mm,`` or ``mmx``), ``text:a|b``,
#: ``out:.png``, ``dir``, ``in:KIND`` or ``url``. An empty option is a positional argument.
CLI_SPECS: tuple[tuple[str, str, str, str], ...] = (
    (f"plan --delta {BANANA}", "--threshold-kpa", "0.05", "kPa"),
    (f"plan --delta {BANANA}", "--pitch-mm", "45", "mm"),
    (f"plan --delta {BANANA}", "--safety-shift", "0.2", "frac"),
    (f"plan --delta {BANANA}", "--layout", "2x3", "text:2x3|3x3|4x4"),
    (f"plan --delta {BANANA}", "--gripper", "10/4", "text:10/4|6/2|4/0"),
    (f"plan --delta {BANANA}", "--planner", "thesis", "text:thesis|gripper-aware"),
    (f"plan --delta {BANANA}", "--png", "plan.png", "out:.png"),
    (f"plan --delta {BANANA}", "--config", "toml0.toml", "in:toml"),
    ("plan", "--delta", BANANA, "kPa*6"),
    (f"plan --reference {SIX}", "--pressures", "1.2,1.1,1.15,1.1,1.1,1.1", "kPa*6"),
    ("plan --pressures 1.2,1.1,1.15,1.1,1.1,1.1", "--reference", SIX, "kPa*6"),
    ("plan", "--frame", "frame0.json", "in:frame"),
    ("run --objects object-5", "--hold-s", "15", "s"),
    ("run --objects object-5", "--p0-kpa", "1.1", "kPa"),
    ("run --objects object-5", "--object-threshold-kpa", "0.05", "kPa"),
    ("run --objects object-5", "--contact-threshold-kpa", "0.09", "kPa"),
    ("run --objects object-5", "--window", "10", "int"),
    ("run --objects object-5", "--approach-speed-mps", "0.05", "m/s"),
    ("run --objects object-5", "--landing-height-mm", "17", "mm"),
    ("run --objects object-5", "--max-attempts", "2", "int"),
    ("run --objects object-5", "--png", "run.png", "out:.png"),
    ("run --objects object-5", "--record", "run.mcap", "out:.mcap"),
    ("run --objects object-5", "--box", "sim://?seed=3", "url"),
    ("run --objects object-5", "--config", "toml0.toml", "in:toml"),
    ("run", "--objects", "object-5", "text:object-5|banana|object-1,object-4"),
    ("box read", "--count", "10", "int0"),
    ("box read", "--every", "1", "int+"),
    ("box read --count 2", "--box", "sim://", "url"),
    ("box monitor", "--count", "3", "int0"),
    ("box monitor --count 3", "--period-s", "0.5", "s"),
    ("box monitor --count 3", "--layout", "2x3", "text:2x3|3x3"),
    ("box monitor --foxglove", "--port", "8765", "int"),
    ("box stats", "--box", "zenoh://127.0.0.1:7447", "url"),
    ("box serve --sim", "--watchdog-s", "0.5", "s"),
    ("box serve --sim", "--duration-s", "10", "h+"),  # days of serving are plausible
    ("box serve --sim", "--rate-hz", "100", "Hz"),
    ("box serve --sim", "--rt-priority", "10", "int"),
    ("box serve --sim", "--listen", "tcp/127.0.0.1:7447", "text:tcp/127.0.0.1:7447"),
    ("box serve --sim", "--port", "7447", "int"),
    ("box serve --sim", "--config", "toml0.toml", "in:toml"),
    ("box inflate", "--p0-kpa", "1.1", "kPa"),
    ("box inflate", "--modules", "6", "int"),
    ("config check", "", "toml0.toml", "in:toml"),
    ("trials --objects object-5", "--trials", "5", "int"),
    ("trials --objects object-5", "--seeds", "0-3", "text:0|0-3|1,2"),
    ("trials --objects object-5", "--workers", "1", "int"),
    ("trials --objects object-5", "--hold-s", "15", "s"),
    ("trials --objects object-5", "--record", "t.mcap", "base:.mcap"),
    ("trials", "--objects-file", "set0.toml", "in:set"),
    ("trials --objects object-5", "--scheduler", "tcp://127.0.0.1:1", "text:tcp://127.0.0.1:1"),
    ("compare --objects object-5", "--trials", "5", "int"),
    ("compare --objects object-5", "--idle-hours", "1", "h"),
    ("compare --objects object-5", "--png", "c.png", "out:.png"),
    ("compare --objects object-5", "--pair", "thesis/thesis", "text:thesis/thesis"),
    ("validate", "--placements", "40", "int"),
    ("validate", "--seeds", "0", "text:0|0-1"),
    ("validate", "--trials", "5", "int"),
    ("calibrate", "", "rec.mcap", "in:mcap"),
    ("results", "--out", "r.md", "out:.md"),
    ("results", "--workers", "2", "int"),
    ("fem sweep", "--thickness-mm", "1.5", "mm"),
    ("fem sweep", "--width-mm", "45", "mm"),
    ("fem sweep", "--max-pressure-kpa", "3", "kPa"),
    ("fem sweep", "--points", "13", "int"),
    ("fem sweep", "--csv", "s.csv", "out:.csv"),
    ("fem sweep", "--png", "s.png", "out:.png"),
    ("fem sweep", "--model", "yeoh", "text:yeoh|neo-hookean"),
    ("fem design", "--values-mm", "1,1.5,2", "mm*"),
    ("fem design", "--pressure-kpa", "1", "kPa"),
    ("fem stiffness", "--pressures-kpa", "0.5,1", "kPa*"),
    ("fem stiffness", "--forces-n", "0.2,0.5", "N*"),
    ("fem stiffness", "--radius-mm", "10", "mm"),
    ("fem sensitivity", "--fraction", "0.5", "frac"),
    ("fem sensitivity", "--probe-g", "12.6", "g"),
    ("fem sensitivity", "--threshold-kpa", "0.05", "kPa"),
    ("fem chamber", "--pressure-kpa", "1.1", "kPa"),
    ("fem chamber", "--footprint-mm", "42x31", "mmx"),
    ("fem chamber", "--masses-g", "6,12.6", "g*"),
    ("fem chamber", "--dead-volume-ml", "3.3", "ml"),
    ("fem chamber", "--noise-kpa", "0.008", "kPa"),
    ("fem chamber", "--threshold-kpa", "0.05", "kPa"),
    ("fem fit", "--data", "csv0.csv", "in:csv"),
    ("fem fit --data csv0.csv", "--max-evals", "60", "int"),
    ("fem compare", "--data", "csv0.csv", "in:csv"),
    ("fem characteristic", "--out", "c.npz", "out:.npz"),
    ("fem characteristic", "--loads-n", "0,0.5", "N*"),
    ("fem characteristic", "--gap-volume-ml", "0.2", "ml"),
    ("fem response", "--out", "r.npz", "out:.npz"),
    ("fem response", "--pressures-kpa", "0.5,1.1,2", "kPa*"),
    ("design --quick", "--pitch-mm", "45", "mm*"),
    ("design --quick", "--thickness-mm", "1.5", "mm*"),
    ("design --quick", "--p0-kpa", "1.1", "kPa*"),
    ("design --quick", "--hold-s", "15", "s"),
    ("design --quick", "--trials", "1", "int"),
    ("design --quick", "--grid", "2x3", "text:2x3|3x3,2x3"),
    ("design --quick", "--objects", "set0.toml", "in:set"),
    ("design --quick", "--csv", "d.csv", "out:.csv"),
    ("design --quick", "--png", "d.png", "out:.png"),
    ("pad probe --force-n 0.2 --footprint-mm 10,10", "--at", "1,1", "xy"),
    ("pad probe --at 1,1 --footprint-mm 10,10", "--force-n", "0.2", "N"),
    ("pad probe --at 1,1 --force-n 0.2", "--footprint-mm", "10,10", "mm,"),
    ("pad map --force-n 1 --footprint-mm 10,10 --png m.png", "--step-mm", "2.5", "mm"),
    ("pad map --force-n 1 --footprint-mm 10,10", "--png", "m.png", "out:.png"),
    ("demo", "--out", "rep", "dir"),
    ("demo", "--trials", "5", "int"),
    ("replay", "", "rec.mcap", "in:mcap"),
    ("log info", "", "rec.mcap", "in:mcap"),
    ("log plot rec.mcap", "--png", "p.png", "out:.png"),
    ("log plot rec.mcap", "--pad-png", "pp.png", "out:.png"),
    ("log export rec.mcap", "--csv", "e.csv", "out:.csv"),
    ("log export rec.mcap", "--out", "e.mcap", "out:.mcap"),
    ("log recover", "", "rec.mcap", "in:mcap"),
    ("log recover rec.mcap", "--out", "rc.mcap", "out:.mcap"),
    ("bench", "--only", "planning", "text:planning|safety"),
    ("sim arm-node", "--port", "5757", "int"),
    ("sim arm-node", "--box", "sim://", "url"),
    ("completion", "", "bash", "text:bash|zsh"),
)

#: Thousandfold mix-ups by unit: the factor a value given in the neighbouring unit carries.
UNIT_MIXUPS = {
    "kPa": (1e3, "pascals given as kPa"),
    "mm": (1e-3, "metres given as mm"),
    "s": (1e3, "milliseconds given as seconds"),
    "g": (1e-3, "kilograms given as grams"),
    "m/s": (1e3, "mm/s given as m/s"),
}
MALFORMED = (
    "1..2",
    "0x1F",
    "1,5",
    "\u0663",  # Arabic-Indic three
    "1_000",
    "\u00bd",
    "",
    " ",
    "e3",
    "1e",
    "+-1",
    "1 2",
    "12abc",
    "--",
    "\uff11",  # fullwidth one
    "0.5kPa",
    "1;2",
)
NONFINITE = ("nan", "NaN", "inf", "-inf", "1e999", "-1e999", "+Infinity")
URLS = (
    ("sim://", False, False),
    ("sim://?seed=7", False, False),
    ("sim://?rate_hz=nan", True, False),
    ("sim://?rate_hz=-100", True, False),
    ("sim://?channels=0", True, False),
    ("sim://?inflated_kpa=1100", True, True),
    ("sim://?pitch_mm=0.045", True, True),
    ("sim://?supply_kpa=10000", True, True),
    ("sim://?seed=1.5", True, False),
    ("sim://?bogus=1", True, False),
    ("sim://?faults=stuck:inflate@", True, False),
    ("replay://rec.mcap", False, False),
    ("replay://cut0.mcap", False, False),  # a crash-cut recording: frames up to the cut
    ("replay://missing.mcap", True, False),
    ("zenoh://127.0.0.1:99999", True, False),
    ("zenoh://127.0.0.1:abc", True, False),
    ("zenoh://localhost", True, False),
    ("zenoh://127.0.0.1:1?timeout_s=nan", True, False),
    ("ftp://127.0.0.1/x", True, False),
    ("", True, False),
    ("sim:/", True, False),
)


def _fmt(v: float) -> str:
    return f"{v:.6g}"


def _junk(rng: np.random.Generator) -> str:
    """A few random characters that are not a plain number."""
    alphabet = "0123456789.,-+eE xX_;:/\\'\"\u0660\u00b5\u2212\u00b0kPamms"
    text = "".join(rng.choice(list(alphabet), size=int(rng.integers(1, 8))))
    if re.fullmatch(r"\s*[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\s*", text):
        text += "k"
    return text


def _scalar(
    tag: str, valid: str, rng: np.random.Generator, huge_ok: bool = False
) -> list[tuple[str, str, bool, bool]]:
    """(kind, value, invalid, mixup) for one number with unit ``tag`` (``huge_ok``: no upper
    limit, a thousandfold value is no mix-up either)."""
    v = float(valid)
    out = [
        ("malformed", str(rng.choice(MALFORMED)), True, False),
        ("malformed", _junk(rng), True, False),
        ("nonfinite", str(rng.choice(NONFINITE)), True, False),
        ("negative", _fmt(-v * rng.uniform(0.5, 2)), True, False),
        ("huge", _fmt(10 ** rng.uniform(7, 15)), not huge_ok, False),
        ("valid", _fmt(v * rng.uniform(0.8, 1.2)), False, False),
    ]
    if tag in UNIT_MIXUPS and not huge_ok:
        f = UNIT_MIXUPS[tag][0]
        out.append(("unit", _fmt(v * f * rng.uniform(0.8, 1.2)), True, True))
    if tag == "kPa":
        bad = str(rng.choice(["50", "-5", "300", "101.325", "12"]))
        out.append(("pressure", bad, True, False))
    return out


def _number_list(
    tag: str, valid: str, rng: np.random.Generator
) -> list[tuple[str, str, bool, bool]]:
    unit, fixed = tag.split("*")
    items = [float(s) for s in valid.split(",")]
    n = len(items)
    wrong_n = int(rng.choice([k for k in (0, 1, n - 1, n + 1, 2 * n) if k != n and k >= 0]))
    pick = [items[int(i)] for i in rng.integers(0, n, size=max(wrong_n, 1))][:wrong_n]
    bad_item = int(rng.integers(0, n))
    with_nan = [_fmt(x) for x in items]
    with_nan[bad_item] = str(rng.choice(NONFINITE))
    with_junk = [_fmt(x) for x in items]
    with_junk[bad_item] = str(rng.choice([m for m in MALFORMED[:6] if m != "1,5"]))
    out = [
        ("nonfinite", ",".join(with_nan), True, False),
        ("malformed", ",".join(with_junk), True, False),
        ("malformed", str(rng.choice([";", " "])).join(_fmt(x) for x in items), n > 1, False),
        ("malformed", ",".join(_fmt(x) for x in items) + ",", True, False),
        ("valid", ",".join(_fmt(x * rng.uniform(0.9, 1.1)) for x in items), False, False),
    ]
    if fixed:
        out.append(("count", ",".join(_fmt(x) for x in pick), True, False))
    if unit in UNIT_MIXUPS and any(items):
        f = UNIT_MIXUPS[unit][0]
        out.append(("unit", ",".join(_fmt(x * f) for x in items), True, True))
    if unit == "kPa":
        bad = [_fmt(x) for x in items]
        bad[bad_item] = str(rng.choice(["-5", "50", "101.325"]))
        out.append(("pressure", ",".join(bad), True, False))
    return out


def _pair(tag: str, valid: str, rng: np.random.Generator) -> list[tuple[str, str, bool, bool]]:
    sep = "x" if tag.endswith("x") else ","
    a, b = (float(s) for s in valid.split(sep))
    out = [
        ("count", _fmt(a), True, False),
        ("count", sep.join(_fmt(x) for x in (a, b, a)), True, False),
        ("nonfinite", f"{_fmt(a)}{sep}{rng.choice(NONFINITE)}", True, False),
        ("malformed", f"{rng.choice(MALFORMED[:6])}{sep}{_fmt(b)}", True, False),
        ("valid", sep.join(_fmt(x * rng.uniform(0.9, 1.1)) for x in (a, b)), False, False),
    ]
    if tag.startswith("mm"):
        out.append(("unit", sep.join(_fmt(x * 1e-3) for x in (a, b)), True, True))
        out.append(("negative", sep.join(_fmt(-x) for x in (a, b)), True, False))
    else:  # a position in module units: far off the pad
        out.append(("huge", f"{_fmt(10 ** rng.uniform(3, 9))},{_fmt(b)}", True, False))
    return out


def _integer(
    valid: str, rng: np.random.Generator, zero: bool, huge_ok: bool
) -> list[tuple[str, str, bool, bool]]:
    small = str(rng.choice(["0", "-1", "-100"]))
    return [
        ("count", small, small != "0" or not zero, False),
        (
            "malformed",
            str(rng.choice(["2.5", "1e3", "x", "", "\u0663", "0x10", "1_0"])),
            True,
            False,
        ),
        ("huge", str(10 ** int(rng.integers(20, 40))), not huge_ok, False),
        ("nonfinite", str(rng.choice(NONFINITE)), True, False),
        ("valid", valid, False, False),
    ]


def _text(tag: str, valid: str, rng: np.random.Generator) -> list[tuple[str, str, bool, bool]]:
    choices = tag.split(":", 1)[1].split("|")
    return [
        (
            "unknown",
            str(rng.choice(["teapot", "object-99", "5x0", "0x3", "thesis2", "*"])),
            True,
            False,
        ),
        (
            "malformed",
            str(rng.choice(["", " ", ",", "\u00e9\u00e9", "a\tb", "x" * 300])),
            True,
            False,
        ),
        ("malformed", _junk(rng), True, False),
        ("valid", str(rng.choice(choices)), False, False),
    ]


def _file_out(tag: str, rng: np.random.Generator) -> list[tuple[str, str, bool, bool]]:
    suffix = tag.split(":", 1)[1] if ":" in tag else ""
    other = str(rng.choice([s for s in (".png", ".csv", ".npz", ".md") if s != suffix]))
    existing = f"old{suffix}" if suffix else "report"
    # a base name (trials --record) names other files: FILE-OBJECT-tK.mcap
    return [
        ("existing", existing, not tag.startswith("base:"), False),
        ("existing", f"old{other}", True, False),
        ("force", existing, False, False),
        (
            "folder",
            str(rng.choice(["/nonexistent/x" + suffix, "/proc/x" + suffix, "out"])),
            True,
            False,
        ),
        ("malformed", str(rng.choice(["", " "])), True, False),
        ("valid", f"new{int(rng.integers(1e6))}{suffix}", False, False),
    ]


def _file_in(tag: str, files: dict[str, list[str]], rng: np.random.Generator):
    kind = tag.split(":", 1)[1]
    names = files[kind]
    valid = "rec.mcap" if kind == "mcap" else names[0]
    bad = [n for n in names if n != valid]
    picks = [str(x) for x in rng.choice(bad, size=min(3, len(bad)), replace=False)]
    mixups = {"toml1.toml", "toml2.toml", "toml7.toml", "toml8.toml", "frame1.json", "frame5.json"}
    mixups |= {"csv1.csv", "csv2.csv", "set1.toml", "set2.toml"}
    # a crash-cut recording may still hold frames: reading them is not an error
    out = [
        ("unit" if p in mixups else "corrupt", p, not p.startswith("cut"), p in mixups)
        for p in picks
    ]
    out += [
        ("missing", "missing." + valid.rsplit(".", 1)[1], True, False),
        ("folder", "report", True, False),
        ("valid", valid, False, False),
    ]
    return out


def _values(tag: str, valid: str, files: dict[str, list[str]], rng: np.random.Generator):
    """Every (kind, value, invalid, mixup) the campaign can give an option with ``tag``."""
    if tag.startswith("int"):  # int0: 0 (endless) and any count allowed; int+: any count
        return _integer(valid, rng, zero=tag == "int0", huge_ok=tag in ("int0", "int+"))
    if "*" in tag:
        return _number_list(tag, valid, rng)
    if tag in ("mm,", "mmx", "xy"):
        return _pair(tag, valid, rng)
    if tag.startswith("text:"):
        return _text(tag, valid, rng)
    if tag.startswith(("out:", "base:")) or tag == "dir":
        return _file_out(tag, rng)
    if tag.startswith("in:"):
        return _file_in(tag, files, rng)
    if tag == "url":
        url, invalid, mixup = URLS[int(rng.integers(len(URLS)))]
        return [("unit" if mixup else "url" if invalid else "valid", url, invalid, mixup)]
    return _scalar(tag.rstrip("+"), valid, rng, huge_ok=tag.endswith("+"))


def _generic(words: list[str], rng: np.random.Generator) -> tuple[str, list[str], tuple[str, ...]]:
    """An unknown option, an option without its value, or a stray argument."""
    kind = str(rng.choice(["unknown", "missing", "stray"]))
    if kind == "unknown":
        flag = str(rng.choice(["--bogus", "--pitch_mm", "-x", "--p0-pa", "--threshold", "--forse"]))
        return "unknown", [*words, flag, "1"], (flag,)
    if kind == "missing":
        return "missing", [*words, "--config"], ("--config",)
    return "stray", [*words, "extra-word"], ("extra-word",)


def cli_cases(n: int, seed: int, files: dict[str, list[str]]) -> list[Case]:
    """``n`` command lines drawn with a generator seeded ``seed`` (see :data:`CLI_SPECS`)."""
    rng = np.random.default_rng([seed, 1])
    cases = []
    for i in range(n):
        base, flag, valid, tag = CLI_SPECS[int(rng.integers(len(CLI_SPECS)))]
        words = base.split()
        if rng.random() < 0.06:
            kind, argv, names = _generic(words, rng)
            cases.append(Case("cli", kind, f"cli-{i}", argv=argv, names=names))
            continue
        options = _values(tag, valid, files, rng)
        kind, value, invalid, mixup = options[int(rng.integers(len(options)))]
        if flag == "":
            argv = [*words, value]
        elif value.startswith("-") or rng.random() < 0.5:
            argv = [*words, f"{flag}={value}"]
        else:
            argv = [*words, flag, value]
        if kind == "force":
            argv.append("--force")
        if rng.random() < 0.25:
            argv.append("--json")
        items = tuple(s.strip() for s in re.split(r"[,x;]", value) if s.strip())
        names = (flag or value, value, value.strip(), *items)
        cases.append(Case("cli", kind, f"cli-{i}", argv, None, names, invalid, mixup))
    return cases


# ----------------------------------------------------------------------------- API misuses

#: (module, record or function, fixed keyword arguments, field, a valid value, unit). Unit
#: ``m``, ``Pa``, ``s``, ``m/s`` and ``m3`` have a thousandfold mix-up (mm, kPa, ms, mm/s, ml).
API_FIELDS: tuple[tuple[str, str, dict[str, Any], str, Any, str], ...] = (
    ("layout", "GripperSpec", {}, "max_width_m", 0.06, "m"),
    ("layout", "GripperSpec", {}, "min_width_m", 0.02, "m"),
    ("layout", "GripperSpec", {}, "finger_length_m", 0.095, "m"),
    ("layout", "PadLayout", {}, "pitch_m", 0.045, "m"),
    ("layout", "PadLayout", {}, "rows", 2, "int"),
    ("layout", "PadPose", {}, "x_m", 0.4, "m"),
    ("layout", "PadPose", {}, "z_m", 0.02, "m"),
    ("layout", "parse_layout", {"text": "2x3"}, "pitch_m", 0.045, "m"),
    ("planning", "PlannerParams", {}, "object_threshold_pa", 50.0, "Pa"),
    ("planning", "PlannerParams", {}, "safety_shift", 0.2, "frac"),
    ("sensing", "ThesisContactDetector", {}, "threshold_pa", 90.0, "Pa"),
    ("sensing", "ThesisContactDetector", {}, "window", 10, "int"),
    ("sensing", "ThesisObjectDetector", {}, "threshold_pa", 50.0, "Pa"),
    ("sensing", "RunningAverage", {}, "length", 10, "int"),
    ("box", "SafetyLimits", {}, "max_pressure_pa", 3000.0, "Pa"),
    ("box", "SafetyLimits", {}, "release_pa", 2500.0, "Pa"),
    ("box", "SimBox", {}, "sample_rate_hz", 100.0, "Hz"),
    ("box", "SimBox", {}, "channels", 8, "int"),
    ("control", "ExecutionParams", {}, "approach_speed_m_s", 0.05, "m/s"),
    ("control", "ExecutionParams", {}, "contact_threshold_pa", 90.0, "Pa"),
    ("control", "ExecutionParams", {}, "hold_s", 15.0, "s"),
    ("control", "ExecutionParams", {}, "approach_height_m", 0.12, "m"),
    ("control", "ExecutionParams", {}, "landing_height_m", 0.017, "m"),
    ("control", "ExecutionParams", {}, "filter_length", 10, "int"),
    ("control", "InflationParams", {}, "target_pa", 1100.0, "Pa"),
    ("control", "InflationParams", {}, "max_pressure_pa", 3000.0, "Pa"),
    ("control", "InflationParams", {}, "timeout_s", 30.0, "s"),
    ("control", "FaultThresholds", {}, "max_pressure_pa", 3000.0, "Pa"),
    ("control", "FaultThresholds", {}, "supply_min_pa", 5000.0, "Pa"),
    (
        "sim",
        "ObjectPose",
        {"y_m": 0.0, "z_m": 0.01, "yaw_rad": 0.0, "tilt_rad": 0.0},
        "x_m",
        0.05,  # an object on a 2x3 pad: its centre is 67.5 mm from the corner
        "m",
    ),
    ("sim", "Placement", {"y_m": 0.0}, "x_m", 0.05, "m"),
    ("sim", "SensorParams", {}, "drift_time_s", 2.0, "s"),
    ("sim", "PneumaticParams", {}, "supply_pa", 10000.0, "Pa"),
    ("sim", "PneumaticParams", {}, "tubing_volume_m3", 3.14e-6, "m3"),
    ("sim", "SimGripper", {}, "max_width_m", 0.1, "m"),
    ("sim", "PadPhysics", {}, "free_height_m", 0.0083, "m"),
    ("config", "Thresholds", {}, "p0_pa", 1100.0, "Pa"),
    ("config", "Thresholds", {}, "object_threshold_pa", 50.0, "Pa"),
    ("config", "Thresholds", {}, "contact_threshold_pa", 90.0, "Pa"),
    ("config", "Thresholds", {}, "filter_window", 10, "int"),
    ("config", "PadSettings", {}, "pitch_m", 0.045, "m"),
    ("config", "PadSettings", {}, "z_m", 0.02, "m"),
    ("config", "LinkSettings", {}, "watchdog_s", 0.5, "s"),
    ("config", "BoxSettings", {}, "sample_rate_hz", 1000.0, "Hz"),
    ("design", "PadDesign", {}, "pitch_m", 0.045, "m"),
    ("design", "PadDesign", {}, "thickness_m", 0.0015, "m"),
    ("design", "PadDesign", {}, "p0_pa", 1100.0, "Pa"),
    ("design", "TrialOptions", {}, "hold_s", 15.0, "s"),
    ("design", "TrialOptions", {}, "position_sigma_m", 0.003, "m"),
    ("design", "TrialOptions", {}, "trials", 1, "int"),
    ("trials", "TrialConfig", {}, "position_sigma_m", 0.003, "m"),
    ("trials", "TrialConfig", {}, "sample_rate_hz", 100.0, "Hz"),
    ("fem", "ModuleGeometry", {}, "width_m", 0.045, "m"),
    ("fem", "ModuleGeometry", {}, "thickness_m", 0.0015, "m"),
    ("fem", "LoadPatch", {}, "size_x_m", 0.03, "m"),
)
API_MIXUPS = {"m": 1e3, "Pa": 1e-3, "s": 1e3, "m/s": 1e3, "m3": 1e6}


def _api_field_values(value: Any, unit: str, rng: np.random.Generator):
    """(kind, value, invalid, mixup) misuses of one field."""
    if unit == "int":
        return [
            ("count", int(rng.choice([0, -1, -7])), True, False),
            ("type", float(value) + 0.5, True, False),
            ("type", str(value), True, False),
            ("type", None, True, False),
            ("valid", value, False, False),
        ]
    out = [
        ("nonfinite", float(rng.choice([math.nan, math.inf, -math.inf])), True, False),
        ("type", str(rng.choice([str(value), "fast", ""])), True, False),
        ("type", None, True, False),
        ("type", [value, value], True, False),
        ("negative", -abs(value) * rng.uniform(0.5, 2) - 1e-9, unit != "m", False),
        ("valid", value * rng.uniform(0.9, 1.1), False, False),
    ]
    if unit in API_MIXUPS:
        out.append(("unit", value * API_MIXUPS[unit] * rng.uniform(0.9, 1.1), True, True))
    return out


def _field_cases(rng: np.random.Generator) -> list[Case]:
    import importlib

    cases = []
    for module, name, fixed, fname, value, unit in API_FIELDS:
        target = getattr(importlib.import_module(f"softpad.{module}"), name)
        for kind, bad, invalid, mixup in _api_field_values(value, unit, rng):
            kwargs = {**fixed, fname: bad}

            def call(target: Any = target, kwargs: dict[str, Any] = kwargs) -> Any:
                return target(**kwargs)

            label = f"{name}({fname}={bad!r})"
            quantity = fname.rsplit("_", 1)[0].replace("_", " ") if unit != "int" else fname
            names = (fname, quantity, repr(bad), str(bad))
            cases.append(Case("api", kind, label, [], call, names, invalid, mixup))
    return cases


def _call(
    label: str,
    kind: str,
    fn: Callable[[], Any],
    names: tuple[str, ...],
    invalid: bool = True,
    mixup: bool = False,
) -> Case:
    return Case("api", kind, label, [], fn, names, invalid, mixup)


def _array_cases(rng: np.random.Generator) -> list[Case]:
    """Misused arrays of the planning and sensing functions."""
    banana = np.array([0.0, 124.0, 78.0, 109.0, 0.0, 0.0]) * rng.uniform(0.9, 1.1)
    k = int(rng.integers(6))
    nan_at = banana.copy()
    nan_at[k] = math.nan
    p = 1100.0 + rng.uniform(0, 150, 6)
    r = np.full(6, 1100.0)
    return _planning_cases(banana, nan_at, k) + _sensing_cases(banana, nan_at, k, p, r)


def _planning_cases(banana: np.ndarray, nan_at: np.ndarray, k: int) -> list[Case]:
    from softpad.planning import plan_grasps

    return [
        _call(
            "plan_grasps(kPa)",
            "unit",
            lambda: plan_grasps(banana / 1e3, "2x3"),
            ("kPa", "pascals"),
            mixup=True,
        ),
        _call(
            "plan_grasps(NaN)",
            "nonfinite",
            lambda: plan_grasps(nan_at, "2x3"),
            (f"module {k + 1}", "nan", "finite"),
        ),
        _call("plan_grasps(5)", "length", lambda: plan_grasps(banana[:5], "2x3"), ("5", "6")),
        _call("plan_grasps(7)", "length", lambda: plan_grasps([*banana, 1.0], "2x3"), ("7", "6")),
        _call(
            "plan_grasps(2d)",
            "length",
            lambda: plan_grasps(banana.reshape(2, 3), "2x3"),
            ("shape", "2", "6"),
        ),
        _call(
            "plan_grasps(text)",
            "type",
            lambda: plan_grasps("0,124,78,109,0,0", "2x3"),
            ("number", "0,124"),
        ),
        _call(
            "plan_grasps(None)",
            "type",
            lambda: plan_grasps(None, "2x3"),
            ("None", "number", "increments"),
        ),
        _call("plan_grasps(layout 23)", "type", lambda: plan_grasps(banana, 23), ("layout", "23")),
        _call("plan_grasps(layout 2x)", "malformed", lambda: plan_grasps(banana, "2x"), ("2x",)),
        _call(
            "plan_grasps(-5 kPa)",
            "pressure",
            lambda: plan_grasps(np.where(np.arange(6) == k, -5000.0, banana), "2x3"),
            (f"module {k + 1}", "-5000", "range"),
        ),
    ]


def _sensing_cases(
    banana: np.ndarray, nan_at: np.ndarray, k: int, p: np.ndarray, r: np.ndarray
) -> list[Case]:
    from softpad.layout import parse_layout
    from softpad.planning import format_plans
    from softpad.sensing import detect_objects, increments

    return [
        _call(
            "increments(kPa)", "unit", lambda: increments(p / 1e3, r / 1e3), ("kPa",), mixup=True
        ),
        _call("increments(lengths)", "length", lambda: increments(p[:5], r), ("5", "6", "length")),
        _call(
            "increments(NaN)",
            "nonfinite",
            lambda: increments(np.where(np.arange(6) == k, math.nan, p), r),
            ("nan", "finite", f"{k + 1}"),
        ),
        _call("increments(text)", "type", lambda: increments("1100", r), ("1100", "number")),
        _call(
            "detect_objects(kPa threshold)",
            "unit",
            lambda: detect_objects(banana, "2x3", threshold_pa=0.05),
            ("threshold", "0.05"),
            mixup=True,
        ),
        _call(
            "detect_objects(NaN threshold)",
            "nonfinite",
            lambda: detect_objects(banana, "2x3", threshold_pa=math.nan),
            ("threshold", "nan"),
        ),
        _call(
            "detect_objects(NaN)",
            "nonfinite",
            lambda: detect_objects(nan_at, "2x3"),
            ("nan", "finite"),
        ),
        _call(
            "format_plans(4)",
            "length",
            lambda: format_plans(banana[:4], [], parse_layout("2x3"), 50.0),
            ("4", "6"),
        ),
    ]


def _box_cases(rng: np.random.Generator) -> list[Case]:
    from softpad.box import PressureFrame, open_box, parse_url

    cases = [
        _call(
            f"open_box({url!r})",
            "unit" if mixup else "url" if invalid else "valid",
            lambda url=url: open_box(url),
            (url, url.split("?")[-1].split("=")[0] or url),
            invalid,
            mixup,
        )
        for url, invalid, mixup in URLS
        if not url.startswith("zenoh")  # a client would connect; the CLI part parses them
    ]
    six = np.full(6, 1100.0)
    cases += [
        _call("open_box(123)", "type", lambda: open_box(123), ("123", "URL")),
        _call("parse_url(None)", "type", lambda: parse_url(None), ("None", "URL")),
        _call(
            "PressureFrame(NaN t)", "nonfinite", lambda: PressureFrame(math.nan, six, 0.0), ("t_s",)
        ),
        _call(
            "PressureFrame(2d)",
            "length",
            lambda: PressureFrame(0.0, six.reshape(2, 3), 0.0),
            ("pressures_pa", "shape"),
        ),
        _call(
            "PressureFrame(NaN supply)",
            "nonfinite",
            lambda: PressureFrame(0.0, six, math.nan),
            ("supply_pa",),
        ),
        _call(
            "PressureFrame(text)",
            "type",
            lambda: PressureFrame(0.0, "1100", 0.0),
            ("pressures_pa", "1100"),
        ),
    ]
    return cases


def _config_cases(rng: np.random.Generator) -> list[Case]:
    from softpad.config import check_endpoint, parse_installation

    raw = [
        ({"thresholds": {"p0_kpa": 1100}}, True, ("p0_kpa",)),
        ({"pad": {"pitch_mm": 0.045}}, True, ("pitch_mm",)),
        ({"link": {"watchdog_s": 500}}, True, ("watchdog_s",)),
        ({"thresholds": {"t_g_kpa": 90}}, True, ("t_g_kpa",)),
        ({"thresholds": {"max_pressure_kpa": 3000}}, True, ("max_pressure_kpa",)),
        ({"box": {"sample_rate_hz": "fast"}}, False, ("sample_rate_hz", "fast")),
        ({"thresholds": {"p0_kpa": math.nan}}, False, ("p0_kpa",)),
        ({"thresholds": {"p0_pa": 1100}}, False, ("p0_pa",)),
        ({"thresholds": []}, False, ("thresholds",)),
        ({"unknown": {}}, False, ("unknown",)),
        ({"pad": {"rows": 2.5}}, False, ("rows", "2.5")),
        ([], False, ("table", "list")),
        (None, False, ("table", "None")),
    ]
    cases = [
        _call(
            f"parse_installation({d!r})",
            "unit" if mix else "config",
            lambda d=d: parse_installation(d),
            names,
            True,
            mix,
        )
        for d, mix, names in raw
    ]
    for ep in (
        "tcp/0.0.0.0:7447",
        "tcp/127.0.0.1:99999",
        "tcp/127.0.0.1",
        "udp/127.0.0.1:7447",
        "tcp/[::1:7447",
        "",
        "tcp/127.0.0.1:-1",
    ):
        # 0.0.0.0 is well formed: the remote policy (check_remote_policy) refuses it
        ok = ep == "tcp/0.0.0.0:7447"
        cases.append(
            _call(
                f"check_endpoint({ep!r})",
                "valid" if ok else "endpoint",
                lambda ep=ep: check_endpoint(ep, "listen"),
                ("listen", ep or "empty"),
                not ok,
            )
        )
    return cases


def _misc_cases(rng: np.random.Generator) -> list[Case]:
    from softpad.harness import resolve_objects
    from softpad.sim import get_object, parse_mounting
    from softpad.trials import trial_seed, wilson_interval

    return [
        *_design_cases(),
        _call("wilson_interval(6, 5)", "count", lambda: wilson_interval(6, 5), ("6", "5")),
        _call("wilson_interval(-1, 5)", "count", lambda: wilson_interval(-1, 5), ("-1",)),
        _call("wilson_interval(1.5, 5)", "type", lambda: wilson_interval(1.5, 5), ("1.5",)),
        _call(
            "trial_seed(2**40)",
            "count",
            lambda: trial_seed(2**40, "banana", 0),
            ("seed", str(2**40)),
        ),
        _call(
            "trial_seed(trial -1)", "count", lambda: trial_seed(0, "banana", -1), ("trial", "-1")
        ),
        _call("resolve_objects(['nope'])", "unknown", lambda: resolve_objects(["nope"]), ("nope",)),
        _call("resolve_objects([5])", "type", lambda: resolve_objects([5]), ("5",)),
        _call("get_object('')", "unknown", lambda: get_object(""), ("''", "object")),
        _call("parse_mounting('10-4')", "malformed", lambda: parse_mounting("10-4"), ("10-4",)),
        _call(
            "parse_mounting('100/40')",
            "unit",
            lambda: parse_mounting("100/40"),
            ("100/40",),
            True,
            True,
        ),
    ]


def _design_cases() -> list[Case]:
    from softpad.design import object_set_from_dict, parse_grids, parse_values

    obj = {"name": "brick", "mass_g": 12.6, "shape": "box", "size_mm": [31, 31, 23]}

    def oset(**change: Any) -> Any:
        return object_set_from_dict(
            {"schema": "softpad-object-set/1", "name": "x", "object": [{**obj, **change}]}
        )

    return [
        _call("parse_grids('2x')", "malformed", lambda: parse_grids("2x"), ("2x",)),
        _call("parse_grids('0x3')", "count", lambda: parse_grids("0x3"), ("0x3",)),
        _call(
            "parse_values('45,x')",
            "malformed",
            lambda: parse_values("45,x", "--pitch-mm", 1e-3, (0.02, 0.1)),
            ("x", "--pitch-mm"),
        ),
        _call(
            "parse_values('0.045')",
            "unit",
            lambda: parse_values("0.045", "--pitch-mm", 1e-3, (0.02, 0.1)),
            ("0.045", "--pitch-mm"),
            True,
            True,
        ),
        _call(
            "object set: size in m",
            "unit",
            lambda: oset(size_mm=[0.031, 0.031, 0.023]),
            ("size_mm", "0.031"),
            True,
            True,
        ),
        _call(
            "object set: mass in kg",
            "unit",
            lambda: oset(mass_g=0.0126),
            ("mass_g", "0.0126"),
            True,
            True,
        ),
        _call(
            "object set: NaN mass", "nonfinite", lambda: oset(mass_g=math.nan), ("mass_g", "nan")
        ),
        _call("object set: shape", "unknown", lambda: oset(shape="teapot"), ("teapot", "shape")),
        _call("object set: size 2", "length", lambda: oset(size_mm=[31, 31]), ("size_mm",)),
    ]


def _file_cases(folder: Path, files: dict[str, list[str]], rng: np.random.Generator) -> list[Case]:
    """The recording functions on corrupt files and existing outputs (no force)."""
    from softpad.record import McapRecorder, check_output, load_recording, recover, to_rosbag1

    # a crash-cut recording reads up to its cut (valid); the others are no recordings
    cases = [
        _call(
            f"load_recording({n!r})",
            "corrupt",
            lambda n=n: load_recording(folder / n),
            (n,),
            invalid=not n.startswith("cut"),
        )
        for n in files["mcap"]
    ]
    cases += [
        _call(
            "load_recording(folder)",
            "folder",
            lambda: load_recording(folder / "report"),
            ("report",),
        ),
        _call(
            "McapRecorder(existing)",
            "existing",
            lambda: McapRecorder(folder / "old.mcap", {}),
            ("old.mcap", "force"),
        ),
        _call(
            "McapRecorder(.png)",
            "existing",
            lambda: McapRecorder(folder / "old.png", {}),
            ("old.png", ".mcap"),
        ),
        _call(
            "recover(out=existing)",
            "existing",
            lambda: recover(folder / "cut3.mcap", folder / "old.mcap"),
            ("old.mcap", "force"),
        ),
        _call(
            "to_rosbag1(existing)",
            "existing",
            lambda: to_rosbag1(folder / "rec.mcap", folder / "old.mcap"),
            ("old.mcap", "force", ".bag"),
        ),
        _call(
            "check_output(existing)",
            "existing",
            lambda: check_output(folder / "old.mcap"),
            ("old.mcap", "force"),
        ),
    ]
    return cases


def api_cases(n: int, seed: int, folder: Path, files: dict[str, list[str]]) -> list[Case]:
    """``n`` API misuses drawn (without repeats) with a generator seeded ``seed``."""
    rng = np.random.default_rng([seed, 2])
    pool = _field_cases(rng) + _array_cases(rng) + _box_cases(rng) + _config_cases(rng)
    pool += _misc_cases(rng) + _file_cases(folder, files, rng)
    if n > len(pool):
        raise ValueError(f"at most {len(pool)} API misuses, asked for {n}")
    picks = sorted(rng.choice(len(pool), size=n, replace=False))
    return [pool[int(i)] for i in picks]


# ----------------------------------------------------------------------------- campaign


def campaign(
    n_cli: int = 600, n_api: int = 180, seed: int = SEED, progress: bool = False
) -> list[Result]:
    """Run the campaign in a fresh temporary folder; return every input's result."""
    import matplotlib

    matplotlib.use("Agg")
    results: list[Result] = []
    old_cwd, old_cache = os.getcwd(), os.environ.get("XDG_CACHE_HOME")
    with tempfile.TemporaryDirectory(prefix="softpad-fuzz-") as tmp:
        folder = Path(tmp)
        files = make_files(folder, np.random.default_rng([seed, 0]))
        os.chdir(folder)
        os.environ["XDG_CACHE_HOME"] = str(folder / ".cache")  # design's result cache
        try:
            with stubbed():
                for case in cli_cases(n_cli, seed, files):
                    results.append(run_cli(case, folder))
                    if progress:
                        _tick(results[-1])
            for case in api_cases(n_api, seed, folder, files):
                results.append(run_api(case, folder))
                if progress:
                    _tick(results[-1])
        finally:
            os.chdir(old_cwd)
            if old_cache is None:
                os.environ.pop("XDG_CACHE_HOME", None)
            else:
                os.environ["XDG_CACHE_HOME"] = old_cache
    return results


def _tick(r: Result) -> None:
    if r.outcome in BAD or r.outcome in ("vague", "accepted_invalid"):
        print(
            f"{r.outcome:>16s} {r.case.surface} {r.case.kind}: {r.case.label} {r.case.argv} -> {r.message[:200]}",
            file=sys.stderr,
            flush=True,
        )


def summary(results: list[Result]) -> dict[str, Any]:
    out: dict[str, Any] = {"seed": SEED}
    for surface in ("cli", "api"):
        rs = [r for r in results if r.case.surface == surface]
        counts = Counter(r.outcome for r in rs)
        out[surface] = {"inputs": len(rs), **{o: counts.get(o, 0) for o in OUTCOMES}}
        out[surface]["seconds"] = round(sum(r.seconds for r in rs), 1)
        out[surface]["slowest_s"] = round(max((r.seconds for r in rs), default=0.0), 2)
        out[surface]["kinds"] = dict(sorted(Counter(r.case.kind for r in rs).items()))
    out["bad"] = sum(out[s][o] for s in ("cli", "api") for o in BAD)
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cli", type=int, default=600)
    p.add_argument("--api", type=int, default=180)
    p.add_argument("--seed", type=int, default=SEED)
    p.add_argument("--json", action="store_true")
    p.add_argument(
        "--show", action="append", default=[], help="print every input with this outcome"
    )
    args = p.parse_args(argv)
    t0 = time.perf_counter()
    results = campaign(args.cli, args.api, args.seed, progress=not args.json)
    s = summary(results)
    s["seed"], s["wall_s"] = args.seed, round(time.perf_counter() - t0, 1)
    for r in results:
        if r.outcome in args.show:
            print(
                f"{r.outcome}: {r.case.label} {r.case.argv} -> {r.message[:300]}", file=sys.stderr
            )
    if args.json:
        print(json.dumps(s))
    else:
        for surface in ("cli", "api"):
            row = s[surface]
            print(
                f"{surface}: {row['inputs']} inputs in {row['seconds']} s: "
                + ", ".join(f"{o} {row[o]}" for o in OUTCOMES)
            )
        print(f"bad (traceback, clobbered, mixup, timeout): {s['bad']}; wall {s['wall_s']} s")
    return 1 if s["bad"] else 0


if __name__ == "__main__":
    sys.exit(main())
