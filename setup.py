"""The compiled parts: the box's over-pressure guard (src/softpad/box/_fastguard.c), the
simulated box's exact pressure solve (src/softpad/box/_fastsim.c) and the fault monitor's
steady-rise rates (src/softpad/control/_fastmonitor.c).

Everything else is in pyproject.toml. ``optional=True``: without a C compiler the package
still installs, the box daemon runs its guard in Python only (it says so when it starts) and
the simulated box solves with NumPy (the same bits, slower). ``-ffp-contract=off``: no fused
multiply-add, so the compiled solve rounds as NumPy does.
"""

from setuptools import Extension, setup

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
    ]
)
