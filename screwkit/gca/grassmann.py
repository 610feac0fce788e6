"""Grassmann line geometry: the class of a set of lines by Merlet's names, with its witness.

Merlet (1989) classifies the linear varieties spanned by lines (the linear spaces of Plücker
vectors they span, intersected with the Klein quadric of lines) by rank and by the geometry of that
intersection; a parallel manipulator whose wrench lines fall in a variety of rank below 6 is
singular, and the class says *how*. :func:`grassmann_class` decides the class of any set of lines,
finite or at infinity, and returns the geometric object that witnesses it.

The algorithm uses only linear algebra on Plücker vectors (direction first, ``(s; r × s)``; a line
at infinity ``(0; n)``; :mod:`screwkit.algebra.screw`) and the Klein form
``K(x, y) = x_s·y_m + x_m·y_s`` (the reciprocal product; ``K(x, x) = 0`` exactly for lines, and
``K(x, y) = 0`` for two lines exactly when they meet, Pottmann & Wallner 2001, §2.1):

* the lines are expressed about their own reference point with moments over their characteristic
  length (:func:`screwkit.algebra.reference_frame.scaled_frame`), so every decision is the same in
  any frame and any unit of length;
* the rank ``r`` of the span ``V`` is the number of singular values above ``rtol`` times the
  largest; its *reciprocal complement* ``V^⊥`` (the screws reciprocal to every line, of dimension
  ``6 − r``) is the null space of the Klein form on ``V``;
* rank 3: the Klein form restricted to ``V`` is 0 (all lines pairwise meet: a star, "3a", or a
  planar field, "3b", told apart by the point on every line or the plane holding every line), of
  rank 2 (two flat pencils with a common line, "3c") or of rank 3 (a regulus, "3d");
* rank 4: the lines of ``V`` are those meeting every line of ``V^⊥``; the Klein form on the
  2-dimensional ``V^⊥`` is 0 (``V^⊥`` is a flat pencil: the lines in its plane or through its
  point, "4b"), indefinite (two real skew directrices, the hyperbolic congruence "4a"), of rank 1
  (one double directrix, the parabolic congruence "4c") or definite (no real directrix, the
  elliptic congruence "4d");
* rank 5: ``V^⊥`` is one screw ``c``; the lines are the linear complex ``{L : c ∘ L = 0}``, singular
  ("5b": every line meets the line ``c``) when ``c`` is itself a line (``K(c, c) = 0``, pitch 0 or
  infinite pitch, i.e. an axis at infinity), general ("5a", axis and pitch of ``c``) otherwise.

Every zero test on the Klein form compares with ``rtol`` the eigenvalues of its matrix on an
orthonormal basis of unit scaled rows (they lie in ``[−1, 1]``).

References
----------
.. [1] J.-P. Merlet, "Singular configurations of parallel manipulators and Grassmann geometry",
   The International Journal of Robotics Research 8(5), pp. 45–56, 1989.
.. [2] J.-P. Merlet, *Parallel Robots*, 2nd ed., Springer, 2006, ch. 6 (§6.2, the varieties of
   rank 1 to 5).
.. [3] H. Pottmann and J. Wallner, *Computational Line Geometry*, Springer, 2001, §2.1 (Plücker
   coordinates, the Klein quadric) and §3.1 (linear complexes and congruences).

Examples
--------
>>> lines = [[0, 0, 1, 0, 0, 0], [1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0]]   # three lines through 0
>>> found = grassmann_class(lines)
>>> found.name, found.witness["point"].tolist()
('3a', [0.0, 0.0, 0.0, 1.0])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np

from ..algebra.backend import DEFAULT_RTOL, as_array
from ..algebra.checks import checked_rtol
from ..algebra.reference_frame import scaled_frame
from ..exceptions import ScrewkitValueError

__all__ = ["CLASS_DESCRIPTIONS", "GrassmannClass", "grassmann_class"]

Array = np.ndarray

#: Merlet's names of the varieties and what each says about the lines (Merlet 1989, Fig. 5;
#: Merlet 2006, §6.2).
CLASS_DESCRIPTIONS: Mapping[str, str] = MappingProxyType(
    {
        "1": "one line",
        "2": "two lines",
        "3a": "a star: every line passes through one point",
        "3b": "a planar field: every line lies in one plane",
        "3c": "two flat pencils (in two planes, about two points) sharing one line",
        "3d": "a regulus: the lines of one ruling of a hyperboloid, all meeting three transversals",
        "4a": "a hyperbolic congruence: every line meets two skew lines",
        "4b": "a degenerate congruence: every line lies in one plane or passes through one point of it",
        "4c": "a parabolic congruence: every line meets one line (a double directrix)",
        "4d": "an elliptic congruence: the lines of two linear complexes with no real common directrix",
        "5a": "a general linear complex: every line is reciprocal to one screw of non-zero finite pitch",
        "5b": "a singular linear complex: every line meets one line",
        "6": "six independent lines (no singularity)",
    }
)

_KLEIN = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])


@dataclass(frozen=True, eq=False)
class GrassmannClass:
    """The Grassmann-geometry class of a set of lines (:func:`grassmann_class`).

    Attributes
    ----------
    name : str
        Merlet's name: ``"1"``, ``"2"``, ``"3a"`` … ``"3d"``, ``"4a"`` … ``"4d"``, ``"5a"``,
        ``"5b"`` or ``"6"``.
    rank : int
        The dimension of the lines' span (6 for independent lines).
    witness : Mapping[str, numpy.ndarray or float]
        The geometric object that makes the class, in the lines' coordinates: ``"point"`` (a
        projective point ``(x, y, z, w)``, w = 1 when finite, 0 at infinity with a unit
        direction), ``"plane"`` (``(n, d)`` with ``n·x + d = 0``, unit ``n``; ``(0, 0, 0, 1)`` is
        the plane at infinity), ``"line"`` / ``"lines"`` (Plücker vectors ``(s; r × s)`` with a
        unit direction, or ``(0; n)`` with a unit ``n`` at infinity), ``"points"`` /
        ``"planes"`` (3c), ``"transversals"`` (3d), ``"axis"`` and ``"pitch"`` (5a),
        ``"complexes"`` (4d: two screws whose common lines are the congruence).
    description : str
        What the class says about the lines (:data:`CLASS_DESCRIPTIONS`).
    """

    name: str
    rank: int
    witness: Mapping[str, Any] = field(default_factory=dict)
    description: str = ""

    def __post_init__(self) -> None:
        frozen = {}
        for key, value in dict(self.witness).items():
            if isinstance(value, np.ndarray):
                value = value.copy()
                value.setflags(write=False)
            frozen[key] = value
        object.__setattr__(self, "witness", MappingProxyType(frozen))
        if not self.description:
            object.__setattr__(self, "description", CLASS_DESCRIPTIONS[self.name])

    @property
    def is_singular(self) -> bool:
        """Whether the lines are dependent (rank below 6).

        Returns
        -------
        bool

        Examples
        --------
        >>> grassmann_class([[0, 0, 1, 0, 0, 0]]).is_singular
        True
        """
        return self.rank < 6

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready mapping: name, rank, description and the witness as lists of floats.

        Returns
        -------
        dict

        Examples
        --------
        >>> grassmann_class([[0, 0, 1, 0, 0, 0]]).to_dict()["witness"]
        {'line': [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]}
        """
        witness = {
            key: (np.asarray(value, dtype=float) + 0.0).tolist() for key, value in self.witness.items()
        }
        return {"name": self.name, "rank": self.rank, "description": self.description, "witness": witness}

    def __str__(self) -> str:
        parts = [f"Grassmann class {self.name} (rank {self.rank}): {self.description}"]
        for key, value in self.witness.items():
            parts.append(f"  {key}: {_describe(key, value)}")
        return "\n".join(parts)


