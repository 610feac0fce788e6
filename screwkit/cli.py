"""The ``screwkit`` command line: a thin layer over the public API (design.md §7).

``main(argv=None) -> int`` returns the exit status: 0 success, 1 analysis error, 2 usage error.
One ``run_*`` function per command; each prints text by default and JSON with ``--json``.

Examples
--------
>>> main(["screw", "--revolute", "0", "0", "1", "--point", "1", "0", "0"])
screw (0, 0, 1; 0, -1, 0)  pitch 0  kind zero pitch
0
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence

from . import __version__
from .exceptions import ScrewkitError
from .screw import Screw

__all__ = ["get_parser", "main", "run_screw"]


def get_parser() -> argparse.ArgumentParser:
    """Build the argument parser (a factory, so tests and docs can inspect it).

    Examples
    --------
    >>> get_parser().prog
    'screwkit'
    """
    parser = argparse.ArgumentParser(
        prog="screwkit",
        description="Find and explain the singularities of parallel robots with screw theory "
        "and Grassmann-Cayley algebra.",
    )
    parser.add_argument("--version", action="version", version=f"screwkit {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    screw = commands.add_parser(
        "screw",
        help="describe one screw (a joint twist or a wrench): coordinates, pitch, axis",
        description="Describe a screw given as a revolute axis, a prismatic direction or Plücker "
        "coordinates. Lengths in any unit; the answer is in the same unit.",
    )
    kind = screw.add_mutually_exclusive_group(required=True)
    kind.add_argument(
        "--revolute",
        nargs=3,
        type=float,
        metavar=("SX", "SY", "SZ"),
        help="axis direction of a revolute joint (needs --point)",
    )
    kind.add_argument(
        "--prismatic",
        nargs=3,
        type=float,
        metavar=("DX", "DY", "DZ"),
        help="direction of a prismatic joint",
    )
    kind.add_argument(
        "--plucker",
        nargs=6,
        type=float,
        metavar="C",
        help="the six coordinates (s; s0), direction first",
    )
    screw.add_argument(
        "--point", nargs=3, type=float, metavar=("X", "Y", "Z"), help="a point of the revolute axis"
    )
    screw.add_argument("--json", action="store_true", help="print JSON instead of text")
    return parser


def _number(value: float) -> str:
    return "0" if value == 0 else f"{value:.6g}"


def run_screw(args: argparse.Namespace) -> int:
    """Describe one screw; see ``screwkit screw --help``."""
    if args.revolute is not None:
        if args.point is None:
            print("screwkit screw: error: --revolute needs --point X Y Z", file=sys.stderr)
            return 2
        screw = Screw.revolute(args.revolute, args.point)
    elif args.prismatic is not None:
        screw = Screw.prismatic(args.prismatic)
    else:
        screw = Screw(args.plucker)
    described = screw.to_dict()
    if args.json:
        print(json.dumps(described))
        return 0
    coords = [_number(v) for v in screw.coords]
    pitch = described["pitch"]
    pitch_text = pitch if isinstance(pitch, str) else _number(pitch)
    print(
        f"screw ({', '.join(coords[:3])}; {', '.join(coords[3:])})  pitch {pitch_text}  "
        f"kind {described['kind']}"
    )
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 1 analysis error, 2 usage error).

    Examples
    --------
    >>> main(["--version"])
    Traceback (most recent call last):
    ...
    SystemExit: 0
    """
    parser = get_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    try:
        return run_screw(args)
    except ScrewkitError as err:
        print(f"screwkit {args.command}: error: {err}", file=sys.stderr)
        return 1
