"""Screw systems: the linear spans of screws, their sums, intersections and reciprocals.

A screw system of order n (an n-system) is the set of screws linearly dependent on n independent
screws (paper 002, §3). For a serial chain the twist system is the sum of the joints' twist systems
and the wrench system the intersection of theirs (paper 002, Eq. 1); across parallel chains the
roles swap (Eq. 2). Twist and wrench systems of a chain are reciprocal: ``T = W^⊥``, ``W = T^⊥``,
and ``order(W) = 6 - order(T)``.

Every rank decision takes ``rtol`` and ``length_scale`` (:mod:`screwkit.algebra.ranks`); a system keeps
the values it was built with and passes them on to the systems it produces, so a whole analysis uses
one characteristic length. Symbolic systems use sympy's exact (generic) rank.

Examples
--------
>>> from screwkit.algebra.screw import couple, force
>>> wrenches = ScrewSystem.span([force([1, 0, 0], [0, 0, 0]), couple([0, 0, 1])])
>>> wrenches.order, wrenches.reciprocal().order
(2, 4)
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from . import backend as B
from .ranks import _independent_rows, characteristic_length, screw_nullspace, screw_rank, unit_rows
from .readable import _COUPLES, _about, _axes_centre, _numeric_readable, _symbolic_readable
from .screwvalue import Screw
from .zero_tests import _binary_exponents

__all__ = ["ScrewSystem"]

Array = np.ndarray


@dataclass(frozen=True, slots=True, eq=False)
class ScrewSystem:
    """A screw system, held as a basis of rows ``(order, 6)``.

    Build one with :meth:`span` (which picks an independent subset of the generators); the
    constructor expects an already independent basis.

    Parameters
    ----------
    basis : array_like, shape (k, 6)
        Independent screws (numbers or sympy expressions). Stored read-only.
    rtol : float, default 1e-9
        Relative tolerance of every rank decision made with this system.
    length_scale : float or None
        Characteristic length (see ``screwkit.algebra.backend``); None derives it from the basis.

    Examples
    --------
    >>> from screwkit.algebra.screw import revolute_twist
    >>> hinge = ScrewSystem.span([revolute_twist([0, 0, 1], [0, 0, 0])])
    >>> hinge.order, hinge.reciprocal().order
    (1, 5)
    """

    basis: Array = field()
    rtol: float = B.DEFAULT_RTOL
    length_scale: float | None = None

    def __post_init__(self) -> None:
        rows = B.as_array(self.basis, "basis", (6,)).reshape(-1, 6)
        length = characteristic_length(rows, self.length_scale, self.rtol)
        object.__setattr__(self, "length_scale", length)
        rank = screw_rank(rows, rtol=self.rtol, length_scale=length)
        if rank != rows.shape[0]:
            raise ScrewkitValueError(
                f"Expected `basis` to hold independent screws, got {rows.shape[0]} rows of "
                f"rank {rank}; use ScrewSystem.span to pick a basis."
            )
        rows = rows.copy()
        rows.flags.writeable = False
        object.__setattr__(self, "basis", rows)

    # constructors -------------------------------------------------------------------------
    @classmethod
    def span(
        cls,
        screws: Any,
        *,
        rtol: float = B.DEFAULT_RTOL,
        length_scale: float | None = None,
    ) -> ScrewSystem:
        """The system spanned by screws: a sequence of :class:`Screw` or an array ``(k, 6)``.

        The basis is the maximal independent subset of the generators, in their order.

        Parameters
        ----------
        screws : sequence of Screw, or array_like of shape (k, 6)
            The generators (floats or sympy expressions).
        rtol : float, default 1e-9
            Relative tolerance of every rank decision of the system.
        length_scale : float, optional
            The characteristic length of those decisions (default: derived from the screws).

        Returns
        -------
        ScrewSystem

        Examples
        --------
        >>> from screwkit.algebra.screw import prismatic_twist
        >>> ScrewSystem.span([prismatic_twist([1, 0, 0]), prismatic_twist([2, 0, 0])]).order
        1
        """
        rows = _rows(screws, "screws")
        length_scale = characteristic_length(rows, length_scale, rtol)
        basis = _independent_rows(rows, rtol, length_scale) if rows.shape[0] else rows
        # independent by construction: _independent_rows took the (generic) rank of these very rows
        return cls.from_independent(basis, rtol=rtol, length_scale=length_scale)

    @classmethod
    def from_independent(
        cls, basis: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None
    ) -> ScrewSystem:
        """A system from rows known to be independent (e.g. moved by a rigid motion), unchecked.

        Parameters
        ----------
        basis : array_like, shape (k, 6)
            Independent rows (not checked).
        rtol : float, default 1e-9
            Relative tolerance of every rank decision of the system.
        length_scale : float, optional
            The characteristic length of those decisions (default: derived from the screws).

        Returns
        -------
        ScrewSystem

        Examples
        --------
        >>> from screwkit.algebra.screw import couple
        >>> ScrewSystem.from_independent([couple([0, 0, 1])], length_scale=1.0).order
        1
        """
        rows = B.as_array(basis, "basis", (6,)).reshape(-1, 6).copy()
        rows.flags.writeable = False
        system = object.__new__(cls)
        object.__setattr__(system, "basis", rows)
        object.__setattr__(system, "rtol", rtol)
        object.__setattr__(system, "length_scale", length_scale)
        return system

    @classmethod
    def full(cls, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None) -> ScrewSystem:
        """The 6-system of all screws.

        Parameters
        ----------
        rtol : float, default 1e-9
            Relative tolerance of every rank decision of the system.
        length_scale : float, optional
            The characteristic length of those decisions (default: derived from the screws).

        Returns
        -------
        ScrewSystem

        Examples
        --------
        >>> ScrewSystem.full().order
        6
        """
        return cls(np.eye(6), rtol=rtol, length_scale=length_scale)

    @classmethod
    def zero(cls, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None) -> ScrewSystem:
        """The 0-system.

        Parameters
        ----------
        rtol : float, default 1e-9
            Relative tolerance of every rank decision of the system.
        length_scale : float, optional
            The characteristic length of those decisions (default: derived from the screws).

        Returns
        -------
        ScrewSystem

        Examples
        --------
        >>> ScrewSystem.zero().reciprocal().order
        6
        """
        return cls(np.zeros((0, 6)), rtol=rtol, length_scale=length_scale)

    # basic properties ---------------------------------------------------------------------
    @property
    def order(self) -> int:
        """The order n of the n-system (the number of basis screws)."""
        return int(self.basis.shape[0])

    @property
    def is_symbolic(self) -> bool:
        """True when the basis holds sympy expressions."""
        return B.is_symbolic(self.basis)

    def screws(self) -> list[Screw]:
        """The basis as :class:`~screwkit.algebra.screwvalue.Screw` values.

        Returns
        -------
        list of Screw

        Examples
        --------
        >>> len(ScrewSystem.full().screws())
        6
        """
        return [Screw(row) for row in self.basis]

    def _like(self, rows: Array) -> ScrewSystem:
        return ScrewSystem.span(rows, rtol=self.rtol, length_scale=self.length_scale)

    def _other(self, other: Any) -> ScrewSystem:
        if isinstance(other, ScrewSystem):
            return other
        raise ScrewkitTypeError(f"Expected `other` to be a ScrewSystem, got {type(other).__name__}.")

    def _stack(self, *parts: Array) -> Array:
        promoted = B.promote(*[np.asarray(p).reshape(-1, 6) for p in parts])
        return np.concatenate(promoted, axis=0)

    # algebra ------------------------------------------------------------------------------
    def reciprocal(self) -> ScrewSystem:
        """The reciprocal system: every screw whose reciprocal product with all of ``self`` is 0.

        ``order(S) + order(S^⊥) = 6`` and ``(S^⊥)^⊥ = S`` (paper 002, §3).

        Returns
        -------
        ScrewSystem
            Of order ``6 - self.order``.

        Examples
        --------
        >>> from screwkit.algebra.screw import line
        >>> lines = ScrewSystem.span([line([1, 0, 0], [0, 0, 0]), line([0, 1, 0], [0, 0, 0])])
        >>> lines.reciprocal().order
        4
        """
        rows = screw_nullspace(self.basis, rtol=self.rtol, length_scale=self.length_scale)
        if self.length_scale is not None and not self.is_symbolic:
            # orthonormal in the coordinates scaled by this length: independent by construction
            return ScrewSystem.from_independent(rows, rtol=self.rtol, length_scale=self.length_scale)
        return ScrewSystem(rows, rtol=self.rtol, length_scale=self.length_scale)

    def sum(self, other: ScrewSystem) -> ScrewSystem:
        """The smallest system holding both (span of the union); also ``self + other``.

        Parameters
        ----------
        other : ScrewSystem
            The other system.

        Returns
        -------
        ScrewSystem

        Examples
        --------
        >>> from screwkit.algebra.screw import couple
        >>> (ScrewSystem.span([couple([1, 0, 0])]) + ScrewSystem.span([couple([0, 1, 0])])).order
        2
        """
        return self._like(self._stack(self.basis, self._other(other).basis))

    __add__ = sum

    def intersection(self, other: ScrewSystem) -> ScrewSystem:
        """The screws common to both: ``(A^⊥ + B^⊥)^⊥``; also ``self & other``.

        Parameters
        ----------
        other : ScrewSystem
            The other system.

        Returns
        -------
        ScrewSystem

        Examples
        --------
        >>> from screwkit.algebra.screw import couple
        >>> a = ScrewSystem.span([couple([1, 0, 0]), couple([0, 1, 0])])
        >>> b = ScrewSystem.span([couple([0, 1, 0]), couple([0, 0, 1])])
        >>> (a & b).order
        1
        """
        return (self.reciprocal() + self._other(other).reciprocal()).reciprocal()

    __and__ = intersection

    def contains(self, item: Screw | ScrewSystem | Any) -> bool:
        """True if a screw (or every screw of a system, or rows ``(k, 6)``) lies in ``self``.

        Parameters
        ----------
        item : Screw, ScrewSystem or array_like of shape (6,) or (k, 6)
            The screws tested.

        Returns
        -------
        bool

        Examples
        --------
        >>> from screwkit.algebra.screw import couple
        >>> plane = ScrewSystem.span([couple([1, 0, 0]), couple([0, 1, 0])])
        >>> plane.contains(Screw.couple([1, 1, 0])), plane.contains(Screw.couple([0, 0, 1]))
        (True, False)
        """
        if isinstance(item, ScrewSystem):
            rows = item.basis
        elif isinstance(item, Screw):
            rows = item.coords.reshape(1, 6)
        else:
            rows = _rows(item, "item")
        stacked = self._stack(self.basis, rows)
        rank = screw_rank(stacked, rtol=self.rtol, length_scale=self.length_scale)
        return bool(rank == self.order)

    def __contains__(self, item: Any) -> bool:
        """``screw in system`` is :meth:`contains`.

        Examples
        --------
        >>> from screwkit.algebra.screw import couple
        >>> Screw.couple([1, 1, 0]) in ScrewSystem.span([couple([1, 0, 0]), couple([0, 1, 0])])
        True
        """
        return self.contains(item)

    def is_equivalent(self, other: ScrewSystem) -> bool:
        """True if both systems are the same set of screws.

        Parameters
        ----------
        other : ScrewSystem
            The other system.

        Returns
        -------
        bool

        Examples
        --------
        >>> from screwkit.algebra.screw import couple
        >>> a = ScrewSystem.span([couple([1, 0, 0]), couple([0, 1, 0])])
        >>> a.is_equivalent(ScrewSystem.span([couple([1, 1, 0]), couple([1, -1, 0])]))
        True
        """
        other = self._other(other)
        return other.order == self.order and self.contains(other)

    # readable presentation ----------------------------------------------------------------
    def couple_subsystem(self) -> ScrewSystem:
        """The screws of infinite pitch in ``self`` (a linear subsystem: ``self ∩ couples``).

        Returns
        -------
        ScrewSystem

        Examples
        --------
        >>> from screwkit.algebra.screw import couple, force
        >>> ScrewSystem.span([force([1, 0, 0], [0, 0, 0]), couple([0, 1, 0])]).couple_subsystem().order
        1
        """
        return (self.reciprocal() + _couples_reciprocal(self.rtol, self.length_scale)).reciprocal()

    def readable_basis(self, near: Any = None) -> Array:
        """A basis that reads like a designer's sketch: translations/couples and lines first.

        1. The infinite-pitch subsystem (translations, couples) comes first, along the frame's
           ``x``, ``y``, ``z`` where it holds them, completed orthonormally (unit moments).
        2. The rest is parametrised by its directions ``s`` (a subspace ``D``): each direction
           carries one screw up to the couples of the system. Candidate directions are the frame's
           axes in ``D``, the principal directions of the pitch form on ``D`` (Hunt, *Kinematic
           Geometry of Mechanisms*, 1978, §12: principal screws) and, where that form is
           indefinite, its isotropic directions: combinations ``√|λ₋| e₊ ± √λ₊ e₋`` of a positive
           and a negative principal direction have pitch 0, so a 3-system spanned by three skew
           lines yields three lines (each meeting every line of the reciprocal regulus).
        3. For each candidate the couples of the system move the screw to zero pitch where they
           can and bring its axis nearest to ``near`` (a least-squares shift of the moment about
           ``near``, constrained to zero pitch). Lines through one point stay through it.
        4. Independent candidates are taken greedily: lines before other screws, axis directions
           before others. Lines have unit direction, couples unit moment.

        Parameters
        ----------
        near : array_like, shape (3,), optional
            Where axes are placed when the system lets them move (e.g. a mechanism's reference
            point); default the origin of the frame, or, for axes more than 10 lengths from it, the
            point nearest them (the basis is then decided there, not about the far origin, whose
            moments would swamp the rank decisions).

        Returns
        -------
        numpy.ndarray, shape (order, 6)

        Examples
        --------
        >>> from screwkit.algebra.screw import couple, force
        >>> mixed = [force([1, 0, 0], [0, 0, 0]) + couple([1, 0, 0]), couple([1, 0, 0])]
        >>> ScrewSystem.span(mixed).readable_basis() + 0.0
        array([[0., 0., 0., 1., 0., 0.],
               [1., 0., 0., 0., 0., 0.]])
        >>> from screwkit.algebra.screw import prismatic_twist, revolute_twist
        >>> schoenflies = ScrewSystem.span([prismatic_twist([1, 1, 0]), prismatic_twist([0, 1, 1]),
        ...     prismatic_twist([1, 0, 1]), revolute_twist([0, 0, 1], [40.0, 0, 0])])
        >>> schoenflies.readable_basis(near=[1.0, 2.0, 0.0]).round(12) + 0.0
        array([[ 0.,  0.,  0.,  1.,  0.,  0.],
               [ 0.,  0.,  0.,  0.,  1.,  0.],
               [ 0.,  0.,  0.,  0.,  0.,  1.],
               [ 0.,  0.,  1.,  2., -1.,  0.]])
        """
        if self.is_symbolic:
            return _symbolic_readable(self, near)
        centre = np.zeros(3) if near is None else B.as_array(near, "near", (3,), symbolic=False)
        if centre.shape != (3,):
            raise ScrewkitValueError(f"Expected `near` to have shape (3,), got {centre.shape}.")
        rows = np.ascontiguousarray(self.basis, dtype=float).tobytes()
        given = None if near is None else np.asarray(centre, dtype=float).tobytes()
        return _readable(rows, self.rtol, self.length_scale, given).copy()

    def _readable_about(self, near: Array | None) -> Array:
        """:meth:`readable_basis` of a numeric system (what :func:`_readable` remembers)."""
        length = float(self.length_scale or 1.0)
        # each row times a power of two (exact; the same span): no square below overflows or underflows
        rows = np.ldexp(self.basis, -_binary_exponents(self.basis))
        origin = _axes_centre(rows, length, self.rtol)
        if np.linalg.norm(origin) > 10.0 * length:
            # far from the frame's origin the moments dwarf the length scale and every rank decision
            # below would judge rounding: decide about a point among the axes, then move back
            local = ScrewSystem(_about(rows, origin), rtol=self.rtol, length_scale=self.length_scale)
            return _about(_numeric_readable(local, np.zeros(3) if near is None else near - origin), -origin)
        system = ScrewSystem.from_independent(rows, rtol=self.rtol, length_scale=self.length_scale)
        return _numeric_readable(system, np.zeros(3) if near is None else near)

    def pitch_range(self) -> tuple[float, float]:
        """Least and greatest pitch of the screws of ``self`` with a non-zero direction.

        The pitch is the Rayleigh quotient ``s·s0 / s·s`` over the system; its extreme values
        are the principal pitches (for a 2-system, those of its cylindroid). When the system
        holds a couple that can change the pitch of a finite screw, the range is unbounded.

        Returns
        -------
        (float, float)
            In the system's unit of length; ``(nan, nan)`` is never returned: a pure-couple
            system raises instead.

        Raises
        ------
        ScrewkitValueError
            If every screw of the system has infinite pitch (or the system is empty).

        Examples
        --------
        >>> from screwkit.algebra.screw import helical_twist
        >>> pair = [helical_twist([1, 0, 0], [0, 0, 0], 1.0), helical_twist([0, 1, 0], [0, 0, 0], -2.0)]
        >>> ScrewSystem.span(pair).pitch_range()
        (-2.0, 1.0)
        """
        if self.is_symbolic:
            raise ScrewkitTypeError("pitch_range is numeric; substitute values into the system first.")
        length = float(self.length_scale or 1.0)
        scaled = unit_rows(self.basis, length)  # the same span, no square overflows
        if scaled.shape[0]:
            scaled = np.linalg.qr(scaled.T)[0].T  # orthonormal basis of the same span
        dirs, mom = scaled[:, :3], scaled[:, 3:]
        gram = dirs @ dirs.T
        form = 0.5 * (dirs @ mom.T + mom @ dirs.T)
        values, vectors = np.linalg.eigh(gram)
        tol = self.rtol * max(1.0, float(values.max(initial=0.0)))
        finite = vectors[:, values > tol]
        if finite.shape[1] == 0:
            raise ScrewkitValueError(
                f"Expected a system holding a screw of finite pitch, got only couples (order {self.order})."
            )
        kernel = vectors[:, values <= tol]
        if kernel.size and np.abs(kernel.T @ form @ finite).max() > tol:
            return (-np.inf, np.inf)
        reduced_gram = finite.T @ gram @ finite
        reduced_form = finite.T @ form @ finite
        root = np.linalg.cholesky(reduced_gram)
        inv = np.linalg.inv(root)
        pitches = np.linalg.eigvalsh(inv @ reduced_form @ inv.T) * length
        return (float(pitches[0]), float(pitches[-1]))

    def contains_pitch(self, value: float) -> bool:
        """True if the system holds a screw of pitch ``value`` (``math.inf`` for couples).

        Parameters
        ----------
        value : float
            The pitch (``math.inf`` for couples).

        Returns
        -------
        bool

        Examples
        --------
        >>> from screwkit.algebra.screw import couple, line
        >>> system = ScrewSystem.span([line([1, 0, 0], [0, 0, 0]), couple([0, 0, 1])])
        >>> system.contains_pitch(0.0), system.contains_pitch(float("inf"))
        (True, True)
        """
        if np.isinf(value):
            return self.couple_subsystem().order > 0
        try:
            low, high = self.pitch_range()
        except ScrewkitValueError:
            return False
        slack = self.rtol * float(self.length_scale or 1.0)
        return bool(low - slack <= value <= high + slack)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: order and readable basis.

        Returns
        -------
        dict
            ``order`` and ``basis`` (the readable basis, each row as :meth:`Screw.to_dict`).

        Examples
        --------
        >>> ScrewSystem.zero().to_dict()
        {'order': 0, 'basis': []}
        """
        return {"order": self.order, "basis": [Screw(r).to_dict() for r in self.readable_basis()]}

    def __str__(self) -> str:
        rows = "; ".join(str(Screw(r)) for r in self.readable_basis())
        return f"{self.order}-system [{rows}]"

    def __repr__(self) -> str:
        """One line: the order and the readable basis, its screws as screws (rounding noise shown as 0).

        Returns
        -------
        str

        Examples
        --------
        >>> ScrewSystem.span([[1, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 1]])
        ScrewSystem(order=2: Screw(0, 0, 0, 0, 0, 1), Screw(1, 0, 0, 0, 0, 0))
        """
        rows = ", ".join(str(Screw(r)) for r in self.readable_basis())
        return f"ScrewSystem(order={self.order}{': ' + rows if rows else ''})"


