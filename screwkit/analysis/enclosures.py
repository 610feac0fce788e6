"""Enclosures of the singularity conditions of the four-limb robots with a nacelle articulated
about vertical axes (Quattro, H4) and of the Delta robot over boxes of pose space, in closed form
(:class:`DeltaModel` for the Delta: the same limbs, its own statements; :func:`model_of` picks).

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
from typing import Any, ClassVar

import numpy as np

from ..exceptions import ScrewkitValueError
from .delta_enclosure import DeltaModel
from .intervals import Enclosure
from .limb_enclosures import (
    Vector,
    _ClosedFormModel,
    _Constant,
    _constants,
    _cross,
    _cross_constant,
    _dot,
    _relative,
    _scaled_by,
    _sum,
)

__all__ = ["COVERED", "FourLimbModel", "model_of"]

Array = np.ndarray

#: What certification covers: the four-limb family with a nacelle articulated about vertical axes,
#: and the Delta. Left out: the V4 (``articulated_y``): Eq. (6) with the axis ``y`` vanishes at V4
#: poses the core finds regular (e.g. x, y, z, phi = 503.5, -492, -352, 0.2 rad: constraint
#: closeness 0.79), so the V4's constraint condition is another one, not written here; the screw
#: pair (Veloce, Ragnar) has another constraint condition too; the McGill SMG, the Peppermill and
#: the planar 3-RRP have no enclosure written; mechanisms from ``screwkit.mechanism`` (loop-closure
#: kinematics) would need an interval-Newton (Krawczyk) enclosure of their loop equations.
COVERED = "the four_limb family with platform_kind articulated_z (Quattro, H4) and the delta family (Delta)"

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
            family = getattr(mechanism, "family", None)
            missing = (
                "no closed-form kinematics to enclose: a loop-closure mechanism would need an "
                "interval-Newton enclosure of its loop equations, not written"
                if family in (None, "loop_closure")
                else "no enclosure of its conditions written"
            )
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
            float(params.platform_offset),
            mode,
            params.subplatform_limbs,
            base,
        )

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
        x, y, z, phi = pose
        cos, sin = phi.cos_sin()
        r = self.radius
        bar: Vector = [cos, sin, None]  # R_z(φ) i
        s: Vector = [-sin, cos, None]  # its derivative R_z(φ) j
        a_rows, u_rows, _, _ = self.base
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
            normals = [_cross_constant(rod_i, u_rows[i]) for i, rod_i in enumerate(w)]
            s_one, s_two = _cross(normals[i1], normals[i2]), _cross(normals[j1], normals[j2])
            constraint = _cross(s_one, s_two)[2]
            assert constraint is not None
            out["constraint"] = constraint
        return out


def model_of(mechanism: Any, options: Mapping[str, Any] | None = None) -> FourLimbModel | DeltaModel:
    """The closed-form model certification encloses for a mechanism, or a one-line refusal
    naming what is covered (:data:`COVERED`) and what is missing.

    Parameters
    ----------
    mechanism : Mechanism
    options : mapping, optional
        Inverse-kinematics options (a working mode).

    Returns
    -------
    FourLimbModel or DeltaModel

    Raises
    ------
    ScrewkitValueError
        When certification does not cover the mechanism, naming what is missing.

    Examples
    --------
    >>> type(model_of(load_mechanism("delta"))).__name__
    'DeltaModel'
    >>> model_of(load_mechanism("veloce"))
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `mechanism` among what certification covers ...
    """
    if getattr(mechanism, "family", None) == "delta":
        return DeltaModel.of(mechanism, options)
    return FourLimbModel.of(mechanism, options)

