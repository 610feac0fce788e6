"""The commands over the pose space: ``map``, ``path``, ``certify`` and ``table4``.

Each ``run_*`` takes the parsed arguments (:func:`screwkit.interface.cli_parser.get_parser`), checks
them against the caps below before computing (never a hang or an allocation beyond memory), calls
the public API (:mod:`screwkit.analysis.workspace`, :func:`screwkit.papers.paper_004_table4.table_4`),
prints its answer and returns the exit status; :func:`screwkit.interface.cli.main` dispatches to them.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
from typing import Any

import numpy as np

from ..exceptions import ScrewkitError
from ._cli_io import (
    UsageError,
    check_coordinate,
    check_writable,
    error_reason,
    json_text,
    mechanism_over_poses,
    pose_coordinates,
    pose_values,
    print_text,
    shown_path,
)

__all__ = ["MAX_MAP_POSES", "MAX_PATH_SAMPLES", "run_certify", "run_map", "run_path", "run_table4"]

#: Caps of the workspace commands (never a hang or an allocation beyond memory): poses in a map,
#: samples along a path, grid points per axis and refinement rounds of ``table4``.
MAX_MAP_POSES = 2 * 10**6  # the README's 10^6-pose map fits; 2e6 poses take ~15 min at 2,000 poses/s
MAX_PATH_SAMPLES = 10**4


def run_map(args: argparse.Namespace) -> int:
    """Map a quantity over a 2-D slice; see ``screwkit map --help``.

    Parameters
    ----------
    args : argparse.Namespace
        From :func:`~screwkit.interface.cli_parser.get_parser`: ``mechanism``, ``quantity``, one option
        per pose coordinate, ``grid``, ``out``, ``chunk`` and ``no_progress`` of ``screwkit map``.

    Returns
    -------
    int
        0, the map written to ``--out`` and summarised (region, extremes and where they
        occur); options beyond the caps (:data:`MAX_MAP_POSES`) raise a usage error before computing.

    Examples
    --------
    >>> from screwkit.interface.cli_parser import get_parser
    >>> import tempfile, os
    >>> out = os.path.join(tempfile.mkdtemp(), "m.json")
    >>> run_map(get_parser().parse_args(["map", "h4", "--quantity", "verdict", "--z", "-900", "-600", "2",
    ...     "--phi", "-10", "10", "2", "--out", out]))  # doctest: +ELLIPSIS
    verdict over H4: z in [-900, -600] mm (2 values) x phi in [-10, 10] deg (2 values), x = 0 mm, y = 0 mm
      verdicts of the reachable poses (codes in the JSON's `codes`): regular 100.0%
      loci in the slice: none found (no singular curve or reach boundary between the samples)
      reachable 100.0%; written to ...
    0
    """
    from ..analysis.quantities import quantity as checked_quantity
    from ..analysis.workspace import grid_map

    try:
        quantity = checked_quantity(args.quantity)
    except ScrewkitError as err:
        raise UsageError(f"screwkit map: error: --quantity: {err}") from err
    if not args.out.lower().endswith((".png", ".npz", ".json")):
        raise UsageError(f"screwkit map: error: --out expects FILE.npz, .json or .png, got {args.out!r}")
    _check_out("map", args.out, ".npz or .json")
    if not 2 <= args.grid <= MAX_MAP_POSES // 2:
        raise UsageError(
            f"screwkit map: error: --grid expects an integer in 2..{MAX_MAP_POSES // 2}, got {args.grid}"
        )
    if args.chunk is not None and args.chunk < 1:
        raise UsageError(f"screwkit map: error: --chunk expects a positive integer, got {args.chunk}")
    mechanism = mechanism_over_poses("map", args.mechanism)
    axes, fixed = [], {}
    for name in pose_coordinates():
        values = getattr(args, name)
        if values is None:
            continue
        if name not in mechanism.pose_names:
            raise UsageError(
                f"screwkit map: error: --{name}: {mechanism.name} has pose coordinates "
                f"{list(mechanism.pose_names)}"
            )
        if len(values) not in (1, 2, 3) or not all(math.isfinite(v) for v in values):
            raise UsageError(
                f"screwkit map: error: --{name} expects LO HI [N] or one value, got "
                f"{' '.join(map(str, values))}"
            )
        for value in values[:2]:
            check_coordinate("screwkit map", f"--{name}", mechanism, name, value)
        if len(values) == 1:
            fixed[name] = values[0]
        else:
            count = args.grid if len(values) == 2 else values[2]
            if not 2 <= count <= MAX_MAP_POSES // 2 or count != int(count):
                raise UsageError(
                    f"screwkit map: error: --{name}: N must be an integer in 2..{MAX_MAP_POSES // 2}, "
                    f"got {count:g}"
                )
            if not values[0] < values[1]:
                raise UsageError(
                    f"screwkit map: error: --{name}: expected LO < HI, got {values[0]:g} and {values[1]:g}"
                )
            axes.append((name, values[0], values[1], int(count)))
    if len(axes) != 2:
        raise UsageError(
            "screwkit map: error: expected exactly two ranges (LO HI [N]) among "
            f"--{' --'.join(mechanism.pose_names)}, "
            f"got {len(axes)}"
        )
    if axes[0][3] * axes[1][3] > MAX_MAP_POSES:
        raise UsageError(
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
    def write() -> None:
        if args.out.lower().endswith(".png"):
            from .plot import save_map_png

            save_map_png(result, args.out)
        else:
            result.save(args.out)

    _write("map", args.out, write)

    def where(pose: dict[str, float]) -> str:
        return ", ".join(f"{k} = {v:g} {result.units.get(k, '')}".rstrip() for k, v in pose.items()) or "-"

    lines = [f"{quantity} over {result.region}"]
    if result.meaning:
        lines.append(f"  {result.meaning}")
    singular_loci = [locus for locus in result.loci if locus.kind != "reach"]
    if result.quantity == "verdict" and result.reachable.any():  # codes mean kinds: say which were found
        from ..analysis.quantities import verdict_name

        codes, counts = np.unique(result.values[result.reachable], return_counts=True)
        if singular_loci and codes.tolist() == [0]:  # the samples missed the curves: no "regular 100 %"
            lines.append(
                f"  sampled poses: all {counts.sum()} reachable samples read regular, "
                "but the slice holds the singular loci below (between the samples)"
            )
        else:
            found = ", ".join(
                f"{verdict_name(int(c))} {n / counts.sum():.1%}" for c, n in zip(codes, counts, strict=True)
            )
            lines.append(f"  verdicts of the reachable poses (codes in the JSON's `codes`): {found}")
    for kind in result.inside:
        lines.append(f"  the whole slice lies inside the {kind} singular set")
    if result.loci:
        lines.append(f"  loci in the slice ({len(singular_loci)} singular; points in the JSON's `loci`):")
        lines += [f"    {locus}" for locus in result.loci]
    else:
        lines.append(
            "  loci in the slice: none found (no singular curve or reach boundary between the samples)"
        )
    if not result.reachable.any():
        lines.append("  no pose of the map is reachable: no minimum or maximum")
    elif result.quantity != "verdict":  # a verdict map's codes are categories: their shares are above
        lines.append(f"  minimum {result.minimum:g} at {where(result.argmin)}")
        lines.append(f"  maximum {result.maximum:g} at {where(result.argmax)}")
    lines.append(f"  reachable {result.reachable.mean():.1%}; written to {args.out}")
    print_text("\n".join(lines))
    return 0



def _check_out(command: str, out: str, other: str) -> None:
    """``--out`` writable, and a ``.png`` only with matplotlib (before the computation, not after it)."""
    check_writable(f"screwkit {command}", "--out", out)
    if out.lower().endswith(".png") and importlib.util.find_spec("matplotlib") is None:
        raise UsageError(
            f"screwkit {command}: error: --out FILE.png needs matplotlib, which is not installed: install "
            f'the optional extra `plot` (pip install "screwkit[plot]"), or write {other}'
        )


def _write(command: str, out: str, write: Any) -> None:
    """Run ``write()``, its I/O errors as a usage error naming ``--out``."""
    try:
        write()
    except (OSError, ValueError) as err:
        shown = f"--out {shown_path(out)}: cannot write: {error_reason(err)}"
        raise UsageError(f"screwkit {command}: error: {shown}") from err


def run_path(args: argparse.Namespace) -> int:
    """Check a straight path; see ``screwkit path --help``.

    Parameters
    ----------
    args : argparse.Namespace
        From :func:`~screwkit.interface.cli_parser.get_parser`: ``mechanism``, ``start`` (``--from``),
        ``end`` (``--to``), ``samples``, ``certify`` and ``json`` of ``screwkit path``.

    Returns
    -------
    int
        0, the check printed (the crossings found, or "singularity-free"); more samples than
        :data:`MAX_PATH_SAMPLES` raise a usage error.

    Examples
    --------
    >>> from screwkit.interface.cli_parser import get_parser
    >>> run_path(get_parser().parse_args(["path", "h4", "--from", "0", "0", "-800", "0",
    ...     "--to", "0", "0", "-700", "20", "--samples", "20"]))
    singularity-free (20 samples, refined)
    0
    """
    from ..analysis.paths import check_path

    if not 2 <= args.samples <= MAX_PATH_SAMPLES:
        raise UsageError(
            f"screwkit path: error: --samples expects an integer in 2..{MAX_PATH_SAMPLES}, got {args.samples}"
        )
    mechanism = mechanism_over_poses("path", args.mechanism)
    for option, values in (("--from", args.start), ("--to", args.end)):
        pose_values("screwkit path", option, mechanism, values)
    result = check_path(
        mechanism, args.start, args.end, samples=args.samples, angles="deg", certify=bool(args.certify)
    )
    print_text(json_text(result.to_dict(), indent=2, ensure_ascii=False) if args.json else str(result))
    return 0



def run_certify(args: argparse.Namespace) -> int:
    """Certify a box of pose space; see ``screwkit certify --help``.

    Parameters
    ----------
    args : argparse.Namespace
        From :func:`~screwkit.interface.cli_parser.get_parser`: ``mechanism``, one option per pose
        coordinate (``LO HI`` or one value, angles in degrees), ``resolution``, ``kinds``,
        ``max_boxes`` and ``out`` of ``screwkit certify``.

    Returns
    -------
    int
        0, the certificate written to ``--out`` (``.json``, or ``.png``: the paving with the loci
        over it, two ranges only) and summarised.

    Examples
    --------
    >>> from screwkit.interface.cli_parser import get_parser
    >>> import tempfile, os
    >>> out = os.path.join(tempfile.mkdtemp(), "c.json")
    >>> run_certify(get_parser().parse_args(["certify", "quattro", "--x", "100", "200", "--y", "100", "200",
    ...     "--z", "-750", "--phi", "0", "--out", out]))  # doctest: +ELLIPSIS
    Quattro: x in [100, 200], y in [100, 200], z = -750, phi = 0 (deg)
      certified free of constraint, actuation, serial singularities: free ...
    0
    """
    from ..analysis.certify import certify

    out = args.out.lower()
    if not out.endswith((".json", ".png")):
        raise UsageError(f"screwkit certify: error: --out expects FILE.json or FILE.png, got {args.out!r}")
    _check_out("certify", args.out, ".json")
    mechanism = mechanism_over_poses("certify", args.mechanism)
    region: dict[str, object] = {}
    for name in pose_coordinates():
        values = getattr(args, name)
        if values is None:
            continue
        if name not in mechanism.pose_names:
            raise UsageError(
                f"screwkit certify: error: --{name}: {mechanism.name} has pose coordinates "
                f"{list(mechanism.pose_names)}"
            )
        if len(values) not in (1, 2) or not all(math.isfinite(v) for v in values):
            raise UsageError(
                f"screwkit certify: error: --{name} expects LO HI or one value, got "
                f"{' '.join(map(str, values))}"
            )
        for value in values:
            check_coordinate("screwkit certify", f"--{name}", mechanism, name, value)
        region[name] = values[0] if len(values) == 1 else (values[0], values[1])
    ranges = [n for n, v in region.items() if isinstance(v, tuple)]
    if out.endswith(".png") and len(ranges) != 2:
        raise UsageError(
            f"screwkit certify: error: --out FILE.png draws two ranges (LO HI), got {len(ranges)}: "
            "write .json"
        )
    try:
        result = certify(
            mechanism,
            region,
            kinds=tuple(args.kinds),
            resolution=args.resolution,
            angles="deg",
            max_boxes=args.max_boxes,
        )
    except ScrewkitError as err:
        raise UsageError(f"screwkit certify: error: {err}") from err
    def write() -> None:
        if out.endswith(".png"):
            from ..analysis.loci import loci
            from .plot_certify import save_certificate_png

            (x_name, (x_lo, x_hi)), (y_name, (y_lo, y_hi)) = result.region.items()
            found = loci(mechanism, x=(x_name, x_lo, x_hi, 101), y=(y_name, y_lo, y_hi, 101),
                         fixed=result.fixed, angles="deg")
            save_certificate_png(result, args.out, loci=found)
        else:
            with open(args.out, "w") as handle:
                handle.write(result.to_json(indent=1))

    _write("certify", args.out, write)
    print_text(f"{result}\n  written to {args.out}")
    return 0


def run_table4(args: argparse.Namespace) -> int:
    """Paper 004's Table 4 regenerated; see ``screwkit table4 --help``.

    Parameters
    ----------
    args : argparse.Namespace
        From :func:`~screwkit.interface.cli_parser.get_parser`: ``grid``, ``refine``, ``robot`` and
        ``json`` of ``screwkit table4``.

    Returns
    -------
    int
        0, the table printed with the paper's values beside ours; an unknown robot or a grid or
        refinement out of range raises a usage error.

    Examples
    --------
    >>> from screwkit.interface.cli_parser import get_parser
    >>> run_table4(get_parser().parse_args(["table4", "--robot", "veloce", "--grid", "11", "--refine", "0"]))
    ... # doctest: +ELLIPSIS
    paper 004, Table 4: ...
    Veloce       0 deg  cone     0.287 ...
    0
    """
    from ..papers.paper_004_table4 import MAX_GRID, MAX_REFINE, TABLE_4, table_4

    known = sorted({row[1] for row in TABLE_4})
    for name in args.robot or []:
        if name not in known:
            raise UsageError(f"screwkit table4: error: unknown robot {name!r}; expected one of {known}.")
    for option, value, least, most in (
        ("--grid", args.grid, 2, MAX_GRID), ("--refine", args.refine, 0, MAX_REFINE)
    ):
        if not least <= value <= most:
            raise UsageError(f"screwkit table4: error: expected {option} in {least}..{most}, got {value}.")
    robots = None if args.robot is None else list(dict.fromkeys(args.robot))
    rows = table_4(grid=args.grid, refine=args.refine, robots=robots)
    if args.json:
        print_text(json_text([row.to_dict() for row in rows], indent=2))
        return 0
    print_text(
        f"paper 004, Table 4: min/max LTI (Eq. 16) over the workspace; ours: {args.grid}^3 grid + "
        f"{args.refine} rounds of refinement (screwkit.papers.paper_004_table4.index_extremes)"
    )
    print_text(f"{'robot':<10} {'phi':>5}      {'region':<8} {'min: paper':>10} {'ours':>7} {'diff':>7}"
          f"   {'max: paper':>10} {'ours':>7} {'diff':>7}")
    notes = []
    for row in rows:
        region = "eq_19" if row.region.startswith("super") else "cone"
        print_text(
            f"{row.robot:<10} {row.phi_deg:>5.0f} deg  {region:<8} {row.paper_min:>10.3f} "
            f"{row.ours.minimum:>7.3f} {row.ours.minimum - row.paper_min:>+7.3f}   {row.paper_max:>10.3f} "
            f"{row.ours.maximum:>7.3f} {row.ours.maximum - row.paper_max:>+7.3f}"
        )
        notes += [f"  {row.robot} {row.phi_deg:g} deg {key}: {text}" for key, text in row.notes.items()]
    print_text("regions: cone = the assumed workspace (paper 004's Fig. 6 is missing), eq_19 = Eq. (19)")
    if notes:
        print_text("where ours differs from the paper's by more than 0.002:")
        for note in notes:
            print_text(note)
    return 0

