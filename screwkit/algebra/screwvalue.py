"""The immutable :class:`Screw` value: one screw ``(s; s0)`` for people, over the array kernels.

Computation runs on ``(..., 6)`` arrays (:mod:`screwkit.algebra.screw`, where the conventions are
written); a :class:`Screw` is a frozen facade over a read-only ``(6,)`` array with the same
constructors, properties and operations as methods, projective equality with a tolerance
(:meth:`Screw.is_equivalent`; never ``==``) and a JSON-ready :meth:`Screw.to_dict` (docs/architecture.md §4).

Examples
--------
>>> from screwkit.algebra.screw import revolute_twist, reciprocal_product
>>> force_along_y = Screw.force([0, 1, 0], [0, 0, 0])
>>> float(reciprocal_product(revolute_twist([0, 0, 1], [1, 0, 0]), force_along_y))
-1.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from . import backend as B
from .branch_values import plain
from .ranks import screw_rank
from .screw import (
    axis,
    couple,
    force,
    from_plucker,
    helical_twist,
    is_infinite_pitch,
    is_zero_pitch,
    magnitude,
    normalize,
    pitch,
    prismatic_twist,
    reciprocal_product,
    revolute_twist,
    transform,
)

__all__ = ["Screw"]

Array = np.ndarray


@dataclass(frozen=True, slots=True, eq=False)
class Screw:
    """An immutable screw ``(s; s0)`` (conventions: module docstring).

    Equality is projective and tolerance-based: use :meth:`is_equivalent`, never ``==``.

    Parameters
    ----------
    coords : array_like, shape (6,)
        Numbers or sympy expressions; stored as a read-only array.

    Examples
    --------
    >>> twist = Screw.revolute([0, 0, 1], [1, 0, 0])
    >>> twist.pitch, twist.is_zero_pitch()
    (0.0, True)
    >>> Screw.couple([0, 0, 1]).pitch
    inf
    >>> twist.coords[0] = 5.0
    Traceback (most recent call last):
    ...
    ValueError: assignment destination is read-only
    """

    coords: Array = field()

    def __post_init__(self) -> None:
        arr = B.as_array(self.coords, "coords", (6,))
        if arr.ndim != 1:
            raise ScrewkitValueError(
                f"Expected `coords` to have shape (6,) for one Screw, got {arr.shape}; "
                "use the module's kernels for batches."
            )
        arr = arr.copy()
        arr.flags.writeable = False
        object.__setattr__(self, "coords", arr)

    def __array__(self, dtype: Any = None, copy: Any = None) -> Array:
        """The ``(6,)`` coordinates, so that numpy and every function taking screws accept a Screw.

        Examples
        --------
        >>> np.asarray(Screw.couple([0, 0, 1]))
        array([0., 0., 0., 0., 0., 1.])
        >>> float(reciprocal_product(Screw.force([1, 0, 0], [0, 0, 0]), Screw.prismatic([1, 0, 0])))
        1.0
        """
        if dtype is None and not copy:
            return self.coords
        return np.array(self.coords, dtype=dtype)

    # constructors -------------------------------------------------------------------------
    @classmethod
    def revolute(cls, axis: Any, point: Any) -> Screw:
        """Zero-pitch twist of a revolute joint (:func:`revolute_twist`).

        Parameters
        ----------
        axis : array_like, shape (3,)
            The axis direction (non-zero; normalised).
        point : array_like, shape (3,)
            A point of the axis.

        Returns
        -------
        Screw

        Examples
        --------
        >>> Screw.revolute([1, 0, 0], [0, 1, 0]).coords
        array([ 1.,  0.,  0.,  0.,  0., -1.])
        """
        return cls(revolute_twist(axis, point))

    @classmethod
    def prismatic(cls, direction: Any) -> Screw:
        """Infinite-pitch twist of a prismatic joint (:func:`prismatic_twist`).

        Parameters
        ----------
        direction : array_like, shape (3,)
            The sliding direction (non-zero; normalised).

        Returns
        -------
        Screw

        Examples
        --------
        >>> Screw.prismatic([1, 0, 0]).is_infinite_pitch()
        True
        """
        return cls(prismatic_twist(direction))

    @classmethod
    def helical(cls, axis: Any, point: Any, pitch: Any) -> Screw:
        """Twist of a helical joint (:func:`helical_twist`).

        Parameters
        ----------
        axis : array_like, shape (3,)
            The axis direction (non-zero; normalised).
        point : array_like, shape (3,)
            A point of the axis.
        pitch : float or sympy.Expr
            Length per radian.

        Returns
        -------
        Screw

        Examples
        --------
        >>> Screw.helical([0, 0, 1], [0, 0, 0], 2).pitch
        2.0
        """
        return cls(helical_twist(axis, point, pitch))

    @classmethod
    def force(cls, direction: Any, point: Any) -> Screw:
        """Pure force on a line (:func:`force`).

        Parameters
        ----------
        direction : array_like, shape (3,)
            The force's direction (non-zero).
        point : array_like, shape (3,)
            A point of its line.

        Returns
        -------
        Screw

        Examples
        --------
        >>> Screw.force([0, 1, 0], [1, 0, 0]).coords
        array([0., 1., 0., 0., 0., 1.])
        """
        return cls(force(direction, point))

    @classmethod
    def couple(cls, moment_vector: Any) -> Screw:
        """Pure couple (:func:`couple`).

        Parameters
        ----------
        moment_vector : array_like, shape (3,)
            The couple's moment.

        Returns
        -------
        Screw

        Examples
        --------
        >>> Screw.couple([1, 0, 0]).coords
        array([0., 0., 0., 1., 0., 0.])
        """
        return cls(couple(moment_vector))

    @classmethod
    def from_plucker(cls, direction: Any, moment_vector: Any) -> Screw:
        """From the two halves (:func:`from_plucker`).

        Parameters
        ----------
        direction, moment_vector : array_like, shape (3,)
            The halves ``s`` and ``s0``.

        Returns
        -------
        Screw

        Examples
        --------
        >>> Screw.from_plucker([0, 0, 1], [0, 0, 3]).pitch
        3.0
        """
        return cls(from_plucker(direction, moment_vector))

    # properties ---------------------------------------------------------------------------
    @property
    def is_symbolic(self) -> bool:
        """True when the coordinates are sympy expressions."""
        return B.is_symbolic(self.coords)

    @property
    def direction(self) -> Array:
        """The direction half ``s``."""
        return self.coords[:3]

    @property
    def moment(self) -> Array:
        """The moment half ``s0`` about the origin."""
        return self.coords[3:]

    @property
    def pitch(self) -> Any:
        """Pitch (:func:`pitch`): a float, ``inf``, or a sympy expression."""
        return pitch(self.coords)

    @property
    def magnitude(self) -> Any:
        """Magnitude (:func:`magnitude`)."""
        return magnitude(self.coords)

    @property
    def axis(self) -> tuple[Array, Array]:
        """Point nearest the origin and unit direction of the axis (:func:`axis`)."""
        return axis(self.coords)

    # predicates and operations ------------------------------------------------------------
    def is_zero_pitch(self, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0) -> bool:
        """Zero pitch within tolerance (:func:`is_zero_pitch`).

        Parameters
        ----------
        rtol : float, default 1e-9
            Relative tolerance of the decision.
        length_scale : float, default 1.0
            The characteristic length dividing the moment half.

        Returns
        -------
        bool
        """
        return bool(is_zero_pitch(self.coords, rtol=rtol, length_scale=length_scale))

    def is_infinite_pitch(self, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0) -> bool:
        """Infinite pitch within tolerance (:func:`is_infinite_pitch`).

        Parameters
        ----------
        rtol : float, default 1e-9
            Relative tolerance of the decision.
        length_scale : float, default 1.0
            The characteristic length dividing the moment half.

        Returns
        -------
        bool
        """
        return bool(is_infinite_pitch(self.coords, rtol=rtol, length_scale=length_scale))

    def reciprocal_product(self, other: Screw) -> Any:
        """Reciprocal product with another screw (:func:`reciprocal_product`).

        Parameters
        ----------
        other : Screw
            The other screw.

        Returns
        -------
        float or sympy.Expr

        Examples
        --------
        >>> float(Screw.revolute([0, 0, 1], [0, 0, 0]).reciprocal_product(Screw.couple([0, 0, 1])))
        1.0
        """
        return reciprocal_product(self.coords, _as_screw(other, "other").coords)

    def normalized(self) -> Screw:
        """The screw scaled to unit magnitude (:func:`normalize`).

        Returns
        -------
        Screw
        """
        return Screw(normalize(self.coords))

    def transformed(self, rotation: Any, translation: Any) -> Screw:
        """The screw after a rigid motion (:func:`transform`).

        Parameters
        ----------
        rotation : array_like, shape (3, 3)
            A proper rotation.
        translation : array_like, shape (3,)
            The translation.

        Returns
        -------
        Screw
        """
        return Screw(transform(self.coords, rotation, translation))

    def is_equivalent(
        self, other: Screw, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None
    ) -> bool:
        """True if both screws span the same 1-system (projective equality, any non-zero factor).

        Parameters
        ----------
        other : Screw
            The other screw.
        rtol : float, default 1e-9
            Relative tolerance of the rank decision.
        length_scale : float, optional
            The characteristic length (default: derived from the two screws).

        Returns
        -------
        bool

        Examples
        --------
        >>> Screw.force([1, 0, 0], [0, 1, 0]).is_equivalent(Screw.force([-2, 0, 0], [5, 1, 0]))
        True
        """
        rows = np.stack([self.coords, _as_screw(other, "other").coords])
        return int(screw_rank(rows, rtol=rtol, length_scale=length_scale)) == 1

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: coordinates, pitch, kind, and the axis where finite.

        Returns
        -------
        dict
            ``coords``, ``pitch`` and ``kind``; for a numeric screw also ``direction`` (of the axis,
        or of the moment for infinite pitch) and, for a finite axis, ``point``.

        Examples
        --------
        >>> Screw.couple([0, 0, 1]).to_dict()["kind"]
        'infinite pitch'
        """
        coords = [plain(v) for v in self.coords]
        h = self.pitch
        if self.is_symbolic:
            return {"coords": coords, "pitch": str(h), "kind": "symbolic"}
        if math.isinf(h):
            return {
                "coords": coords,
                "pitch": "inf",
                "kind": "infinite pitch",
                "direction": [float(v) for v in self.moment],
            }
        point, unit = self.axis
        kind = "zero pitch" if self.is_zero_pitch(length_scale=1.0) else "finite pitch"
        return {
            "coords": coords,
            "pitch": float(h),
            "kind": kind,
            "point": point.tolist(),
            "direction": unit.tolist(),
        }

    def __str__(self) -> str:
        values = ", ".join(str(v) if self.is_symbolic else f"{v:.6g}" for v in self.coords)
        return f"Screw({values})"

    def __repr__(self) -> str:
        return f"Screw(coords={self.coords!r})"


def _as_screw(value: Any, name: str) -> Screw:
    if isinstance(value, Screw):
        return value
    raise ScrewkitTypeError(f"Expected `{name}` to be a Screw, got {type(value).__name__}.")
