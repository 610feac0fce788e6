"""The commands on one configuration, the catalog and one screw: ``analyze``, ``graph``, ``list``, ``screw``.

Each ``run_*`` takes the parsed arguments (:func:`screwkit.interface.cli_parser.get_parser`), prints
its answer (text, or JSON with ``--json``) and returns the exit status; :func:`screwkit.interface.cli.main`
dispatches to them and turns errors into exit statuses.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

from ..algebra.checks import MAX_RTOL, MIN_FLOAT_RTOL, MIN_LENGTH_SCALE
from ..algebra.screwvalue import Screw
from ..exceptions import ScrewkitError
from ..graphs.reduction import equivalent_twist_graph
from ..robots.catalog import list_mechanisms, load_mechanism
from ..robots.snapshot import load_snapshot
from ..robots.toml_fields import MAX_COORDINATE
from ._cli_io import UsageError, error_reason, json_text, print_text, shown_path, target_and_pose
from .report import analyze

__all__ = ["run_analyze", "run_graph", "run_list", "run_screw"]


def run_analyze(args: argparse.Namespace) -> int:
    """The main job; see ``screwkit analyze --help``.

    Parameters
    ----------
    args : argparse.Namespace
        From :func:`~screwkit.interface.cli_parser.get_parser`: ``mechanism``, ``pose``, ``rtol``,
        ``length_scale``, ``json``, ``latex``, ``no_superbracket`` and ``progress`` of ``screwkit
        analyze``.

    Returns
    -------
    int
        0, the report printed (text, JSON or LaTeX); a malformed option raises a usage error
        (status 2 in :func:`~screwkit.interface.cli.main`), an analysis error a
        :class:`~screwkit.exceptions.ScrewkitError` (status 1).

    Examples
    --------
    >>> from screwkit.interface.cli_parser import get_parser
    >>> args = get_parser().parse_args(["analyze", "h4", "--no-superbracket"])
    >>> run_analyze(args)  # doctest: +ELLIPSIS
    H4  (...h4.toml)
    ...
    0
    """
    if args.rtol is not None and not MIN_FLOAT_RTOL <= args.rtol <= MAX_RTOL:
        raise UsageError(
            f"screwkit analyze: error: --rtol expects a number in [{MIN_FLOAT_RTOL:g}, {MAX_RTOL:g}], "
            f"got {args.rtol:g}"
        )
    length = args.length_scale
    bounds = (MIN_LENGTH_SCALE, 1 / MIN_LENGTH_SCALE)
    if length is not None and not (math.isfinite(length) and bounds[0] <= length <= bounds[1]):
        raise UsageError(
            "screwkit analyze: error: --length-scale expects a positive length in the file's length unit, "
            f"in [{bounds[0]:g}, {bounds[1]:g}], got {length:g}"
        )
    if args.latex and args.no_superbracket:
        raise UsageError(
            "screwkit analyze: error: --latex prints the superbracket's conditions; drop --no-superbracket"
        )
    target, pose = target_and_pose(args)
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
        print_text(_latex(report))
    else:
        print_text(json_text(report.to_dict(), indent=2, ensure_ascii=False) if args.json else str(report))
    return 0



def _latex(report: Any) -> str:
    """The superbracket's conditions in LaTeX, or a LaTeX comment saying why there are none."""
    if report.superbracket is None:
        return f"% no superbracket conditions: {report.superbracket_note}"
    return str(report.superbracket.to_latex())



def _stage_printer(command: str) -> Any:
    """A progress callback that names each stage on stderr with the time since the start."""
    import time

    start = time.perf_counter()

    def show(stage: str) -> None:
        print(f"screwkit {command}: {time.perf_counter() - start:5.1f} s  {stage} ...", file=sys.stderr)

    return show



