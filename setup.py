"""The compiled parts: the box's over-pressure guard (src/softpad/box/_fastguard.c), the
simulated box's exact pressure solve (src/softpad/box/_fastsim.c), the fault monitor's
steady-rise rates (src/softpad/control/_fastmonitor.c) and the MuJoCo world's steps
(src/softpad/sim/_fastworld.c, with the mujoco wheel's headers; no link: it calls MuJoCo
through function pointers it is handed).

Everything else is in pyproject.toml. ``optional=True``: without a C compiler the package
still installs, the box daemon runs its guard in Python only (it says so when it starts) and
the simulated box solves with NumPy (the same bits, slower). ``-ffp-contract=off``: no fused
multiply-add, so the compiled solve rounds as NumPy does.
"""

import os

from setuptools import Extension, setup


def _mujoco_include() -> list[str]:
    """The mujoco wheel's headers, when mujoco is importable at build time."""
    try:
        import mujoco
    except ImportError:
        return []
    return [os.path.join(os.path.dirname(mujoco.__file__), "include")]


setup(
    ext_modules=[
        Extension(
            "softpad.box._fastguard",
            ["src/softpad/box/_fastguard.c"],
            extra_compile_args=["-O2", "-std=c11"],
            optional=True,
        ),
        Extension(
            "softpad.box._fastsim",
            ["src/softpad/box/_fastsim.c"],
            extra_compile_args=["-O2", "-std=c11", "-ffp-contract=off"],
            optional=True,
        ),
        Extension(
            "softpad.control._fastmonitor",
            ["src/softpad/control/_fastmonitor.c"],
            extra_compile_args=["-O2", "-std=c11", "-ffp-contract=off"],
            optional=True,
        ),
        Extension(
            "softpad.sim._fastworld",
            ["src/softpad/sim/_fastworld.c"],
            include_dirs=_mujoco_include(),
            extra_compile_args=["-O2", "-std=c11", "-ffp-contract=off"],
            optional=True,
        ),
    ]
)
