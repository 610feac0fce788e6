"""The ``screwkit`` command line: a thin layer over the public API (docs/architecture.md §7).

``main(argv=None) -> int`` returns the exit status, the same rule for every command: 0 success; 2 bad
input (a malformed command line, an unknown mechanism, or a value the analysis refuses as an argument:
a plain :class:`~screwkit.exceptions.ScrewkitValueError` or :class:`~screwkit.exceptions.ScrewkitTypeError`,
e.g. a condition index out of range, a quantity the mechanism does not have, a zero screw direction);
1 the analysis could not be done (a pose out of reach, a degenerate geometry, a malformed or unreadable
file, an output that cannot be written). Errors are one line on stderr.
One ``run_*`` function per command; each prints text by default and JSON with ``--json``: the parser
in :mod:`screwkit.interface.cli_parser`, the commands on one configuration in
:mod:`screwkit.interface.cli_mechanism`, those over the pose space in :mod:`screwkit.interface.cli_workspace`.

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
    Paper 004's Table 4 regenerated (:func:`screwkit.papers.paper_004_table4.table_4`): each min/max
    LTI beside ours, the difference, and why they differ where they do.
``screwkit map NAME|FILE.toml --quantity Q --Z LO HI [N] --PHI LO HI [N] [--X V ...] [--grid N] --out F``
    A map of a quantity over a 2-D slice (:func:`screwkit.analysis.workspace.grid_map`): two pose
    coordinates given as ranges, the others fixed (default: the default pose); writes .png, .npz or
    .json and prints the region, minimum and maximum and where they occur.
``screwkit path NAME|FILE.toml --from Q... --to Q... [--samples N] [--certify] [--json]``
    Check a straight path for singularities (:func:`screwkit.analysis.paths.check_path`).
``screwkit certify NAME|FILE.toml --X LO HI --Y LO HI [--Z V|LO HI] [--PHI V|LO HI] --out F``
    Prove a box of poses free of singularities or singular with a witness
    (:func:`screwkit.analysis.certify.certify`).

Examples
--------
>>> main(["screw", "--revolute", "0", "0", "1", "--point", "1", "0", "0"])
screw (0, 0, 1; 0, -1, 0)  pitch 0  kind zero pitch  axis through (1, 0, 0) along (0, 0, 1)
0
"""

from __future__ import annotations

import gc
import os
import sys
from collections.abc import Sequence

from ..exceptions import ScrewkitError, ScrewkitTypeError, ScrewkitValueError
from ._cli_io import UsageError, error_reason
from .cli_mechanism import run_analyze, run_graph, run_list, run_screw
from .cli_parser import get_parser
from .cli_workspace import run_certify, run_map, run_path, run_table4

__all__ = ["BAD_INPUT", "console", "main"]

#: The errors that refuse an argument's type or value (exit status 2, as a usage error); their
#: subclasses say the analysis could not be done (a pose out of reach, a degenerate geometry, a
#: malformed file: exit status 1).
BAD_INPUT = (ScrewkitValueError, ScrewkitTypeError)


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
    produces depends on a finaliser; a full collection instead would cost ≈ 35 ms.

    Returns
    -------
    int
        The exit status of :func:`main` (the console script passes it to :func:`sys.exit`).

    Examples
    --------
    >>> import subprocess, sys
    >>> done = subprocess.run([sys.executable, "-m", "screwkit", "list"], capture_output=True, text=True)
    >>> done.returncode, "h4" in done.stdout.split()
    (0, True)
    """
    status = main()
    gc.freeze()
    return status



def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 1 analysis error, 2 usage error or bad input).

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments after the program's name; default ``sys.argv[1:]``.

    Returns
    -------
    int
        0 on success (also when no command is given: the help is printed; and when the reader of
        standard output closed the pipe), 1 for an analysis error or an output that cannot be
        written, 2 for a malformed command line or a value refused as an argument (:data:`BAD_INPUT`);
        each error is one line on standard error.
        ``--version`` and ``--help`` exit (:class:`SystemExit`, status 0) as argparse does.

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
            "certify": run_certify,
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
    except UsageError as err:
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
        return 2 if type(err) in BAD_INPUT else 1
    except OSError as err:  # writing the output (standard output on a full disk, ...)
        sys.stdout = open(os.devnull, "w")  # the final flush stays silent
        reason = error_reason(err)
        print(f"screwkit {args.command}: error: cannot write the output: {reason}", file=sys.stderr)
        return 1
