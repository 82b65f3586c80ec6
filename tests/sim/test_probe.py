"""Probing the simulated pad against the FEM (issue 10's done-when checks).

The default pad is the cast pad (softpad.fem._cast) with the line gain's nominal; the checks
against the FEM run on the pure FEM (gain 1). Tolerances: the simulator runs the FEM response through equivalent loads, the packaged
characteristic table (bilinear, 100 Pa rows) and the gas law; against the FEM's small-load
reciprocity prediction it agrees within 5 % (measured 2-3 %, the table's chords and the
patch sampling); against the FEM's nonlinear sealed chamber (``sealed_chamber_study``,
contact and the gas law solved by the finite elements) within 10 % (the issue's figure;
measured 2 %).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from softpad import thesis
from softpad.box import open_box
from softpad.errors import InputError
from softpad.fem import sealed_rises_pa
from softpad.sim import default_cast_response, default_response
from softpad.sim._probe import probe_box, sealed_rise_map
from softpad.sim._response import rect_points

G = 9.80665
R = default_response()
CAST = default_cast_response()
PITCH = thesis.MODULE_PITCH_M
URL = "sim://?inflated_kpa=1.1&noise=0"


def _fem_rise(dx_m: float, size_m: tuple[float, float], force_n: float) -> float:
    """The clamped FEM's small-load rise of module 2 for a block centred dx_m right of its
    centre, straight from the stored response (no simulator code in between)."""
    s = R.mean_influence((dx_m, 0.0), size_m, thesis.P0_PA)
    return force_n * s * R.sealed_rise_per_newton(thesis.P0_PA)


def _cast_rise(at_m: tuple[float, float], size_m: tuple[float, float], force_n: float) -> Any:
    """The cast pad FEM's small-load rise of every module for a block at ``at_m`` (pad frame),
    straight from the stored table (its frame scaled to the 45 mm pitch; no simulator code)."""
    assert CAST is not None
    k = CAST.pitch_m / PITCH
    pts = rect_points(np.array(at_m) * k, np.array(size_m) * k)
    return sealed_rises_pa(CAST, pts, force_n / len(pts), thesis.P0_PA)


def _box(pad_model: str = "cast") -> Any:
    """A simulated box at 1.1 kPa, ideal sensor, on the pure FEM response (line gain 1)."""
    from softpad.box import SimBox
    from softpad.sim import AnalyticWorld, PadResponse, SensorParams

    world = AnalyticWorld(response=PadResponse(pad_model=pad_model, line_gain=1.0))
    return SimBox(world, sensor=SensorParams.ideal(), initial_pressure_pa=thesis.P0_PA)


def test_probe_centre_15_mm_off_and_line_fall_and_match_the_cast_fem() -> None:
    """A 10 mm block of 0.2 N at module 2's centre, 15 mm off it, and on the line between
    modules 2 and 3 (x = 2 module units): every module's rise within 5 % (or 1 Pa) of the cast
    pad FEM's; on the line both modules alike."""
    size, force = (0.010, 0.010), 0.2
    rises = []
    for dx in (0.0, 0.015, 0.0225):
        at = (1.5 * PITCH + dx, 1.5 * PITCH)
        with _box() as box:
            res = probe_box(box, at, size, force)
        fem = _cast_rise(at, size, force)
        np.testing.assert_allclose(res.delta_pa, fem, rtol=0.05, atol=1.0)
        rises.append(res.delta_pa[1])
    assert rises[0] > rises[1] > rises[2] > 0
    # modules 2 and 3 are not mirror images on the 2 x 3 cast pad (2 has a neighbour either side)
    assert res.delta_pa[2] == pytest.approx(res.delta_pa[1], rel=0.02)
    assert rises[2] < 0.2 * rises[0]  # the line: the bonded strip barely moves


def test_clamped_pad_keeps_the_seam_insensitive() -> None:
    """The clamped modules (the old map, still available): a block on the seam loads only the
    two modules either side, each as the stored module response says (5 %)."""
    with _box("clamped") as box:
        res = probe_box(box, (2 * PITCH, 1.5 * PITCH), (0.010, 0.010), 0.2)
    fem2 = _fem_rise(0.0225, (0.010, 0.010), 0.2)
    np.testing.assert_allclose(res.delta_pa[[1, 2]], fem2, rtol=0.05)
    np.testing.assert_allclose(np.delete(res.delta_pa, [1, 2]), 0.0, atol=1e-6)


