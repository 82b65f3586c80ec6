"""SoftPad: soft sensorized pneumatic surfaces that help rigid grippers grasp.

Sub-packages, in the order data flows (see the README's Architecture section):

``fem`` -> ``sim`` -> ``box`` -> ``control`` / ``sensing`` -> ``planning`` -> ``record`` -> ``cli``

``import softpad`` stays light: heavy dependencies (FElupe, MuJoCo, matplotlib) are imported
lazily inside the functions that need them.
"""

from softpad.errors import SoftPadError

__version__ = "0.1.0"

__all__ = ["SoftPadError", "__version__"]
