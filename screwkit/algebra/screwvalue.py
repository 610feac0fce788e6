"""The immutable :class:`Screw` value: a screw ``(s; s0)``, or a batch of them, over the array kernels.

Computation runs on ``(..., 6)`` arrays (:mod:`screwkit.algebra.screw`, where the conventions are
written); a :class:`Screw` is a frozen facade over a read-only ``(..., 6)`` array with the same
constructors, properties and operations as methods, projective equality with a tolerance
(:meth:`Screw.is_equivalent`; never ``==``) and a JSON-ready :meth:`Screw.to_dict` (docs/architecture.md §4).
Like the other value classes it carries a leading batch :attr:`Screw.shape` (``()`` for one screw)
and indexes to one element; per-screw properties and methods answer elementwise over the batch.

Examples
--------
>>> from screwkit.algebra.screw import revolute_twist, reciprocal_product
>>> force_along_y = Screw.force([0, 1, 0], [0, 0, 0])
>>> float(reciprocal_product(revolute_twist([0, 0, 1], [1, 0, 0]), force_along_y))
-1.0
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..exceptions import ScrewkitIndexError, ScrewkitTypeError, ScrewkitValueError
from . import backend as B
from .branch_values import plain
from .display import clean, elided, number_text
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
    """An immutable screw ``(s; s0)``, or a batch of screws (conventions: module docstring).

    Equality is projective and tolerance-based: use :meth:`is_equivalent`, never ``==``.

    A batch (``coords`` of shape ``(..., 6)``) has the batch :attr:`shape`, a length, indexes to a
    Screw of the indexed shape and iterates over its first axis; per-screw properties and methods
    return arrays of the batch shape (a Python scalar for one screw). A Screw is always truthy.

    Parameters
    ----------
    coords : array_like, shape (6,) or (..., 6)
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
    >>> joints = Screw.revolute([[0, 0, 1], [1, 0, 0]], [[1, 0, 0], [0, 0, 0]])
    >>> joints.shape, len(joints), joints[1].coords
    ((2,), 2, array([1., 0., 0., 0., 0., 0.]))
    """

    coords: Array = field()

    def __post_init__(self) -> None:
        arr = B.as_array(self.coords, "coords", (6,)).copy()
        arr.flags.writeable = False
        object.__setattr__(self, "coords", arr)

    def __array__(self, dtype: Any = None, copy: Any = None) -> Array:
        """The ``(..., 6)`` coordinates, so that numpy and every function taking screws accept a Screw.

        Parameters
        ----------
        dtype : numpy.dtype, optional
            The requested dtype (a copy when given).
        copy : bool, optional
            True for a copy.

        Returns
        -------
        numpy.ndarray, shape (..., 6)

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

    # batch ------------------------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, ...]:
        """The batch shape: ``()`` for one screw, ``coords.shape[:-1]`` for a batch."""
        return tuple(self.coords.shape[:-1])

    @property
    def single(self) -> bool:
        """True for one screw (batch shape ``()``)."""
        return self.coords.ndim == 1

    def __bool__(self) -> bool:
        return True  # a screw (even an empty batch) is a value, not a container to test for emptiness

    def __len__(self) -> int:
        """The length of the first batch axis.

        Returns
        -------
        int

        Raises
        ------
        TypeError
            For one screw, which has no length.

        Examples
        --------
        >>> len(Screw(np.zeros((3, 6))))
        3
        """
        if self.single:
            raise TypeError("a single Screw has no length")
        return self.coords.shape[0]

    def __getitem__(self, index: Any) -> Screw:
        """The screw(s) of a batch at ``index`` (indexing the batch axes only, never the coordinates).

        Parameters
        ----------
        index : int, slice, array_like or tuple of them
            A numpy index into the batch shape.

        Returns
        -------
        Screw
            Of the indexed batch shape (``()`` for an integer index into a 1-d batch).

        Raises
        ------
        ScrewkitTypeError
            For one screw: index its :attr:`coords` for a coordinate.
        ScrewkitIndexError
            For an index out of the batch's range or with too many axes.

        Examples
        --------
        >>> batch = Screw.couple([[1, 0, 0], [0, 1, 0], [0, 0, 1]])
        >>> batch[2].coords, batch[:2].shape
        (array([0., 0., 0., 0., 0., 1.]), (2,))
        """
        if self.single:
            raise ScrewkitTypeError(
                "Expected `index` to index a batch of screws, got a single Screw (shape ()); "
                "index its `coords` for a coordinate."
            )
        try:
            flat = np.arange(self.coords.size // 6).reshape(self.shape)[index]
        except IndexError as err:
            raise ScrewkitIndexError(
                f"Expected `index` to index the batch of shape {self.shape}, got {index!r} ({err})."
            ) from err
        return Screw(self.coords.reshape(-1, 6)[flat])

    def __iter__(self) -> Iterator[Screw]:
        """The screws along the first batch axis.

        Yields
        ------
        Screw

        Raises
        ------
        TypeError
            For one screw, which is not iterable.

        Examples
        --------
        >>> [screw.pitch for screw in Screw.couple([[1, 0, 0], [0, 1, 0]])]
        [inf, inf]
        """
        for i in range(len(self)):
            yield self[i]

    # constructors -------------------------------------------------------------------------
    @classmethod
    def revolute(cls, axis: Any, point: Any) -> Screw:
        """Zero-pitch twist of a revolute joint (:func:`revolute_twist`).

        Parameters
        ----------
        axis : array_like, shape (3,) or (..., 3)
            The axis direction (non-zero; normalised).
        point : array_like, shape (3,) or (..., 3)
            A point of the axis.

        Returns
        -------
        Screw
            Of the arguments' broadcast batch shape.

        Examples
        --------
        >>> Screw.revolute([1, 0, 0], [0, 1, 0]).coords
        array([ 1.,  0.,  0.,  0.,  0., -1.])
        >>> Screw.revolute([0, 0, 1], [[0, 0, 0], [1, 0, 0]]).shape
        (2,)
        """
        return cls(revolute_twist(axis, point))

    @classmethod
    def prismatic(cls, direction: Any) -> Screw:
        """Infinite-pitch twist of a prismatic joint (:func:`prismatic_twist`).

        Parameters
        ----------
        direction : array_like, shape (3,) or (..., 3)
            The sliding direction (non-zero; normalised).

        Returns
        -------
        Screw
            Of the arguments' broadcast batch shape.

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
        axis : array_like, shape (3,) or (..., 3)
            The axis direction (non-zero; normalised).
        point : array_like, shape (3,) or (..., 3)
            A point of the axis.
        pitch : float, sympy.Expr or array_like, shape (...)
            Length per radian.

        Returns
        -------
        Screw
            Of the arguments' broadcast batch shape.

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
        direction : array_like, shape (3,) or (..., 3)
            The force's direction (non-zero).
        point : array_like, shape (3,) or (..., 3)
            A point of its line.

        Returns
        -------
        Screw
            Of the arguments' broadcast batch shape.

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
        moment_vector : array_like, shape (3,) or (..., 3)
            The couple's moment.

        Returns
        -------
        Screw
            Of the arguments' broadcast batch shape.

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
        direction, moment_vector : array_like, shape (3,) or (..., 3) or (..., 3)
            The halves ``s`` and ``s0``.

        Returns
        -------
        Screw
            Of the arguments' broadcast batch shape.

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
        """The direction half ``s``: ``numpy.ndarray`` of shape ``(..., 3)``."""
        return self.coords[..., :3]

    @property
    def moment(self) -> Array:
        """The moment half ``s0`` about the origin: ``numpy.ndarray`` of shape ``(..., 3)``."""
        return self.coords[..., 3:]

    @property
    def pitch(self) -> Any:
        """Pitch (:func:`pitch`): a float, ``inf``, or a sympy expression; an array over a batch."""
        return pitch(self.coords)

    @property
    def magnitude(self) -> Any:
        """Magnitude (:func:`magnitude`): a float or sympy expression; an array over a batch."""
        return magnitude(self.coords)

    @property
    def axis(self) -> tuple[Array, Array]:
        """Point nearest the origin and unit direction of the axis (:func:`axis`), each ``(..., 3)``."""
        return axis(self.coords)

    # predicates and operations ------------------------------------------------------------
    def is_zero_pitch(self, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0) -> Any:
        """Zero pitch within tolerance (:func:`is_zero_pitch`).

        Parameters
        ----------
        rtol : float, default 1e-9
            Relative tolerance of the decision.
        length_scale : float, default 1.0
            The characteristic length dividing the moment half.

        Returns
        -------
        bool or numpy.ndarray of bool, shape (...)
            One bool for one screw, an array of the batch shape for a batch.

        Examples
        --------
        >>> Screw.helical([0, 0, 1], [0, 0, 0], [0.0, 0.5]).is_zero_pitch()
        array([ True, False])
        """
        return is_zero_pitch(self.coords, rtol=rtol, length_scale=length_scale)

    def is_infinite_pitch(self, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0) -> Any:
        """Infinite pitch within tolerance (:func:`is_infinite_pitch`).

        Parameters
        ----------
        rtol : float, default 1e-9
            Relative tolerance of the decision.
        length_scale : float, default 1.0
            The characteristic length dividing the moment half.

        Returns
        -------
        bool or numpy.ndarray of bool, shape (...)
            One bool for one screw, an array of the batch shape for a batch.

        Examples
        --------
        >>> Screw([[0, 0, 0, 0, 0, 1], [0, 0, 1, 0, 0, 0]]).is_infinite_pitch()
        array([ True, False])
        """
        return is_infinite_pitch(self.coords, rtol=rtol, length_scale=length_scale)

    def reciprocal_product(self, other: Screw) -> Any:
        """Reciprocal product with another screw (:func:`reciprocal_product`).

        Parameters
        ----------
        other : Screw
            The other screw(s), of a batch shape broadcastable with this one's.

        Returns
        -------
        float, sympy.Expr or numpy.ndarray, shape (...)
            An array of the broadcast batch shape for batches.

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
            Of the same batch shape.

        Examples
        --------
        >>> Screw([[0, 0, 2, 0, 0, 0], [0, 0, 0, 3, 4, 0]]).normalized().magnitude
        array([1., 1.])
        """
        return Screw(normalize(self.coords))

    def transformed(self, rotation: Any, translation: Any) -> Screw:
        """The screw after a rigid motion (:func:`transform`).

        Parameters
        ----------
        rotation : array_like, shape (3, 3) or (..., 3, 3)
            A proper rotation (or a batch of them).
        translation : array_like, shape (3,) or (..., 3)
            The translation (or a batch of them).

        Returns
        -------
        Screw
            Of the broadcast batch shape.

        Examples
        --------
        >>> Screw.couple([0, 0, 1]).transformed(np.eye(3), [1, 0, 0]).coords
        array([0., 0., 0., 0., 0., 1.])
        """
        return Screw(transform(self.coords, rotation, translation))

    def is_equivalent(
        self, other: Screw, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None
    ) -> Any:
        """True if both screws span the same 1-system (projective equality, any non-zero factor).

        Over batches, elementwise on the broadcast batch shape: each pair is decided as two single
        screws are (the default length scale derived from that pair alone).

        Parameters
        ----------
        other : Screw
            The other screw(s), of a batch shape broadcastable with this one's.
        rtol : float, default 1e-9
            Relative tolerance of the rank decision.
        length_scale : float, optional
            The characteristic length (default: derived from the two screws).

        Returns
        -------
        bool or numpy.ndarray of bool, shape (...)
            One bool for two single screws, an array of the broadcast batch shape otherwise.

        Examples
        --------
        >>> Screw.force([1, 0, 0], [0, 1, 0]).is_equivalent(Screw.force([-2, 0, 0], [5, 1, 0]))
        True
        >>> Screw.couple([[0, 0, 1], [0, 1, 0]]).is_equivalent(Screw.couple([0, 0, 3]))
        array([ True, False])
        """
        a, b = B.promote(self.coords, _as_screw(other, "other").coords)
        batch = np.broadcast_shapes(a.shape[:-1], b.shape[:-1])
        pairs = np.stack([np.broadcast_to(a, (*batch, 6)), np.broadcast_to(b, (*batch, 6))], axis=-2)
        ranks = [screw_rank(pairs[i], rtol=rtol, length_scale=length_scale) for i in np.ndindex(batch)]
        equivalent = np.array([int(r) == 1 for r in ranks], dtype=bool).reshape(batch)
        return bool(equivalent) if not batch else equivalent

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description of one screw: coordinates, pitch, kind, and the axis where finite.

        A batch is refused: describe its elements (``[s.to_dict() for s in batch]``).

        Returns
        -------
        dict
            ``coords``, ``pitch`` and ``kind``; for a numeric screw also ``direction`` (of the axis,
            or of the moment for infinite pitch) and, for a finite axis, ``point``.

        Raises
        ------
        ScrewkitValueError
            For a batch of screws.

        Examples
        --------
        >>> Screw.couple([0, 0, 1]).to_dict()["kind"]
        'infinite pitch'
        """
        if not self.single:
            raise ScrewkitValueError(
                f"Expected a single Screw to describe, got a batch of shape {self.shape}; "
                "index it (`screw[i].to_dict()`) or iterate over it."
            )
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
        """``Screw(s1, ..., s0z)`` for one screw; a batch lists its screws in nested brackets.

        Rounding noise is shown as 0 (display only, :func:`screwkit.algebra.display.clean`).

        Returns
        -------
        str

        Examples
        --------
        >>> print(Screw.couple([[0, 0, 1], [0, 2, 0]]))
        [Screw(0, 0, 0, 0, 0, 1), Screw(0, 0, 0, 0, 2, 0)]
        >>> print(Screw([0, 0, 1, 0.4, -0.5, 5e-18]))
        Screw(0, 0, 1, 0.4, -0.5, 0)
        """
        if not self.single:
            return "[" + ", ".join(str(screw) for screw in self) + "]"
        coords = self.coords if self.is_symbolic else clean(self.coords)
        return f"Screw({', '.join(number_text(v) for v in coords)})"

    def __repr__(self) -> str:
        """One line: the screw as :meth:`__str__`; a batch with its shape, its first screws listed.

        >>> Screw.couple(np.eye(3) * [[1], [2], [3]])
        Screw(shape=(3,)): [Screw(0, 0, 0, 1, 0, 0), Screw(0, 0, 0, 0, 2, 0), … (3 in all)]
        """
        if self.single:
            return str(self)
        flat = self.coords.reshape(-1, 6)
        return f"Screw(shape={self.shape}): [{elided((str(Screw(row)) for row in flat), limit=2)}]"


def _as_screw(value: Any, name: str) -> Screw:
    if isinstance(value, Screw):
        return value
    raise ScrewkitTypeError(f"Expected `{name}` to be a Screw, got {type(value).__name__}.")
