"""``python -m screwkit``: the command-line interface (:mod:`screwkit.cli`)."""

import sys

from .cli import console

sys.exit(console())
