"""SoftPad: soft sensorized pneumatic surfaces that help rigid grippers grasp.

One sub-package per domain, in layers: which may import which is the table
``softpad.layering.ALLOWED_IMPORTS``, drawn in docs/architecture.md (and README.md) by
``python -m softpad.layering``.

``import softpad`` stays light: heavy dependencies (FElupe, MuJoCo, matplotlib) are imported
lazily inside the functions that need them.
"""

from softpad.errors import SoftPadError

#: The package's version, its one source (pyproject.toml reads it; recordings, the box
#: daemon's info and the design cache's keys carry it).
__version__ = "0.3.0"

#: Version of every JSON document SoftPad prints or writes; bumped when a key changes meaning.
SCHEMA_VERSION = 2

__all__ = ["SCHEMA_VERSION", "SoftPadError", "__version__"]
