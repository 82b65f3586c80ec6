"""How well two models of the pad explain the MuJoCo world's readings of an object at its true
placement (a development aid, docs/beat-the-thesis.md section 5c).

    python docs/pad_model_check.py TRIALS.json [--objects-file FILE.toml] [--objects A,B]

TRIALS.json: the output of ``softpad trials --randomize --json``. For every trial the object as
the trial drew it (its parts, size and mass from the trial's parameters, its placement) is put
on the pad under two models, each predicting the six increments up to one scale (fitted by
least squares); the script prints, per object, the median over trials of the rms residual over
the largest increment:

* ``spread``: the weight spread evenly over the contact footprint (the parts' undersides within
  2 mm of the lowest), each point weighted by the FEM response where it acts: the model of the
  model-based planner.
* ``domes``: a rigid object on the inflated tops. Each top is a half-ellipsoid over its chamber
  (``PadPhysics.dome_height_m`` high); it meets the object where the object's underside comes
  closest to it, and carries it on a spring of the support stiffness, compressed by the object's
  plane less the gap there. Force and moment balance about the centre of mass fix the plane;
  each force is weighted by the FEM response at its point.

The placement is where the object was put, not where it came to rest: a ball or a lying can
rolls, so their residuals say little about either model.
"""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

import numpy as np

from softpad.cli._trials import select_objects
from softpad.layout import PadLayout
from softpad.planning._model_based import packaged_pad_model
from softpad.sim import LabVariation, Placement
from softpad.sim._footprint import to_pad_frame
from softpad.sim._mujoco_model import GRAVITY_M_S2, PadPhysics

#: Stiffness of one top carrying an object, N/m: the simulated top's slide spring
#: (``PadPhysics.distributed_stiffness_n_m``, 400 N/m) in series with the sealed chamber's
#: 1.14 kN/m (a newton on the central patch lowers the top 0.88 mm at p0, the FEM
#: characteristic quoted in ``PadPhysics``): 296 N/m.
SUPPORT_STIFFNESS_N_M = 1.0 / (1.0 / PadPhysics().distributed_stiffness_n_m + 0.88e-3)

LAYOUT = PadLayout()
MODEL = packaged_pad_model()
PITCH = LAYOUT.pitch_m
_G = (np.arange(45) + 0.5) / 45  # 1 mm grid over a module, module units
GX, GY = (a.ravel() for a in np.meshgrid(_G, _G, indexing="ij"))


def module_points() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pad-frame sample points (m) of every module, and each one's module (0-based)."""
    mods = np.repeat(np.arange(LAYOUT.n_modules), GX.size)
    row, col = np.array([LAYOUT.row_col(m) for m in LAYOUT.modules]).T
    cols, rows_up = col[mods], (LAYOUT.rows - 1 - row)[mods]
    return (
        (cols + np.tile(GX, LAYOUT.n_modules)) * PITCH,
        (rows_up + np.tile(GY, LAYOUT.n_modules)) * PITCH,
        mods,
    )


def underside_m(spec: Any, placement: tuple[float, float, float], x: np.ndarray, y: np.ndarray):
    """Height of the object's underside above its lowest point at pad points (inf: none)."""
    x0, y0, yaw0 = placement
    c0, s0 = math.cos(yaw0), math.sin(yaw0)
    ox, oy = c0 * (x - x0) + s0 * (y - y0), -s0 * (x - x0) + c0 * (y - y0)
    z = np.full(x.shape, np.inf)
    for p in spec.parts:
        cp, sp = math.cos(p.yaw_rad), math.sin(p.yaw_rad)
        u = cp * (ox - p.pos_m[0]) + sp * (oy - p.pos_m[1])
        v = -sp * (ox - p.pos_m[0]) + cp * (oy - p.pos_m[1])
        z = np.minimum(z, _part_underside(p, u, v))
    finite = np.isfinite(z)
    return z - z[finite].min() if finite.any() else z


