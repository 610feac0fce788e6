"""Enclosures of the singularity conditions of the four-limb robots with an articulated nacelle
(Quattro, H4, V4) or a screw pair (Ragnar, Veloce) over boxes of pose space, in closed form;
:func:`model_of` picks the model of a mechanism (:class:`DeltaModel` for the Delta: the same limbs,
its own statements; :class:`~screwkit.analysis.mcgill_enclosure.McGillModel`,
:class:`~screwkit.analysis.peppermill_enclosure.PeppermillModel` for the two-limb SMGs).

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
* **constraint**, nacelle axis ``e = k`` (Quattro, H4): paper 002's Eq. (6),
  ``(s_I × s_II)·e = 0`` with ``s_I = n_I1 × n_I2``, ``n_i = w_i × F_i i`` (the couple of limb
  ``i``'s parallelogram). Derivation: sub-platform I, held by the couples ``n_I1``, ``n_I2``, may
  turn about ``s_I``; with ``R_I`` (axis ``e``) its branch lets the end effector turn about
  ``span(s_I, e)`` only, i.e. it exerts the couple ``c_I = s_I × e``; the two couples
  ``c_I, c_II`` (both normal to ``e``) are dependent iff
  ``c_I × c_II = e [e·(s_I × s_II)]`` vanishes (the identity ``(a × e) × (b × e) = e [e·(a × b)]``).
* **constraint**, nacelle axis ``e = j`` (V4, whose sub-platforms each hold one limb ``p`` with
  its actuated axis ``u_p ∥ e``: limbs 4 and 3): then ``n_p·e = 0`` and
  ``c = (n_q × n_p) × e = (n_q·e) n_p`` (``q`` the sub-platform's other limb), so Eq. (6) factors
  as ``(n_qI·e)(n_qII·e) e·(n_pI × n_pII)``. The first two factors are *not* singular: where
  ``n_q·e = (w_q × u_q)·e`` vanishes (limbs 1, 2 with ``u = i``: their rod horizontal) the couple
  ``n_q`` is normal to ``e`` as well, so the branch holds the end effector by **two** couples normal
  to ``e`` (one more, not one less; the sub-platform gains a turn about ``e`` that ``R_I`` undoes).
  The V4's constraint condition is the last factor, ``e·(n_pI × n_pII) = 0``: the couples of the
  limbs whose axes are along the nacelle's are parallel, i.e. the rods ``w_3``, ``w_4`` and ``j`` are
  coplanar (``det[w_3, w_4, j] = 0``). Its zeros are singular or limits of singular poses (where
  also some ``n_q·e = 0``: a set of lower dimension); where it is nonzero no constraint singularity
  exists, which is what a free box needs.
* **screw pair** (Ragnar): ``c_i = r R_z(γ_i) i + mod(i, 2) (hφ/2π) k + p`` (Table 1), so
  ``det A = det[w_i, mod(i, 2) (h/2π) w_i·k]`` (Eq. 7 with ``∂c_i/∂φ``), and the constraint is
  Eq. (6) with ``e = k``: the helical joint's twist ``(k; q × k + pitch k)`` differs from a revolute
  one by a translation every branch already has, so the branch's couple is ``s × k`` as above.
* **a sub-platform with two parallel actuated axes** (Veloce: ``u_3 = -u_1``, ``u_4 = -u_2``): its
  couples ``n_a``, ``n_b`` are both normal to ``u_a``, so ``s = n_a × n_b = λ u_a`` with
  ``λ = (n_a × n_b)·u_a`` and Eq. (6) factors as ``λ_I λ_II (u_I × u_II)·k``. Every factor is singular
  (unlike the V4's): where ``λ_I = 0`` the couples of sub-platform I are parallel, its twist system
  is a 5-system, its branch (with the helical or revolute joint about ``k``, ``n_a·k ≠ 0``) a
  6-system exerting no couple, and the end effector keeps one couple: a constraint singularity
  (paper 002, Sec. 5.3, case (c)). The enclosed function is ``λ_I λ_II`` (the constant
  ``(u_I × u_II)·k`` dropped; ``λ_I (u_I × s_II)·k`` when only sub-platform I has parallel axes).
  ``tests/analysis/test_certify_veloce.py`` checks it by a rank computation from the joint screws.

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
from typing import Any, ClassVar

import numpy as np

from ..exceptions import ScrewkitValueError
from .delta_enclosure import DeltaModel
from .intervals import Enclosure
from .limb_enclosures import (
    _CONSTANT_SPREAD,
    Vector,
    _ClosedFormModel,
    _Constant,
    _constants,
    _cross,
    _cross_constant,
    _dot,
    _dot_constant,
    _mul,
    _relative,
    _scaled_by,
    _sum,
)
from .loop_closure_enclosure import LoopClosureModel
from .mcgill_enclosure import McGillModel
from .peppermill_enclosure import PeppermillModel
from .planar_3rrp_enclosure import Planar3RRPModel

__all__ = ["COVERED", "FourLimbModel", "model_of"]

Array = np.ndarray

#: What certification covers: the four-limb family with a nacelle articulated about vertical axes
#: (Quattro, H4), about ``j`` with one actuated axis along ``j`` per sub-platform (V4) or a screw
#: pair (Ragnar, Veloce), the Delta, the McGill SMG, the Peppermill, the planar 3-RRP, and mechanisms
#: from ``screwkit.mechanism`` whose limbs are serial chains of lower pairs (a Krawczyk enclosure of
#: their loop equations: :mod:`screwkit.analysis.loop_closure_enclosure`, which names what it refuses).
COVERED = (
    "the four_limb family with platform_kind articulated_z (Quattro, H4), articulated_y with one "
    "actuated axis along j per sub-platform (V4) or screw_pair (Ragnar, Veloce), the delta "
    "(Delta), mcgill_smg (McGill SMG), peppermill (Peppermill) and planar_3rrp (planar 3-RRP) "
    "families, and twist-graph mechanisms whose limbs are serial chains of R, P, H, C, U and S joints"
)

PLATFORMS = ("articulated_z", "articulated_y", "screw_pair")

_SGN_COS_ETA = (1.0, -1.0, -1.0, 1.0)  # paper 004, Table 1: sgn(cos eta_i), eta_i = (2i - 1) pi/4
_SGN_SIN_ETA = (1.0, 1.0, -1.0, -1.0)  # sgn(sin eta_i)

_STATEMENTS = {
    "constraint": "(s_I x s_II).e = 0, s_I = n_I1 x n_I2, n_i = w_i x u_i (paper 002, Eq. 6): the "
    "constraint moments of the two sub-platforms are dependent",
    "constraint_paired": "(n_{a} x n_{b}).u_{a} (n_{c} x n_{d}).u_{c} = 0, n_i = w_i x u_i (paper 002, Eq. 6 "
    "over the constant (u_{a} x u_{c}).k: each sub-platform's actuated axes are parallel, s_I = "
    "[(n_{a} x n_{b}).u_{a}] u_{a}): the couples of limbs {a} and {b} (or {c} and {d}) are parallel, "
    "that sub-platform's branch exerts no constraint moment (paper 002, Sec. 5.3, case (c))",
    "constraint_along_axis": "e.(n_{p} x n_{q}) = 0, n_i = w_i x u_i, e = j (paper 002's Eq. 6 "
    "divided by its two non-singular factors (n_k.e)): the couples of limbs {p} and {q}, whose "
    "actuated axes lie along the nacelle's, are parallel; the sub-platforms' constraint moments are "
    "dependent",
    "actuation": "det A = 2r ((w_I1 x w_I2) x (w_II1 x w_II2)).s = 0 (paper 004, Eq. 12): the "
    "actuation forces and the constraint moments are dependent",
    "actuation_screw_pair": "det A = det[w_i, mod(i, 2) (h/2pi) w_i.k] = 0 (paper 004, Eq. 7 with Table "
    "1's screw-pair row): the actuation forces and the constraint moments are dependent",
    "serial": "P_i^2 + Q_i^2 - K_i^2 = 0 (paper 004, Eq. 3; h_i = m_i (b/l) sqrt of it, Eq. 8): "
    "limb {i} at its reach, det B = 0",
}

@dataclass(frozen=True)
class FourLimbModel(_ClosedFormModel):
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
    axis_limbs : tuple of two int, or None
        For a nacelle articulated about ``j`` (V4): the 0-based limb of each sub-platform whose
        actuated axis lies along ``j`` (the constraint condition's limbs); None for ``k``.
    limbs : int
        4.
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
    axis_limbs: tuple[int, int] | None = None
    rise: float | None = None  # screw pair: h/(2π), sub-platform I's rise per radian
    radial: tuple[list[_Constant], ...] = ()  # screw pair: c_i - p at φ = 0, r R_z(γ_i) i
    parallel_axes: tuple[bool, bool] = (False, False)  # per sub-platform: its two actuated axes parallel
    limbs: int = 4
    statements: ClassVar[dict[str, str]] = _STATEMENTS

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
        >>> FourLimbModel.of(load_mechanism("delta"))
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: Expected `mechanism` among what certification covers ...
        """
        from ..robots.families.four_limb.configuration import base_frames
        from ..robots.families.four_limb.kinematics import checked_working_mode

        params: Any = getattr(mechanism, "parameters", None)
        kind = getattr(params, "platform_kind", None)
        family = getattr(mechanism, "family", None)
        axis_limbs = _axis_limbs(params) if family == "four_limb" and kind == "articulated_y" else None
        if family != "four_limb" or kind not in PLATFORMS or axis_limbs == ():
            if family in (None, "loop_closure"):
                missing = (
                    "no closed-form kinematics to enclose: a loop-closure mechanism would need an "
                    "interval-Newton enclosure of its loop equations, not written"
                )
            elif kind == "articulated_y":
                missing = (
                    "no enclosure of its conditions written: without an actuated axis along j in each "
                    "sub-platform paper 002's Eq. (6) does not factor and its non-singular zeros are "
                    "not separated"
                )
            else:
                missing = "no enclosure of its conditions written"
            raise ScrewkitValueError(
                f"Expected `mechanism` among what certification covers ({COVERED}), got "
                f"{getattr(mechanism, 'name', type(mechanism).__name__)} (family {family!r}, platform "
                f"{kind!r}: {missing})."
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
            float(params.platform_offset or 0.0),
            mode,
            params.subplatform_limbs,
            base,
            axis_limbs or None,
            None if params.lead is None else float(params.lead) / (2.0 * np.pi),
            tuple(_constants(_radial(params), exact=False)) if kind == "screw_pair" else (),
            _parallel_axes(params) if axis_limbs is None else (False, False),
        )

    def functions(self) -> dict[str, str]:
        """Each certified function's name and statement (what its vanishing means); the V4's
        constraint statement names its two limbs.

        Returns
        -------
        dict of str to str

        Examples
        --------
        >>> FourLimbModel.of(load_mechanism("v4")).functions()["constraint"][:22]
        'e.(n_4 x n_3) = 0, n_i'
        """
        out = super().functions()
        if self.rise is not None:
            out["actuation"] = self.statements["actuation_screw_pair"]
        if self.axis_limbs is not None:
            p, q = (i + 1 for i in self.axis_limbs)
            out["constraint"] = self.statements["constraint_along_axis"].format(p=p, q=q)
        elif any(self.parallel_axes):
            (a, b), (c, d) = ((i + 1 for i in pair) for pair in self.subplatforms)
            out["constraint"] = self.statements["constraint_paired"].format(a=a, b=b, c=c, d=d)
        return out

    def evaluate(self, pose: list[Enclosure], *, singular: bool = True) -> dict[str, Enclosure]:
        """Enclose every function of ``functions()`` over a batch of boxes of pose space.

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
        if self.rise is not None:
            return self._screw_pair(pose, singular)
        x, y, z, phi = pose
        cos, sin = phi.cos_sin()
        r = self.radius
        if self.axis_limbs is None:
            bar: Vector = [cos, sin, None]  # R_z(φ) i
            s: Vector = [-sin, cos, None]  # its derivative R_z(φ) j
        else:
            bar = [cos, None, -sin]  # R_y(φ) i
            s = [-sin, None, -cos]  # its derivative -R_y(φ) k
        a_rows = self.base[0]
        ds: list[Vector] = []
        for i in range(4):
            sc, ss = _SGN_COS_ETA[i], _SGN_SIN_ETA[i]
            c_i = [
                _sum(_scaled_by(bar[0], sc * r), x),
                _sum(_scaled_by(bar[1], sc * r), y + ss * self.offset),
                _sum(_scaled_by(bar[2], sc * r), z),
            ]
            ds.append([
                _sum(
                    c_i[k],
                    None
                    if a_rows[i][k].value == 0 and a_rows[i][k].spread == 0
                    else -type(x).constant(a_rows[i][k].value, x, relative=_relative(a_rows[i][k])),
                )
                for k in range(3)
            ])
        out, w = self._limb_functions(ds, singular)
        if singular:
            (i1, i2), (j1, j2) = self.subplatforms
            det_a = _dot(_cross(_cross(w[i1], w[i2]), _cross(w[j1], w[j2])), s)
            assert det_a is not None
            out["actuation"] = det_a * (2.0 * r)
            out["constraint"] = self._constraint(w)
        return out

    def _screw_pair(self, pose: list[Enclosure], singular: bool) -> dict[str, Enclosure]:
        """The screw pair's functions: ``c_i = r R_z(γ_i) i + mod(i, 2) (hφ/2π) k + p`` (Table 1),
        det A = det[w_i, mod(i, 2) (h/2π) w_i·k] (Eq. 7 with ``∂c_i/∂φ``), expanded along its last
        column, and Eq. (6) with ``e = k``."""
        x, y, z, phi = pose
        assert self.rise is not None
        lead = type(phi).constant(self.rise, phi, relative=_CONSTANT_SPREAD)  # h/(2π), rounded
        rise = phi * lead
        (i1, i2), _ = self.subplatforms
        a_rows = self.base[0]
        ds: list[Vector] = []
        for i in range(4):
            c_i = [x, y, _sum(z, rise if i in (i1, i2) else None)]
            ds.append([_sum(c_i[k], _constant_of(x, self.radial[i][k]), _constant_of(x, a_rows[i][k], -1.0))
                       for k in range(3)])
        out, w = self._limb_functions(ds, singular)
        if singular:
            terms = []
            for i in (i1, i2):  # cofactors of the last column, (-1)^(i + 3) (0-based row i)
                rest = [w[k] for k in range(4) if k != i]
                minor = _mul(w[i][2], _dot(_cross(rest[0], rest[1]), rest[2]))
                terms.append(_mul(minor, lead if i % 2 else -lead))
            actuation = _sum(*terms)
            assert actuation is not None
            out["actuation"] = actuation
            out["constraint"] = self._constraint(w)
        return out

    def _constraint(self, w: list[Vector]) -> Enclosure:
        """The constraint function from the unit rods (module docstring)."""
        u_rows = self.base[1]
        (i1, i2), (j1, j2) = self.subplatforms
        normals = [_cross_constant(rod_i, u_rows[i]) for i, rod_i in enumerate(w)]
        if self.axis_limbs is None:  # Eq. (6) with e = k
            s_one, s_two = _cross(normals[i1], normals[i2]), _cross(normals[j1], normals[j2])
            one, two = self.parallel_axes
            if one or two:  # s = λ u_a for a sub-platform with parallel axes (module docstring)
                lam_one = _dot_constant(s_one, u_rows[i1]) if one else None
                lam_two = _dot_constant(s_two, u_rows[j1]) if two else None
                if one and two:
                    constraint = _mul(lam_one, lam_two)
                elif one:  # λ_I (u_I × s_II)·k = -λ_I (s_II × u_I)·k
                    constraint = _mul(lam_one, _cross_constant(s_two, u_rows[i1])[2])
                    constraint = None if constraint is None else -constraint
                else:  # λ_II (s_I × u_II)·k
                    constraint = _mul(_cross_constant(s_one, u_rows[j1])[2], lam_two)
            else:
                constraint = _cross(s_one, s_two)[2]
        else:  # e·(n_pI × n_pII), e = j: Eq. (6) without its non-singular factors (module docstring)
            p_one, p_two = self.axis_limbs
            constraint = _cross(normals[p_one], normals[p_two])[1]
        assert constraint is not None
        return constraint


def _radial(params: Any) -> Array:
    """``r R_z(γ_i) i``, ``γ_i = (2i - 1)π/4`` (paper 004, Table 1, screw pair)."""
    gamma = (2 * np.arange(1, 5) - 1) * np.pi / 4
    return float(params.platform_radius) * np.stack([np.cos(gamma), np.sin(gamma), np.zeros(4)], -1)


def _parallel_axes(params: Any) -> tuple[bool, bool]:
    """Per sub-platform, whether its two actuated axes are parallel (to 1e-12)."""
    from ..robots.families.four_limb.configuration import base_frames

    u = base_frames(params).u
    one, two = (float(np.linalg.norm(np.cross(u[i], u[j]))) < 1e-12 for i, j in params.subplatform_limbs)
    return one, two


def _constant_of(like: Enclosure, c: _Constant, sign: float = 1.0) -> Enclosure | None:
    """The enclosure of ``sign c`` shaped like ``like`` (None for an exact zero)."""
    if c.value == 0 and c.spread == 0:
        return None
    return type(like).constant(sign * c.value, like, relative=_relative(c))


def _axis_limbs(params: Any) -> tuple[int, int] | tuple[()]:
    """The 0-based limb of each sub-platform whose actuated axis is along ``j`` (to 1e-12), or
    ``()`` when some sub-platform has none or two."""
    from ..robots.families.four_limb.configuration import base_frames

    u = base_frames(params).u
    along = np.linalg.norm(np.cross(u, [0.0, 1.0, 0.0]), axis=-1) < 1e-12
    found = [[i for i in limbs if along[i]] for limbs in params.subplatform_limbs]
    if any(len(limbs) != 1 for limbs in found):
        return ()
    return found[0][0], found[1][0]


def model_of(mechanism: Any, options: Mapping[str, Any] | None = None) -> Any:
    """The closed-form model certification encloses for a mechanism, or a one-line refusal
    naming what is covered (:data:`COVERED`) and what is missing.

    Parameters
    ----------
    mechanism : Mechanism
    options : mapping, optional
        Inverse-kinematics options (a working mode).

    Returns
    -------
    FourLimbModel, DeltaModel, McGillModel or PeppermillModel

    Raises
    ------
    ScrewkitValueError
        When certification does not cover the mechanism, naming what is missing.

    Examples
    --------
    >>> type(model_of(load_mechanism("delta"))).__name__
    'DeltaModel'
    >>> model_of(load_mechanism("veloce")).parallel_axes     # u_3 = -u_1, u_4 = -u_2
    (True, True)
    """
    family = getattr(mechanism, "family", None)
    if family == "mcgill_smg":
        return McGillModel.of(mechanism, options)
    if family == "peppermill":
        return PeppermillModel.of(mechanism, options)
    if family == "delta":
        return DeltaModel.of(mechanism, options)
    if family == "planar_3rrp":
        return Planar3RRPModel.of(mechanism, options)
    if family == "loop_closure":
        return LoopClosureModel.of(mechanism, options)
    return FourLimbModel.of(mechanism, options)

