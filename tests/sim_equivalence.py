"""Is the simulated box the same, bit for bit? Record what it gives on one tree, compare with
another (issue 36 item 4: the plain box in layers; any refactoring of the simulator).

Records, for fixed seeds and seeded valve-command sequences, N frames (3000 by default) of 42
``sim://`` URLs (plain, 100 Hz to 1 kHz, objects, disturbances, every fault kind alone and
combined), faults injected at run time, plain ``SimBox`` constructors, real-time pacing on a
fake clock, ``check_conformance``, refused URLs and ``run_simulated`` with faults: frames'
times, pressures (their bytes) and supply, true pressures, heights, valve states, trips,
exceptions and their messages. ``compare`` wants every record equal (exit 1 names the first
difference of each scenario)::

    PYTHONPATH=OLD_TREE/src python tests/sim_equivalence.py record before.pkl
    PYTHONPATH=src python tests/sim_equivalence.py record after.pkl
    python tests/sim_equivalence.py compare before.pkl after.pkl

About 10-20 s a record on a 2-core machine. Not a test (it compares two trees).
"""

from __future__ import annotations

import pickle
import random
import re
import sys
import time

import numpy as np

URLS = [
    "sim://?seed=1",
    "sim://?seed=2&rate_hz=1000",
    "sim://?seed=3&noise=0&inflated_kpa=1.1",
    "sim://?seed=4&inflated_kpa=1.1&object=object-5",
    "sim://?seed=4&rate_hz=1000&inflated_kpa=1.1&object=banana",
    "sim://?seed=5&disturbances=1",
    "sim://?seed=5&disturbances=1&rate_hz=1000&inflated_kpa=1.1",
    "sim://?seed=6&disturbances=1&noise=0&inflated_kpa=1.1&object=object-5",
    "sim://?seed=7&layout=3x4&channels=12&rate_hz=200",
    "sim://?seed=8&characteristic=analytic&supply_kpa=8",
]
FAULTS = [
    "nan:3@2",
    "dropout:2@1.5",
    "dropout:7",
    "stuck:3:inflate@1",
    "stuck:1:deflate",
    "stuck:4:closed@0.5",
    "leak:2:0.02@1",
    "leak:5",
    "supply_loss@5",
    "disconnect@8",
    "nan:3@2,disconnect@6,stuck:2:inflate@1",
    "nan:1,dropout:1@3,leak:1:1@2",
    "disconnect",
    "nan:4@6.5,stuck:4:inflate@6.5",
    "supply_loss@0.3,dropout:8@0.3",
]
for f in FAULTS:
    URLS.append(f"sim://?seed=11&faults={f}")
    quick = re.sub(r"@([0-9.]+)", lambda m: f"@{float(m.group(1)) / 4:g}", f)
    URLS.append(f"sim://?seed=12&rate_hz=1000&inflated_kpa=1.1&faults={quick}")
URLS.append("sim://?seed=13&disturbances=1&faults=nan:3@2,dropout:5@4,disconnect@20")
URLS.append("sim://?seed=14&disturbances=1&rate_hz=1000&faults=stuck:2:inflate@1,leak:4@2")

CMDS = ["closed", "inflate", "deflate", "closed", "inflate"]


def exc(e: BaseException) -> tuple[str, str]:
    return (type(e).__name__, str(e))


def arr(a) -> tuple:
    a = np.asarray(a, dtype=np.float64)
    return (a.shape, a.tobytes())


