"""The ``screwkit`` command line: a thin layer over the public API (design.md §7).

``main(argv=None) -> int`` returns the exit status: 0 success, 1 analysis error (e.g. a pose out of
reach), 2 usage error (unknown mechanism, malformed arguments). Errors are one line on stderr.
One ``run_*`` function per command; each prints text by default and JSON with ``--json``.

Commands
--------
``screwkit analyze NAME|FILE.toml [--pose X Y Z PHI] [--rtol R] [--length-scale L] [--json]``
    The whole analysis (:func:`screwkit.interface.report.analyze`): twist graph, wrench systems, wrench
    diagram, superbracket, conditions, verdict. Lengths in the catalog file's unit, angle in degrees.
``screwkit graph NAME|FILE.toml [--pose ...] [--equivalent] [--format dot|json|toml] [--out FILE]``
    The twist graph (or its equivalent graph) as Graphviz DOT, JSON or a snapshot file.
``screwkit list [--json]``
    The catalog.
``screwkit screw (--revolute SX SY SZ --point X Y Z | --prismatic DX DY DZ | --plucker C*6)``
    Describe one screw.
``screwkit table4 [--grid N] [--refine K] [--robot NAME ...] [--json]``
    Paper 004's Table 4 regenerated (:func:`screwkit.analysis.indices.table_4`): each min/max LTI beside
    ours, the difference, and why they differ where they do.
``screwkit map NAME|FILE.toml --quantity Q --Z LO HI [N] --PHI LO HI [N] [--X V ...] [--grid N] --out F``
    A map of a quantity over a 2-D slice (:func:`screwkit.analysis.workspace.grid_map`): two pose
    coordinates given as ranges, the others fixed (default: the default pose); writes .png, .npz or
    .json and prints the region, minimum and maximum and where they occur.
``screwkit path NAME|FILE.toml --from Q... --to Q... [--samples N] [--json]``
    Check a straight path for singularities (:func:`screwkit.analysis.workspace.check_path`).

Examples
--------
>>> main(["screw", "--revolute", "0", "0", "1", "--point", "1", "0", "0"])
screw (0, 0, 1; 0, -1, 0)  pitch 0  kind zero pitch  axis through (1, 0, 0) along (0, 0, 1)
0
"""

from __future__ import annotations

import argparse
import gc
import importlib.util
import math
import os
import re
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NoReturn

import numpy as np

from .. import __version__
from ..algebra.checks import MAX_RTOL, MIN_FLOAT_RTOL, MIN_LENGTH_SCALE
from ..algebra.screwvalue import Screw
from ..exceptions import ScrewkitError, ScrewkitValueError
from ..graphs.reduction import equivalent_twist_graph
from ..robots.catalog import list_mechanisms, load_mechanism, unknown_mechanism
from ..robots.snapshot import load_snapshot
from ..robots.toml_fields import MAX_COORDINATE, degrees_to_radians, file_kind, load_toml
from .report import analyze

__all__ = [
    "console",
    "get_parser",
    "main",
    "run_analyze",
    "run_graph",
    "run_list",
    "run_map",
    "run_path",
    "run_screw",
    "run_table4",
]


class _UsageError(Exception):
    """A malformed command line (exit status 2)."""


#: What the command line takes for a negative number: any decimal form ``float`` reads after a minus
#: sign (argparse's own pattern misses exponents, so ``--pose 0 0 -7.5e2 0`` read ``-7.5e2`` as an
#: option), digit groups (``-1_000``), and ``-inf``/``-nan`` (refused then as not finite, not as an
#: unknown option). No option of screwkit's reads as a number.
_NEGATIVE_NUMBER = re.compile(
    r"^-((\d[\d_]*\.?[\d_]*|\.\d[\d_]*)([eE][+-]?\d[\d_]*)?|inf|infinity|nan)$", re.IGNORECASE
)
#: Caps of the workspace commands (never a hang or an allocation beyond memory): poses in a map,
#: samples along a path, grid points per axis and refinement rounds of ``table4``.
MAX_MAP_POSES = 2 * 10**6  # the README's 10^6-pose map fits; 2e6 poses take ~15 min at 2,000 poses/s
MAX_PATH_SAMPLES = 10**4


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
        "(screwkit.analysis.indices.index_extremes); the paper's value, ours, the difference and its cause.",
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


