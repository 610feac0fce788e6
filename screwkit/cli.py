"""The ``screwkit`` command line: a thin layer over the public API (design.md §7).

``main(argv=None) -> int`` returns the exit status: 0 success, 1 analysis error (e.g. a pose out of
reach), 2 usage error (unknown mechanism, malformed arguments). Errors are one line on stderr.
One ``run_*`` function per command; each prints text by default and JSON with ``--json``.

Commands
--------
``screwkit analyze NAME|FILE.toml [--pose X Y Z PHI] [--rtol R] [--json]``
    The whole analysis (:func:`screwkit.report.analyze`): twist graph, wrench systems, wrench
    diagram, superbracket, conditions, verdict. Lengths in the catalog file's unit, angle in degrees.
``screwkit list [--json]``
    The catalog.
``screwkit screw (--revolute SX SY SZ --point X Y Z | --prismatic DX DY DZ | --plucker C*6)``
    Describe one screw.

Examples
--------
>>> main(["screw", "--revolute", "0", "0", "1", "--point", "1", "0", "0"])
screw (0, 0, 1; 0, -1, 0)  pitch 0  kind zero pitch
0
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
from collections.abc import Sequence
from typing import Any, NoReturn

import numpy as np

from . import __version__
from .catalog import list_mechanisms, load_mechanism, load_toml
from .exceptions import ScrewkitError
from .report import analyze
from .screw import Screw

__all__ = ["get_parser", "main", "run_analyze", "run_list", "run_screw"]


class _UsageError(Exception):
    """A malformed command line (exit status 2)."""


#: What the command line takes for a negative number (argparse's own pattern misses exponents, so
#: ``--pose 0 0 -7.5e2 0`` read ``-7.5e2`` as an option).
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (the usage is in ``--help``) and negative numbers in any
    decimal form."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message: str) -> NoReturn:
        raise _UsageError(f"{self.prog}: error: {message} (see --help)")


def get_parser() -> argparse.ArgumentParser:
    """Build the argument parser (a factory, so tests and docs can inspect it).

    Examples
    --------
    >>> get_parser().prog
    'screwkit'
    """
    parser = _Parser(
        prog="screwkit",
        description="Find and explain the singularities of parallel robots with screw theory "
        "and Grassmann-Cayley algebra.",
    )
    parser.add_argument("--version", action="version", version=f"screwkit {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    analyze_parser = commands.add_parser(
        "analyze",
        help="analyse a mechanism at a pose: wrench systems, diagram, superbracket, labelled conditions",
        description="Analyse a catalog mechanism (by name, see `screwkit list`) or a catalog/snapshot "
        "TOML file: twist graph, constraint and actuation wrenches, wrench diagram, factored "
        "superbracket, geometric and vector-form conditions with their labels, and the verdict.",
    )
    analyze_parser.add_argument("mechanism", help="a catalog name (e.g. h4) or a .toml file")
    analyze_parser.add_argument(
        "--pose",
        nargs="+",
        type=float,
        metavar="Q",
        help="the pose, e.g. X Y Z PHI for an SMG: lengths in the catalog file's length unit "
        "(mm for h4), the angle in DEGREES; default: the catalog's default pose",
    )
    analyze_parser.add_argument(
        "--rtol",
        type=float,
        default=None,
        metavar="R",
        help="relative tolerance of every rank decision, in [0, 1) (default 1e-9)",
    )
    output = analyze_parser.add_mutually_exclusive_group()
    output.add_argument("--json", action="store_true", help="print the whole report as JSON")
    output.add_argument(
        "--latex",
        action="store_true",
        help="print the factored superbracket and its labelled conditions as a LaTeX align* block",
    )
    analyze_parser.add_argument(
        "--no-superbracket", action="store_true", help="skip the superbracket expansion (faster)"
    )
    listing = commands.add_parser("list", help="list the catalog's mechanisms")
    listing.add_argument("--json", action="store_true", help="print JSON instead of text")
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
        "--prismatic", nargs=3, type=float, metavar=("DX", "DY", "DZ"), help="direction of a prismatic joint"
    )
    kind.add_argument(
        "--plucker", nargs=6, type=float, metavar="C", help="the six coordinates (s; s0), direction first"
    )
    screw.add_argument(
        "--point", nargs=3, type=float, metavar=("X", "Y", "Z"), help="a point of the revolute axis"
    )
    screw.add_argument("--json", action="store_true", help="print JSON instead of text")
    return parser


def _number(value: float) -> str:
    return "0" if value == 0 else f"{value:.6g}"


def run_screw(args: argparse.Namespace) -> int:
    """Describe one screw; see ``screwkit screw --help``.

    Examples
    --------
    >>> run_screw(get_parser().parse_args(["screw", "--prismatic", "0", "0", "2"]))
    screw (0, 0, 0; 0, 0, 2)  pitch inf  kind infinite pitch
    0
    """
    if args.revolute is not None:
        if args.point is None:
            raise _UsageError("screwkit screw: error: --revolute needs --point X Y Z")
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


def _pose(args: argparse.Namespace, mechanism: Any) -> Any:
    """The --pose in the API's units (the family's angles from degrees to radians)."""
    if args.pose is None:
        return None
    names = mechanism.pose_names
    if len(args.pose) != len(names) or not all(math.isfinite(v) for v in args.pose):
        expected = " ".join(n.upper() for n in names)
        got = " ".join(map(str, args.pose))
        raise _UsageError(
            f"screwkit analyze: error: --pose expects {len(names)} finite numbers ({expected}), got {got}"
        )
    angles = set(mechanism.angle_names)
    return np.array([math.radians(v) if n in angles else v for n, v in zip(names, args.pose, strict=True)])


def run_analyze(args: argparse.Namespace) -> int:
    """The main job; see ``screwkit analyze --help``.

    Examples
    --------
    >>> args = get_parser().parse_args(["analyze", "h4", "--no-superbracket"])
    >>> run_analyze(args)  # doctest: +ELLIPSIS
    H4  (...h4.toml)
    ...
    0
    """
    if args.rtol is not None and not 0 <= args.rtol < 1:
        raise _UsageError(f"screwkit analyze: error: --rtol expects a number in [0, 1), got {args.rtol:g}")
    target: Any = args.mechanism
    snapshot = args.mechanism.endswith(".toml") and (_toml_kind(args.mechanism) == "snapshot")
    if not snapshot:
        if not args.mechanism.endswith(".toml") and args.mechanism.lower() not in list_mechanisms():
            raise _UsageError(
                f"screwkit analyze: error: unknown mechanism {args.mechanism!r}: expected one of "
                f"{list_mechanisms()} or a .toml file"
            )
        target = load_mechanism(args.mechanism)  # a malformed file is an analysis error (exit 1)
        pose = _pose(args, target)
    elif args.pose is not None:
        raise _UsageError(
            f"screwkit analyze: error: {args.mechanism} is a snapshot (one configuration); "
            "--pose does not apply"
        )
    else:
        pose = None
    if args.latex and args.no_superbracket:
        raise _UsageError(
            "screwkit analyze: error: --latex prints the superbracket's conditions; drop --no-superbracket"
        )
    report = analyze(target, pose, rtol=args.rtol, superbracket=not args.no_superbracket)
    if args.latex:
        _print(_latex(report))
    else:
        _print(json.dumps(report.to_dict(), indent=2, ensure_ascii=False) if args.json else str(report))
    return 0


def _latex(report: Any) -> str:
    """The superbracket's conditions in LaTeX, or a LaTeX comment saying why there are none."""
    if report.superbracket is None:
        return f"% no superbracket conditions: {report.superbracket_note}"
    from .conditions import latex

    result = report.superbracket
    return latex(result.simplification.factored, result.conditions, result.diagram.line_text())


