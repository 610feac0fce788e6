"""The argument parser of the ``screwkit`` command line (:mod:`screwkit.interface.cli`).

:func:`get_parser` builds it: one subcommand per job (``analyze``, ``graph``, ``list``, ``screw``,
``table4``, ``map``, ``path``), errors as one line (:class:`~screwkit.interface._cli_io.UsageError`,
exit status 2; the usage is in ``--help``), negative numbers in any decimal form. Building and
parsing imports no analysis: the map's quantities are read only when its help is shown.
"""

from __future__ import annotations

import argparse
import re
from typing import Any, NoReturn

from ..version import __version__
from ._cli_io import UsageError, pose_coordinates

__all__ = ["get_parser"]

#: Values per map axis given as ``LO HI`` when ``--grid`` is not given.
_MAP_GRID = 50


#: What the command line takes for a negative number: any decimal form ``float`` reads after a minus
#: sign (argparse's own pattern misses exponents, so ``--pose 0 0 -7.5e2 0`` read ``-7.5e2`` as an
#: option), digit groups (``-1_000``), and ``-inf``/``-nan`` (refused then as not finite, not as an
#: unknown option). No option of screwkit's reads as a number.
_NEGATIVE_NUMBER = re.compile(
    r"^-((\d[\d_]*\.?[\d_]*|\.\d[\d_]*)([eE][+-]?\d[\d_]*)?|inf|infinity|nan)$", re.IGNORECASE
)