def _pose_coordinates() -> list[str]:
    """Every family's pose coordinates (the map command takes one option per coordinate)."""
    from ..robots.families import families

    return families().pose_names()


class _MapQuantities:
    """The quantities a map can show (:data:`screwkit.analysis.workspace.QUANTITIES`), listed in
    ``map --help``: read when the help is shown, so that parsing a command does not import
    :mod:`screwkit.analysis.workspace`."""

    def __str__(self) -> str:
        from ..analysis.workspace import QUANTITIES

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
    for name in _pose_coordinates():
        mapping.add_argument(
            f"--{name}",
            nargs="+",
            type=float,
            metavar="V",
            help=f"{name}: LO HI [N] for an axis, or one value",
        )
    mapping.add_argument(
        "--grid", type=int, default=50, metavar="N", help="values per axis given as LO HI (default 50)"
    )
    mapping.add_argument("--out", required=True, metavar="FILE", help="FILE.png, FILE.npz or FILE.json")
    mapping.add_argument(
        "--chunk", type=int, default=None, metavar="C", help="poses per chunk (bounded memory)"
    )
    mapping.add_argument("--no-progress", action="store_true", help="no progress line on stderr")
    path = commands.add_parser(
        "path",
        help="check a straight path in pose space for singularities (the first crossing, refined)",
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


def _add_pose_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--pose",
        nargs="+",
        type=float,
        metavar="Q",
        help="the pose, e.g. X Y Z PHI for an SMG: lengths in the catalog file's length unit "
        "(mm for h4), the angle in DEGREES; default: the catalog's default pose",
    )


def _number(value: float) -> str:
    return "0" if value == 0 else f"{value:.6g}"


def run_screw(args: argparse.Namespace) -> int:
    """Describe one screw; see ``screwkit screw --help``.

    Examples
    --------
    >>> run_screw(get_parser().parse_args(["screw", "--prismatic", "0", "0", "2"]))
    screw (0, 0, 0; 0, 0, 2)  pitch inf  kind infinite pitch  direction (0, 0, 2)
    0
    """
    if args.point is not None and any(abs(v) > MAX_COORDINATE for v in args.point):
        raise _UsageError(
            f"screwkit screw: error: --point expects coordinates up to {MAX_COORDINATE:g} in magnitude, "
            f"got {' '.join(map(str, args.point))}"
        )
    if args.plucker is not None:
        direction, moment = (max(abs(v) for v in part) for part in (args.plucker[:3], args.plucker[3:]))
        if direction > 0 and moment > MAX_COORDINATE * direction:  # an axis or pitch beyond 1e100
            raise _UsageError(
                "screwkit screw: error: --plucker expects a moment at most "
                f"{MAX_COORDINATE:g} times the direction (the axis's distance and pitch in range), "
                f"got {' '.join(map(str, args.plucker))}"
            )
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
        _print(_dumps(described))
        return 0
    coords = [_number(v) for v in screw.coords]
    pitch = described["pitch"]
    pitch_text = pitch if isinstance(pitch, str) else _number(pitch)
    axis = (
        f"  axis through ({', '.join(_number(v + 0.0) for v in described['point'])}) along "
        f"({', '.join(_number(v + 0.0) for v in described['direction'])})"
        if described.get("point") is not None
        else f"  direction ({', '.join(_number(v + 0.0) for v in described['direction'])})"
        if described.get("direction") is not None
        else ""
    )
    _print(
        f"screw ({', '.join(coords[:3])}; {', '.join(coords[3:])})  pitch {pitch_text}  "
        f"kind {described['kind']}{axis}"
    )
    return 0


