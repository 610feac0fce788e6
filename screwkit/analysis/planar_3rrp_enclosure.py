"""The closed-form model of the planar 3-RRP (paper 003) for certification
(:class:`Planar3RRPModel`).

Limb ``k``'s elbow ``A_k`` slides on a guide line fixed in the platform, through
``Q_k = C + R(φ) P_k`` with direction ``b_k = R(φ) (cos β_k, sin β_k)``
(:mod:`screwkit.robots.families.planar_3rrp`). With ``n_k = E b_k`` (``E`` the quarter turn),
``d_k = Q_k - M_k`` and ``h_k = d_k·n_k`` (the distance from ``M_k`` to the guide):

* **serial / reach**, one per limb: ``g_k = l_k² - h_k²``. The circle of radius ``l_k`` about
  ``M_k`` meets the guide iff ``g_k >= 0``, and ``J_kk = σ_k √g_k`` (paper 003, Eq. 11a), so the
  inverse (type-1) singularities (Eq. 12) are exactly the zeros of ``g_k``: the reach boundary.
* **actuation** (direct singularity): the actuation wrench of limb ``k`` is the planar force through
  the elbow ``A_k = Q_k + γ_k b_k`` normal to the guide (the line ``L_k`` reciprocal to the passive
  R at ``A_k`` and the P along ``b_k``), ``γ_k = -d_k·b_k + σ_k √g_k`` (the inverse kinematics).
  Its planar line coordinates are ``(n_k, A_k × n_k)`` with ``A_k × n_k = Q_k × n_k + γ_k`` (as
  ``b_k × n_k = 1``), and the three lines are concurrent or parallel (paper 003, Sec. 4.2: the
  platform's instant centre undetermined) iff ``det[n_kx, n_ky, Q_k × n_k + γ_k] = 0``.
* **constraint**: none. Every limb's twists (R, R about ``z``, P in the plane) lie in the planar
  motions, so each limb exerts the planarity wrenches (forces along ``z``, couples about horizontal
  axes), a 3-system that no pose changes: the 3-RRP has no constraint singularity.

Examples
--------
>>> model = Planar3RRPModel.of(load_mechanism("planar_3rrp"))
>>> sorted(model.functions())
['actuation', 'serial:1', 'serial:2', 'serial:3']
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..exceptions import ScrewkitValueError
from .intervals import Enclosure
from .limb_enclosures import _ClosedFormModel, _Constant, _constants, _relative

__all__ = ["Planar3RRPModel"]

_STATEMENTS = {
    "constraint": "none: every limb's twists are planar, its planarity wrenches never change",
    "actuation": "det[n_k, A_k x n_k] = 0 (paper 003, Sec. 4.2): the three actuation lines (through "
    "the elbows, normal to the guides) are concurrent or parallel, a direct singularity",
    "serial": "l_k^2 - h_k^2 = 0, h_k the distance from M_k to the guide (paper 003, Eqs. 11a-12): "
    "limb {i} at its reach, J_kk = 0 (an inverse singularity)",
}


@dataclass(frozen=True)
class Planar3RRPModel(_ClosedFormModel):
    """The planar 3-RRP's conditions in closed form, for enclosures (module docstring).

    Attributes
    ----------
    name : str
    pose_names : tuple of str
        ``("x", "y", "phi")``.
    working_mode : tuple of int
        ``σ_k``.
    base : tuple
        Constants: ``M_k``, ``P_k`` (platform frame), ``(cos β_k, sin β_k)`` (3 rows of 2 each).
    lengths : tuple of float
        ``l_k``.
    limbs : int
        3.
    """

    name: str
    pose_names: tuple[str, ...]
    working_mode: tuple[int, int, int]
    base: tuple[list[list[_Constant]], ...]
    lengths: tuple[float, float, float]
    limbs: int = 3
    statements: ClassVar[dict[str, str]] = _STATEMENTS

    @classmethod
    def of(cls, mechanism: Any, options: Mapping[str, Any] | None = None) -> Planar3RRPModel:
        """The model of a planar 3-RRP catalog mechanism.

        Parameters
        ----------
        mechanism : Mechanism
            Of the ``planar_3rrp`` family.
        options : mapping, optional
            ``working_mode``: three signs ``σ_k`` (default ``(1, 1, 1)``).

        Returns
        -------
        Planar3RRPModel

        Raises
        ------
        ScrewkitValueError
            For another family, or options other than a working mode of three signs.

        Examples
        --------
        >>> Planar3RRPModel.of(load_mechanism("planar_3rrp"), {"working_mode": (1, -1, 1)}).working_mode
        (1, -1, 1)
        """
        if getattr(mechanism, "family", None) != "planar_3rrp":
            raise ScrewkitValueError(
                "Expected `mechanism` of the planar_3rrp family, got "
                f"{getattr(mechanism, 'name', mechanism)!r}."
            )
        given = dict(options or {})
        mode = given.pop("working_mode", (1, 1, 1))
        signs = (
            isinstance(mode, tuple | list | np.ndarray) and len(mode) == 3 and all(m in (-1, 1) for m in mode)
        )
        if given or not signs:
            raise ScrewkitValueError(
                f"Expected `mode` to give only a working_mode of three signs (+1 or -1), got {options!r}."
            )
        params = mechanism.parameters
        guides = np.stack([np.cos(params.guide_angles), np.sin(params.guide_angles)], axis=-1)
        base = (
            _constants(params.base_points, exact=False),
            _constants(params.platform_points, exact=False),
            _constants(guides, exact=False),
        )
        lengths = tuple(float(v) for v in params.link_lengths)
        return cls(
            mechanism.name,
            tuple(mechanism.pose_names),
            (int(mode[0]), int(mode[1]), int(mode[2])),
            base,
            (lengths[0], lengths[1], lengths[2]),
        )

    def functions(self) -> dict[str, str]:
        """Each certified function's name and statement (no constraint function: module docstring).

        Returns
        -------
        dict of str to str

        Examples
        --------
        >>> Planar3RRPModel.of(load_mechanism("planar_3rrp")).functions()["serial:2"][:18]
        'l_k^2 - h_k^2 = 0,'
        """
        out = super().functions()
        del out["constraint"]  # a planar mechanism's planarity wrenches never change (module docstring)
        return out

    def evaluate(self, pose: list[Enclosure], *, singular: bool = True) -> dict[str, Enclosure]:
        """Enclose every function of ``functions()`` over a batch of boxes of pose space.

        Parameters
        ----------
        pose : list of 3 Enclosure
            ``x, y, φ`` (radians) over the boxes.
        singular : bool, default True
            Also the actuation function (else the reach functions only).

        Returns
        -------
        dict of str to Enclosure

        Examples
        --------
        >>> model = Planar3RRPModel.of(load_mechanism("planar_3rrp"))
        >>> at = Enclosure.variables(np.array([[0.0, 0.0, 0.0]]), np.array([[0.01, 0.01, 0.01]]))
        >>> values = model.evaluate(at)
        >>> bool(values["serial:1"].lo[0] > 0 and values["actuation"].excludes_zero()[0])
        True
        """
        x, y, phi = pose
        cos, sin = phi.cos_sin()
        base_rows, platform_rows, guide_rows = self.base
        out: dict[str, Enclosure] = {}
        rows = []
        for k in range(3):
            px, py = (_constant(x, c) for c in platform_rows[k])
            cb, sb = (_constant(x, c) for c in guide_rows[k])
            mx, my = (_constant(x, c) for c in base_rows[k])
            qx = x + cos * px - sin * py  # Q_k = C + R(φ) P_k
            qy = y + sin * px + cos * py
            bx = cos * cb - sin * sb  # b_k = R(φ) (cos β_k, sin β_k)
            by = sin * cb + cos * sb
            nx, ny = -by, bx  # n_k = E b_k
            dx, dy = qx - mx, qy - my
            h = dx * nx + dy * ny
            squared = self.lengths[k] ** 2  # within half a unit in the last place of l_k²
            g = h.square() * -1.0 + type(x).constant(squared, x, relative=2.0**-53)
            out[f"serial:{k + 1}"] = g
            if singular:
                gamma = (dx * bx + dy * by) * -1.0 + g.sqrt() * float(self.working_mode[k])
                rows.append((nx, ny, qx * ny - qy * nx + gamma))
        if singular:
            (a1, a2, a3), (b1, b2, b3), (c1, c2, c3) = rows
            out["actuation"] = a1 * (b2 * c3 - b3 * c2) - a2 * (b1 * c3 - b3 * c1) + a3 * (b1 * c2 - b2 * c1)
        return out


def _constant(like: Enclosure, c: _Constant) -> Enclosure:
    """The enclosure of the constant ``c`` shaped like ``like``."""
    return type(like).constant(c.value, like, relative=_relative(c))
