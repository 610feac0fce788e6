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
from .ranks import characteristic_length, scale_moments, screw_nullspace, screw_rank
from .readable import _about, _axes_centre, _axis_first, _finite_candidates, _orthonormal_couples
from .screwvalue import Screw

__all__ = ["ScrewSystem", "motion_type"]

Array = np.ndarray
_COUPLES = np.hstack([np.zeros((3, 3)), np.eye(3)])


def _independent_rows(rows: Array, rtol: float, length_scale: float | None) -> Array:
    """The rows that raise the rank, in order (a basis made of the given generators)."""
    chosen: list[Array] = []
    rank = 0
    total = screw_rank(rows, rtol=rtol, length_scale=length_scale) if rows.shape[0] else 0
    if total == rows.shape[0]:
        return rows.copy()
    for row in rows:
        trial = np.array([*chosen, row], dtype=rows.dtype)
        new_rank = screw_rank(trial, rtol=rtol, length_scale=length_scale)
        if new_rank > rank:
            chosen.append(row)
            rank = new_rank
            if rank == total:
                break
    return np.array(chosen, dtype=rows.dtype).reshape(len(chosen), 6)


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
        length = characteristic_length(rows, self.length_scale)
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

        Examples
        --------
        >>> from screwkit.algebra.screw import prismatic_twist
        >>> ScrewSystem.span([prismatic_twist([1, 0, 0]), prismatic_twist([2, 0, 0])]).order
        1
        """
        rows = _rows(screws, "screws")
        length_scale = characteristic_length(rows, length_scale)
        basis = _independent_rows(rows, rtol, length_scale) if rows.shape[0] else rows
        # independent by construction: _independent_rows took the (generic) rank of these very rows
        return cls.from_independent(basis, rtol=rtol, length_scale=length_scale)

    @classmethod
    def from_independent(
        cls, basis: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None
    ) -> ScrewSystem:
        """A system from rows known to be independent (e.g. moved by a rigid motion), unchecked.

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

        Examples
        --------
        >>> ScrewSystem.full().order
        6
        """
        return cls(np.eye(6), rtol=rtol, length_scale=length_scale)

    @classmethod
    def zero(cls, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None) -> ScrewSystem:
        """The 0-system.

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
            return self._readable_symbolic(near)
        centre = np.zeros(3) if near is None else B.as_array(near, "near", (3,), symbolic=False)
        if centre.shape != (3,):
            raise ScrewkitValueError(f"Expected `near` to have shape (3,), got {centre.shape}.")
        rows = np.ascontiguousarray(self.basis, dtype=float).tobytes()
        given = None if near is None else np.asarray(centre, dtype=float).tobytes()
        return _readable(rows, self.rtol, self.length_scale, given).copy()

    def _readable_about(self, near: Array | None) -> Array:
        """:meth:`readable_basis` of a numeric system (what :func:`_readable` remembers)."""
        length = float(self.length_scale or 1.0)
        origin = _axes_centre(self.basis, length, self.rtol)
        if np.linalg.norm(origin) > 10.0 * length:
            # far from the frame's origin the moments dwarf the length scale and every rank decision
            # below would judge rounding: decide about a point among the axes, then move back
            local = ScrewSystem(_about(self.basis, origin), rtol=self.rtol, length_scale=self.length_scale)
            return _about(local._readable_numeric(np.zeros(3) if near is None else near - origin), -origin)
        return self._readable_numeric(np.zeros(3) if near is None else near)

    def _readable_numeric(self, centre: Array) -> Array:
        """:meth:`readable_basis` of a numeric system in its own frame (axes placed near ``centre``)."""
        couples = _axis_first(_orthonormal_couples(self.couple_subsystem().basis)[:, 3:], self.rtol)
        finite = _finite_candidates(self.basis, couples, centre, self.rtol, float(self.length_scale or 1.0))
        rows = np.concatenate([np.hstack([np.zeros_like(couples), couples]), *finite]).reshape(-1, 6)
        return _pick(self._stack(rows, self.basis), self.order, self)

    def _readable_symbolic(self, near: Any) -> Array:
        """The symbolic readable basis (generic decisions, :mod:`screwkit.algebra.symbolic`): the frame's
        translations where the system holds them; with all three, the other rows become lines
        through ``near`` (the origin by default); else the couple subsystem, then the basis."""
        axes = [row for row in _COUPLES.astype(int) if self.contains(row)]
        stacked = self._stack(self.basis, _COUPLES.astype(int))
        translations = self.order + 3 - int(screw_rank(stacked))
        couples = (
            np.array(axes).reshape(-1, 6) if len(axes) == translations else self.couple_subsystem().basis
        )
        rows = self.basis
        if translations == 3:
            centre = B.as_array(np.zeros(3) if near is None else near, "near", (3,), symbolic=True)
            rows = np.concatenate(
                [rows[:, :3], B.cross(np.broadcast_to(centre, rows[:, :3].shape), rows[:, :3])], axis=1
            )
        return _pick(self._stack(couples, rows), self.order, self)

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
        scaled, _ = scale_moments(self.basis, length)
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
        return f"ScrewSystem(order={self.order}, basis={self.basis!r})"