def _describe(key: str, value: Any) -> str:
    """One witness entry in words (points and planes at infinity said so)."""
    array = np.asarray(value, dtype=float)
    if array.ndim == 0:
        return f"{float(array):.6g}"
    if array.ndim == 2:
        return "; ".join(_describe(key, row) for row in array)
    numbers = ", ".join(f"{x:.6g}" for x in array + 0.0)
    if array.shape == (4,) and key.startswith("point"):
        return f"at infinity, direction ({numbers})" if array[3] == 0 else f"({numbers})"
    if array.shape == (4,) and key.startswith("plane"):
        return "the plane at infinity" if not array[:3].any() else f"({numbers})"
    if array.shape == (6,) and not array[:3].any():
        return f"at infinity ({numbers})"
    return f"({numbers})"


def grassmann_class(lines: Any, *, rtol: float = DEFAULT_RTOL) -> GrassmannClass:
    """The Grassmann-geometry class of a set of lines (Merlet 1989) and its witness.

    Parameters
    ----------
    lines : array_like, shape (n, 6)
        Plücker vectors of lines, direction first: ``(s; r × s)`` for a finite line, ``(0; n)`` for
        a line at infinity (a pure couple). Any non-zero multiple is the same line.
    rtol : float, default 1e-9
        Relative tolerance of every rank and zero decision (on unit rows in the lines' own scaled
        frame, so independent of frame and unit).

    Returns
    -------
    GrassmannClass
        ``.name`` by Merlet's names, ``.rank``, ``.witness`` and ``.description``.

    Raises
    ------
    ScrewkitValueError
        If ``lines`` is not a non-empty ``(n, 6)`` array of finite numbers, a row is zero or a row
        is not a line (a screw of non-zero finite pitch).

    Examples
    --------
    Five lines meeting the z axis span the singular complex of that axis:

    >>> rng = np.random.default_rng(0)
    >>> feet = np.c_[np.zeros((5, 2)), rng.normal(size=5)]      # points on the z axis
    >>> s = rng.normal(size=(5, 3))
    >>> found = grassmann_class(np.c_[s, np.cross(feet, s)])
    >>> found.name, found.witness["line"].round(9).tolist()
    ('5b', [0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    """
    rows = as_array(lines, "lines", (6,))
    tol = checked_rtol(rtol)
    if rows.ndim != 2 or len(rows) == 0:
        raise ScrewkitValueError(f"Expected `lines` to have shape (n, 6) with n >= 1, got {rows.shape}.")
    norms = np.linalg.norm(rows, axis=1)
    if not np.all(norms > 0):
        raise ScrewkitValueError(
            f"Expected `lines` to hold non-zero rows, got zero rows at {np.flatnonzero(norms == 0).tolist()}."
        )
    point, length, scaled = scaled_frame(rows)
    assert scaled is not None
    pitch_like = np.abs(np.einsum("ij,ij->i", scaled[:, :3], scaled[:, 3:]))
    if np.any(pitch_like > max(tol, 1e-12) ** 0.5):
        bad = int(np.argmax(pitch_like))
        raise ScrewkitValueError(
            f"Expected `lines` to be lines (zero or infinite pitch), got row {bad} with "
            f"s·m / |(s; m)|² = {pitch_like[bad]:.3g} in scaled coordinates."
        )
    frame = (point, float(length))
    _, sigma, vt = np.linalg.svd(scaled)
    rank = int(np.sum(sigma > tol * sigma[0]))
    span, complement = vt[:rank], _KLEIN @ vt[rank:].T  # complement: reciprocal to the span
    complement = complement.T
    if rank == 6:
        return GrassmannClass("6", 6)
    if rank == 1:
        return GrassmannClass("1", 1, {"line": _to_user(span[0], frame)})
    if rank == 2:
        return GrassmannClass("2", 2, {"lines": np.array([_to_user(v, frame) for v in span])})
    if rank == 3:
        return _rank_three(scaled, span, complement, frame, tol)
    if rank == 4:
        return _rank_four(complement, frame, tol)
    return _rank_five(complement[0], frame, tol)