def run_graph(args: argparse.Namespace) -> int:
    """Export a twist graph; see ``screwkit graph --help``.

    Parameters
    ----------
    args : argparse.Namespace
        From :func:`~screwkit.interface.cli_parser.get_parser`: ``mechanism``, ``pose``, ``format``,
        ``equivalent`` and ``out`` of ``screwkit graph``.

    Returns
    -------
    int
        0, the graph printed or written to ``--out``; an unwritable ``--out`` raises a usage error.

    Examples
    --------
    >>> from screwkit.interface.cli_parser import get_parser
    >>> run_graph(get_parser().parse_args(["graph", "h4", "--format", "dot"]))  # doctest: +ELLIPSIS
    digraph "H4" {
    ...
      "base" -> "arm1" [label="A1 (R)", style=bold];
    ...
    0
    """
    from .export import graph_dot, graph_json, snapshot_text

    target, pose = target_and_pose(args)
    twist_graph = load_snapshot(target) if isinstance(target, str) else target.twist_graph(pose)
    if args.equivalent:
        twist_graph = equivalent_twist_graph(twist_graph)
    writers = {"dot": graph_dot, "json": graph_json, "toml": snapshot_text}
    text = writers[args.format](twist_graph)
    if args.out is None:
        print_text(text.rstrip("\n"))
        return 0
    try:
        Path(args.out).write_text(text, encoding="utf-8")
    except (OSError, ValueError) as err:  # ValueError: a NUL character in the path
        shown = f"--out {shown_path(args.out)}: cannot write: {error_reason(err)}"
        raise UsageError(f"screwkit graph: error: {shown}") from err
    return 0



def run_list(args: argparse.Namespace) -> int:
    """List the catalog; see ``screwkit list --help``.

    Parameters
    ----------
    args : argparse.Namespace
        From :func:`~screwkit.interface.cli_parser.get_parser`: ``json`` of ``screwkit list``.

    Returns
    -------
    int
        0, one line (or JSON entry) per catalog mechanism printed.

    Examples
    --------
    >>> from screwkit.interface.cli_parser import get_parser
    >>> import contextlib, io
    >>> with contextlib.redirect_stdout(io.StringIO()) as out:
    ...     status = run_list(get_parser().parse_args(["list"]))
    >>> status, "h4           H4           family four_limb, lengths in mm" in out.getvalue().splitlines()
    (0, True)
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
        print_text(json_text(entries, indent=2))
    else:
        for entry in entries:
            print_text(
                f"{entry['name']:<12} {entry['title']:<12} family {entry['family']}, lengths in "
                f"{entry['length_unit']}"
            )
    return 0



def run_screw(args: argparse.Namespace) -> int:
    """Describe one screw; see ``screwkit screw --help``.

    Parameters
    ----------
    args : argparse.Namespace
        From :func:`~screwkit.interface.cli_parser.get_parser`: ``revolute``, ``point``, ``prismatic``,
        ``plucker`` and ``json`` of ``screwkit screw``.

    Returns
    -------
    int
        0, the screw described; coordinates out of range raise a usage error.

    Examples
    --------
    >>> from screwkit.interface.cli_parser import get_parser
    >>> run_screw(get_parser().parse_args(["screw", "--prismatic", "0", "0", "2"]))
    screw (0, 0, 0; 0, 0, 2)  pitch inf  kind infinite pitch  direction (0, 0, 2)
    0
    """
    if args.point is not None and any(abs(v) > MAX_COORDINATE for v in args.point):
        raise UsageError(
            f"screwkit screw: error: --point expects coordinates up to {MAX_COORDINATE:g} in magnitude, "
            f"got {' '.join(map(str, args.point))}"
        )
    if args.plucker is not None:
        direction, moment = (max(abs(v) for v in part) for part in (args.plucker[:3], args.plucker[3:]))
        if direction > 0 and moment > MAX_COORDINATE * direction:  # an axis or pitch beyond 1e100
            raise UsageError(
                "screwkit screw: error: --plucker expects a moment at most "
                f"{MAX_COORDINATE:g} times the direction (the axis's distance and pitch in range), "
                f"got {' '.join(map(str, args.plucker))}"
            )
    if args.revolute is not None and args.point is None:
        raise UsageError("screwkit screw: error: --revolute needs --point X Y Z")
    given = [name for name in ("revolute", "prismatic") if getattr(args, name) is not None]
    option = f"--{given[0]}" if given else "--plucker"
    try:  # the screw is the command's whole input: whatever is refused in it is bad input (exit 2)
        if args.revolute is not None:
            screw = Screw.revolute(args.revolute, args.point)
        elif args.prismatic is not None:
            screw = Screw.prismatic(args.prismatic)
        else:
            screw = Screw(args.plucker)
        described = screw.to_dict()  # the zero screw has no pitch
    except ScrewkitError as err:
        raise UsageError(f"screwkit screw: error: {option}: {err}") from err
    if args.json:
        print_text(json_text(described))
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
    print_text(
        f"screw ({', '.join(coords[:3])}; {', '.join(coords[3:])})  pitch {pitch_text}  "
        f"kind {described['kind']}{axis}"
    )
    return 0



def _number(value: float) -> str:
    return "0" if value == 0 else f"{value:.6g}"

