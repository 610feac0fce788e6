"""The closed-form model of the Peppermill (CRRHHRRC, paper 000) for certification
(:class:`PeppermillModel`).

Limb ``i`` (``a_1 = i``, ``x_1 = j``, ``y_1 = k``; ``a_2 = j``, ``x_2 = k``, ``y_2 = i``; ``o_1 = -b0 k``,
``o_2 = b0 k``) drives its C joint to ``d_1 = x``, ``d_2 = y`` (Eq. 19) and closes the planar two-link
problem ``q_i = r_i u_i + l_i v_i``, ``q_i = P_i - o_i - d_i a_i``, ``P_i = C + (p_i/2π) φ k`` (Eqs. 11,
20): with ``P = q_i·x_i``, ``Q = q_i·y_i``, ``ρ² = P² + Q²``, ``K = (ρ² + r_i² - l_i²)/(2 r_i)`` (Eq. 26)
and ``g_i = ρ² - K²``, the root of the working mode ``m_i`` (``θ_i = atan2(Q, P) - m_i arccos(K/ρ)``,
Eq. 25) is ``cos θ_i = (P K + m_i Q √g_i)/ρ²``, ``sin θ_i = (Q K - m_i P √g_i)/ρ²`` and
``v_i = (q_i - r_i u_i)/l_i`` (Eq. 27). The certified functions:

* ``serial:1``, ``serial:2``: ``g_i``, zero iff ``sin λ_i = v_i·u_θi = 0`` (the links aligned:
  ``det B = sin λ_1 sin λ_2``, Eq. 47), negative out of reach;
* ``actuation``: ``det A = v_1z v_2z (p_2 - p_1)/2π`` (Eq. 48);
* ``constraint``: the constant ``((a_1 × k) × (a_2 × k))·k = (a_1 × a_2)·k = 1``. Each limb's joints
  turn about ``a_i`` (the C joint and the R joints at ``B_i``, ``P_i``) or screw about ``k`` (the H
  joint), so the limb exerts the couple along ``a_i × k`` at every pose (its other twists only
  translate), and the two couples, along ``-j`` and ``i``, never become dependent: the Peppermill has
  no constraint singularity (the report's factor ``[gbif]`` reads the same fixed directions).

Examples
--------
>>> sorted(PeppermillModel.of(load_mechanism("peppermill")).functions())
['actuation', 'constraint', 'serial:1', 'serial:2']
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .intervals import Enclosure
from .limb_enclosures import _ClosedFormModel, _divided, _family_mode

__all__ = ["PeppermillModel"]

_PEPPERMILL_STATEMENTS = {
    "constraint": "((a_1 x k) x (a_2 x k)).k = 1: the limbs' couples along a_1 x k and a_2 x k are "
    "fixed and independent (no constraint singularity)",
    "actuation": "det A = v_1z v_2z (p_2 - p_1)/2pi = 0 (paper 000, Eq. 48): a distal link horizontal, "
    "second-kind singularity",
    "serial": "rho_i^2 - K_i^2 = 0 (paper 000, Eqs. 25-26; det B = sin lambda_1 sin lambda_2, Eq. 47): "
    "limb {i}'s links aligned, at its reach",
}


@dataclass(frozen=True)
class PeppermillModel(_ClosedFormModel):
    """The Peppermill's closed-form model (module docstring), for enclosures.

    Attributes
    ----------
    name : str
    pose_names : tuple of str
        ``("x", "y", "z", "phi")``.
    proximal, distal, rises : tuple of float
        ``r_i``, ``l_i`` and ``p_i/2π`` per limb.
    offset : float
        ``b0``.
    working_mode : tuple of int
        ``(sgn sin λ_1, sgn sin λ_2)``.
    limbs : int
        2.

    Examples
    --------
    >>> values = PeppermillModel.of(load_mechanism("peppermill")).values([[30.0, -20.0, -450.0, 0.5]])
    >>> bool(values["serial:1"][0] > 0 and abs(values["actuation"][0]) > 1.0)
    True
    """

    name: str
    pose_names: tuple[str, ...]
    proximal: tuple[float, float]
    distal: tuple[float, float]
    rises: tuple[float, float]
    offset: float
    working_mode: tuple[int, int]
    limbs: int = 2
    statements: ClassVar[dict[str, str]] = _PEPPERMILL_STATEMENTS

    @classmethod
    def of(cls, mechanism: Any, options: Mapping[str, Any] | None = None) -> PeppermillModel:
        """The model of a Peppermill catalog mechanism.

        Parameters
        ----------
        mechanism : Mechanism
            Of the ``peppermill`` family.
        options : mapping, optional
            Inverse-kinematics options (``mode``: two signs).

        Returns
        -------
        PeppermillModel

        Raises
        ------
        ScrewkitValueError
            For another family, or options other than a mode of two signs.

        Examples
        --------
        >>> PeppermillModel.of(load_mechanism("peppermill")).working_mode
        (1, 1)
        """
        from ..robots.families.peppermill import DEFAULT_MODE

        mode = _family_mode(mechanism, options, "peppermill", DEFAULT_MODE)
        p = mechanism.parameters
        return cls(
            mechanism.name,
            tuple(mechanism.pose_names),
            (float(p.r1), float(p.r2)),
            (float(p.l1), float(p.l2)),
            (float(p.p1) / (2.0 * np.pi), float(p.p2) / (2.0 * np.pi)),
            float(p.b0),
            (mode[0], mode[1]),
        )

    def evaluate(self, pose: list[Enclosure], *, singular: bool = True) -> dict[str, Enclosure]:
        """Each limb's reach function ``ρ_i² - K_i²`` and, with ``singular``, det A (Eq. 48) and the
        constant constraint function, enclosed over a batch of boxes of pose space.

        Parameters
        ----------
        pose : list of 4 Enclosure
            ``x, y, z, φ`` over the boxes (``φ`` in radians: it moves the nuts, Eq. 11).
        singular : bool, default True
            Also ``actuation`` and ``constraint``.

        Returns
        -------
        dict of str to Enclosure

        Examples
        --------
        >>> model = PeppermillModel.of(load_mechanism("peppermill"))
        >>> at = Enclosure.variables(np.array([[20.0, -30.0, -460.0, 0.4]]),
        ...                          np.array([[30.0, -20.0, -450.0, 0.5]]))
        >>> bool(model.evaluate(at)["actuation"].excludes_zero()[0])
        True
        """
        x, y, z, phi = pose
        leads = [phi * type(phi).constant(rise, phi, relative=1e-15) for rise in self.rises]
        # limb 1: q = (0, y, z + h_1 φ + b0), P = q·j, Q = q·k;
        # limb 2: q = (x, 0, z + h_2 φ - b0), P = q·k, Q = q·i
        heights = [z + leads[0] + self.offset, z + leads[1] - self.offset]
        planar = [(y, heights[0]), (heights[1], x)]
        out: dict[str, Enclosure] = {}
        vertical = []
        for i in range(2):
            big_p, big_q = planar[i]
            r, length, m = self.proximal[i], self.distal[i], float(self.working_mode[i])
            rho2 = big_p.square() + big_q.square()
            big_k = _divided(rho2 + (r * r - length * length), 2.0 * r)
            assert big_k is not None
            g = rho2 - big_k.square()
            out[f"serial:{i + 1}"] = g
            if not singular:
                continue
            root = g.sqrt() * m
            inv = rho2.reciprocal()
            # u_z = sin θ_1 (y_1 = k) for limb 1, cos θ_2 (x_2 = k) for limb 2; q_z = Q resp. P
            u_z = (big_q * big_k - big_p * root) * inv if i == 0 else (big_p * big_k + big_q * root) * inv
            q_z = big_q if i == 0 else big_p
            v_z = _divided(q_z - u_z * r, length)
            assert v_z is not None
            vertical.append(v_z)
        if singular:
            out["actuation"] = vertical[0] * vertical[1] * (self.rises[1] - self.rises[0])
            out["constraint"] = type(x).constant(1.0, x)
        return out
