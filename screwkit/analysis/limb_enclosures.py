"""Interval vector algebra over enclosures and the arm-and-parallelogram limb shared by the
closed-form models of :mod:`screwkit.analysis.enclosures` and :mod:`screwkit.analysis.delta_enclosure`.

A vector is a list of three :class:`~screwkit.analysis.intervals.Enclosure` (or
:class:`~screwkit.analysis.intervals.Values`, the same operations on floats), None standing for an
exact zero; constants computed by trigonometry are enclosed within 1e-15 of their array's largest
entry (exact zeros stay exact). Private to :mod:`screwkit.analysis`.

Examples
--------
>>> from screwkit.analysis.intervals import Values
>>> x, y = Values.variables(np.array([[1.0, 2.0]]))
>>> _dot(_cross([x, None, None], [None, y, None]), [None, None, x]).tolist()
[2.0]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..exceptions import ScrewkitValueError
from .intervals import Enclosure, Values

__all__: list[str] = []

Array = np.ndarray

#: Relative size of the enclosure of a constant computed by trigonometry.
_CONSTANT_SPREAD = 1e-15

Vector = list[Enclosure | None]


@dataclass(frozen=True)
class _Constant:
    """A float constant and the bound of its error (0: exact)."""

    value: float
    spread: float


def _constants(array: Array, exact: bool) -> list[list[_Constant]]:
    """Rows of constants; ``exact=False``: each nonzero entry enclosed within 1e-15 of the
    array's largest entry (computed by trigonometry)."""
    spread = 0.0 if exact else _CONSTANT_SPREAD * float(np.max(np.abs(array)))
    return [[_Constant(float(v), 0.0 if v == 0.0 else spread) for v in row] for row in np.atleast_2d(array)]


_COUNTS = {2: "two", 3: "three", 4: "four"}


def _family_mode(
    mechanism: Any, options: Any, family: str, default: tuple[int, ...]
) -> tuple[int, ...]:
    """The working mode in ``options`` (``{"mode": signs}``, else ``default``) of a mechanism of
    ``family``, checked: as many signs (+1 or -1) as ``default``, nothing else in ``options``."""
    if getattr(mechanism, "family", None) != family:
        raise ScrewkitValueError(
            f"Expected `mechanism` of the {family} family, got {getattr(mechanism, 'name', mechanism)!r}."
        )
    given = dict(options or {})
    mode = given.pop("mode", default)
    count = len(default)
    signs = isinstance(mode, tuple | list) and len(mode) == count and all(m in (-1, 1) for m in mode)
    if given or not signs:
        raise ScrewkitValueError(
            f"Expected `mode` to give only a mode of {_COUNTS[count]} signs (+1 or -1), got {options!r}."
        )
    return tuple(int(m) for m in mode)


def _times(x: Enclosure | None, c: _Constant) -> Enclosure | None:
    """``x · c`` (None stands for an exact zero)."""
    if x is None or (c.value == 0.0 and c.spread == 0.0):
        return None
    if c.spread == 0.0:
        return x * c.value
    return x * type(x).constant(c.value, x, relative=c.spread / abs(c.value))


def _sum(*terms: Enclosure | None) -> Enclosure | None:
    out = None
    for t in terms:
        if t is not None:
            out = t if out is None else out + t
    return out


def _mul(a: Enclosure | None, b: Enclosure | None) -> Enclosure | None:
    return None if a is None or b is None else a * b


def _sub(a: Enclosure | None, b: Enclosure | None) -> Enclosure | None:
    return _sum(a, None if b is None else -b)


def _cross(a: Vector, b: Vector) -> Vector:
    return [
        _sub(_mul(a[1], b[2]), _mul(a[2], b[1])),
        _sub(_mul(a[2], b[0]), _mul(a[0], b[2])),
        _sub(_mul(a[0], b[1]), _mul(a[1], b[0])),
    ]


def _dot(a: Vector, b: Vector) -> Enclosure | None:
    return _sum(*(_mul(x, y) for x, y in zip(a, b, strict=True)))


def _dot_constant(a: Vector, row: list[_Constant]) -> Enclosure | None:
    return _sum(*(_times(x, c) for x, c in zip(a, row, strict=True)))


