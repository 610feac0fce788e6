"""Paper 004's actuation singularity surfaces (Sec. 5.3, Figs. 14-16): ``|A| = 0`` at one rotation.

The zero set of ``|A|`` (Eq. 12, Table 2: :func:`screwkit.papers.paper_004.det_A_closed_form`) over
a region at a fixed rotation ``φ``, triangulated by marching tetrahedra
(:func:`screwkit.analysis.isosurface.zero_surface`); drawn by
:func:`screwkit.interface.plot.plot_singularity_surfaces`.

Source: paper 004 (Wu, Bai, Caro, JMR 10(5), 2018) (docs/papers.md).

Examples
--------
>>> from screwkit.papers.paper_004_table4 import TABLE_4_CONE
>>> surface = actuation_singularity_surface(load_mechanism("quattro"), np.pi / 2, TABLE_4_CONE, grid=8)
>>> surface.triangles.shape[1:]
(3, 3)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..analysis.isosurface import zero_surface
from ..analysis.loci import SingularSurface
from ..exceptions import ScrewkitValueError
from .paper_004 import _four_limb_parameters, det_A_closed_form
from .paper_004_table4 import Region, _region_grid

__all__ = ["MAX_SURFACE_GRID", "actuation_singularity_surface"]

#: The largest grid of :func:`actuation_singularity_surface`: its marching tetrahedra hold the whole
#: grid's cells at once (≈ 0.6 GB at 64, measured 2 GB at 100 and 16 GB at 201 on the Quattro).
MAX_SURFACE_GRID = 64

# --------------------------------------------------------------------------------------------------
# Actuation singularity surfaces (paper 004, Sec. 5.3, Figs. 14-16)
# --------------------------------------------------------------------------------------------------


def actuation_singularity_surface(
    mechanism: Any,
    phi: float,
    region: Region | None = None,
    *,
    grid: int = 32,
    working_mode: Any = None,
) -> SingularSurface:
    """Paper 004's actuation singularity locus at a rotation ``φ`` as a surface (Sec. 5.3, Figs. 14-16).

    The paper draws the poses where ``ζ = |cos σ| ≤ ε`` (Eq. 15, ``ε = 0.001``) at a fixed ``φ``
    inside the operational workspace. Here: the zero set of ``|A|`` (Eq. 12 / Table 2,
    :func:`det_A_closed_form`), where ``ζ = 0`` (``|A| = 2r |w_I × w_II| cos σ`` for the articulated
    platforms, ``-h/(2π) |w_I × w_II| cos σ`` for the screw pair) or ``w_I × w_II = 0``. ``|A|``
    is sampled on a ``grid``³ grid over the region's box (the family's inverse kinematics; poses out
    of reach left out), its zero set triangulated by marching tetrahedra and every vertex moved onto
    it by bisection along its grid edge (:mod:`screwkit.analysis.isosurface`); the triangles whose centroid
    lies in the region are kept, so the surface's edge follows the region's boundary to within a
    grid cell. A thin sheet between two grid points of equal sign is missed: refine ``grid``.

    Parameters
    ----------
    mechanism : Mechanism
        A four-limb catalog mechanism.
    phi : float
        The rotation of the platform, radians.
    region : Region, optional
        Default: the box of the mechanism's ``[workspace]``.
    grid : int
        Grid points per axis (at least 2).
    working_mode : sequence of 4 int, optional
        Signs of ``h_i`` (Eq. 8); default the paper's ``(-1, -1, -1, -1)``.

    Returns
    -------
    SingularSurface
        Kind ``"actuation"``, its ``triangles`` on ``|A| = 0`` (Eq. 12, Table 2) in the robot's length
        unit, their vertices as ``points``, ``fixed = {"phi": phi}``, the region searched (the
        triangles whose centroids lie inside it are kept).

    Raises
    ------
    ScrewkitValueError
        Not a four-limb mechanism, a non-finite ``phi``, ``grid`` below 2.
    ScrewkitTypeError
        ``region`` is not a Region.

    Examples
    --------
    The Quattro has no actuation singularity in its (assumed) workspace at ``φ = 0`` (Table 4's
    ``η_min = 0.380``); at ``φ = 90°`` it has (Sec. 5.1, Fig. 14b):

    >>> from screwkit.papers.paper_004_table4 import TABLE_4_CONE
    >>> quattro = load_mechanism("quattro")
    >>> len(actuation_singularity_surface(quattro, 0.0, TABLE_4_CONE, grid=12).triangles)
    0
    >>> actuation_singularity_surface(quattro, np.pi / 2, TABLE_4_CONE, grid=12).area > 0
    True
    """

    _four_limb_parameters(mechanism)  # a four-limb mechanism, or the message naming the family
    if isinstance(grid, int | np.integer) and not isinstance(grid, bool) and grid > MAX_SURFACE_GRID:
        raise ScrewkitValueError(
            f"Expected `grid` to be an integer in 2..{MAX_SURFACE_GRID} for a surface, got {grid!r}."
        )
    region, mode, axes = _region_grid(mechanism, region, phi, working_mode, grid=grid)
    angle = float(phi)

    def det_a(points: np.ndarray) -> np.ndarray:
        poses = np.column_stack([points, np.full(len(points), angle)])
        ok = mechanism.reachable(poses)
        values = np.full(len(points), np.nan)
        if ok.any():
            config: Any = mechanism.at(poses[ok], working_mode=mode).configuration
            values[ok] = det_A_closed_form(config)
        return values

    points = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    triangles = zero_surface(axes, det_a(points).reshape((int(grid),) * 3), det_a)
    inside = region.contains(triangles.mean(axis=1)) if len(triangles) else np.zeros(0, dtype=bool)
    kept = triangles[inside]
    vertices = np.unique(kept.reshape(-1, 3), axis=0)
    return SingularSurface(
        "actuation", None, ("x", "y", "z"), vertices, np.full(len(vertices), np.nan), kept, {"phi": angle},
        region, mechanism.name,
    )
