"""The one compiled part: the box's over-pressure guard (src/softpad/box/_fastguard.c).

Everything else is in pyproject.toml. ``optional=True``: without a C compiler the package
still installs, and the box daemon runs its guard in Python only (it says so when it starts).
"""

from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "softpad.box._fastguard",
            ["src/softpad/box/_fastguard.c"],
            extra_compile_args=["-O2", "-std=c11"],
            optional=True,
        )
    ]
)