def _pose(args: argparse.Namespace, mechanism: Any) -> Any:
    """The --pose in the API's units (the family's angles from degrees to radians)."""
    if args.pose is None:
        return None
    values = _pose_values(f"screwkit {args.command}", "--pose", mechanism, args.pose)
    angles = set(mechanism.angle_names)
    pairs = zip(mechanism.pose_names, values, strict=True)
    return np.array([math.radians(v) if n in angles else v for n, v in pairs])


def _pose_values(command: str, option: str, mechanism: Any, values: Sequence[float]) -> list[float]:
    """A pose given on the command line (lengths in the file's unit, angles in degrees), checked:
    one finite number per pose coordinate, lengths up to :data:`~screwkit.robots.toml_fields.MAX_COORDINATE`,
    angles up to :data:`~screwkit.robots.toml_fields.MAX_ANGLE_DEGREES`."""
    names = mechanism.pose_names
    if len(values) != len(names) or not all(math.isfinite(v) for v in values):
        expected = " ".join(n.upper() for n in names)
        raise _UsageError(
            f"{command}: error: {option} expects {len(names)} finite numbers ({expected}), "
            f"got {' '.join(map(str, values))}"
        )
    for name, value in zip(names, values, strict=True):
        _check_coordinate(command, option, mechanism, name, value)
    return list(values)


def _check_coordinate(command: str, option: str, mechanism: Any, name: str, value: float) -> None:
    """One pose coordinate from the command line: an angle in degrees up to MAX_ANGLE_DEGREES, a
    length up to MAX_COORDINATE (beyond, squares of coordinates overflow in the inverse kinematics)."""
    if name in mechanism.angle_names:
        try:
            degrees_to_radians(value)
        except ScrewkitValueError as err:
            raise _UsageError(f"{command}: error: {option}: {name}: {err}") from err
    elif not abs(value) <= MAX_COORDINATE:
        raise _UsageError(
            f"{command}: error: {option}: {name}: expected a length of at most {MAX_COORDINATE:g} "
            f"{mechanism.length_unit} in magnitude, got {value:g}"
        )


def _target_and_pose(args: argparse.Namespace) -> tuple[Any, Any]:
    """The mechanism (a :class:`Mechanism`, or a snapshot's path) and the pose of ``analyze``/``graph``."""
    if args.mechanism.endswith(".toml") and _toml_kind(args.mechanism) == "snapshot":
        if args.pose is not None:
            raise _UsageError(
                f"screwkit {args.command}: error: {args.mechanism} is a snapshot (one configuration); "
                "--pose does not apply"
            )
        return args.mechanism, None
    if not args.mechanism.endswith(".toml") and args.mechanism.lower() not in list_mechanisms():
        raise _UsageError(f"screwkit {args.command}: error: {unknown_mechanism(args.mechanism)}")
    mechanism = load_mechanism(args.mechanism)  # a malformed file is an analysis error (exit 1)
    return mechanism, _pose(args, mechanism)


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
    if args.rtol is not None and not MIN_FLOAT_RTOL <= args.rtol <= MAX_RTOL:
        raise _UsageError(
            f"screwkit analyze: error: --rtol expects a number in [{MIN_FLOAT_RTOL:g}, {MAX_RTOL:g}], "
            f"got {args.rtol:g}"
        )
    length = args.length_scale
    bounds = (MIN_LENGTH_SCALE, 1 / MIN_LENGTH_SCALE)
    if length is not None and not (math.isfinite(length) and bounds[0] <= length <= bounds[1]):
        raise _UsageError(
            "screwkit analyze: error: --length-scale expects a positive length in the file's length unit, "
            f"in [{bounds[0]:g}, {bounds[1]:g}], got {length:g}"
        )
    if args.latex and args.no_superbracket:
        raise _UsageError(
            "screwkit analyze: error: --latex prints the superbracket's conditions; drop --no-superbracket"
        )
    target, pose = _target_and_pose(args)
    shown = sys.stderr.isatty() if args.progress is None else args.progress
    report = analyze(
        target,
        pose,
        rtol=args.rtol,
        length_scale=args.length_scale,
        superbracket=not args.no_superbracket,
        progress=_stage_printer(args.command) if shown else None,
    )
    if args.latex:
        _print(_latex(report))
    else:
        _print(_dumps(report.to_dict(), indent=2, ensure_ascii=False) if args.json else str(report))
    return 0