def _rows(screws: Any, name: str) -> Array:
    if isinstance(screws, ScrewSystem):
        return screws.basis
    if isinstance(screws, Screw):
        return screws.coords.reshape(-1, 6)  # one screw or a batch of them
    if isinstance(screws, list | tuple) and screws and all(isinstance(s, Screw) for s in screws):
        return np.concatenate(B.promote(*[s.coords.reshape(1, 6) for s in screws]), axis=0)
    if isinstance(screws, list | tuple) and not screws:
        return np.zeros((0, 6))
    return B.as_array(screws, name, (6,)).reshape(-1, 6)


@functools.lru_cache(maxsize=16)
def _couples_reciprocal(rtol: float, length_scale: float | None) -> ScrewSystem:
    """The reciprocal of the couples (:meth:`ScrewSystem.intersection` with them, for
    :meth:`~ScrewSystem.couple_subsystem`): the same system for every system of this ``rtol`` and
    length scale, made once."""
    return ScrewSystem(_COUPLES, rtol=rtol, length_scale=length_scale).reciprocal()


@functools.lru_cache(maxsize=64)
def _readable(rows: bytes, rtol: float, length_scale: float | None, near: bytes | None) -> Array:
    """The readable basis (read-only) of the numeric system with these basis rows (the bytes of a
    float ``(k, 6)`` array), ``rtol`` and ``length_scale``, axes placed near the point ``near`` (the
    bytes of a float ``(3,)`` array; None: not given). A pure function of its arguments, remembered:
    the diagram and the report take the readable bases of the same per-pose systems (a leg's
    constraint wrenches, rebuilt from the same frames) one after the other."""
    basis = np.frombuffer(rows, dtype=float).reshape(-1, 6)
    system = ScrewSystem.from_independent(basis, rtol=rtol, length_scale=length_scale)
    found = system._readable_about(None if near is None else np.frombuffer(near, dtype=float))
    found.flags.writeable = False
    return found
