"""The zero set of a scalar field sampled on a 3-D grid, as triangles.

Marching tetrahedra (Doi & Koide, "An efficient method of triangulating equi-valued surfaces by using
tetrahedral cells", IEICE Trans. E74(1), 1991): each grid cell is cut into six tetrahedra around its
diagonal from corner ``(0, 0, 0)`` to ``(1, 1, 1)`` (neighbouring cells then cut their shared faces
the same way, so the surface has no cracks); a tetrahedron whose corners' values change sign holds
one triangle (one corner apart from three) or two (two and two), with vertices on the edges whose
ends differ in sign. Unlike marching cubes this has no ambiguous cases. A vertex is placed by linear
interpolation on its edge, then, if the field can be evaluated anywhere (``field``), moved onto the
zero set by bisection along the edge, each edge once. Corners where the field is NaN (e.g. poses out
of reach) drop the tetrahedra that use them.

Examples
--------
>>> axes = [np.linspace(-1.0, 1.0, 5)] * 3
>>> grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
>>> triangles = zero_surface(axes, grid[..., 2] - 0.1)  # the plane z = 0.1
>>> triangles.shape[1:], bool(np.allclose(triangles[..., 2], 0.1))
((3, 3), True)
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["zero_surface"]

Array = np.ndarray

# corner c of a cell is at offset (c & 1, c >> 1 & 1, c >> 2 & 1); six tetrahedra around diagonal 0-7
_CORNERS = np.array([[c & 1, (c >> 1) & 1, (c >> 2) & 1] for c in range(8)])
_TETRAHEDRA = np.array([[0, 1, 3, 7], [0, 3, 2, 7], [0, 2, 6, 7], [0, 6, 4, 7], [0, 4, 5, 7], [0, 5, 1, 7]])


def _cells(shape: tuple[int, int, int]) -> Array:
    """Flat grid indices of the four corners of every tetrahedron, ``(6 (nx-1)(ny-1)(nz-1), 4)``."""
    nx, ny, nz = shape
    i, j, k = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1), np.arange(nz - 1), indexing="ij")
    origin = np.stack([i.ravel(), j.ravel(), k.ravel()], axis=-1)  # (cells, 3)
    corners = origin[:, None, :] + _CORNERS[None, :, :]  # (cells, 8, 3)
    flat = np.ravel_multi_index((corners[..., 0], corners[..., 1], corners[..., 2]), shape)  # (cells, 8)
    return flat[:, _TETRAHEDRA].reshape(-1, 4)


def _crossing_edges(tetrahedra: Array, positive: Array) -> Array:
    """Per tetrahedron whose corners change sign, the edges (pairs of grid indices) of its triangles:
    ``(t, 3, 2)`` with the one-against-three and the two-against-two cases (two triangles each)."""
    count = positive.sum(axis=1)
    edges = []
    lone = (count == 1) | (count == 3)
    if lone.any():
        signs, corners = positive[lone], tetrahedra[lone]
        odd = np.where(count[lone] == 1, np.argmax(signs, axis=1), np.argmin(signs, axis=1))
        others = np.array([[j for j in range(4) if j != i] for i in range(4)])[odd]  # (t, 3)
        apex = corners[np.arange(len(odd)), odd]
        rest = np.take_along_axis(corners, others, axis=1)
        edges.append(np.stack([np.repeat(apex[:, None], 3, axis=1), rest], axis=-1))
    pairs = count == 2
    if pairs.any():
        order = np.argsort(~positive[pairs], axis=1, kind="stable")  # two positive corners first
        corners = np.take_along_axis(tetrahedra[pairs], order, axis=1)
        p1, p2, n1, n2 = corners.T
        edges.append(np.stack([np.stack([p1, p1, p2], -1), np.stack([n1, n2, n2], -1)], axis=-1))
        edges.append(np.stack([np.stack([p1, p2, p2], -1), np.stack([n1, n2, n1], -1)], axis=-1))
    return np.concatenate(edges) if edges else np.zeros((0, 3, 2), dtype=int)


def zero_surface(
    axes: list[Array] | tuple[Array, Array, Array],
    values: Array,
    field: Callable[[Array], Array] | None = None,
    *,
    steps: int = 40,
) -> Array:
    """Triangles ``(m, 3, 3)`` of the surface ``values = 0`` over the grid ``axes`` (three increasing
    1-D arrays; ``values`` of shape ``(len(axes[0]), len(axes[1]), len(axes[2]))``, NaN allowed).

    ``field(points (k, 3)) -> (k,)``, if given, is the function sampled; each vertex is then moved
    onto its zero by ``steps`` bisections of its edge (kept where the field is NaN between the ends).

    Parameters
    ----------
    axes : sequence of 3 numpy.ndarray
        The grid's increasing coordinates along each axis.
    values : numpy.ndarray, shape (n0, n1, n2)
        The field at the grid points (NaN: undefined there).
    field : callable, optional
        The field itself, to bisect each vertex onto the zero set.
    steps : int
        Bisections per vertex.

    Returns
    -------
    numpy.ndarray, shape (m, 3, 3)
        The triangles' vertices.

    Examples
    --------
    >>> axes = [np.linspace(0.0, 1.0, 3)] * 3
    >>> grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    >>> len(zero_surface(axes, grid[..., 0] - 2.0))  # no zero in the box
    0
    """
    shape = values.shape
    points = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    flat = values.ravel()
    tetrahedra = _cells(shape)
    corner_values = flat[tetrahedra]
    usable = np.all(np.isfinite(corner_values), axis=1)
    edges = _crossing_edges(tetrahedra[usable], corner_values[usable] > 0)
    if not len(edges):
        return np.zeros((0, 3, 3))
    unique, inverse = np.unique(np.sort(edges.reshape(-1, 2), axis=1), axis=0, return_inverse=True)
    low, high = points[unique[:, 0]], points[unique[:, 1]]
    f_low, f_high = flat[unique[:, 0]], flat[unique[:, 1]]
    vertices = low + (f_low / (f_low - f_high))[:, None] * (high - low)
    if field is not None:
        start, end = np.zeros(len(unique)), np.ones(len(unique))  # f(low) and f(high) differ in sign
        low_positive = f_low > 0
        defined = np.ones(len(unique), dtype=bool)
        for _ in range(steps):
            middle = 0.5 * (start + end)
            value = field(low + middle[:, None] * (high - low))
            defined &= np.isfinite(value)
            same = (value > 0) == low_positive
            start, end = np.where(same, middle, start), np.where(same, end, middle)
        bisected = low + (0.5 * (start + end))[:, None] * (high - low)
        vertices = np.where(defined[:, None], bisected, vertices)
    return vertices[inverse.ravel()].reshape(-1, 3, 3)