def _part_underside(p: Any, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Underside height of one part at points (u, v) of its own frame (inf: not over it)."""
    if p.shape == "box":
        lx, ly, lz = p.size_m
        inside = (np.abs(u) <= lx / 2) & (np.abs(v) <= ly / 2)
        return np.where(inside, p.pos_m[2] - lz / 2, np.inf)
    r, r2 = p.radius_m, u**2 + v**2
    if p.shape == "sphere":
        return np.where(r2 < r * r, p.pos_m[2] - np.sqrt(np.clip(r * r - r2, 0, None)), np.inf)
    if p.axis == "z":  # a standing cylinder: a flat disc underneath
        return np.where(r2 < r * r, p.pos_m[2] - p.length_m / 2, np.inf)
    along, side = (u, v) if p.axis == "x" else (v, u)
    inside = (np.abs(along) <= p.length_m / 2) & (np.abs(side) < r)
    return np.where(inside, p.pos_m[2] - np.sqrt(np.clip(r * r - side**2, 0, None)), np.inf)


def spread(spec: Any, placement: tuple[float, float, float]) -> np.ndarray:
    """Predicted increments (up to scale) of the weight spread over the footprint."""
    x, y, mods = module_points()
    foot = underside_m(spec, placement, x, y) < 2e-3
    resp = MODEL.on_pad(np.column_stack([x, y]) / PITCH, LAYOUT)
    return np.bincount(mods, weights=resp * foot, minlength=LAYOUT.n_modules)


def domes(spec: Any, placement: tuple[float, float, float], stiffness_n_m: float) -> np.ndarray:
    """Predicted increments (up to scale) of the object resting rigidly on the domes."""
    phys = PadPhysics()
    x, y, _ = module_points()
    zb = underside_m(spec, placement, x, y)
    lx, ly = np.tile(GX, LAYOUT.n_modules) - 0.5, np.tile(GY, LAYOUT.n_modules) - 0.5
    r2 = (lx**2 + ly**2) / (phys.sensitive_side_m / 2 / PITCH) ** 2
    top = np.where(r2 < 1, phys.dome_height_m * np.sqrt(np.clip(1 - r2, 0, None)), -np.inf)
    gap = (top - zb).reshape(LAYOUT.n_modules, -1)
    best = gap.argmax(axis=1)
    touch = np.isfinite(gap[np.arange(LAYOUT.n_modules), best])
    k = np.flatnonzero(touch)
    idx = k * GX.size + best[k]
    pts = np.column_stack([x[idx], y[idx]])
    drop = phys.dome_height_m - gap[k, best[k]]
    com = to_pad_frame(np.array([spec.com_m[:2]]), Placement(*placement))[0]
    mass = spec.mass_kg
    force = balanced(pts - com, drop, mass * GRAVITY_M_S2 / stiffness_n_m) * stiffness_n_m
    out = np.zeros(LAYOUT.n_modules)
    out[k] = force * MODEL.on_pad(pts / PITCH, LAYOUT)
    return out


def balanced(arm: np.ndarray, drop: np.ndarray, sink_m: float) -> np.ndarray:
    """Compressions (m) of springs at ``arm`` from the centre of mass under a plane (offset,
    tilt) less each one's ``drop``, summing to ``sink_m`` with no moment; springs the plane
    would stretch are dropped (active set)."""
    on = np.ones(len(drop), dtype=bool)
    comp = np.zeros(len(drop))
    for _ in range(len(drop)):
        basis = np.column_stack([np.ones(on.sum()), arm[on]])
        rhs = np.array([sink_m, 0.0, 0.0]) + basis.T @ drop[on]
        plane = np.linalg.lstsq(basis.T @ basis, rhs, rcond=None)[0]
        comp = np.column_stack([np.ones(len(drop)), arm]) @ plane - drop
        if ((comp > 0) == on).all() or not (comp > 0).any():
            break
        on = comp > 0
    return np.where(on, np.clip(comp, 0.0, None), 0.0)


def relative_residual(measured: np.ndarray, predicted: np.ndarray) -> float:
    """rms of measured - fitted scale x predicted, over the largest measured increment."""
    scale = (predicted @ measured) / (predicted @ predicted)
    return float(np.sqrt(((measured - scale * predicted) ** 2).mean()) / measured.max())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("trials", nargs="+", help="softpad trials --json output")
    ap.add_argument("--objects-file", default=None)
    ap.add_argument("--objects", default=None, help="comma-separated names (default: all)")
    ap.add_argument("--stiffness-n-m", type=float, default=SUPPORT_STIFFNESS_N_M)
    args = ap.parse_args()
    specs = {s.name: s for s in select_objects(None, args.objects_file)}
    wanted = set(args.objects.split(",")) if args.objects else None
    res: dict[str, dict[str, list[float]]] = {}
    for path in args.trials:
        with open(path) as fh:
            trials = json.load(fh)["trials"]
        for t in trials:
            if not t["increments_pa"] or (wanted and t["object"] not in wanted):
                continue
            spec = specs[t["object"]]
            spec = LabVariation.of(t["parameters"]).object(spec) if t["parameters"] else spec
            inc, placed = np.asarray(t["increments_pa"], dtype=float), tuple(t["placement"])
            r = res.setdefault(t["object"], {"spread": [], "domes": []})
            r["spread"].append(relative_residual(inc, spread(spec, placed)))
            r["domes"].append(relative_residual(inc, domes(spec, placed, args.stiffness_n_m)))
    for name, r in res.items():
        s, d = np.median(r["spread"]), np.median(r["domes"])
        print(f"{name:24s} trials {len(r['spread']):3d}  spread {s:.3f}  domes {d:.3f}")


if __name__ == "__main__":
    main()
