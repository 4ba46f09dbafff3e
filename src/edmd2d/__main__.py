"""``python -m edmd2d``: the command line of :mod:`edmd2d.cli`."""

import sys

from .cli import main

sys.exit(main())