class _Once(argparse.Action):
    """The ``store`` action of every option with a value, refusing the option given twice (argparse
    keeps the last and drops the first silently) and recording which options were given, so that
    :func:`_refuse_what_does_not_apply` can tell a given option from its default."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: Any,
                 option_string: str | None = None) -> None:
        given = vars(namespace).setdefault(_GIVEN, set())
        if self.dest in given:
            parser.error(f"{option_string} given twice; give it once")
        given.add(self.dest)
        setattr(namespace, self.dest, values)


#: The namespace attribute naming the options given on the command line (removed after the checks).
_GIVEN = "_given_options"


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (the usage is in ``--help``), negative numbers in any
    decimal form, and options with a value given at most once."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER
        self.register("action", None, _Once)  # the default action (argparse registers None and "store")
        self.register("action", "store", _Once)

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{self.prog}: error: {message} (see --help)")


class _CommandParser(_Parser):
    """The top-level parser: after parsing, options that do not apply to the subcommand's mode are
    refused (:func:`_refuse_what_does_not_apply`), never ignored."""

    def parse_known_args(self, args: Any = None, namespace: Any = None) -> Any:
        parsed, rest = super().parse_known_args(args, namespace)
        given: set[str] = getattr(parsed, _GIVEN, set())
        if hasattr(parsed, _GIVEN):
            delattr(parsed, _GIVEN)
        _refuse_what_does_not_apply(parsed, given)
        return parsed, rest


def _refuse_what_does_not_apply(args: argparse.Namespace, given: set[str]) -> None:
    """Refuse an option the subcommand's mode would ignore, naming it and the mode; fill the
    defaults that depend on the mode.

    ``screw``: ``--point`` belongs to ``--revolute`` (a prismatic direction or Plücker coordinates
    carry no point). ``map``: ``--grid`` sets N for the axes given as ``LO HI``; with every axis
    given as ``LO HI N`` (or none) it would set nothing. (``analyze`` and ``graph`` refuse
    ``--pose`` for a snapshot and ``--latex`` with ``--no-superbracket`` once the file is read.)
    """
    command = getattr(args, "command", None)
    if command == "screw" and args.point is not None and args.revolute is None:
        mode = "--prismatic" if args.prismatic is not None else "--plucker"
        raise UsageError(
            f"screwkit screw: error: --point applies to --revolute only; {mode} carries no point "
            "(drop --point, or give the screw with --revolute)"
        )
    if command == "map":
        ranges = [values for values in (getattr(args, name) for name in pose_coordinates()) if values]
        if "grid" in given and not any(len(values) == 2 for values in ranges):
            raise UsageError(
                "screwkit map: error: --grid sets N for the axes given as LO HI, and no axis is (each "
                "gives its N as LO HI N, or is fixed); drop --grid"
            )
        if args.grid is None:
            args.grid = _MAP_GRID



def get_parser() -> argparse.ArgumentParser:
    """Build the argument parser (a factory, so tests and docs can inspect it).

    Returns
    -------
    argparse.ArgumentParser
        The ``screwkit`` parser: ``--version`` and one subcommand per job, its name in the
        namespace's ``command`` (None when none is given); errors raise a usage error (one line).

    Examples
    --------
    >>> get_parser().prog
    'screwkit'
    """
    parser = _CommandParser(
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
    _add_pose_argument(analyze_parser)
    analyze_parser.add_argument(
        "--rtol",
        type=float,
        default=None,
        metavar="R",
        help="relative tolerance of every rank decision, in [1e-12, 0.1] (default 1e-9)",
    )
    analyze_parser.add_argument(
        "--length-scale",
        type=float,
        default=None,
        metavar="L",
        help="characteristic length of every rank decision (moments are divided by it), in the "
        "file's length unit; default: derived from the screws at the pose",
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
    analyze_parser.add_argument(
        "--progress",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="name each stage on stderr as it starts (default: when stderr is a terminal)",
    )
    graph = commands.add_parser(
        "graph",
        help="export the twist graph (or its equivalent graph) as DOT, JSON or a snapshot TOML file",
        description="Write a mechanism's twist graph at a pose: Graphviz DOT (links as nodes, joints as "
        "labelled edges), JSON (screwkit.graphs.twistgraph.to_data) or a snapshot TOML file that `screwkit "
        "analyze` reads back. --equivalent writes the equivalent graph instead, closed sub-loops "
        "(parallelograms, 4S) replaced by virtual serial chains.",
    )
    graph.add_argument("mechanism", help="a catalog name (e.g. h4) or a .toml file")
    _add_pose_argument(graph)
    graph.add_argument(
        "--format", choices=("dot", "json", "toml"), default="dot", help="output format (default dot)"
    )
    graph.add_argument(
        "--equivalent", action="store_true", help="the equivalent graph (closed sub-loops reduced)"
    )
    graph.add_argument("--out", metavar="FILE", help="write to FILE instead of standard output")
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
    table4 = commands.add_parser(
        "table4",
        help="paper 004's Table 4 (min/max LTI) regenerated, the paper's values beside ours",
        description="Regenerate paper 004's Table 4: the extremes of the local transmission index "
        "(Eq. 16) over each robot's workspace, by a grid and a local refinement "
        "(screwkit.papers.paper_004_table4.index_extremes); the paper's value, ours, the difference and its "
        "cause.",
    )
    table4.add_argument("--grid", type=int, default=41, metavar="N", help="grid points per axis (default 41)")
    table4.add_argument(
        "--refine", type=int, default=12, metavar="K",
        help="rounds of local refinement (default 12; 0: grid only)",
    )
    table4.add_argument(
        "--robot", action="append", default=None, metavar="NAME",
        help="a catalog name (quattro, h4, veloce, v4, ragnar); repeat for several (default all)",
    )
    table4.add_argument("--json", action="store_true", help="print JSON instead of text")
    _add_workspace_commands(commands)
    return parser



class _MapQuantities:
    """The quantities a map can show (:data:`screwkit.analysis.quantities.QUANTITIES`), listed in
    ``map --help``: read when the help is shown, so that parsing a command does not import
    :mod:`screwkit.analysis.quantities`."""

    def __str__(self) -> str:
        from ..analysis.quantities import QUANTITIES

        return ", ".join(QUANTITIES)



def _add_workspace_commands(commands: Any) -> None:
    """The ``map`` and ``path`` subcommands (:mod:`screwkit.analysis.workspace`)."""
    mapping = commands.add_parser(
        "map",
        help="map a quantity (verdict, closeness, det A/B, LTI, a condition) over a 2-D slice of poses",
        description="Map a quantity over a slice of the pose space through the batched core. Give two "
        "coordinates as ranges (LO HI [N]) and optionally fix others (one value; default: the default "
        "pose). Lengths in the catalog file's unit, angles in DEGREES.",
    )
    mapping.add_argument("mechanism", help="a catalog name (e.g. h4) or a .toml file")
    quantity = mapping.add_argument(
        "--quantity",
        required=True,
        metavar="Q",
        help="one of %(quantities)s, detA, detB, condition (= condition:0) or condition:K",
    )
    vars(quantity)["quantities"] = _MapQuantities()  # argparse fills %(name)s from the action's attributes
    for name in pose_coordinates():
        mapping.add_argument(
            f"--{name}",
            nargs="+",
            type=float,
            metavar="V",
            help=f"{name}: LO HI [N] for an axis, or one value",
        )
    mapping.add_argument(
        "--grid", type=int, default=None, metavar="N",
        help=f"values per axis given as LO HI (default {_MAP_GRID})",
    )
    mapping.add_argument("--out", required=True, metavar="FILE", help="FILE.png, FILE.npz or FILE.json")
    mapping.add_argument(
        "--chunk", type=int, default=None, metavar="C", help="poses per chunk (bounded memory)"
    )
    mapping.add_argument("--no-progress", action="store_true", help="no progress line on stderr")
    path = commands.add_parser(
        "path",
        help="check a straight path in pose space for singularities (every crossing, refined)",
        description="Check the straight path between two poses: samples through the core, sign changes "
        "of det A, closeness minima and the reach edge refined by root finding. Lengths in the catalog "
        "file's unit, angles in DEGREES.",
    )
    path.add_argument("mechanism", help="a catalog name (e.g. h4) or a .toml file")
    path.add_argument(
        "--from", dest="start", nargs="+", type=float, required=True, metavar="Q", help="start pose"
    )
    path.add_argument("--to", dest="end", nargs="+", type=float, required=True, metavar="Q", help="end pose")
    path.add_argument(
        "--samples", type=int, default=200, metavar="N", help="samples along the path (default 200)"
    )
    path.add_argument("--json", action="store_true", help="print JSON instead of text")
    path.add_argument(
        "--certify",
        action="store_true",
        help="also prove the path free, or enclose each crossing (docs/certify.md: coverage)",
    )
    certify = commands.add_parser(
        "certify",
        help="prove a box of poses free of singularities, or find them with a witness "
        "(catalog robots; snapshots of platforms on serial limbs)",
        description="Pave a box of the pose space into boxes proved free, singular (with a witness) or "
        "undecided, by interval arithmetic. Give ranges (LO HI) and fixed values (one value; default: the "
        "default pose). Lengths in the catalog file's unit, angles in DEGREES.",
    )
    certify.add_argument(
        "mechanism", help="a catalog name (e.g. quattro) or a .toml file (catalog or snapshot)"
    )
    for name in pose_coordinates():
        certify.add_argument(
            f"--{name}", nargs="+", type=float, metavar="V", help=f"{name}: LO HI, or one value"
        )
    certify.add_argument("--resolution", type=float, default=None, metavar="R",
                         help="smallest box width, in the coordinates' units: of the length ranges "
                              "when lengths and angles are both ranged (angles then 1/256 of their "
                              "range), else of every range (default: 1/256 of each range)")
    certify.add_argument("--kinds", nargs="+", default=["constraint", "actuation", "serial"],
                         metavar="K", help="kinds to exclude (default: constraint actuation serial)")
    certify.add_argument("--max-boxes", type=int, default=200_000, metavar="N",
                         help="boxes evaluated before the run stops (the rest undecided)")
    certify.add_argument("--out", required=True, metavar="FILE", help="FILE.json or FILE.png (the paving)")



def _add_pose_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--pose",
        nargs="+",
        type=float,
        metavar="Q",
        help="the pose, e.g. X Y Z PHI for an SMG: lengths in the catalog file's length unit "
        "(mm for h4), the angle in DEGREES; default: the catalog's default pose",
    )

