"""``python -m screwkit``: the command-line interface (:mod:`screwkit.cli`)."""

from .cli import console

console()