class _ClosedFormModel:
    """What certification reads of a closed-form model
    (:class:`~screwkit.analysis.enclosures.FourLimbModel`,
    :class:`~screwkit.analysis.delta_enclosure.DeltaModel`):
    ``pose_names``, ``limbs`` (the reach functions ``serial:1`` .. ``serial:<limbs>``),
    :meth:`functions` (from the model's ``statements``), ``evaluate()`` over enclosures and
    :meth:`values` in floats."""

    pose_names: tuple[str, ...]
    limbs: int
    arm: float
    rod: float
    working_mode: tuple[int, ...]
    base: tuple[list[list[_Constant]], ...]  # per limb: a point, u, F j, F k
    statements: ClassVar[dict[str, str]]  # "constraint", "actuation", "serial" ({i}: the limb)

    def _limb_functions(self, ds: list[Vector], singular: bool) -> tuple[dict[str, Enclosure], list[Vector]]:
        """Each limb's reach function ``serial:i`` from its ``d_i`` and, with ``singular``, the unit
        rods (:func:`_parallelogram_limb` in the limb's branch)."""
        _, _, j_rows, k_rows = self.base
        out: dict[str, Enclosure] = {}
        rods: list[Vector] = []
        for i, d in enumerate(ds):
            mode = float(self.working_mode[i])
            g, rod_vector = _parallelogram_limb(d, j_rows[i], k_rows[i], self.arm, self.rod, mode, singular)
            out[f"serial:{i + 1}"] = g
            if rod_vector is not None:
                rods.append(rod_vector)
        return out, rods

    def functions(self) -> dict[str, str]:
        """Each certified function's name and statement (what its vanishing means).

        Returns
        -------
        dict of str to str
            ``"constraint"``, ``"actuation"``, ``"serial:1"`` .. ``"serial:<limbs>"``.

        Examples
        --------
        >>> from screwkit.analysis.enclosures import FourLimbModel
        >>> FourLimbModel.of(load_mechanism("h4")).functions()["serial:2"][:24]
        'P_i^2 + Q_i^2 - K_i^2 = '
        """
        out = {"constraint": self.statements["constraint"], "actuation": self.statements["actuation"]}
        for i in range(self.limbs):
            out[f"serial:{i + 1}"] = self.statements["serial"].format(i=i + 1)
        return out

    def evaluate(self, pose: list[Enclosure], *, singular: bool = True) -> dict[str, Enclosure]:
        """The model's functions over boxes (each model writes its own)."""
        raise NotImplementedError

    def values(self, poses: Any, *, singular: bool = True) -> dict[str, Array]:
        """Every function of the model's ``functions()`` at poses, in floats: the same closed forms
        as :meth:`evaluate` (inverse kinematics included), one numpy operation per step over the batch
        (:class:`~screwkit.analysis.intervals.Values`; rounded to nearest, not enclosed).

        Parameters
        ----------
        poses : array_like, shape (m, n)
            Over :attr:`pose_names` (API units: radians).
        singular : bool, default True
            Also the constraint and actuation functions.

        Returns
        -------
        dict of str to numpy.ndarray, shape (m,)
            NaN for the constraint and actuation functions where a limb does not reach the pose
            (its ``serial:i`` function negative).

        Raises
        ------
        ScrewkitValueError
            If ``poses`` is not an ``(m, n)`` array of finite numbers.

        Examples
        --------
        >>> from screwkit.analysis.enclosures import FourLimbModel
        >>> model = FourLimbModel.of(load_mechanism("quattro"))
        >>> values = model.values([[100.0, 100.0, -750.0, 0.0], [0.0, 0.0, -5000.0, 0.0]])
        >>> bool(values["serial:1"][0] > 0 > values["serial:1"][1]), bool(np.isnan(values["actuation"][1]))
        (True, True)
        """
        array = np.asarray(poses, dtype=float) if _numeric(poses) else None
        n = len(self.pose_names)
        if array is None or array.ndim != 2 or array.shape[1] != n or not np.isfinite(array).all():
            raise ScrewkitValueError(
                f"Expected `poses` to be an (m, {n}) array of finite numbers {self.pose_names}, got "
                f"{getattr(array, 'shape', type(poses).__name__)}."
            )
        found = self.evaluate(Values.variables(array), singular=singular)  # type: ignore[arg-type]
        return {name: np.asarray(value, dtype=float) for name, value in found.items()}



def _numeric(value: Any) -> bool:
    """Whether ``value`` converts to a float array (no object arrays of text)."""
    try:
        np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return False
    return True


def _parallelogram_limb(
    d: Vector, j_row: list[_Constant], k_row: list[_Constant], arm: float, rod: float, mode: float,
    singular: bool,
) -> tuple[Enclosure, Vector | None]:
    """One arm-and-parallelogram limb from ``d = c - a`` (platform point minus actuated joint point):
    its reach function ``g = P² + Q² - K²`` (``P = d·F j``, ``Q = d·F k``,
    ``K = (|d|² + b² - l²)/(2b)``; paper 004, Eq. 3) and, with ``singular``, its unit rod
    ``w = (d - b v)/l`` with the arm ``v = cos θ F j + sin θ F k`` of the branch ``mode``
    (``cos θ = (P K + m Q √g)/(P² + Q²)``, ``sin θ = (Q K - m P √g)/(P² + Q²)``)."""
    big_p = _dot_constant(d, j_row)
    big_q = _dot_constant(d, k_row)
    squared = _sum(*(None if e is None else e.square() for e in d))
    assert squared is not None and big_p is not None and big_q is not None
    big_k = _divided(squared + (arm * arm - rod * rod), 2.0 * arm)
    assert big_k is not None
    rho2 = big_p.square() + big_q.square()
    g = rho2 - big_k.square()
    if not singular:
        return g, None
    root = g.sqrt()
    inv = rho2.reciprocal()
    cos_t = (big_p * big_k + big_q * root * mode) * inv
    sin_t = (big_q * big_k - big_p * root * mode) * inv
    v = [_sum(_times(cos_t, j_row[k]), _times(sin_t, k_row[k])) for k in range(3)]
    return g, [_divided(_sum(d[k], _scaled_by(v[k], -arm)), rod) for k in range(3)]


def _scaled_by(x: Enclosure | None, value: float) -> Enclosure | None:
    return None if x is None else x * value


def _relative(c: _Constant) -> float:
    return 0.0 if c.value == 0 else c.spread / abs(c.value)


def _divided(x: Enclosure | None, value: float) -> Enclosure | None:
    """``x / value`` for a positive float: a product when ``1/value`` is exact (a power of two),
    else by the enclosure of ``1/value``."""
    if x is None:
        return None
    mantissa, _ = np.frexp(value)
    if mantissa == 0.5:
        return x * (1.0 / value)
    return x * type(x).constant(value, x).reciprocal()


def _cross_constant(w: Vector, u: list[_Constant]) -> Vector:
    """``w × u`` for a constant ``u``."""
    return [
        _sub(_times(w[1], u[2]), _times(w[2], u[1])),
        _sub(_times(w[2], u[0]), _times(w[0], u[2])),
        _sub(_times(w[0], u[1]), _times(w[1], u[0])),
    ]