def drive(box, n: int, seed: int, injections=()) -> list:
    from softpad.box import Fault

    rec: list = []
    rng = random.Random(seed)
    inject = dict(injections)
    for k in range(n):
        if k in inject:
            try:
                box.inject_fault(Fault.parse(inject[k]))
                rec.append(("inject", k, inject[k]))
            except Exception as e:
                rec.append(("inject-exc", k, exc(e)))
        if k % 37 == 0:
            ch = rng.randint(1, box.channels)
            cmd = rng.choice(CMDS)
            try:
                box.set_valve(ch, cmd)
                rec.append(("set", k, ch, cmd))
            except Exception as e:
                rec.append(("set-exc", k, ch, cmd, exc(e)))
        if k % 401 == 0:
            try:
                box.close_inflation() if k % 802 else box.close_valves()
                rec.append(("closeall", k))
            except Exception as e:
                rec.append(("closeall-exc", k, exc(e)))
        try:
            f = box.read()
            rec.append(("frame", k, f.t_s, arr(f.pressures_pa), float(f.supply_pa)))
        except Exception as e:
            rec.append(("read-exc", k, exc(e)))
        if k % 100 == 0:
            rec.append(
                (
                    "truth",
                    k,
                    arr(box.true_pressures_pa),
                    arr(box.module_heights_m),
                    box.time_s,
                    tuple(v.value for v in box.valves),
                )
            )
            rec.append(("trips", k, tuple(bool(x) for x in box.safety.tripped)))
    rec.append(("valves-before-close", tuple(v.value for v in box.valves)))
    try:
        box.close()
        rec.append(("closed", box.closed))
    except Exception as e:
        rec.append(("close-exc", exc(e)))
    rec.append(("valves-after-close", tuple(v.value for v in box.valves)))
    rec.append(("truth-end", arr(box.true_pressures_pa)))
    try:
        box.read()
        rec.append(("read-after-close", "no error"))
    except Exception as e:
        rec.append(("read-after-close", exc(e)))
    return rec


def record(n: int) -> dict:
    """Every scenario's record (module docstring)."""
    from softpad.box import open_box

    out: dict = {}
    for i, url in enumerate(URLS):
        out[url] = drive(open_box(url), n, i)
    # faults injected through the API while running
    out["inject"] = drive(
        open_box("sim://?seed=21&inflated_kpa=1.1"),
        n,
        99,
        {
            500: "nan:4",
            900: "stuck:2:inflate",
            1200: "dropout:6@14",
            1500: "leak:3:0.5",
            1700: "bogus",
            1800: "nan:9",
            1900: "stuck:7:inflate",
            2000: "disconnect@21",
            2100: "supply_loss",
        },
    )
    out["inject-1k"] = drive(
        open_box("sim://?seed=22&rate_hz=1000&disturbances=1"),
        n,
        98,
        {10: "disconnect@2.5", 20: "nan:2@1"},
    )
    out.update(_plain_boxes(n))
    out.update(_paced())
    out.update(_checks())
    out.update(_loops())
    return out


def _plain_boxes(n: int) -> dict:
    """Plain constructors (the trials' boxes), the slow disturbances on one."""
    import softpad.box as sb
    from softpad.box import SimBox
    from softpad.sim import AnalyticWorld, DisturbanceParams, SensorParams

    out: dict = {}
    out["plain"] = drive(SimBox(AnalyticWorld(), seed=31, initial_pressure_pa=1000.0), n, 7)
    out["plain-ideal"] = drive(
        SimBox(seed=32, sensor=SensorParams.ideal(), sample_rate_hz=500.0), n, 8
    )
    # the slow disturbances on a plain constructor (after issue 36: composed with its layers)
    dist = SimBox(
        seed=34, initial_pressure_pa=1100.0, disturbances=DisturbanceParams(update_s=0.05)
    )
    compose = getattr(sb, "compose_sim_box", None)
    out["plain-dist"] = drive(dist if compose is None else compose(dist), n, 10, {700: "nan:2"})
    box = SimBox(seed=33, initial_pressure_pa=1100.0)
    out["plain-leak"] = drive(box, n, 9, {0: "leak:1:0.01", 300: "stuck:2:deflate@4"})
    return out