def _toml_kind(path: str) -> Any:
    header = load_toml(path).get("mechanism", {})
    return header.get("kind") if isinstance(header, dict) else None


def _print(text: str) -> None:
    """Print, falling back to escapes where stdout cannot encode a character (ḟ, χ̇, θ̇ on an
    ASCII or Latin-1 terminal) instead of failing."""
    try:
        print(text)
    except UnicodeEncodeError:
        encoding = getattr(sys.stdout, "encoding", None) or "ascii"
        print(text.encode(encoding, errors="backslashreplace").decode(encoding))


def run_list(args: argparse.Namespace) -> int:
    """List the catalog; see ``screwkit list --help``.

    Examples
    --------
    >>> run_list(get_parser().parse_args(["list"]))  # doctest: +ELLIPSIS
    h4           H4           family four_limb, lengths in mm
    ...0
    """
    entries = []
    for name in list_mechanisms():
        mechanism = load_mechanism(name)
        entries.append(
            {
                "name": name,
                "title": mechanism.name,
                "family": mechanism.family,
                "length_unit": mechanism.length_unit,
                "sources": list(mechanism.sources),
            }
        )
    if args.json:
        print(json.dumps(entries, indent=2))
    else:
        for entry in entries:
            print(
                f"{entry['name']:<12} {entry['title']:<12} family {entry['family']}, lengths in "
                f"{entry['length_unit']}"
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
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            parser.print_help()
            return 0
        runners = {"analyze": run_analyze, "list": run_list, "screw": run_screw}
        return runners[args.command](args)
    except _UsageError as err:
        print(str(err), file=sys.stderr)
        return 2
    except ScrewkitError as err:
        message = " ".join(str(err).split())
        print(f"screwkit {args.command}: error: {message}", file=sys.stderr)
        return 1
