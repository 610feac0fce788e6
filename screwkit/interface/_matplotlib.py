"""matplotlib for the plots (:mod:`screwkit.interface.plot`, :mod:`screwkit.interface.plot_diagrams`).

matplotlib is an optional dependency (the extra ``plot``: ``pip install "screwkit[plot]"``), imported
here and nowhere else; ``import screwkit`` never imports this module. Without matplotlib, importing
it (hence either plotting module) raises :class:`~screwkit.exceptions.MissingDependencyError` naming
the extra. :func:`new_axes` gives the axes a plot draws into.
"""

from __future__ import annotations

from typing import Any

from ..exceptions import MissingDependencyError, ScrewkitTypeError

try:
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import BoundaryNorm, ListedColormap, TwoSlopeNorm, to_rgba
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import FancyArrowPatch, Patch
    from matplotlib.ticker import MaxNLocator
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
except ImportError as err:  # pragma: no cover - exercised in a subprocess without matplotlib
    raise MissingDependencyError(
        "screwkit's plots (screwkit.interface.plot, screwkit.interface.plot_diagrams) need matplotlib, "
        'which is not installed: install the optional extra `plot` (pip install "screwkit[plot]").'
    ) from err

__all__ = [
    "BoundaryNorm",
    "FancyArrowPatch",
    "Figure",
    "Line2D",
    "ListedColormap",
    "MaxNLocator",
    "Patch",
    "Poly3DCollection",
    "PolyCollection",
    "TwoSlopeNorm",
    "new_axes",
    "plt",
    "to_rgba",
]


def new_axes(ax: Any, three_d: bool = False) -> Any:
    """``ax``, checked to be 3-D if ``three_d``, or new axes in a new figure (3-D if ``three_d``)."""
    if ax is None:
        if three_d:
            return plt.figure(figsize=(7, 7)).add_subplot(projection="3d")
        return plt.subplots(figsize=(7, 5.5))[1]
    if three_d and getattr(ax, "name", "") != "3d":
        raise ScrewkitTypeError(
            f"Expected `ax` to be 3-D axes (projection='3d'), got {type(ax).__name__} "
            f"with projection {getattr(ax, 'name', '?')!r}."
        )
    return ax