def _rows(screws: Any, name: str) -> Array:
    if isinstance(screws, ScrewSystem):
        return screws.basis
    if isinstance(screws, Screw):
        return screws.coords.reshape(1, 6)
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


def _pick(candidates: Array, order: int, system: ScrewSystem) -> Array:
    """The first ``order`` independent candidates. The candidates lie in the system to within the
    snapping of :func:`_axis_first` and :func:`_finite_candidates` (``1e3 rtol``: a frame axis, a
    line), so that is the tolerance of their independence; the system's own ``rtol`` decides where
    that would not give ``order`` rows (a system with a singular value between the two)."""
    picked = np.zeros((0, 6))
    if not system.is_symbolic:
        picked = _independent_rows(candidates, min(1e3 * system.rtol, 1e-3), system.length_scale)
    if picked.shape[0] != order:
        picked = _independent_rows(candidates, system.rtol, system.length_scale)
    if picked.shape[0] != order:
        # a large rtol (1e-3 from the command line) blurs the candidates' decisions, made at 1e3 rtol,
        # until they disagree with the system's order: its own basis is then the readable one (it
        # was an "Internal error" for `screwkit analyze h4 --rtol 1e-3`)
        picked = np.asarray(system.basis)
    if system.is_symbolic:
        return picked
    sizes = np.linalg.norm(picked[:, :3], axis=1)
    moments = np.linalg.norm(picked[:, 3:], axis=1)
    scale = np.where(sizes > system.rtol * moments / float(system.length_scale or 1.0), sizes, moments)
    return picked / scale[:, None]


def _motion_label(translations: int, rotations: int) -> str:
    """``"3T1R"``, ``"2R1T"``, ``"3T"``: the larger count first (translations on a tie)."""
    parts = [(translations, "T"), (rotations, "R")]
    parts.sort(key=lambda p: (-p[0], p[1] != "T"))
    return "".join(f"{n}{kind}" for n, kind in parts if n) or "0"


def motion_type(twists: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None) -> Any:
    """The motion type of a twist system: its numbers of translations and other freedoms.

    ``t = dim(T ∩ translations) = order(T) + 3 − order(T + translations)`` and ``r = order(T) − t``
    (the freedoms that are not translations: rotations or screws). Labelled ``"3T1R"`` (a
    Schoenflies motion), ``"3T"``, ``"2R1T"``, ``"3T3R"``: the larger count first, translations
    first on a tie; ``"0"`` for the 0-system.

    Parameters
    ----------
    twists : ScrewSystem or array_like, shape (..., k, 6)
        A system, or generators (numeric, batched over leading axes; or one symbolic ``(k, 6)``
        array, decided generically).
    rtol, length_scale
        As in :func:`screwkit.algebra.ranks.screw_rank` (a ScrewSystem uses its own).

    Returns
    -------
    str, or numpy.ndarray of str over the batch

    Examples
    --------
    >>> from screwkit.algebra.screw import prismatic_twist, revolute_twist
    >>> schoenflies = [*(prismatic_twist(e) for e in np.eye(3)), revolute_twist([0, 0, 1], [1, 2, 0])]
    >>> motion_type(schoenflies), motion_type(ScrewSystem.span(schoenflies[2:]))
    ('3T1R', '1T1R')
    >>> motion_type(np.stack([np.array(schoenflies[:3]), np.array(schoenflies[1:])]))
    array(['3T', '2T1R'], dtype='<U4')
    """
    if isinstance(twists, ScrewSystem):
        rows, rtol, length_scale = twists.basis, twists.rtol, twists.length_scale
    elif isinstance(twists, Screw):
        rows = twists.coords.reshape(1, 6)
    else:
        rows = _rows_batched(twists)
    length_scale = characteristic_length(rows, length_scale) if rows.size else 1.0
    couples = np.broadcast_to(_COUPLES, (*rows.shape[:-2], 3, 6))
    stacked = np.concatenate(B.promote(rows, np.asarray(couples, dtype=float)), axis=-2)
    order = np.asarray(screw_rank(rows, rtol=rtol, length_scale=length_scale))
    translations = order + 3 - np.asarray(screw_rank(stacked, rtol=rtol, length_scale=length_scale))
    labels = np.vectorize(_motion_label, otypes=[str])(translations, order - translations)
    return str(labels) if labels.ndim == 0 else labels


def _rows_batched(twists: Any) -> Array:
    if isinstance(twists, list | tuple) and twists and all(isinstance(s, Screw) for s in twists):
        return _rows(twists, "twists")
    array = B.as_array(twists, "twists", (6,))
    return array.reshape(1, 6) if array.ndim == 1 else array
