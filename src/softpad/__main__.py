"""``python -m softpad``: the ``softpad`` command."""

import sys

from softpad.cli.main import main

if __name__ == "__main__":
    sys.exit(main())
