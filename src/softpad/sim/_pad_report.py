"""The pad probed as ``softpad pad probe|map|sensitivity`` reports it: a block pressed at a
point given in module units, the largest rise of a block anywhere (a heat map), and the pad's
sensitivities, each as a JSON-ready dict and lines of text."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import PadLayout


def probe_report(
    box: Any, at: tuple[float, float], size_m: tuple[float, float], force_n: float, url: str
) -> tuple[dict[str, Any], list[str]]:
    """Press a block on the simulated ``box`` at ``at`` (module units) and report every
    module's rise (:func:`softpad.sim.probe_box`).

    Parameters
    ----------
    box
        An open simulated box (its world's pad is pressed).
    at
        The block's centre, module units (x along the columns, y up the rows).
    size_m
        The block's sides along x and y, m.
    force_n
        The block's force, N.
    url
        The box's URL, for the report.

    Returns
    -------
    tuple
        The dict (kPa, kPa/N) and the lines of the report.
    """
    from softpad.sim._probe import probe_box

    lay = box.world.layout
    x, y = at
    if x > lay.cols or y > lay.rows:
        raise InputError(
            f"--at {x:g},{y:g} is off the {lay.rows}x{lay.cols} pad (x 0..{lay.cols}, "
            f"y 0..{lay.rows} module units)"
        )
    at_m = (x * lay.pitch_m, y * lay.pitch_m)
    result = probe_box(box, at_m, size_m, force_n)

    def kpa(values: Any, per: float = 1.0) -> list[float]:
        return [round(v / 1e3 / per, 6) for v in values]

    out = {
        "command": "pad probe", "box": url, "at": [x, y], "at_m": list(at_m),
        "force_n": force_n, "footprint_mm": [size_m[0] * 1e3, size_m[1] * 1e3],
        "reference_kpa": kpa(result.reference_pa), "delta_kpa": kpa(result.delta_pa),
        "fem_delta_kpa": kpa(result.fem_delta_pa),
        "delta_kpa_per_n": kpa(result.delta_pa, force_n),
        "fem_delta_kpa_per_n": kpa(result.fem_delta_pa, force_n),
    }  # fmt: skip
    lines = [
        f"block {size_m[0] * 1e3:g} x {size_m[1] * 1e3:g} mm, {force_n:g} N at ({x:g}, {y:g}) "
        f"module units on {url}",
        "module  delta_kPa  delta_kPa/N  FEM_kPa  FEM_kPa/N",
    ]
    per_n = 1e3 * force_n  # Pa -> kPa/N
    for k, (d, f) in enumerate(zip(result.delta_pa, result.fem_delta_pa, strict=True), 1):
        lines.append(f"{k:6d}  {d / 1e3:9.4f}  {d / per_n:11.3f}  {f / 1e3:7.4f}  {f / per_n:9.3f}")
    return out, lines


@dataclass(frozen=True)
class PadMap:
    """The largest module rise of a block centred at every point of a grid.

    Attributes
    ----------
    xs_m, ys_m
        The grid's block centres along x and y, m.
    top_pa
        The largest module rise at each centre, Pa (rows along y).
    layout
        The pad.
    size_m
        The block's sides, m.
    force_n
        The block's force, N.
    p0_pa
        The modules' pressure, Pa.
    """

    xs_m: NDArray[np.float64]
    ys_m: NDArray[np.float64]
    top_pa: NDArray[np.float64]
    layout: PadLayout
    size_m: tuple[float, float]
    force_n: float
    p0_pa: float

    def to_dict(self) -> dict[str, Any]:
        """The map's figures: pressure, largest and smallest rise (kPa), the share of
        centres above t_o."""
        top = self.top_pa
        return {
            "force_n": self.force_n,
            "footprint_mm": [self.size_m[0] * 1e3, self.size_m[1] * 1e3],
            "pressure_kpa": self.p0_pa / 1e3,
            "largest_kpa": float(top.max()) / 1e3,
            "smallest_kpa": float(top.min()) / 1e3,
            "share_above_object_threshold": float((top >= thesis.OBJECT_THRESHOLD_PA).mean()),
        }

    def save_png(self, path: str | Path) -> None:
        """Draw the heat map (kPa) with module outlines and the t_o and t_g contours.

        Parameters
        ----------
        path
            The PNG written.
        """
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        lay, top = self.layout, self.top_pa
        fig, ax = plt.subplots(figsize=(1.6 + 2.2 * lay.cols, 0.8 + 2.2 * lay.rows))
        ext = (0.0, lay.cols, 0.0, lay.rows)
        im = ax.imshow(top / 1e3, origin="lower", extent=ext, cmap="viridis", aspect="equal")
        fig.colorbar(im, ax=ax, label="largest module rise (kPa)")
        self._outline(ax)
        ax.set_xlabel("x (module units)")
        ax.set_ylabel("y (module units)")
        w, h = self.size_m
        ax.set_title(
            f"{self.force_n:g} N on {w * 1e3:g} x {h * 1e3:g} mm, p0 = {self.p0_pa / 1e3:.2f} kPa",
            fontsize=10,
        )
        fig.tight_layout()
        fig.savefig(path, format="png", dpi=110)
        plt.close(fig)
        if not math.isfinite(float(top.max())):  # pragma: no cover - guarded by the physics
            raise InputError("the map has no finite values")

    def _outline(self, ax: Any) -> None:
        """Threshold contours, module outlines and numbers."""
        from matplotlib.patches import Rectangle

        lay, top = self.layout, self.top_pa
        units = 1.0 / lay.pitch_m
        levels = [thesis.OBJECT_THRESHOLD_PA / 1e3, thesis.CONTACT_THRESHOLD_PA / 1e3]
        if top.max() / 1e3 > levels[0]:
            cs = ax.contour(
                self.xs_m * units, self.ys_m * units, top / 1e3, levels=levels, colors=["w", "r"]
            )
            ax.clabel(cs, fmt=lambda v: f"{v * 1e3:.0f} Pa")
        for k in range(lay.n_modules):
            r, c = divmod(k, lay.cols)
            ax.add_patch(Rectangle((c, lay.rows - 1 - r), 1, 1, fill=False, ec="k", lw=1.2))
            ax.text(c + 0.05, lay.rows - 1 - r + 0.05, str(k + 1), color="w", fontsize=9)


def pad_map(box: Any, force_n: float, size_m: tuple[float, float], step_m: float) -> PadMap:
    """The largest module rise of a block centred at every ``step_m`` of the pad of the
    simulated ``box`` (:func:`softpad.sim.sealed_rise_map`; the modules inflated).

    Parameters
    ----------
    box
        An open simulated box with inflated modules.
    force_n
        The block's force, N.
    size_m
        The block's sides, m.
    step_m
        Grid step of the block centres, m.
    """
    from softpad.sim._probe import sealed_rise_map

    world = box.world
    lay = world.layout
    xs = np.arange(0.5 * step_m, lay.cols * lay.pitch_m, step_m)
    ys = np.arange(0.5 * step_m, lay.rows * lay.pitch_m, step_m)
    p0 = float(np.median(box.true_pressures_pa[: lay.n_modules]))
    if p0 < thesis.P0_RANGE_PA[0] - 1.0:
        raise InputError(
            f"the box's modules are at {p0 / 1e3:g} kPa; inflate them first "
            f"(e.g. sim://?inflated_kpa=1.1), p0 range {thesis.P0_RANGE_PA[0] / 1e3:g}.."
            f"{thesis.P0_RANGE_PA[1] / 1e3:g} kPa"
        )
    rise = sealed_rise_map(
        world.response, box.characteristic, p0, force_n, size_m, xs, ys, box.pneumatics
    )
    return PadMap(xs, ys, rise.max(axis=2), lay, size_m, force_n, p0)


def sensitivity_lines(out: dict[str, Any], pressure_kpa: float) -> list[str]:
    """The pad's sensitivities (:func:`softpad.sim.pad_sensitivities`'s ``out``) as text.

    Parameters
    ----------
    out
        The sensitivities (Pa/N, g).
    pressure_kpa
        The modules' pressure, kPa.
    """
    lines = [
        f"{out['pad_model']} pad at {pressure_kpa:g} kPa, line gain {out['line_gain']:g}: "
        "sealed rise per newton (Pa/N)"
    ]
    for name, v in out["loads"].items():
        rises = " ".join(f"{r:6.0f}" for r in v["rise_pa_n"])
        lines.append(f"  {name:45s} modules 1-6: {rises}")
    lines.append(
        f"line sensitivity (can strip, least of modules 1, 4): {out['line_pa_n']:.0f} Pa/N"
    )
    lines.append(f"corner sensitivity (least of modules 1, 2, 4, 5): {out['corner_pa_n']:.0f} Pa/N")
    for name, g in out["min_detectable_mass_g"].items():
        lines.append(f"minimum detectable mass at t_o = 50 Pa, {name}: {g:.2f} g")
    return lines


__all__ = ["PadMap", "pad_map", "probe_report", "sensitivity_lines"]
