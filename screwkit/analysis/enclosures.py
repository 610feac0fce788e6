"""Enclosures of the singularity conditions of the four-limb robots with a nacelle articulated
about vertical axes (Quattro, H4) over boxes of pose space, in closed form.

The certified functions (each vanishes exactly on one kind of singular set, in the working mode
``m``, the signs of ``h_i``):

* **serial / reach**, one per limb: ``g_i = P_i² + Q_i² - K_i²`` with paper 004's Eq. (3)
  ``P_i cos θ_i + Q_i sin θ_i = K_i`` (``P_i = d_i·F_i j``, ``Q_i = d_i·F_i k``,
  ``K_i = (|d_i|² + b² - l²)/(2b)``, ``d_i = c_i - a_i``). Limb ``i`` reaches the pose iff
  ``g_i >= 0``, and ``h_i = m_i (b/l) √g_i`` (Eq. 8 with ``θ_i = ψ_i - m_i δ_i``), so
  ``det B = Π h_i`` vanishes exactly where some ``g_i = 0``: the reach boundary is the serial
  singular set.
* **actuation**: ``det A = 2r ((w_I1 × w_I2) × (w_II1 × w_II2))·s`` (paper 004, Eq. 12 and
  Table 2; ``w_i`` the unit rods, ``s = ∂(R(φ) i)/∂φ``), with the rods from the closed-form inverse
  kinematics ``cos θ_i = (P_i K_i + m_i Q_i √g_i)/(P_i² + Q_i²)``,
  ``sin θ_i = (Q_i K_i - m_i P_i √g_i)/(P_i² + Q_i²)``.
* **constraint**: paper 002's Eq. (6), ``(s_I × s_II)·e = 0`` with ``s_I = n_I1 × n_I2``,
  ``n_i = w_i × F_i i`` (the normal of limb ``i``'s parallelogram) and ``e`` the axis of the
  nacelle's revolute joints (``z``).

Everything is evaluated with :class:`~screwkit.analysis.intervals.Enclosure` (outward rounding,
gradients for the mean-value form). Constants computed by the base frames' trigonometry are
enclosed within 1e-15 of their array's largest entry (exact zeros stay exact): the certificate is
for the catalog's parameters as written (lengths, and angles in degrees converted to radians).

Examples
--------
>>> model = FourLimbModel.of(load_mechanism("quattro"))
>>> sorted(model.functions())
['actuation', 'constraint', 'serial:1', 'serial:2', 'serial:3', 'serial:4']
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .intervals import Enclosure, Values

__all__ = ["COVERED", "FourLimbModel"]

Array = np.ndarray

#: What certification covers: the four-limb family with a nacelle articulated about vertical axes.
#: (``articulated_y``, the V4, is left out until its constraint condition, Eq. (6) with the axis
#: ``y``, is checked against the twist graph's labels; the screw pair, Veloce and Ragnar, has
#: another constraint condition.)
COVERED = "the four_limb family with platform_kind articulated_z (Quattro, H4)"

#: Relative size of the enclosure of a constant computed by trigonometry.
_CONSTANT_SPREAD = 1e-15

_SGN_COS_ETA = (1.0, -1.0, -1.0, 1.0)  # paper 004, Table 1: sgn(cos eta_i), eta_i = (2i - 1) pi/4
_SGN_SIN_ETA = (1.0, 1.0, -1.0, -1.0)  # sgn(sin eta_i)

_STATEMENTS = {
    "constraint": "(s_I x s_II).e = 0, s_I = n_I1 x n_I2, n_i = w_i x u_i (paper 002, Eq. 6): the "
    "constraint moments of the two sub-platforms are dependent",
    "actuation": "det A = 2r ((w_I1 x w_I2) x (w_II1 x w_II2)).s = 0 (paper 004, Eq. 12): the "
    "actuation forces and the constraint moments are dependent",
    "serial": "P_i^2 + Q_i^2 - K_i^2 = 0 (paper 004, Eq. 3; h_i = m_i (b/l) sqrt of it, Eq. 8): "
    "limb {i} at its reach, det B = 0",
}

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


@dataclass(frozen=True)
class FourLimbModel:
    """The closed-form model of a four-limb robot with an articulated nacelle, for enclosures.

    Attributes
    ----------
    name : str
    pose_names : tuple of str
        ``("x", "y", "z", "phi")``.
    platform_kind : str
    arm, rod, radius, offset : float
        ``b``, ``l``, ``r``, ``c`` of paper 004 (Table 3).
    working_mode : tuple of int
        The signs ``m_i`` of ``h_i``.
    subplatforms : tuple of two pairs of int
        0-based limbs of sub-platforms I and II.
    """

    name: str
    pose_names: tuple[str, ...]
    platform_kind: str
    arm: float
    rod: float
    radius: float
    offset: float
    working_mode: tuple[int, int, int, int]
    subplatforms: tuple[tuple[int, int], tuple[int, int]]
    base: tuple[list[list[_Constant]], ...]  # a, u, F j, F k: (4 rows of 3 constants) each

    @classmethod
    def of(cls, mechanism: Any, options: Mapping[str, Any] | None = None) -> FourLimbModel:
        """The model of a catalog mechanism, or a one-line refusal naming what is covered.

        Parameters
        ----------
        mechanism : Mechanism
        options : mapping, optional
            Inverse-kinematics options (``working_mode``).

        Returns
        -------
        FourLimbModel

        Raises
        ------
        ScrewkitValueError
            For a mechanism outside :data:`COVERED`.

        Examples
        --------
        >>> FourLimbModel.of(load_mechanism("h4")).working_mode
        (-1, -1, -1, -1)
        >>> FourLimbModel.of(load_mechanism("veloce"))
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: Expected `mechanism` among what certification covers ...
        """
        from ..robots.families.four_limb.configuration import base_frames
        from ..robots.families.four_limb.kinematics import checked_working_mode

        params: Any = getattr(mechanism, "parameters", None)
        kind = getattr(params, "platform_kind", None)
        if getattr(mechanism, "family", None) != "four_limb" or kind != "articulated_z":
            raise ScrewkitValueError(
                f"Expected `mechanism` among what certification covers ({COVERED}), got "
                f"{getattr(mechanism, 'name', type(mechanism).__name__)} (family "
                f"{getattr(mechanism, 'family', None)!r}, platform {kind!r})."
            )
        given = dict(options or {})
        unknown = sorted(set(given) - {"working_mode"})
        if unknown:
            raise ScrewkitValueError(f"Expected `mode` to give only a working_mode, got {unknown}.")
        mode = checked_working_mode(given.get("working_mode", (-1, -1, -1, -1)))
        frames = base_frames(params)
        base = (
            _constants(frames.a, exact=params.base_points is not None),
            _constants(frames.u, exact=False),
            _constants(frames.j_rot, exact=False),
            _constants(frames.k_rot, exact=False),
        )
        return cls(
            mechanism.name,
            tuple(mechanism.pose_names),
            kind,
            float(params.arm_length),
            float(params.rod_length),
            float(params.platform_radius),
            float(params.platform_offset),
            mode,
            params.subplatform_limbs,
            base,
        )

    def functions(self) -> dict[str, str]:
        """Each certified function's name and statement (what its vanishing means).

        Returns
        -------
        dict of str to str
            ``"constraint"``, ``"actuation"``, ``"serial:1"`` .. ``"serial:4"``.

        Examples
        --------
        >>> FourLimbModel.of(load_mechanism("h4")).functions()["serial:2"][:24]
        'P_i^2 + Q_i^2 - K_i^2 = '
        """
        out = {"constraint": _STATEMENTS["constraint"], "actuation": _STATEMENTS["actuation"]}
        for i in range(4):
            out[f"serial:{i + 1}"] = _STATEMENTS["serial"].format(i=i + 1)
        return out

    def evaluate(self, pose: list[Enclosure], *, singular: bool = True) -> dict[str, Enclosure]:
        """Enclose every function of :meth:`functions` over a batch of boxes of pose space.

        Parameters
        ----------
        pose : list of 4 Enclosure
            ``x, y, z, φ`` (API units: radians) over the boxes.
        singular : bool, default True
            Also the constraint and actuation functions (else the reach functions only).

        Returns
        -------
        dict of str to Enclosure

        Examples
        --------
        >>> model = FourLimbModel.of(load_mechanism("quattro"))
        >>> at = Enclosure.variables(np.array([[100.0, 100.0, -750.0, 0.0]]),
        ...                          np.array([[100.0, 100.0, -750.0, 0.0]]), gradient=False)
        >>> values = model.evaluate(at)
        >>> bool(values["serial:1"].lo[0] > 0 and values["actuation"].excludes_zero()[0])
        True
        """
        x, y, z, phi = pose
        cos, sin = phi.cos_sin()
        r, b, rod = self.radius, self.arm, self.rod
        bar: Vector = [cos, sin, None]  # R_z(φ) i
        s: Vector = [-sin, cos, None]  # its derivative R_z(φ) j
        a_rows, u_rows, j_rows, k_rows = self.base
        out: dict[str, Enclosure] = {}
        rods: list[Vector] = []
        for i in range(4):
            sc, ss = _SGN_COS_ETA[i], _SGN_SIN_ETA[i]
            c_i = [
                _sum(_scaled_by(bar[0], sc * r), x),
                _sum(_scaled_by(bar[1], sc * r), y + ss * self.offset),
                _sum(_scaled_by(bar[2], sc * r), z),
            ]
            d = [
                _sum(
                    c_i[k],
                    None
                    if a_rows[i][k].value == 0 and a_rows[i][k].spread == 0
                    else -type(x).constant(a_rows[i][k].value, x, relative=_relative(a_rows[i][k])),
                )
                for k in range(3)
            ]
            big_p = _dot_constant(d, j_rows[i])
            big_q = _dot_constant(d, k_rows[i])
            squared = _sum(*(None if e is None else e.square() for e in d))
            assert squared is not None and big_p is not None and big_q is not None
            big_k = _divided(squared + (b * b - rod * rod), 2.0 * b)
            assert big_k is not None
            rho2 = big_p.square() + big_q.square()
            g = rho2 - big_k.square()
            out[f"serial:{i + 1}"] = g
            if not singular:
                continue
            root = g.sqrt()
            m = float(self.working_mode[i])
            inv = rho2.reciprocal()
            cos_t = (big_p * big_k + big_q * root * m) * inv
            sin_t = (big_q * big_k - big_p * root * m) * inv
            v = [_sum(_times(cos_t, j_rows[i][k]), _times(sin_t, k_rows[i][k])) for k in range(3)]
            # w_i = (c_i - a_i - b v_i) / l = (d_i - b v_i) / l
            rods.append([_divided(_sum(d[k], _scaled_by(v[k], -b)), rod) for k in range(3)])
        if singular:
            (i1, i2), (j1, j2) = self.subplatforms
            det_a = _dot(_cross(_cross(rods[i1], rods[i2]), _cross(rods[j1], rods[j2])), s)
            assert det_a is not None
            out["actuation"] = det_a * (2.0 * r)
            normals = [_cross_constant(w, u_rows[i]) for i, w in enumerate(rods)]
            s_one, s_two = _cross(normals[i1], normals[i2]), _cross(normals[j1], normals[j2])
            constraint = _cross(s_one, s_two)[2]
            assert constraint is not None
            out["constraint"] = constraint
        return out


    def values(self, poses: Any, *, singular: bool = True) -> dict[str, Array]:
        """Every function of :meth:`functions` at poses, in floats: the same closed forms as
        :meth:`evaluate` (inverse kinematics included), one numpy operation per step over the batch
        (:class:`~screwkit.analysis.intervals.Values`; rounded to nearest, not enclosed).

        Parameters
        ----------
        poses : array_like, shape (m, 4)
            ``x, y, z, φ`` (API units: radians).
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
            If ``poses`` is not an ``(m, 4)`` array of finite numbers.

        Examples
        --------
        >>> model = FourLimbModel.of(load_mechanism("quattro"))
        >>> values = model.values([[100.0, 100.0, -750.0, 0.0], [0.0, 0.0, -5000.0, 0.0]])
        >>> bool(values["serial:1"][0] > 0 > values["serial:1"][1]), bool(np.isnan(values["actuation"][1]))
        (True, True)
        """
        array = np.asarray(poses, dtype=float) if _numeric(poses) else None
        if array is None or array.ndim != 2 or array.shape[1] != 4 or not np.isfinite(array).all():
            raise ScrewkitValueError(
                f"Expected `poses` to be an (m, 4) array of finite numbers (x, y, z, phi), got "
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