def test_duplo_brick_matches_the_fem_sealed_chamber() -> None:
    """12.6 g over 42 x 31 mm at 1.1 kPa, centred on module 5 of the clamped pad: within 10 %
    of the FEM's nonlinear sealed chamber (same tubing and gap volumes: softpad.thesis); and
    seen above t_o on the default (cast) pad, as in the thesis."""
    from softpad.fem import sealed_chamber_study

    fem = sealed_chamber_study(masses_kg=(0.0126,)).delta_pressure_pa[0]
    with _box("clamped") as box:
        res = probe_box(box, (1.5 * PITCH, 0.5 * PITCH), (0.042, 0.031), 0.0126 * G)
    np.testing.assert_allclose(res.delta_pa[4], fem, rtol=0.10)
    with open_box(URL) as box:
        res = probe_box(box, (1.5 * PITCH, 0.5 * PITCH), (0.042, 0.031), 0.0126 * G)
    assert res.delta_pa[4] > thesis.OBJECT_THRESHOLD_PA


def test_probe_with_the_sensor_on_averages_the_noise() -> None:
    """With the sensor's noise the 10-read means differ from the ideal rise by a few pascals."""
    with open_box("sim://?inflated_kpa=1.1&seed=3") as box:
        res = probe_box(box, (0.5 * PITCH, 0.5 * PITCH), (0.01, 0.01), 0.2)
        fem = box.world.response.sealed_rise_pa(
            box.world.response.rect_equivalent_loads(
                (0.5 * PITCH, 0.5 * PITCH), (0.01, 0.01), 0.2, thesis.P0_PA
            ),
            thesis.P0_PA,
        )[3]
    assert abs(res.delta_pa[3] - fem) < 0.05 * fem + 15.0


@pytest.mark.mujoco
def test_mujoco_world_reads_the_same_response() -> None:
    from softpad.box import SimBox
    from softpad.sim import MujocoWorld, PadResponse, SensorParams

    world = MujocoWorld(response=PadResponse(line_gain=1.0))
    box = SimBox(world, sensor=SensorParams.ideal(), initial_pressure_pa=1100.0)
    at = (1.5 * PITCH + 0.015, 1.5 * PITCH)
    res = probe_box(box, at, (0.01, 0.01), 0.2)
    np.testing.assert_allclose(res.delta_pa[1], _cast_rise(at, (0.01, 0.01), 0.2)[1], rtol=0.05)


def test_map_agrees_with_the_probe_and_is_symmetric() -> None:
    with open_box(URL) as box:
        xs = np.array([1.5 * PITCH, 1.5 * PITCH + 0.015, 2 * PITCH])
        ys = np.array([1.5 * PITCH])
        rise = sealed_rise_map(
            box.world.response,
            box.characteristic,
            1100.0,
            0.2,
            (0.01, 0.01),
            xs,
            ys,
            box.pneumatics,
        )
        res = probe_box(box, (1.5 * PITCH + 0.015, 1.5 * PITCH), (0.01, 0.01), 0.2)
    np.testing.assert_allclose(rise[0, 1], res.delta_pa, atol=0.5)
    # on the line 2|3 both alike; not exactly: 2 and 3 are not mirror images on the cast pad
    assert rise[0, 2, 1] == pytest.approx(rise[0, 2, 2], rel=0.01)


@pytest.mark.parametrize(
    ("at", "size", "force", "match"),
    [
        ((-0.01, 0.02), (0.01, 0.01), 0.2, "off the pad"),
        ((0.02, 0.02), (0.0, 0.01), 0.2, "width"),
        ((0.02, 0.02), (0.01, 0.3), 0.2, "length"),
        ((0.02, 0.02), (0.01, 0.01), 60.0, "force"),
    ],
)
def test_bad_blocks_are_refused(at, size, force, match) -> None:  # type: ignore[no-untyped-def]
    with open_box(URL) as box, pytest.raises(InputError, match=match):
        probe_box(box, at, size, force)
