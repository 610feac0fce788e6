"""Jacobian matrices ``A χ̇ = B θ̇`` over poses and their Gosselin–Angeles types: one result class.

:class:`Jacobians` holds the forward Jacobian ``A`` and the inverse Jacobian ``B`` of ``A χ̇ = B θ̇``
over a leading batch shape (``()`` for one pose; index it for one pose), their closeness to rank
deficiency and the Gosselin–Angeles type of every pose (Gosselin & Angeles, "Singularity analysis of
closed-loop kinematic chains", IEEE Trans. Robot. Autom. 6(3), 1990: ``B`` singular *inverse*
(serial, first kind), ``A`` singular *direct* (parallel, second kind), both *combined*). Two routes
make one:

* :func:`screwkit.core.jacobians.jacobians_from_wrenches` builds ``A`` and ``B`` from a wrench
  analysis and a twist basis (their rows, the basis, the limbs at a serial singularity and the
  analysis come with them; closeness measures on unit-free matrices, that module's docstring);
* :func:`classify_jacobians` takes given matrices (a paper's own ``A`` and ``B``), whose closeness
  is each matrix's inverse condition number ``σ_min / σ_max``.

:func:`gosselin_angeles_label` names a twist-graph verdict (:mod:`screwkit.core.verdicts`) as one of
the :data:`GOSSELIN_ANGELES_TYPES`.

Examples
--------
>>> result = classify_jacobians(np.eye(2), np.diag([1.0, 0.0]))
>>> result.type, result.closeness["inverse"], result.det_B
('inverse', 0.0, 0.0)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..algebra.backend import DEFAULT_RTOL, as_array
from ..algebra.checks import checked_rtol
from ..exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError
from .wrench_systems import WrenchAnalysis

__all__ = [
    "GOSSELIN_ANGELES_TYPES", "UNREACHABLE", "Jacobians", "classify_jacobians", "gosselin_angeles_label"
]

Array = np.ndarray

#: The four Gosselin–Angeles types, indexed by ``2 * direct + inverse``.
GOSSELIN_ANGELES_TYPES = ("regular", "inverse", "direct", "combined")
#: The type of a pose out of reach in a batch (its matrices and closeness NaN; a posed batch's marker,
#: :attr:`screwkit.robots.posed.PosedMechanism.jacobians`), never one of the four types.
UNREACHABLE = "unreachable"


def _plain(value: Any) -> Any:
    array = np.asarray(value)
    return float(array) if array.ndim == 0 else array


def _json(value: Any) -> Any:
    """Nested lists, NaN (a pose out of reach) as None."""
    array = np.asarray(value, dtype=float)
    if not np.isnan(array).any():
        return array.tolist()
    out = array.astype(object)
    out[np.isnan(array)] = None
    return out.tolist()


def _read_only(value: Any) -> Array:
    array = np.array(value)
    array.flags.writeable = False
    return array


def _safe_divide(numerator: Array, denominator: Array) -> Array:
    """``numerator / denominator``, 0 where the denominator is not positive."""
    return np.divide(
        numerator,
        denominator,
        out=np.zeros(np.broadcast_shapes(numerator.shape, denominator.shape)),
        where=denominator > 0,
    )


def _closeness(matrix: Array) -> Array:
    """``σ_min / σ_max`` over a batch of matrices ``(..., m, n)`` (0 for a zero matrix, NaN for a matrix
    of a pose out of reach, NaN)."""
    missing, filled = _filled(matrix)
    values = np.linalg.svd(filled, compute_uv=False)
    return np.where(missing, np.nan, _safe_divide(values[..., -1], values[..., 0]))


def _filled(matrix: Array) -> tuple[Array, Array]:
    """Where a batch of matrices ``(..., m, n)`` is NaN (a pose out of reach), and the matrices with an
    identity there (so that numpy's linear algebra neither warns nor fails; its results replaced by NaN)."""
    missing = np.isnan(matrix).any(axis=(-2, -1))
    return missing, np.where(missing[..., None, None], np.eye(*matrix.shape[-2:]), matrix)


def _require_square(A: Array) -> None:
    if A.shape[-1] != A.shape[-2]:
        raise ScrewkitValueError(
            f"Expected a square A for A⁻¹B and det A, got A of shape {A.shape[-2:]} "
            f"({A.shape[-2]} actuated joints, {A.shape[-1]} twists in the basis"
            + ("; redundantly actuated: B⁻¹A gives the joint rates" if A.shape[-2] > A.shape[-1] else "")
            + ")."
        )


@dataclass(frozen=True, eq=False)
class Jacobians:
    """Forward and inverse Jacobians ``A χ̇ = B θ̇`` over a batch of poses (shape ``()`` for one).

    Index it (``jac[3]``) for one pose. A pose out of reach in a posed batch has NaN matrices,
    closeness and determinants, the type :data:`UNREACHABLE` and no serial flag. Built from a wrench analysis
    (:func:`~screwkit.core.jacobians.jacobians_from_wrenches`) it also holds the rows ``w_j``, the
    twist basis, the actuated joints, the serial flags and the analysis; built from given matrices
    (:func:`classify_jacobians`) those are None (no actuated joints).

    Attributes
    ----------
    A : numpy.ndarray, shape (..., n, dof)
        The forward (direct) Jacobian; from wrenches ``A_jk = w_j ∘ t_k`` (paper 004 Eq. 6).
    B : numpy.ndarray, shape (..., n, n)
        The inverse Jacobian; from wrenches ``diag(w_j ∘ $_j)``, ``≥ 0``, 0 for a limb at a serial
        singularity.
    closeness : dict of str to float or numpy.ndarray
        ``"direct"`` and ``"inverse"``, 0 at the singularity: from wrenches the measures of
        :mod:`screwkit.core.jacobians` (``"inverse"`` a transmission, which can exceed 1); for given
        matrices ``σ_min / σ_max`` of ``A`` and of ``B`` (computed when not given, or empty).
    rtol : float
        A matrix counts as singular where its closeness is at most ``rtol``.
    wrenches : numpy.ndarray, shape (..., n, 6), or None
        The rows ``w_j``: unit force (or unit couple), user frame.
    twist_basis : numpy.ndarray, shape (..., dof, 6), or None
    actuated_joints : tuple of str
        Row order (the analysis's limb order: sorted names); empty for given matrices.
    serial : numpy.ndarray of bool, shape (..., n), or None
        True where that limb is at a serial singularity (``B_jj = 0`` or transmission ``≤ rtol``).
    analysis : WrenchAnalysis or None

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.jacobians import jacobians_from_wrenches
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [0, 1, 0], actuated=True))])
    >>> result = jacobians_from_wrenches(wrench_analysis(G), [[0, 0, 0, 0, 1, 0]])
    >>> result.wrenches, result.serial_limbs
    (array([[0., 1., 0., 0., 0., 0.]]), ())
    >>> Jacobians(np.eye(2), np.diag([1.0, 0.0])).type
    'inverse'
    """

    A: Array
    B: Array
    closeness: dict[str, Any] = field(default_factory=dict)
    rtol: float = DEFAULT_RTOL
    wrenches: Array | None = None
    twist_basis: Array | None = None
    actuated_joints: tuple[str, ...] = ()
    serial: Array | None = None
    analysis: WrenchAnalysis | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        for name in ("A", "B", "wrenches", "twist_basis", "serial"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, _read_only(getattr(self, name)))
        if not self.closeness:
            closeness = {"direct": _plain(_closeness(self.A)), "inverse": _plain(_closeness(self.B))}
            object.__setattr__(self, "closeness", closeness)

    @property
    def shape(self) -> tuple[int, ...]:
        """The batch shape (``()`` for one pose)."""
        return self.A.shape[:-2]

    @property
    def single(self) -> bool:
        """True for one pose."""
        return self.shape == ()

    def __len__(self) -> int:
        if self.single:
            raise TypeError("the Jacobians of one pose have no length")
        return self.shape[0]

    def __getitem__(self, index: Any) -> Jacobians:
        def pick(value: Any) -> Any:
            return None if value is None else value[index]

        return Jacobians(
            self.A[index],
            self.B[index],
            {k: _plain(np.asarray(v)[index]) for k, v in self.closeness.items()},
            self.rtol,
            pick(self.wrenches),
            pick(self.twist_basis),
            self.actuated_joints,
            pick(self.serial),
            pick(self.analysis),
        )

    @property
    def reached(self) -> Array:
        """True where the pose is in reach (its closeness measures are numbers, not NaN).

        Examples
        --------
        >>> classify_jacobians(np.eye(2), np.eye(2)).reached
        array(True)
        """
        return np.asarray(~(np.isnan(self.closeness["direct"]) | np.isnan(self.closeness["inverse"])))

    @property
    def direct(self) -> Array:
        """True where ``A`` is rank-deficient (direct-kinematic, parallel, second kind); False out of
        reach."""
        return np.asarray(self.closeness["direct"]) <= self.rtol

    @property
    def inverse(self) -> Array:
        """True where ``B`` is rank-deficient (inverse-kinematic, serial, first kind); False out of reach."""
        return np.asarray(self.closeness["inverse"]) <= self.rtol

    @property
    def types(self) -> Array:
        """Gosselin–Angeles type per pose, an array of str of the batch shape; :data:`UNREACHABLE`
        at a pose out of reach (NaN closeness).

        Examples
        --------
        >>> classify_jacobians(np.stack([np.eye(2), np.zeros((2, 2))]), np.eye(2)).types
        array(['regular', 'direct'], dtype='<U8')
        >>> Jacobians(np.full((2, 2), np.nan), np.full((2, 2), np.nan)).type
        'unreachable'
        """
        index = 2 * self.direct.astype(int) + self.inverse.astype(int)
        types, reached = np.asarray(np.asarray(GOSSELIN_ANGELES_TYPES)[index]), self.reached
        return types if reached.all() else np.asarray(np.where(reached, types, UNREACHABLE))

    @property
    def type(self) -> Any:
        """The Gosselin–Angeles type (a str for one pose; :attr:`types` over a batch)."""
        types = self.types
        return str(types) if self.single else types

    @property
    def serial_limbs(self) -> tuple[str, ...]:
        """Actuated joints whose limb is at a serial singularity (one pose; empty for given matrices)."""
        if not self.single:
            raise ScrewkitTypeError(
                f"Expected one pose for `serial_limbs`, got a batch of shape {self.shape}."
            )
        if self.serial is None:
            return ()
        return tuple(name for name, flag in zip(self.actuated_joints, self.serial, strict=True) if flag)

    @property
    def det_A(self) -> Any:
        """``det A`` per pose (from wrenches, unit: length to the number of rotations in the basis; NaN
        out of reach).

        Raises
        ------
        ScrewkitValueError
            If ``A`` is not square.

        Examples
        --------
        >>> Jacobians(2 * np.eye(2), np.eye(2)).det_A
        4.0
        """
        _require_square(self.A)
        missing, filled = _filled(self.A)
        return _plain(np.where(missing, np.nan, np.linalg.det(filled)))

    @property
    def det_B(self) -> Any:
        """``det B`` per pose (from wrenches ``Π_j B_jj``, paper 004 Eq. 10 up to the row scaling; NaN
        out of reach).

        Examples
        --------
        >>> Jacobians(np.eye(2), np.diag([2.0, 3.0])).det_B
        6.0
        """
        if self.B.shape[-1] != self.B.shape[-2]:
            raise ScrewkitValueError(f"Expected a square B for det B, got B of shape {self.B.shape[-2:]}.")
        if self.serial is not None:  # diagonal: the product, exactly
            return _plain(np.prod(np.diagonal(self.B, axis1=-2, axis2=-1), axis=-1))
        missing, filled = _filled(self.B)
        return _plain(np.where(missing, np.nan, np.linalg.det(filled)))

    def kinematic_jacobian(self) -> Array:
        """``J = A⁻¹B`` with ``χ̇ = J θ̇`` (paper 004 Eq. 9), per pose; independent of the row scaling;
        NaN at a pose out of reach.

        Returns
        -------
        numpy.ndarray, shape (..., dof, n)

        Raises
        ------
        ScrewkitValueError
            If ``A`` is not square.
        DegenerateGeometryError
            If ``A`` is singular at some pose (type ``"direct"`` or ``"combined"``; names the first
            batch indices).

        Examples
        --------
        >>> Jacobians(np.array([[0.5]]), np.array([[1.0]])).kinematic_jacobian()
        array([[2.]])
        """
        _require_square(self.A)
        singular = self.direct
        if np.any(singular):
            if self.single:
                raise DegenerateGeometryError(
                    "The kinematic Jacobian A⁻¹B does not exist at this pose: A is singular "
                    f"(Gosselin-Angeles type {self.type!r}, direct closeness "
                    f"{self.closeness['direct']:.3g} <= rtol {self.rtol:g})."
                )
            indices = [tuple(int(i) for i in index) for index in np.argwhere(singular)[:5]]
            raise DegenerateGeometryError(
                f"The kinematic Jacobian A⁻¹B does not exist at {int(singular.sum())} poses of the batch "
                f"(first batch indices {indices}): A is singular there (direct closeness <= rtol "
                f"{self.rtol:g})."
            )
        missing, filled = _filled(self.A)
        out = missing[..., None, None]
        return np.where(out, np.nan, np.linalg.solve(filled, np.where(out, 0.0, self.B)))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (arrays as nested lists).

        Returns
        -------
        dict
            ``type`` (a list over a batch), ``A``, ``B`` (NaN out of reach as None); from wrenches
            ``wrenches``,
            ``twist_basis``, ``actuated_joints``; ``closeness``, ``rtol``; from wrenches
            ``serial_limbs`` (one pose) or ``serial`` (a batch).

        Examples
        --------
        >>> Jacobians(np.eye(1), np.eye(1)).to_dict()["type"]
        'regular'
        """
        result: dict[str, Any] = {
            "type": self.type if self.single else self.types.tolist(),
            "A": _json(self.A),
            "B": _json(self.B),
        }
        if self.wrenches is not None and self.twist_basis is not None:
            result["wrenches"] = _json(self.wrenches)
            result["twist_basis"] = _json(self.twist_basis)
            result["actuated_joints"] = list(self.actuated_joints)
        result["closeness"] = {k: _json(v) for k, v in self.closeness.items()}
        result["rtol"] = self.rtol
        if self.serial is not None:
            if self.single:
                result["serial_limbs"] = list(self.serial_limbs)
            else:
                result["serial"] = self.serial.tolist()
        return result

    def __repr__(self) -> str:
        """One line: the type, the matrices' sizes and the closeness measures (over a batch: its shape
        and the count of each type).

        Returns
        -------
        str

        Examples
        --------
        >>> Jacobians(np.eye(2), np.diag([1.0, 0.0]))
        Jacobians('inverse', A 2x2, B 2x2, closeness direct 1, inverse 0)
        """
        n, dof = self.A.shape[-2:]
        if not self.single:
            return f"Jacobians(shape={self.shape}: {self._tally()})"
        return (
            f"Jacobians({self.type!r}, A {n}x{dof}, B {n}x{self.B.shape[-1]}, closeness direct "
            f"{self.closeness['direct']:.3g}, inverse {self.closeness['inverse']:.3g})"
        )

    def _tally(self) -> str:
        names, counts = np.unique(self.types, return_counts=True)
        return ", ".join(f"{c} {name}" for name, c in zip(names.tolist(), counts.tolist(), strict=True))

    def __str__(self) -> str:
        n, dof = self.A.shape[-2:]
        if not self.single:
            return (
                f"Jacobians over a batch of shape {self.shape}: {n} actuated joint(s), dof {dof}; "
                f"{self._tally()}"
            )
        if self.type == UNREACHABLE:
            return f"unreachable: the pose is out of reach, no Jacobians (A {n}x{dof}, B {n}x{n} NaN)"
        head = "regular" if self.type == "regular" else f"{self.type} singularity"
        lines = [
            f"{head} (Gosselin-Angeles): A {n}x{dof}, B {n}x{self.B.shape[-1]}; closeness direct "
            f"{self.closeness['direct']:.3g}, inverse {self.closeness['inverse']:.3g}"
        ]
        lines.extend(f"  serial singularity of the limb of {name!r} (B_jj = 0)" for name in self.serial_limbs)
        return "\n".join(lines)


def classify_jacobians(A: Any, B: Any, *, rtol: float = DEFAULT_RTOL) -> Jacobians:
    """Gosselin–Angeles type from given (dimensionless) Jacobians ``A``, ``B`` of ``A t = B θ̇``.

    For matrices that come from elsewhere than :func:`~screwkit.core.jacobians.jacobians_from_wrenches`
    (a paper's own ``A`` and ``B``, e.g.), whatever their shapes. The closeness of each matrix to
    rank deficiency is its *inverse condition number* ``σ_min / σ_max``: it lies in ``[0, 1]`` and
    is 0 exactly when the matrix loses rank (Gosselin & Angeles 1990: ``B`` inverse/serial, ``A``
    direct/parallel, both: combined); it does not change under a rigid motion of the base frame
    (which multiplies ``A`` and ``B`` by orthogonal matrices), nor with the unit of length provided
    the characteristic length that makes the matrices dimensionless is given in the same unit.

    Parameters
    ----------
    A, B : (..., m, n) array_like
    rtol : float, default 1e-9
        Threshold on ``σ_min/σ_max``; must lie in ``[0, 1)``.

    Returns
    -------
    Jacobians
        With ``closeness`` ``{"direct": σ_min/σ_max of A, "inverse": σ_min/σ_max of B}``.

    Raises
    ------
    ScrewkitValueError
        ``rtol`` is not a number in ``[0, 1)``, or a matrix is empty.

    References
    ----------
    Gosselin & Angeles, "Singularity analysis of closed-loop kinematic chains", IEEE Trans. Robot.
    Autom. 6(3), 1990.

    Examples
    --------
    >>> classify_jacobians(np.eye(3), np.eye(3)).types.tolist()
    'regular'
    >>> classify_jacobians(np.eye(4), np.diag([1.0, 1.0, 0.0, 1.0]), rtol=1e-9).type
    'inverse'
    """
    tolerance = checked_rtol(rtol, "rtol")
    a, b = (as_array(value, name, (None, None), symbolic=False) for value, name in ((A, "A"), (B, "B")))
    for matrix, name in ((a, "A"), (b, "B")):
        if 0 in matrix.shape[-2:]:
            raise ScrewkitValueError(
                f"Expected `{name}` to be a non-empty matrix (..., m, n), got {matrix.shape}."
            )
    return Jacobians(a, b, rtol=tolerance)


def gosselin_angeles_label(report: Any) -> str:
    """Name a twist-graph verdict (:func:`screwkit.core.singularity.classify`) as a Gosselin–Angeles type.

    A *serial* (limb) singularity, where an actuator cannot move the platform, is the inverse
    (first-kind) singularity of ``B``; a *constraint* or *actuation* singularity, where the
    platform moves with every actuator locked, is the direct (second-kind) singularity of ``A``;
    both at once is the combined (third-kind) one.

    Parameters
    ----------
    report : SingularityReport
        Anything with a ``labels`` tuple drawn from ``"constraint"``, ``"actuation"``,
        ``"serial"``.

    Returns
    -------
    str
        One of :data:`GOSSELIN_ANGELES_TYPES`.

    Raises
    ------
    ScrewkitValueError
        A label outside those three.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> gosselin_angeles_label(SimpleNamespace(labels=("actuation", "serial")))
    'combined'
    """
    labels = tuple(report.labels)
    unknown = sorted(set(labels) - {"constraint", "actuation", "serial"})
    if unknown:
        raise ScrewkitValueError(f"Expected labels among 'constraint', 'actuation', 'serial', got {unknown}.")
    direct = "constraint" in labels or "actuation" in labels
    return GOSSELIN_ANGELES_TYPES[int("serial" in labels) + 2 * int(direct)]
