"""``python -m screwkit``: the command-line interface (:mod:`screwkit.interface.cli`)."""

import sys

from .interface.cli import console

sys.exit(console())
