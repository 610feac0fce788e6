"""The paving plot of a certificate: its boxes coloured free / singular / undecided / unreachable,
with the slice's singular loci drawn over them.

matplotlib is imported through :mod:`screwkit.interface._matplotlib` (the extra ``plot``).
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from ._matplotlib import Figure, Patch, PolyCollection
from .plot import KIND_COLOURS

__all__ = ["STATUS_COLOURS", "plot_certificate", "save_certificate_png"]

#: Colour of each box status.
STATUS_COLOURS = {"free": "#cfe8cf", "singular": "#e06666", "undecided": "#f6c343", "unreachable": "#bbbbbb"}


def plot_certificate(certificate: Any, *, ax: Any = None, loci: Iterable[Any] = ()) -> Any:
    """Draw a 2-D certificate's boxes and the loci over them.

    Parameters
    ----------
    certificate : Certificate
        Over exactly two ranges.
    ax : matplotlib.axes.Axes, optional
    loci : iterable of Locus
        Drawn over the boxes (the slice's, :func:`screwkit.analysis.loci.loci`).

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ScrewkitValueError
        If the certificate is not over two ranges.

    Examples
    --------
    >>> from screwkit.analysis.certify import certify
    >>> c = certify(load_mechanism("h4"), {"x": (0, 50), "y": (100, 150), "z": -800, "phi": 0}, resolution=25)
    >>> plot_certificate(c).get_xlabel()
    'x'
    """
    names = list(certificate.region)
    if len(names) != 2:
        raise ScrewkitValueError(f"Expected a certificate over two ranges to draw, got {names}.")
    if ax is None:
        ax = Figure(figsize=(7, 5.5)).subplots()
    lows, highs = certificate.lows, certificate.highs

    statuses = [b.status for b in certificate.boxes]
    quads = [
        [(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])]
        for lo, hi in zip(lows, highs, strict=True)
    ]
    colours = [STATUS_COLOURS[s] for s in statuses]
    ax.add_collection(PolyCollection(quads, facecolors=colours, edgecolors="#555555", linewidths=0.2))
    for locus in loci:
        points = np.asarray(locus.points, dtype=float).reshape(-1, 2)
        ax.plot(
            points[:, 0],
            points[:, 1],
            linestyle="none",
            marker=".",
            markersize=2,
            color=KIND_COLOURS.get(locus.kind, "black"),
            label=f"{locus.kind} locus",
        )
    (x_lo, x_hi), (y_lo, y_hi) = certificate.region[names[0]], certificate.region[names[1]]
    ax.set_xlim(x_lo, x_hi)
    ax.set_ylim(y_lo, y_hi)
    ax.set_xlabel(names[0])
    ax.set_ylabel(names[1])
    handles = [
        Patch(facecolor=STATUS_COLOURS[s], edgecolor="#555555", label=f"{s} ({certificate.fractions[s]:.1%})")
        for s in STATUS_COLOURS
    ]
    ax.legend(handles=handles + ax.get_legend_handles_labels()[0], loc="upper right", fontsize=7)
    fixed = ", ".join(f"{k} = {v:g}" for k, v in certificate.fixed.items())
    ax.set_title(
        f"{certificate.mechanism}: certified paving" + (f" at {fixed}" if fixed else ""), fontsize=10
    )
    return ax


def save_certificate_png(certificate: Any, path: str | Path, *, loci: Iterable[Any] = ()) -> Path:
    """Draw :func:`plot_certificate` off screen and write it as a PNG.

    Parameters
    ----------
    certificate : Certificate
    path : str or pathlib.Path
    loci : iterable of Locus

    Returns
    -------
    pathlib.Path
        The file written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from screwkit.analysis.certify import certify
    >>> c = certify(load_mechanism("h4"), {"x": (0, 50), "y": (100, 150), "z": -800, "phi": 0}, resolution=25)
    >>> save_certificate_png(c, pathlib.Path(tempfile.mkdtemp()) / "c.png").suffix
    '.png'
    """
    target = Path(path)
    figure = Figure(figsize=(7, 5.5))
    plot_certificate(certificate, ax=figure.subplots(), loci=loci)
    figure.savefig(target, dpi=120, bbox_inches="tight")
    return target