def _klein_eigen(basis: Array, tol: float) -> tuple[Array, Array, int]:
    """Eigenvalues (ascending) and eigenvectors of the Klein form on an orthonormal basis, and how
    many eigenvalues are zero (``|λ| <= tol``)."""
    values, vectors = np.linalg.eigh(basis @ _KLEIN @ basis.T)
    return values, vectors, int(np.sum(np.abs(values) <= tol))


def _isotropic(basis: Array, values: Array, vectors: Array, plus: dict[int, float], minus: int) -> Array:
    """A line of the span of ``basis``: the Klein form vanishes on ``Σ cᵢ eᵢ/√λᵢ + e₋/√|λ₋|`` for
    positive eigen-directions ``eᵢ`` weighted by a unit vector ``c`` (``plus``: {index: cᵢ}) and
    one negative eigen-direction ``e₋``."""
    combo = vectors[:, minus] / np.sqrt(-values[minus])
    for index, weight in plus.items():
        combo = combo + weight * vectors[:, index] / np.sqrt(values[index])
    return combo @ basis


def _rank_three(scaled: Array, span: Array, complement: Array, frame: tuple, tol: float) -> GrassmannClass:
    values, vectors, zero = _klein_eigen(span, tol)
    if zero == 3:  # every pair meets: a star or a planar field
        centre = _common_null(np.concatenate([_point_incidence(x) for x in scaled]), tol)
        if centre is not None:
            return GrassmannClass("3a", 3, {"point": _point_to_user(centre, frame)})
        plane = _least_null(np.concatenate([_plane_incidence(x) for x in scaled]))
        return GrassmannClass("3b", 3, {"plane": _plane_to_user(plane, frame)})
    if zero >= 1:  # a degenerate conic of rank 2: two flat pencils through the common line
        common = vectors[:, int(np.argmin(np.abs(values)))] @ span
        signed = [i for i in range(3) if abs(values[i]) > tol]
        plus, minus = max(signed, key=lambda i: values[i]), min(signed, key=lambda i: values[i])
        ends = [_isotropic(span, values, vectors, {plus: sign}, minus) for sign in (1.0, -1.0)]
        points, planes = [], []
        for other in ends:
            pair = np.stack([common, other])
            points.append(
                _point_to_user(_least_null(np.concatenate([_point_incidence(x) for x in pair])), frame)
            )
            planes.append(
                _plane_to_user(_least_null(np.concatenate([_plane_incidence(x) for x in pair])), frame)
            )
        return GrassmannClass(
            "3c",
            3,
            {"line": _to_user(common, frame), "points": np.array(points), "planes": np.array(planes)},
        )
    values_c, vectors_c, _ = _klein_eigen(complement, tol)  # the opposite regulus: a conic
    if int(np.sum(values_c > 0)) == 1:  # two eigenvalues of one sign, one of the other
        values_c = -values_c
    minus = int(np.argmin(values_c))
    first, second = (i for i in range(3) if i != minus)
    transversals = [
        _to_user(
            _isotropic(complement, values_c, vectors_c, {first: np.cos(a), second: np.sin(a)}, minus), frame
        )
        for a in (0.0, 2.0, 4.0)
    ]
    return GrassmannClass("3d", 3, {"transversals": np.array(transversals)})