def _latex(report: Any) -> str:
    """The superbracket's conditions in LaTeX, or a LaTeX comment saying why there are none."""
    if report.superbracket is None:
        return f"% no superbracket conditions: {report.superbracket_note}"
    from ..gca.conditions import latex

    result = report.superbracket
    return latex(result.simplification.factored, result.conditions, result.diagram.line_text())


def run_graph(args: argparse.Namespace) -> int:
    """Export a twist graph; see ``screwkit graph --help``.

    Examples
    --------
    >>> run_graph(get_parser().parse_args(["graph", "h4", "--format", "dot"]))  # doctest: +ELLIPSIS
    digraph "H4" {
    ...
      "base" -> "arm1" [label="A1 (R)", style=bold];
    ...
    0
    """
    from .export import graph_dot, graph_json, snapshot_text

    target, pose = _target_and_pose(args)
    twist_graph = load_snapshot(target) if isinstance(target, str) else target.twist_graph(pose)
    if args.equivalent:
        twist_graph = equivalent_twist_graph(twist_graph)
    writers = {"dot": graph_dot, "json": graph_json, "toml": snapshot_text}
    text = writers[args.format](twist_graph)
    if args.out is None:
        _print(text.rstrip("\n"))
        return 0
    try:
        Path(args.out).write_text(text, encoding="utf-8")
    except (OSError, ValueError) as err:  # ValueError: a NUL character in the path
        shown = f"--out {_shown(args.out)}: cannot write: {_reason(err)}"
        raise _UsageError(f"screwkit graph: error: {shown}") from err
    return 0


def _stage_printer(command: str) -> Any:
    """A progress callback that names each stage on stderr with the time since the start."""
    import time

    start = time.perf_counter()

    def show(stage: str) -> None:
        print(f"screwkit {command}: {time.perf_counter() - start:5.1f} s  {stage} ...", file=sys.stderr)

    return show


def _toml_kind(path: str) -> Any:
    return file_kind(load_toml(path))


def _dumps(value: Any, **options: Any) -> str:
    """JSON text (the json module loads for the commands that print JSON)."""
    import json

    return json.dumps(value, **options)


def _print(text: str) -> None:
    """Print, falling back to escapes where stdout cannot encode a character (ḟ, χ̇, θ̇ on an
    ASCII or Latin-1 terminal) instead of failing."""
    try:
        print(text)
    except UnicodeEncodeError:
        encoding = getattr(sys.stdout, "encoding", None) or "ascii"
        print(text.encode(encoding, errors="backslashreplace").decode(encoding))


def _catalog_mechanism(command: str, name: str) -> Any:
    """A catalog mechanism by name or file (a snapshot has no pose space to map)."""
    if name.endswith(".toml"):
        if _toml_kind(name) == "snapshot":
            raise _UsageError(
                f"screwkit {command}: error: {name} is a snapshot (one configuration); no poses to vary"
            )
    elif name.lower() not in list_mechanisms():
        raise _UsageError(f"screwkit {command}: error: {unknown_mechanism(name)}")
    return load_mechanism(name)


