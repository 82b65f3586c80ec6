"""SoftPad: soft sensorized pneumatic surfaces that help rigid grippers grasp.

Sub-packages, in the order data flows (docs/architecture.md)::

    thesis, layout -> sensing -> planning
    fem -> sim -> box -> control -> harness -> record -> trials -> cli

``import softpad`` stays light: heavy dependencies (FElupe, MuJoCo, matplotlib) are imported
lazily inside the functions that need them.
"""

from softpad.errors import SoftPadError

__version__ = "0.2.0"

#: Version of every JSON document SoftPad prints or writes; bumped when a key changes meaning.
SCHEMA_VERSION = 2

__all__ = ["SCHEMA_VERSION", "SoftPadError", "__version__"]