def _rank_four(complement: Array, frame: tuple, tol: float) -> GrassmannClass:
    values, vectors, zero = _klein_eigen(complement, tol)
    if zero == 2:  # the complement is a flat pencil: its point and plane
        centre = _least_null(np.concatenate([_point_incidence(x) for x in complement]))
        plane = _least_null(np.concatenate([_plane_incidence(x) for x in complement]))
        return GrassmannClass(
            "4b", 4, {"point": _point_to_user(centre, frame), "plane": _plane_to_user(plane, frame)}
        )
    if zero == 1:
        directrix = vectors[:, int(np.argmin(np.abs(values)))] @ complement
        return GrassmannClass("4c", 4, {"line": _to_user(directrix, frame)})
    if values[0] * values[1] < 0:
        lines = [_isotropic(complement, values, vectors, {1: sign}, 0) for sign in (1.0, -1.0)]
        return GrassmannClass("4a", 4, {"lines": np.array([_to_user(x, frame) for x in lines])})
    return GrassmannClass("4d", 4, {"complexes": np.array([_to_user(x, frame) for x in complement])})


def _rank_five(screw: Array, frame: tuple, tol: float) -> GrassmannClass:
    screw = screw / np.linalg.norm(screw)
    if abs(float(screw @ _KLEIN @ screw)) <= tol:
        return GrassmannClass("5b", 5, {"line": _to_user(screw, frame)})
    axis = _to_user(screw, frame)
    s, m = axis[:3], axis[3:]
    pitch = float(s @ m)  # unit direction
    axis = np.concatenate([s, m - pitch * s])
    return GrassmannClass("5a", 5, {"axis": _positive(axis), "pitch": pitch})