def run_map(args: argparse.Namespace) -> int:
    """Map a quantity over a 2-D slice; see ``screwkit map --help``.

    Examples
    --------
    >>> import tempfile, os
    >>> out = os.path.join(tempfile.mkdtemp(), "m.json")
    >>> main(["map", "h4", "--quantity", "verdict", "--z", "-900", "-600", "2", "--phi", "-10", "10", "2",
    ...       "--out", out])  # doctest: +ELLIPSIS
    verdict over H4: z in [-900, -600] mm (2 values) x phi in [-10, 10] deg (2 values), x = 0 mm, y = 0 mm
      verdicts of the reachable poses (codes in the JSON's `codes`): regular 100.0%
      minimum 0 at ...
    0
    """
    from ..analysis.workspace import _quantity, grid_map

    try:
        quantity = _quantity(args.quantity)
    except ScrewkitError as err:
        raise _UsageError(f"screwkit map: error: --quantity: {err}") from err
    if not args.out.lower().endswith((".png", ".npz", ".json")):
        raise _UsageError(f"screwkit map: error: --out expects FILE.npz, .json or .png, got {args.out!r}")
    _check_writable("screwkit map", "--out", args.out)
    if args.out.lower().endswith(".png") and importlib.util.find_spec("matplotlib") is None:
        raise _UsageError(  # before the computation, not after it
            "screwkit map: error: --out FILE.png needs matplotlib, which is not installed: install the "
            'optional extra `plot` (pip install "screwkit[plot]"), or write .npz or .json'
        )
    if not 2 <= args.grid <= MAX_MAP_POSES // 2:
        raise _UsageError(
            f"screwkit map: error: --grid expects an integer in 2..{MAX_MAP_POSES // 2}, got {args.grid}"
        )
    if args.chunk is not None and args.chunk < 1:
        raise _UsageError(f"screwkit map: error: --chunk expects a positive integer, got {args.chunk}")
    mechanism = _catalog_mechanism("map", args.mechanism)
    axes, fixed = [], {}
    for name in _pose_coordinates():
        values = getattr(args, name)
        if values is None:
            continue
        if name not in mechanism.pose_names:
            raise _UsageError(
                f"screwkit map: error: --{name}: {mechanism.name} has pose coordinates "
                f"{list(mechanism.pose_names)}"
            )
        if len(values) not in (1, 2, 3) or not all(math.isfinite(v) for v in values):
            raise _UsageError(
                f"screwkit map: error: --{name} expects LO HI [N] or one value, got "
                f"{' '.join(map(str, values))}"
            )
        for value in values[:2]:
            _check_coordinate("screwkit map", f"--{name}", mechanism, name, value)
        if len(values) == 1:
            fixed[name] = values[0]
        else:
            count = args.grid if len(values) == 2 else values[2]
            if not 2 <= count <= MAX_MAP_POSES // 2 or count != int(count):
                raise _UsageError(
                    f"screwkit map: error: --{name}: N must be an integer in 2..{MAX_MAP_POSES // 2}, "
                    f"got {count:g}"
                )
            if not values[0] < values[1]:
                raise _UsageError(
                    f"screwkit map: error: --{name}: expected LO < HI, got {values[0]:g} and {values[1]:g}"
                )
            axes.append((name, values[0], values[1], int(count)))
    if len(axes) != 2:
        raise _UsageError(
            "screwkit map: error: expected exactly two ranges (LO HI [N]) among "
            f"--{' --'.join(mechanism.pose_names)}, "
            f"got {len(axes)}"
        )
    if axes[0][3] * axes[1][3] > MAX_MAP_POSES:
        raise _UsageError(
            f"screwkit map: error: expected at most {MAX_MAP_POSES:,} poses in a map, got "
            f"{axes[0][3]:,} x {axes[1][3]:,} (--{axes[0][0]}, --{axes[1][0]}; --grid)"
        )
    result = grid_map(
        mechanism,
        quantity,
        x=axes[0],
        y=axes[1],
        fixed=fixed,
        chunk=args.chunk,
        progress=False if args.no_progress else None,
        angles="deg",
    )
    try:
        result.save(args.out)
    except (OSError, ValueError) as err:
        shown = f"--out {_shown(args.out)}: cannot write: {_reason(err)}"
        raise _UsageError(f"screwkit map: error: {shown}") from err

    def where(pose: dict[str, float]) -> str:
        return ", ".join(f"{k} = {v:g}" for k, v in pose.items()) or "-"

    lines = [f"{quantity} over {result.region}"]
    if result.meaning:
        lines.append(f"  {result.meaning}")
    if result.quantity == "verdict" and result.reachable.any():  # codes mean kinds: say which were found
        from ..analysis.workspace import verdict_name

        codes, counts = np.unique(result.values[result.reachable], return_counts=True)
        found = ", ".join(
            f"{verdict_name(int(c))} {n / counts.sum():.1%}" for c, n in zip(codes, counts, strict=True)
        )
        lines.append(f"  verdicts of the reachable poses (codes in the JSON's `codes`): {found}")
    if result.reachable.any():
        lines.append(f"  minimum {result.minimum:g} at {where(result.argmin)}")
        lines.append(f"  maximum {result.maximum:g} at {where(result.argmax)}")
    else:
        lines.append("  no pose of the map is reachable: no minimum or maximum")
    lines.append(f"  reachable {result.reachable.mean():.1%}; written to {args.out}")
    _print("\n".join(lines))
    return 0


