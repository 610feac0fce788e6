"""``python -m screwkit``: the command-line interface (:mod:`screwkit.cli`)."""

import sys

from .cli import main

sys.exit(main())