def _point_incidence(line: Array) -> Array:
    """Rows ``A`` with ``A @ (x, w) = 0`` exactly when the point lies on the line ``(s; m)``:
    ``x × s − w m = 0`` and ``m·x = 0``."""
    s, m = line[:3], line[3:]
    cross = np.array([[0, s[2], -s[1]], [-s[2], 0, s[0]], [s[1], -s[0], 0]])  # x ↦ x × s
    return np.vstack([np.c_[cross, -m], np.r_[m, 0.0]])


def _plane_incidence(line: Array) -> Array:
    """Rows ``A`` with ``A @ (n, d) = 0`` exactly when the plane ``n·x + d = 0`` holds the line
    ``(s; m)``: ``m × n + d s = 0`` and ``n·s = 0``."""
    s, m = line[:3], line[3:]
    cross = np.array([[0, -m[2], m[1]], [m[2], 0, -m[0]], [-m[1], m[0], 0]])  # n ↦ m × n
    return np.vstack([np.c_[cross, s], np.r_[s, 0.0]])


def _least_null(matrix: Array) -> Array:
    """The direction of least singular value of ``matrix`` (a null vector known to exist)."""
    return np.linalg.svd(matrix)[2][-1]


def _common_null(matrix: Array, tol: float) -> Array | None:
    """The direction of least singular value of ``matrix`` when it is a null vector (relative
    ``tol``), else None."""
    sigma = np.linalg.svd(matrix, compute_uv=False)
    return None if sigma[-1] > tol * sigma[0] else _least_null(matrix)


def _to_user(screw: Array, frame: tuple) -> Array:
    """A scaled screw about the frame back in the lines' coordinates, unit direction (or unit
    moment at infinity), the sign making the first non-zero direction component positive."""
    point, length = frame
    s, m = screw[:3], screw[3:] * length + np.cross(point, screw[:3])
    out = np.concatenate([s, m])
    size = np.linalg.norm(s)
    out = out / (size if size > 1e-12 * np.linalg.norm(out) else np.linalg.norm(m))
    if size <= 1e-12 * np.linalg.norm(out):
        out[:3] = 0.0
    return _positive(out)


def _point_to_user(centre: Array, frame: tuple) -> Array:
    point, length = frame
    x, w = centre[:3], centre[3]
    if abs(w) > 1e-12 * np.linalg.norm(x):
        position = x / w * length + point
        return np.r_[np.where(np.abs(position) <= 1e-12 * length, 0.0, position), 1.0]
    return _positive(np.r_[x / np.linalg.norm(x), 0.0])


def _plane_to_user(plane: Array, frame: tuple) -> Array:
    point, length = frame
    n, d = plane[:3], plane[3]
    size = np.linalg.norm(n)
    if size <= 1e-12 * abs(d):
        return np.array([0.0, 0.0, 0.0, 1.0])
    user = np.r_[n, d * length - n @ point] / size
    return _positive(user)


def _positive(vector: Array) -> Array:
    """The vector with its first clearly non-zero component positive (a projective object's sign)."""
    small = np.abs(vector) <= 1e-12 * np.max(np.abs(vector))  # round-off: shown as 0
    vector = np.where(small, 0.0, vector)
    big = np.flatnonzero(~small)
    return (vector if vector[big[0]] > 0 else -vector) + 0.0