def _reason(err: BaseException) -> str:
    """The reason of an OSError (its strerror), or the message of another error."""
    return str(getattr(err, "strerror", None) or err)


def _check_writable(command: str, option: str, path: str) -> None:
    """Refuse an output path whose folder does not exist (before a long computation, not after)."""
    folder = os.path.dirname(os.path.abspath(path)) if "\0" not in path else ""
    if not os.path.isdir(folder):
        raise _UsageError(f"{command}: error: {option} {_shown(path)}: expected a file in an existing folder")
    if os.path.isdir(path):
        raise _UsageError(f"{command}: error: {option} {_shown(path)}: expected a file, got a folder")


def _shown(path: str) -> str:
    """A path as a message shows it: as given, or quoted with escapes if it holds control characters."""
    return path if path.isprintable() else repr(path)


def run_path(args: argparse.Namespace) -> int:
    """Check a straight path; see ``screwkit path --help``.

    Examples
    --------
    >>> main(["path", "h4", "--from", "0", "0", "-800", "0", "--to", "0", "0", "-700", "20",
    ...       "--samples", "20"])
    singularity-free (20 samples, refined)
    0
    """
    from ..analysis.workspace import check_path

    if not 2 <= args.samples <= MAX_PATH_SAMPLES:
        raise _UsageError(
            f"screwkit path: error: --samples expects an integer in 2..{MAX_PATH_SAMPLES}, got {args.samples}"
        )
    mechanism = _catalog_mechanism("path", args.mechanism)
    for option, values in (("--from", args.start), ("--to", args.end)):
        _pose_values("screwkit path", option, mechanism, values)
    result = check_path(mechanism, args.start, args.end, samples=args.samples, angles="deg")
    _print(_dumps(result.to_dict(), indent=2, ensure_ascii=False) if args.json else str(result))
    return 0


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
        _print(_dumps(entries, indent=2))
    else:
        for entry in entries:
            _print(
                f"{entry['name']:<12} {entry['title']:<12} family {entry['family']}, lengths in "
                f"{entry['length_unit']}"
            )
    return 0


