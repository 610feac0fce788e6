"""The closed-form model of the McGill Schönflies-motion generator (paper 001) for certification
(:class:`McGillModel`).

Leg ``J`` (``s = +1, -1`` for ``I, II``, Eq. 13) reaches its wrist ``O_J3 = P - s R e(φ) -
(b4 + b5) k``, ``e(θ) = (-sin θ, cos θ, 0)``, from its pan axis through ``O_J0 = -s (l0/2) j``: with the
horizontal offset ``o_J = O_J3 - O_J0`` (``ρ_J = |o_J|``), ``κ_J = pan_J ρ_J``, ``u_J = κ_J - s l1``,
``w = z - b4 - b5`` and ``N_J = u_J² + w² - l2² - l3²``, the planar two-link problem of the leg gives
``cos θ_J3 = N_J/(2 l2 l3)``, ``sin θ_J3 = elbow_J √g_J/(2 l2 l3)`` with ``g_J = (2 l2 l3)² - N_J²``,
the proximal direction ``(cos θ_J2, sin θ_J2) = (u (l2 + l3 c3) + w l3 s3, w (l2 + l3 c3) - u l3 s3)/
(u² + w²)`` and the distal one ``d_J = ((u, w) - l2 (cos θ_J2, sin θ_J2))/l3`` in the leg's plane
(``e_J = o_J/κ_J``, ``k``). The certified functions:

* ``serial:1``, ``serial:3`` (legs I, II): ``g_J``, zero iff ``sin θ_J3 = 0`` (the leg stretched or
  folded: ``Δ_J = 0``, paper 001 Eq. 20b), negative out of reach;
* ``serial:2``, ``serial:4``: ``ρ_J²``, zero iff ``O_J3`` lies on the pan axis (``κ_J = 0``: ``v_J = 0``,
  Eq. 20a as corrected in the tests: ``v_J = -(κ_J/L) ρ_J3``); never negative (a codimension-2 set:
  no sign change, boxes meeting it stay undecided);
* ``actuation``: ``det[φ_I, φ_II, k × e(φ)]`` with ``φ_J = f_J × d_J = d_Je k - d_Jk e_J``: ``A t = 0``
  (Eqs. 12, 16-19) iff both ``Ȯ_J3 ∥ φ_J`` with ``Ȯ_I3 - Ȯ_II3 = -2R φ̇ k × e(φ)``, i.e. iff the
  three vectors are dependent (paper 001's Eq. 22, ``φ_I = ±φ_II``, is sufficient, not necessary);
* ``constraint``: ``(cos θ_I2 cos θ_I23)² + (cos θ_II2 cos θ_II23)² + ((e_I × e_II)·k)²``. Each leg's
  joints turn about ``k`` (pan, wrist) or are parallelograms with axes ``f_J`` (vertical short sides);
  a parallelogram is flat (its four axes in one plane, the coupler free to turn about ``f_J``) iff its
  long links are vertical (``cos θ_J2 = 0`` or ``cos θ_J23 = 0``). A leg exerts the two couples normal
  to ``k``, or only the one along ``e_J`` when one of its parallelograms is flat; the end effector
  loses a couple iff both legs are flat and ``e_I ∥ e_II``: a codimension-3 set, where the function
  (a sum of squares) vanishes; no sign change, so boxes meeting it stay undecided.

Examples
--------
>>> model = McGillModel.of(load_mechanism("mcgill_smg"))
>>> sorted(model.functions())
['actuation', 'constraint', 'serial:1', 'serial:2', 'serial:3', 'serial:4']
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

from .intervals import Enclosure
from .limb_enclosures import _ClosedFormModel, _divided, _family_mode

__all__ = ["McGillModel"]

_MCGILL_STATEMENTS = {
    "constraint": "(cos t_I2 cos t_I23)^2 + (cos t_II2 cos t_II23)^2 + ((e_I x e_II).k)^2 = 0: a "
    "parallelogram of each leg flat (long links vertical) and the legs' planes parallel, the end "
    "effector keeps one constraint couple",
    "actuation": "det[phi_I, phi_II, k x e(phi)] = 0, phi_J = f_J x d_J (paper 001, Eqs. 12, 16-19; "
    "Eq. 22 is the special case phi_I = +-phi_II): A loses rank, the plate moves with the actuators "
    "locked",
    "reach": "(2 l2 l3)^2 - (u_J^2 + w^2 - l2^2 - l3^2)^2 = 0 (paper 001, Eq. 20b, Delta_J = 0): leg {leg} "
    "stretched or folded, at its reach",
    "pan": "|O_J3 - O_J0|^2 = 0 (paper 001, Eq. 20a, kappa_J = 0): the wrist of leg {leg} on its pan "
    "axis",
}


@dataclass(frozen=True)
class McGillModel(_ClosedFormModel):
    """The McGill SMG's closed-form model (module docstring), for enclosures.

    Attributes
    ----------
    name : str
    pose_names : tuple of str
        ``("x", "y", "z", "phi")``.
    lengths : tuple of float
        ``(l0, l1, l2, l3, R, b4 + b5)``.
    mode : tuple of int
        ``(pan_I, elbow_I, pan_II, elbow_II)``.
    limbs : int
        4: the reach and pan functions of both legs (``serial:1`` .. ``serial:4``).

    Examples
    --------
    >>> values = McGillModel.of(load_mechanism("mcgill_smg")).values([[30.0, -20.0, -790.0, 0.17]])
    >>> bool(values["serial:1"][0] > 0 and abs(values["actuation"][0]) > 0.01)
    True
    """

    name: str
    pose_names: tuple[str, ...]
    lengths: tuple[float, float, float, float, float, float]
    mode: tuple[int, int, int, int]
    limbs: int = 4
    statements: ClassVar[dict[str, str]] = _MCGILL_STATEMENTS

    @classmethod
    def of(cls, mechanism: Any, options: Mapping[str, Any] | None = None) -> McGillModel:
        """The model of a McGill SMG catalog mechanism.

        Parameters
        ----------
        mechanism : Mechanism
            Of the ``mcgill_smg`` family.
        options : mapping, optional
            Inverse-kinematics options (``mode``: four signs).

        Returns
        -------
        McGillModel

        Raises
        ------
        ScrewkitValueError
            For another family, or options other than a mode of four signs.

        Examples
        --------
        >>> McGillModel.of(load_mechanism("mcgill_smg")).mode
        (1, 1, -1, -1)
        """
        from ..robots.families.mcgill_smg.parameters import DEFAULT_MODE

        mode = _family_mode(mechanism, options, "mcgill_smg", DEFAULT_MODE)
        p = mechanism.parameters
        lengths = (float(p.l0), float(p.l1), float(p.l2), float(p.l3), float(p.radius), float(p.b4 + p.b5))
        return cls(mechanism.name, tuple(mechanism.pose_names), lengths, mode)  # type: ignore[arg-type]

    def functions(self) -> dict[str, str]:
        """Each certified function's name and statement.

        Returns
        -------
        dict of str to str

        Examples
        --------
        >>> McGillModel.of(load_mechanism("mcgill_smg")).functions()["serial:2"][:18]
        '|O_J3 - O_J0|^2 = '
        """
        out = {"constraint": self.statements["constraint"], "actuation": self.statements["actuation"]}
        for index, leg in enumerate(("I", "II")):
            out[f"serial:{2 * index + 1}"] = self.statements["reach"].format(leg=leg)
            out[f"serial:{2 * index + 2}"] = self.statements["pan"].format(leg=leg)
        return out

    def evaluate(self, pose: list[Enclosure], *, singular: bool = True) -> dict[str, Enclosure]:
        """The legs' reach and pan functions and, with ``singular``, ``det[φ_I, φ_II, k × e(φ)]`` and
        the flat-parallelogram function, enclosed over a batch of boxes of the plate's poses.

        Parameters
        ----------
        pose : list of 4 Enclosure
            The plate's ``x, y, z`` and ``φ`` (radians) over the boxes.
        singular : bool, default True
            Also ``actuation`` and ``constraint`` (else ``serial:1`` .. ``serial:4`` only).

        Returns
        -------
        dict of str to Enclosure
            By the names of :meth:`functions`.

        Examples
        --------
        >>> model = McGillModel.of(load_mechanism("mcgill_smg"))
        >>> at = Enclosure.variables(np.array([[20.0, -30.0, -800.0, 0.1]]),
        ...                          np.array([[30.0, -20.0, -790.0, 0.2]]))
        >>> bool(model.evaluate(at)["actuation"].excludes_zero()[0])
        True
        """
        x, y, z, phi = pose
        l0, l1, l2, l3, radius, drop = self.lengths
        cos, sin = phi.cos_sin()
        w = z - drop
        two = 2.0 * l2 * l3
        out: dict[str, Enclosure] = {}
        legs = []
        for index, sign in enumerate((1.0, -1.0)):
            pan, elbow = float(self.mode[2 * index]), float(self.mode[2 * index + 1])
            ox = x + sin * (sign * radius)  # o_J = P - s R e(φ) - O_J0 (horizontal)
            oy = y - cos * (sign * radius) + sign * l0 / 2.0
            rho2 = ox.square() + oy.square()
            rho = rho2.sqrt()
            u = rho * pan - sign * l1
            d2 = u.square() + w.square()
            big_n = d2 - (l2 * l2 + l3 * l3)
            g = two * two - big_n.square()
            out[f"serial:{2 * index + 1}"], out[f"serial:{2 * index + 2}"] = g, rho2
            if not singular:
                continue
            c3 = _divided(big_n, two)
            s3 = _divided(g.sqrt() * elbow, two)
            assert c3 is not None and s3 is not None
            along, across = c3 * l3 + l2, s3 * l3
            inv = d2.reciprocal()
            c2 = (u * along + w * across) * inv
            s2 = (w * along - u * across) * inv
            d_e = _divided(u - c2 * l2, l3)
            d_k = _divided(w - s2 * l2, l3)
            inv_rho = rho.reciprocal() * pan
            e_x, e_y = ox * inv_rho, oy * inv_rho
            assert d_e is not None and d_k is not None
            legs.append((c2 * d_e, (-(d_k * e_x), -(d_k * e_y), d_e), (e_x, e_y)))
        if singular:
            (flat_one, phi_one, e_one), (flat_two, phi_two, e_two) = legs
            m_x, m_y = -cos, -sin  # k × e(φ), horizontal
            # det[φ_I, φ_II, m] expanded along m (m_z = 0)
            minor_x = phi_one[1] * phi_two[2] - phi_one[2] * phi_two[1]
            minor_y = phi_one[2] * phi_two[0] - phi_one[0] * phi_two[2]
            out["actuation"] = minor_x * m_x + minor_y * m_y
            parallel = e_one[0] * e_two[1] - e_one[1] * e_two[0]
            out["constraint"] = flat_one.square() + flat_two.square() + parallel.square()
        return out