def _paced() -> dict:
    """Real-time pacing on a fake clock: frames and the sleeps asked for."""
    from softpad.box import open_box

    out: dict = {}
    clock = [100.0]
    sleeps: list[float] = []
    real = (time.perf_counter, time.sleep)
    time.perf_counter = lambda: clock[0]  # type: ignore[assignment]
    time.sleep = lambda s: sleeps.append(s)  # type: ignore[assignment]
    try:
        for url in (
            "sim://?realtime=1&rate_hz=50",
            "sim://?realtime=1&faults=disconnect@0.5&seed=3",
            "sim://?realtime=1&rate_hz=1000&disturbances=1&faults=nan:1@0.1",
        ):
            sleeps.clear()
            b = open_box(url)
            recs = []
            for k in range(200):
                clock[0] += 0.003 if k % 3 else 0.0
                try:
                    f = b.read()
                    recs.append((f.t_s, arr(f.pressures_pa)))
                except Exception as e:
                    recs.append(exc(e))
            b.close()
            out["rt " + url] = (recs, list(sleeps))
    finally:
        time.perf_counter, time.sleep = real
    return out


def _checks() -> dict:
    """The conformance check on three URLs, and refused URLs' messages."""
    from softpad.box import check_conformance, open_box

    out: dict = {}
    for url in ("sim://?seed=1", "sim://?faults=stuck:3:inflate&seed=2", "sim://?disturbances=1"):
        try:
            check_conformance(open_box(url))
            out["conf " + url] = "ok"
        except Exception as e:
            out["conf " + url] = exc(e)
    for url in (
        "sim://?faults=melt:3",
        "sim://?faults=leak:3:-1",
        "sim://?faults=nan:9",
        "sim://?faults=stuck:7:inflate",
        "sim://?faults=nan",
        "sim://?realtime=2",
        "sim://?faults=supply_loss:3",
        "sim://?disturbances=x",
    ):
        try:
            open_box(url)
            out["bad " + url] = "opened"
        except Exception as e:
            out["bad " + url] = exc(e)
    return out


def _loops() -> dict:
    """The closed loop through the harness, with faults."""
    out: dict = {}
    from softpad.harness import run_simulated

    for url in (
        "sim://?seed=2&faults=stuck:1:inflate@6.0",
        "sim://?seed=1&faults=nan:4@6.5",
        "sim://?seed=3&disturbances=1",
        "sim://?seed=4&faults=disconnect@7",
        "sim://?seed=5&rate_hz=1000&faults=dropout:2@7,leak:5:0.05@3",
    ):
        try:
            r = run_simulated(["object-5"], url)
            out["run " + url] = repr(r.to_dict())
        except Exception as e:
            d = {k: repr(getattr(e, k, None)) for k in ("faults", "safe_state")}
            out["run " + url] = (exc(e), d)
    return out


def compare(a: dict, b: dict) -> int:
    bad = 0
    for key in sorted(set(a) | set(b), key=str):
        if key not in a or key not in b:
            print("MISSING", key)
            bad += 1
            continue
        if a[key] != b[key]:
            bad += 1
            ra, rb = a[key], b[key]
            if isinstance(ra, list) and isinstance(rb, list):
                for i, (x, y) in enumerate(zip(ra, rb, strict=False)):
                    if x != y:
                        print("DIFF", key, "at", i, "\n  ", str(x)[:300], "\n  ", str(y)[:300])
                        break
                else:
                    print("DIFF", key, "length", len(ra), len(rb))
            else:
                print("DIFF", key, "\n  ", str(ra)[:400], "\n  ", str(rb)[:400])
    n_frames = sum(
        1
        for v in a.values()
        if isinstance(v, list)
        for r in v
        if isinstance(r, tuple) and r and r[0] == "frame"
    )
    print(f"{len(a)} scenarios, {n_frames} frames compared; {bad} differ")
    return 1 if bad else 0


if __name__ == "__main__":
    if sys.argv[1] == "record":
        n = int(sys.argv[3]) if len(sys.argv) > 3 else 3000
        t0 = time.time()
        data = record(n)
        with open(sys.argv[2], "wb") as fh:
            pickle.dump(data, fh)
        print(f"recorded {len(data)} scenarios in {time.time() - t0:.0f} s")
    else:
        with open(sys.argv[2], "rb") as fa, open(sys.argv[3], "rb") as fb:
            sys.exit(compare(pickle.load(fa), pickle.load(fb)))