def run_table4(args: argparse.Namespace) -> int:
    """Paper 004's Table 4 regenerated; see ``screwkit table4 --help``.

    Examples
    --------
    >>> run_table4(get_parser().parse_args(["table4", "--robot", "veloce", "--grid", "11", "--refine", "0"]))
    ... # doctest: +ELLIPSIS
    paper 004, Table 4: ...
    Veloce       0 deg  cone     0.287 ...
    0
    """
    from ..analysis.indices import MAX_GRID, MAX_REFINE, TABLE_4, table_4

    known = sorted({row[1] for row in TABLE_4})
    for name in args.robot or []:
        if name not in known:
            raise _UsageError(f"screwkit table4: error: unknown robot {name!r}; expected one of {known}.")
    for option, value, least, most in (
        ("--grid", args.grid, 2, MAX_GRID), ("--refine", args.refine, 0, MAX_REFINE)
    ):
        if not least <= value <= most:
            raise _UsageError(f"screwkit table4: error: expected {option} in {least}..{most}, got {value}.")
    robots = None if args.robot is None else list(dict.fromkeys(args.robot))
    rows = table_4(grid=args.grid, refine=args.refine, robots=robots)
    if args.json:
        _print(_dumps([row.to_dict() for row in rows], indent=2))
        return 0
    _print(
        f"paper 004, Table 4: min/max LTI (Eq. 16) over the workspace; ours: {args.grid}^3 grid + "
        f"{args.refine} rounds of refinement (screwkit.analysis.indices.index_extremes)"
    )
    _print(f"{'robot':<10} {'phi':>5}      {'region':<8} {'min: paper':>10} {'ours':>7} {'diff':>7}"
          f"   {'max: paper':>10} {'ours':>7} {'diff':>7}")
    notes = []
    for row in rows:
        region = "eq_19" if row.region.startswith("super") else "cone"
        _print(
            f"{row.robot:<10} {row.phi_deg:>5.0f} deg  {region:<8} {row.paper_min:>10.3f} "
            f"{row.ours.minimum:>7.3f} {row.ours.minimum - row.paper_min:>+7.3f}   {row.paper_max:>10.3f} "
            f"{row.ours.maximum:>7.3f} {row.ours.maximum - row.paper_max:>+7.3f}"
        )
        notes += [f"  {row.robot} {row.phi_deg:g} deg {key}: {text}" for key, text in row.notes.items()]
    _print("regions: cone = the assumed workspace (paper 004's Fig. 6 is missing), eq_19 = Eq. (19)")
    if notes:
        _print("where ours differs from the paper's by more than 0.002:")
        for note in notes:
            _print(note)
    return 0


def console() -> int:
    """The ``screwkit`` command (and ``python -m screwkit``): :func:`main`, its objects then frozen
    for the exit.

    At exit the interpreter's cyclic garbage collector traverses every object left, numpy's, sympy's
    and networkx's included, several times while the modules are torn down: ≈ 0.1–0.15 s, longer than a
    whole analysis of a small robot. :func:`gc.freeze` moves them out of its reach first; modules are
    still torn down, streams flushed and exit handlers (``atexit``) run as usual. The price: objects
    left in unreachable reference cycles are not finalised at exit (their ``__del__`` does not run;
    an H4 analysis leaves ≈ 800 such objects, numpy's and sympy's, none holding a resource). Every
    command writes and closes its output files before it returns (``with`` blocks), so nothing it
    produces depends on a finaliser; a full collection instead would cost ≈ 35 ms. Returns the exit
    status (the console script passes it to :func:`sys.exit`).

    Examples
    --------
    >>> import subprocess, sys
    >>> done = subprocess.run([sys.executable, "-m", "screwkit", "list"], capture_output=True, text=True)
    >>> done.returncode, done.stdout.split()[:2]
    (0, ['h4', 'H4'])
    """
    status = main()
    gc.freeze()
    return status


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
        runners = {
            "analyze": run_analyze,
            "graph": run_graph,
            "list": run_list,
            "map": run_map,
            "path": run_path,
            "screw": run_screw,
            "table4": run_table4,
        }
        status = runners[args.command](args)
        sys.stdout.flush()  # a full disk or a closed pipe shows here, not as a traceback at exit
        return status
    except _UsageError as err:
        print(str(err), file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader closed the pipe (`screwkit graph h4 | head`): not an error
        sys.stdout = open(os.devnull, "w")  # the final flush stays silent
        return 0
    except ScrewkitError as err:
        message = " ".join(str(err).split())
        source = getattr(args, "mechanism", None)
        if source and source.endswith(".toml") and source not in message:
            message = f"{source}: {message}"  # an analysis error of a file names the file
        print(f"screwkit {args.command}: error: {message}", file=sys.stderr)
        return 1
    except OSError as err:  # writing the output (standard output on a full disk, ...)
        sys.stdout = open(os.devnull, "w")  # the final flush stays silent
        print(f"screwkit {args.command}: error: cannot write the output: {_reason(err)}", file=sys.stderr)
        return 1
