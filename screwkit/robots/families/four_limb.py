"""Four-limb Schönflies-motion generators: Quattro, H4, V4, Veloce, Ragnar.

Source: paper 004 (Wu, Bai, Caro, "A transmission quality index for a class of four-limb parallel
Schönflies motion generators", JMR 10(5), 2018), file ``/work/shared/papers/004_60e52c5ada55e36d.txt``.
All equation and table numbers below refer to that paper; limbs are numbered 1..4 as in it (array
index ``i - 1``).

The model
---------
Each limb is ``R-R-Π-R-R``: an actuated revolute joint at ``A_i`` (axis ``u_i``), an arm of length
``b`` to the elbow ``B_i``, a parallelogram of length ``l`` to the platform point ``C_i``.

* ``a_i = R [cos η_i, sin η_i, 0]``, ``η_i = (2i - 1)π/4`` (Eq. 1), or explicit points (Ragnar,
  text after Table 4);
* ``u_i = R_z(α_i) i``, ``α_1 = -α_2 = α``, ``α_3 = -α_4 = β`` (Sec. 2), generalised to inclined
  actuated axes ``u_i = F_i i`` with ``F_i = R_z(α_i) R_y(ε_i)``, ``ε_1 = -ε_2 = ε_3 = -ε_4 = ε``
  (``axis_inclination``, 0 for every robot of Table 3; the Ragnar, item 6);
* ``v_i = F_i R_x(θ_i) j``, ``b_i = a_i + b v_i`` (Eq. 2; ``F_i = R_z(α_i)`` when ``ε = 0``);
* ``c_i`` from Table 1 (corrected, see below); ``|c_i - b_i| = l`` (Eq. 3);
* ``w_i = (c_i - b_i)/l``, ``A χ̇ = B θ̇`` with rows ``e_i = [w_i, r w_i·s_i]`` and
  ``B = diag(h_i)``, ``h_i = b w_i·(u_i × v_i)`` (Eqs. 6-8).

Each limb has two inverse-kinematics branches, told apart by the sign of ``h_i``; a *working mode*
is the tuple of the four signs. The paper uses ``h_i < 0`` for every limb (Sec. 3), the default here.

Platforms (Table 1, with ``σ_i = sgn(cos η_i) = (+, -, -, +)``, ``τ_i = sgn(sin η_i) = (+, +, -, -)``)

* ``"articulated_z"`` (Quattro, H4): ``c_i = σ_i r R_z(φ) i + τ_i c j + p``. The ``c_i`` of limbs with
  equal ``σ_i`` differ by a constant vector, so limbs 1, 4 share the translating sub-platform I and
  limbs 2, 3 share sub-platform II. The end effector (the bar ``P_I P_II`` of length ``2r``) turns by
  ``φ`` about ``k``; it is joined to the sub-platforms by revolute joints ``R_I``, ``R_II`` of axis
  ``k`` through ``P_I = p + r R_z(φ) i`` and ``P_II = p - r R_z(φ) i``.
* ``"articulated_y"`` (V4): ``c_i = σ_i r R_y(φ) i + τ_i c j + p`` (Table 1 corrected, item 3
  below), revolute axes along ``j`` through ``P_I = p + r R_y(φ) i`` (limbs 1, 4) and
  ``P_II = p - r R_y(φ) i`` (limbs 2, 3). At ``φ = 0`` the points coincide with the H4's; only the
  axis of rotation differs.
* ``"screw_pair"`` (Veloce, Ragnar): ``c_i = r R_z(γ_i) i + mod(i, 2) (hφ/2π) k + p`` with
  ``γ_i = (2i - 1)π/4`` (Table 3). Limbs 1, 3 share sub-platform I (centre ``p + (hφ/2π) k``), limbs
  2, 4 share sub-platform II (centre ``p``). Modelling choice consistent with Table 1: the end effector
  (position ``p``, angle ``φ``) is joined to sub-platform II by a revolute joint and to sub-platform I by
  a helical joint, both of axis ``k`` through ``p``; the helical joint has pitch ``-h/(2π)`` in the
  screw convention ``(s; r × s + pitch s)`` (the end effector turns by ``+φ`` while sub-platform I
  rises by ``hφ/(2π)`` relative to it).

Parallelograms: the two rods of limb ``i`` join the sphere centres ``m_i = b_i - (d/2) u_i``,
``n_i = b_i + (d/2) u_i`` on the arm to ``p_i = c_i - (d/2) u_i``, ``q_i = c_i + (d/2) u_i`` on the
sub-platform (short sides parallel to the actuated axis, as in paper 002, Sec. 4.2). The width ``d``
is not given by paper 004; it does not enter the kinematics. Its default, 100 mm, is *our choice*.

Where paper 004 is garbled or wrong (each is checked in ``tests/test_families_four_limb.py``)
---------------------------------------------------------------------------------------------
1. Table 1, ``s_i`` of Quattro/H4/V4, printed ``sgn(cos η_i) r s``: differentiating ``c_i`` gives
   ``∂c_i/∂φ = σ_i r ∂(R(φ) i)/∂φ``; Eq. (4) writes this as ``r s_i`` and calls ``s_i`` a unit
   vector, so the correct entry is ``s_i = σ_i s`` with ``s = ∂(R(φ) i)/∂φ`` (the printed ``r`` is
   spurious). For the Quattro/H4 ``s = R_z(φ) j`` as printed.
2. Table 1, ``s_i`` of the Veloce, printed ``mod(i, 2) hφ/(2π) k``: differentiating gives
   ``∂c_i/∂φ = mod(i, 2) h/(2π) k``, so ``r s_i = mod(i, 2) h/(2π) k`` (no ``φ``; not a unit vector).
3. Table 1, ``c_i`` of the V4, printed ``-sgn(cos η_i) r R_y(φ) i + sgn(cos η_i) c j + p``: the
   second term makes ``C_1 = C_4`` and ``C_2 = C_3`` (two limbs on one point). The row that
   reproduces Table 4's V4 values (``η`` in [0.008, 0.872] at ``φ = 0``, max 0.804 at 45°, with the
   workspace stated in the tests) is ``sgn(cos η_i) r R_y(φ) i + sgn(sin η_i) c j + p``: both the
   leading minus sign and the second ``cos`` are garbles. Over the same workspace the printed row
   gives η in [0, 0.711] at ``φ = 0``, and correcting only one of the two signs gives η_max 0.786
   (first sign) or 0.811 (second), against the paper's 0.872. With the right-handed ``R_y``,
   ``s = ∂(R_y(φ) i)/∂φ = -R_y(φ) k``; Table 1's ``s = R_y(φ) k`` corresponds to measuring ``φ``
   about ``-j``. The indices are even in ``φ``, so Table 4 cannot tell the two apart.
6. Ragnar (text after Table 4): "``u_i`` parallel to the x-z plane" with ``u_i = R_z(α_i) i`` means
   ``u_i = ±i``, i.e. ``α = 0``, ``β = π`` (the arms then point away from the x axis). With these
   horizontal axes all four parallelogram couples ``u_i × w_i`` are normal to ``i``: nothing
   constrains a rotation about ``x`` (a 5-DOF platform) and Table 4's Ragnar values are not
   reproduced (η_max 0.937 against 0.892 over Eq. 19). The real Ragnar (paper 004's ref. [15]) has
   its actuated axes *inclined* out of the base plane, in planes parallel to x-z. ``axis_inclination``
   ``ε`` models this: ``u_i = R_z(α_i) R_y(ε_i) i`` with ``ε_1 = -ε_2 = ε_3 = -ε_4 = ε``, the sign
   pattern that makes the Ragnar (``α = 0``, ``β = π``) symmetric under both mirrors ``x → -x``
   (limbs 1 ↔ 2, 3 ↔ 4) and ``y → -y`` (1 ↔ 4, 2 ↔ 3). Then ``u_1 ∦ u_3`` and ``u_2 ∦ u_4``: each
   sub-platform of the screw pair may only turn about one axis ``n_I`` (``n_II``), and the end
   effector, joined to both by joints of axis ``k``, only about ``span(n_I, k) ∩ span(n_II, k) = k``.
   Paper 004 does not print ``ε``; ``mechanisms/ragnar.toml`` says where its value comes from.
Items 4, 5 and 7 (Table 2, Eqs. 11 and 13, Sec. 5.1) concern the Jacobians and the transmission
indices of Sec. 4, which live in :mod:`screwkit.analysis.indices` with the rest of that erratum list.

The joint table
---------------
:func:`joints` gives the physical mechanism as paper 002 models the H4 (§4.1, Fig. 2): per limb an
actuated revolute joint and a parallelogram with explicit spherical joints at its four corners; the
sub-platforms join the end effector by ``R_I`` and ``R_II``. :func:`twist_basis` gives the end
effector's nominal (Schoenflies) twists, the columns of the forward Jacobian of
:func:`screwkit.core.jacobians.jacobians_from_wrenches`. Paper 002 numbers the H4's legs differently: its
``b_I`` carries legs ``l1, l2`` and ``b_II`` carries ``l3, l4``, whereas here (Table 1) sub-platform
I carries limbs 1 and 4; paper 002's ``(l1, l2, l3, l4)`` are limbs ``(1, 4, 2, 3)``
(:data:`PAPER_002_LEGS`).

Examples
--------
>>> import numpy as np
>>> from screwkit.robots.families.four_limb import FourLimbParameters, inverse_kinematics
>>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375.0,
...     rod_length=800.0, alpha=0.0, beta=np.pi / 2, platform_radius=80.0, platform_offset=70.0,
...     base_radius=275.0)
>>> config = inverse_kinematics(h4, [0.0, 0.0, -700.0, 0.3])
>>> config.theta.shape, config.subplatform_limbs
((4,), ((0, 3), (1, 2)))
>>> bool(np.all(config.h < 0))
True
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, fields
from typing import Any, NamedTuple

import numpy as np

from ...algebra import screw as S
from ...algebra.backend import as_array, cross
from ...core.jacobians import schoenflies_basis
from ...exceptions import CatalogError, ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError
from ...graphs.joints import JointSpec, JointTable
from ..two_limb import at_reach, within_reach
from . import Family

__all__ = [
    "DEFAULT_PARALLELOGRAM_WIDTH_MM",
    "FAMILY",
    "PAPER_002_LEGS",
    "PLATFORM_KINDS",
    "SUBPLATFORMS",
    "ForwardKinematicsError",
    "FourLimbConfiguration",
    "FourLimbParameters",
    "forward_kinematics",
    "inverse_kinematics",
    "joints",
    "reachable",
    "twist_basis",
]

#: The platform variants of Table 1 (paper 004).
PLATFORM_KINDS = ("articulated_z", "articulated_y", "screw_pair")

#: Default spacing of the two rods of a parallelogram when ``length_unit == "mm"``. Paper 004 does
#: not give it and the kinematics do not depend on it; 100 mm is our choice.
DEFAULT_PARALLELOGRAM_WIDTH_MM = 100.0

#: η_i = (2i - 1)π/4 (Eq. 1), also the platform angles γ_i of the screw-pair platform (Table 3).
_ETA = (2.0 * np.arange(1, 5) - 1.0) * np.pi / 4.0
#: sgn(cos η_i) and sgn(sin η_i) of Table 1.
_SGN_COS_ETA = np.array([1.0, -1.0, -1.0, 1.0])
_SGN_SIN_ETA = np.array([1.0, 1.0, -1.0, -1.0])
#: mod(i, 2) of Table 1 (limbs 1 and 3 carry the screw-pair offset).
_ODD_LIMB = np.array([1.0, 0.0, 1.0, 0.0])
#: Limbs (0-based) on sub-platforms I and II, derived from Table 1 (module docstring).
_SUBPLATFORMS = {
    "articulated_z": ((0, 3), (1, 2)),
    "articulated_y": ((0, 3), (1, 2)),
    "screw_pair": ((0, 2), (1, 3)),
}
_DEFAULT_WORKING_MODE = (-1, -1, -1, -1)
_K = np.array([0.0, 0.0, 1.0])


class ForwardKinematicsError(ScrewkitValueError):
    """Newton's method did not reach an assembly of the requested working mode.

    Defined here because :mod:`screwkit.exceptions` has no convergence error (yet).
    """


# --------------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------------

_REQUIRED = ("name", "platform_kind", "arm_length", "rod_length", "alpha", "beta", "platform_radius")
_POSITIVE_LENGTHS = (
    "arm_length",
    "rod_length",
    "platform_radius",
    "platform_offset",
    "lead",
    "base_radius",
    "parallelogram_width",
)


def _is_real(value: Any) -> bool:
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(
        value, bool | np.bool_
    )


def _normalised_fields(
    values: Mapping[str, Any],
    source: str,
    structure_error: type[Exception],
    type_error: type[Exception],
) -> dict[str, Any]:
    """Check types, presence rules and ranges; return the fields with floats and tuples."""
    out = dict(values)
    for key in ("name", "platform_kind", "length_unit"):
        if not isinstance(out.get(key), str) or not out[key].strip():
            raise type_error(
                f"{source}: expected field `{key}` to be a non-empty string, got {out.get(key)!r}."
            )
    for key in (*_POSITIVE_LENGTHS, "alpha", "beta", "axis_inclination"):
        value = out.get(key)
        if value is None:
            continue
        if not _is_real(value):
            raise type_error(
                f"{source}: expected field `{key}` to be a real number, got "
                f"{type(value).__name__} {value!r}."
            )
        if not math.isfinite(value):
            raise ScrewkitValueError(
                f"{source}: expected field `{key}` to be finite, got {value!r}."
            )
        out[key] = float(value)
        if key in _POSITIVE_LENGTHS and value <= 0:
            raise ScrewkitValueError(
                f"{source}: expected field `{key}` (a length) to be > 0, got {value!r}."
            )
    kind = out["platform_kind"]
    if kind not in PLATFORM_KINDS:
        raise ScrewkitValueError(
            f"{source}: expected field `platform_kind` to be one of {PLATFORM_KINDS}, got {kind!r}."
        )
    needed, unused = ("lead", "platform_offset") if kind == "screw_pair" else ("platform_offset",
                                                                              "lead")
    if out.get(needed) is None:
        raise structure_error(f"{source}: field `{needed}` is required when platform_kind={kind!r}.")
    if out.get(unused) is not None:
        raise structure_error(
            f"{source}: field `{unused}` does not apply when platform_kind={kind!r}; remove it."
        )
    if (out.get("base_radius") is None) == (out.get("base_points") is None):
        raise structure_error(
            f"{source}: give exactly one of `base_radius` (Eq. 1 layout) and `base_points` "
            f"(explicit A_i), got base_radius={out.get('base_radius')!r}, "
            f"base_points={out.get('base_points')!r}."
        )
    if out.get("base_points") is not None:
        out["base_points"] = _base_points(out["base_points"], source, type_error)
    if out.get("parallelogram_width") is None:
        if out["length_unit"] != "mm":
            raise structure_error(
                f"{source}: field `parallelogram_width` has no default for length_unit="
                f"{out['length_unit']!r} (the default {DEFAULT_PARALLELOGRAM_WIDTH_MM} is in mm); "
                "give it explicitly."
            )
        out["parallelogram_width"] = DEFAULT_PARALLELOGRAM_WIDTH_MM
    return out


def _base_points(
    value: Any, source: str, type_error: type[Exception]
) -> tuple[tuple[float, float, float], ...]:
    rows = value if isinstance(value, Sequence) and not isinstance(value, str) else None
    if (
        rows is None
        or len(rows) != 4
        or not all(
            isinstance(row, Sequence) and not isinstance(row, str) and len(row) == 3
            and all(_is_real(x) for x in row)
            for row in rows
        )
    ):
        raise type_error(
            f"{source}: expected field `base_points` to be 4 points of 3 real numbers, got {value!r}."
        )
    points = tuple((float(p[0]), float(p[1]), float(p[2])) for p in rows)
    if not all(math.isfinite(x) for p in points for x in p):
        raise ScrewkitValueError(f"{source}: expected field `base_points` to be finite, got {value!r}.")
    return points


@dataclass(frozen=True, slots=True)
class FourLimbParameters:
    """Geometry of one four-limb Schönflies-motion generator (paper 004, Tables 1 and 3, Eq. 1).

    All lengths are in ``length_unit``; angles in radians.

    Parameters
    ----------
    name : str
        Robot name, e.g. ``"H4"``.
    platform_kind : {"articulated_z", "articulated_y", "screw_pair"}
        Table 1 row: Quattro/H4, V4, Veloce (and Ragnar).
    arm_length : float
        ``b``, length of the actuated arm ``A_i B_i``.
    rod_length : float
        ``l``, length of the parallelogram ``B_i C_i``.
    alpha, beta : float
        ``α``, ``β`` of Table 3: ``α_1 = -α_2 = α``, ``α_3 = -α_4 = β``, ``u_i = R_z(α_i) i``.
    axis_inclination : float, optional
        ``ε``: the actuated axes leave the base plane, ``u_i = R_z(α_i) R_y(ε_i) i`` with
        ``ε_1 = -ε_2 = ε_3 = -ε_4 = ε`` (module docstring, item 6). Default 0 (Table 3's robots).
    platform_radius : float
        ``r`` of Table 3.
    platform_offset : float, optional
        ``c`` of Table 3; required for the articulated platforms, refused for the screw pair.
    lead : float, optional
        ``h``, lead of the screw pair (length per turn); required for ``"screw_pair"`` only.
    base_radius : float, optional
        ``R`` of Eq. (1); give this or ``base_points``.
    base_points : tuple of 4 (x, y, z), optional
        Explicit ``a_i`` (Ragnar, text after Table 4).
    parallelogram_width : float, optional
        Spacing of the two rods of each parallelogram (not in paper 004, no effect on kinematics).
        Defaults to :data:`DEFAULT_PARALLELOGRAM_WIDTH_MM` when ``length_unit == "mm"``; required
        otherwise.
    length_unit : str
        Unit of every length and of poses (default ``"mm"``, the paper's unit).

    Raises
    ------
    ScrewkitTypeError
        A field has the wrong type.
    ScrewkitValueError
        A length is not positive, a kind is unknown, or a field is missing or does not apply.

    Examples
    --------
    >>> p = FourLimbParameters(name="Veloce", platform_kind="screw_pair", arm_length=375,
    ...     rod_length=800, alpha=-np.pi / 4, beta=3 * np.pi / 4, platform_radius=100, lead=20,
    ...     base_radius=275)
    >>> p.parallelogram_width, p.subplatform_limbs
    (100.0, ((0, 2), (1, 3)))
    """

    name: str
    platform_kind: str
    arm_length: float
    rod_length: float
    alpha: float
    beta: float
    platform_radius: float
    platform_offset: float | None = None
    lead: float | None = None
    base_radius: float | None = None
    base_points: tuple[tuple[float, float, float], ...] | None = None
    parallelogram_width: float | None = None
    length_unit: str = "mm"
    axis_inclination: float = 0.0

    def __post_init__(self) -> None:
        values = {f.name: getattr(self, f.name) for f in fields(self)}
        checked = _normalised_fields(
            values, "FourLimbParameters", ScrewkitValueError, ScrewkitTypeError
        )
        for key, value in checked.items():
            object.__setattr__(self, key, value)

    @classmethod
    def from_mapping(
        cls, mapping: Mapping[str, Any], *, source: str = "<mapping>"
    ) -> FourLimbParameters:
        """Build parameters from a mapping (e.g. a TOML table), naming ``source`` in every error.

        Keys are the field names of this class; ``alpha`` and ``beta`` are in radians.

        Raises
        ------
        CatalogError
            Unknown, missing or wrongly typed fields.
        ScrewkitValueError
            Values out of range (e.g. a negative length, an unknown ``platform_kind``).

        Examples
        --------
        >>> FourLimbParameters.from_mapping({"name": "H4"}, source="h4.toml")
        Traceback (most recent call last):
        ...
        screwkit.exceptions.CatalogError: h4.toml: missing field(s) ['alpha', 'arm_length', ...
        """
        if not isinstance(mapping, Mapping):
            raise CatalogError(f"{source}: expected a mapping of parameters, got "
                               f"{type(mapping).__name__}.")
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(mapping) - known)
        if unknown:
            raise CatalogError(
                f"{source}: unknown field(s) {unknown}; expected a subset of {sorted(known)}."
            )
        missing = sorted(set(_REQUIRED) - set(mapping))
        if missing:
            raise CatalogError(f"{source}: missing field(s) {missing}.")
        values = {f.name: f.default for f in fields(cls)} | dict(mapping)
        checked = _normalised_fields(values, source, CatalogError, CatalogError)
        return cls(**checked)

    @property
    def subplatform_limbs(self) -> tuple[tuple[int, int], tuple[int, int]]:
        """0-based limb indices carried by sub-platforms I and II (derived from Table 1)."""
        return _SUBPLATFORMS[self.platform_kind]

    @property
    def limb_alphas(self) -> np.ndarray:
        """``α_i = (α, -α, β, -β)`` (Sec. 2), shape (4,)."""
        return np.array([self.alpha, -self.alpha, self.beta, -self.beta])

    @property
    def limb_inclinations(self) -> np.ndarray:
        """``ε_i = (ε, -ε, ε, -ε)`` (module docstring, item 6), shape (4,)."""
        return self.axis_inclination * np.array([1.0, -1.0, 1.0, -1.0])


# --------------------------------------------------------------------------------------------------
# Configuration
# --------------------------------------------------------------------------------------------------

_ARRAY_FIELDS = (
    "pose", "theta", "a", "u", "b", "v", "c", "w", "h", "s", "platform_s",
    "elbow_corners", "platform_corners", "platform_joint_points", "platform_joint_axis",
)


@dataclass(frozen=True, slots=True, eq=False)
class FourLimbConfiguration:
    """Every point and axis of a four-limb SMG at one pose (or a batch of poses).

    All arrays are read-only; ``...`` is the batch shape of the pose. Limb ``i`` of paper 004 is
    index ``i - 1`` on the limb axis.

    Attributes
    ----------
    params : FourLimbParameters
    working_mode : tuple of 4 int
        Requested signs of ``h_i`` (Eq. 8).
    pose : (..., 4) ndarray
        ``χ = (x, y, z, φ)``.
    theta : (..., 4) ndarray
        Actuated angles ``θ_i`` in ``[-π, π)``.
    a, u : (..., 4, 3) ndarray
        Actuated joint points ``A_i`` (Eq. 1) and unit axes ``u_i = R_z(α_i) i``.
    b, v : (..., 4, 3) ndarray
        Elbow points ``B_i`` and unit arm directions ``v_i`` (Eq. 2).
    c, w : (..., 4, 3) ndarray
        Platform points ``C_i`` (Table 1) and unit parallelogram directions ``w_i = (c_i - b_i)/l``.
    h : (..., 4) ndarray
        ``h_i = b w_i·(u_i × v_i)`` (Eq. 8), the diagonal of ``B``.
    s : (..., 4, 3) ndarray
        ``s_i`` with ``∂c_i/∂φ = r s_i`` (Eq. 4; Table 1 corrected, see the module docstring).
    platform_s : (..., 3) ndarray
        The unit vector ``s`` of Tables 1-2: ``R_z(φ) j`` (Quattro, H4), ``-R_y(φ) k`` (V4, see the
        module docstring) or ``k`` (screw pair).
    elbow_corners, platform_corners : (..., 4, 2, 3) ndarray
        Sphere centres ``(m_i, n_i) = b_i ∓ (d/2) u_i`` and ``(p_i, q_i) = c_i ∓ (d/2) u_i``.
    subplatform_limbs : tuple of two pairs of int
        0-based limbs carried by sub-platforms I and II.
    platform_joint_points : (..., 2, 3) ndarray
        A point on the axis of the joint between sub-platform I (resp. II) and the end effector:
        ``P_I``, ``P_II`` for articulated platforms; the sub-platform centres on the screw axis for
        the screw pair.
    platform_joint_axis : (..., 3) ndarray
        Unit direction of both joints (``k``, ``j`` or ``k``).
    platform_joint_pitches : tuple of 2 float
        Pitch of each joint: 0 for a revolute joint, ``-h/(2π)`` for the helical joint of the
        screw-pair platform (sub-platform I).

    Examples
    --------
    >>> cfg = inverse_kinematics(FourLimbParameters(name="H4", platform_kind="articulated_z",
    ...     arm_length=375, rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80,
    ...     platform_offset=70, base_radius=275), [[0, 0, -700, 0], [100, 0, -800, 0.5]])
    >>> cfg.batch_shape, cfg.elbow_corners.shape, cfg.platform_joint_points.shape
    ((2,), (2, 4, 2, 3), (2, 2, 3))
    >>> cfg.theta.flags.writeable
    False
    """

    params: FourLimbParameters
    working_mode: tuple[int, int, int, int]
    pose: np.ndarray
    theta: np.ndarray
    a: np.ndarray
    u: np.ndarray
    b: np.ndarray
    v: np.ndarray
    c: np.ndarray
    w: np.ndarray
    h: np.ndarray
    s: np.ndarray
    platform_s: np.ndarray
    elbow_corners: np.ndarray
    platform_corners: np.ndarray
    subplatform_limbs: tuple[tuple[int, int], tuple[int, int]]
    platform_joint_points: np.ndarray
    platform_joint_axis: np.ndarray
    platform_joint_pitches: tuple[float, float]

    def __post_init__(self) -> None:
        for name in _ARRAY_FIELDS:
            array = np.array(getattr(self, name), dtype=float)
            array.flags.writeable = False
            object.__setattr__(self, name, array)

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """Leading (batch) shape of the pose."""
        return self.pose.shape[:-1]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (arrays become nested lists)."""
        out: dict[str, Any] = {
            "parameters": asdict(self.params),
            "working_mode": list(self.working_mode),
            "subplatform_limbs": [list(pair) for pair in self.subplatform_limbs],
            "platform_joint_pitches": list(self.platform_joint_pitches),
        }
        out |= {name: getattr(self, name).tolist() for name in _ARRAY_FIELDS}
        return out

    def __str__(self) -> str:
        return (
            f"FourLimbConfiguration({self.params.name}, {self.params.platform_kind}, "
            f"batch shape {self.batch_shape}, working mode {self.working_mode})"
        )


class _Platform(NamedTuple):
    c: np.ndarray  # (..., 4, 3)
    dc_dphi: np.ndarray  # (..., 4, 3), = r s_i
    platform_s: np.ndarray  # (..., 3)
    joint_points: np.ndarray  # (..., 2, 3)
    joint_axis: np.ndarray  # (..., 3)


class _Base(NamedTuple):
    a: np.ndarray  # (4, 3) actuated joint points A_i
    u: np.ndarray  # (4, 3) F_i i, the actuated axes
    j_rot: np.ndarray  # (4, 3) F_i j = R_z(α_i) j (R_y leaves j fixed)
    k_rot: np.ndarray  # (4, 3) F_i k = R_z(α_i) R_y(ε_i) k (k when ε = 0)


def _base(params: FourLimbParameters) -> _Base:
    """``a_i`` (Eq. 1 or explicit) and the limb frames ``F_i = R_z(α_i) R_y(ε_i)`` (item 6); read
    only, computed once per parameter set (every chunk of a batch asks)."""
    try:
        return _cached_base(params)
    except TypeError:  # unhashable parameters: computed afresh
        return _base_of(params)


@functools.lru_cache(maxsize=64)
def _cached_base(params: FourLimbParameters) -> _Base:
    return _base_of(params)


def _base_of(params: FourLimbParameters) -> _Base:
    if params.base_points is not None:
        a = np.array(params.base_points, dtype=float)
    else:
        assert params.base_radius is not None  # guaranteed by validation
        a = params.base_radius * np.stack([np.cos(_ETA), np.sin(_ETA), np.zeros(4)], axis=-1)
    alphas, tilts = params.limb_alphas, params.limb_inclinations
    ca, sa, ce, se = np.cos(alphas), np.sin(alphas), np.cos(tilts), np.sin(tilts)
    u = np.stack([ca * ce, sa * ce, -se], axis=-1)
    j_rot = np.stack([-sa, ca, np.zeros(4)], axis=-1)
    k_rot = np.stack([ca * se, sa * se, ce], axis=-1)
    for array in (a, u, j_rot, k_rot):
        array.flags.writeable = False
    return _Base(a, u, j_rot, k_rot)


def _platform(params: FourLimbParameters, pose: np.ndarray) -> _Platform:
    """Points ``c_i`` of Table 1 (corrected) and their derivative with respect to ``φ``."""
    p = pose[..., None, :3]
    phi = pose[..., 3]
    cos, sin, zero = np.cos(phi), np.sin(phi), np.zeros_like(phi)
    r = params.platform_radius
    j_vec = np.array([0.0, 1.0, 0.0])
    if params.platform_kind == "screw_pair":
        assert params.lead is not None
        radial = np.stack([np.cos(_ETA), np.sin(_ETA), np.zeros(4)], axis=-1)
        rise = params.lead / (2.0 * np.pi)
        c = r * radial + (_ODD_LIMB[:, None] * rise * phi[..., None, None]) * _K + p
        dc_dphi = np.broadcast_to(_ODD_LIMB[:, None] * rise * _K, c.shape)
        axis = np.broadcast_to(_K, (*pose.shape[:-1], 3))
        centre = pose[..., :3]
        joint_points = np.stack([centre + (rise * phi)[..., None] * _K, centre], axis=-2)
        return _Platform(c, dc_dphi, axis, joint_points, axis)
    assert params.platform_offset is not None
    offsets = (_SGN_SIN_ETA * params.platform_offset)[:, None] * j_vec
    if params.platform_kind == "articulated_z":
        bar = np.stack([cos, sin, zero], axis=-1)  # R_z(φ) i
        s = np.stack([-sin, cos, zero], axis=-1)  # ∂(R_z(φ) i)/∂φ = R_z(φ) j
        axis = np.broadcast_to(_K, s.shape)
    else:  # articulated_y, Table 1 corrected (module docstring, item 3)
        bar = np.stack([cos, zero, -sin], axis=-1)  # R_y(φ) i
        s = np.stack([-sin, zero, -cos], axis=-1)  # ∂(R_y(φ) i)/∂φ = -R_y(φ) k
        axis = np.broadcast_to(j_vec, s.shape)
    c = _SGN_COS_ETA[:, None] * r * bar[..., None, :] + offsets + p
    dc_dphi = _SGN_COS_ETA[:, None] * r * s[..., None, :]
    joint_points = pose[..., None, :3] + np.array([1.0, -1.0])[:, None] * r * bar[..., None, :]
    return _Platform(c, dc_dphi, s, joint_points, axis)


def _require(value: Any, cls: type, name: str) -> None:
    if not isinstance(value, cls):
        raise ScrewkitTypeError(
            f"Expected `{name}` to be a {cls.__name__}, got {type(value).__name__}."
        )


def _checked_working_mode(working_mode: Any) -> tuple[int, int, int, int]:
    if isinstance(working_mode, str | bytes) or not isinstance(working_mode, Sequence | np.ndarray):
        raise ScrewkitTypeError(
            f"Expected `working_mode` to be a sequence of 4 signs (+1 or -1) of h_i (paper 004, "
            f"Eq. 8), got {type(working_mode).__name__} {working_mode!r}."
        )
    values = list(np.asarray(working_mode, dtype=object).ravel()) if isinstance(
        working_mode, np.ndarray
    ) else list(working_mode)
    if len(values) != 4 or not all(_is_real(x) and x in (-1, 1) for x in values):
        raise ScrewkitValueError(
            "Expected `working_mode` to be 4 signs (+1 or -1) of h_i (paper 004, Eq. 8), got "
            f"{tuple(values)!r}."
        )
    return (int(values[0]), int(values[1]), int(values[2]), int(values[3]))


def _assemble(
    params: FourLimbParameters,
    pose: np.ndarray,
    theta: np.ndarray,
    working_mode: tuple[int, int, int, int],
    platform: _Platform,
    base: _Base,
) -> FourLimbConfiguration:
    """Build the configuration from a pose and the actuated angles that close it (``base``:
    :func:`_base` of ``params``, computed once by the caller)."""
    a, u, j_rot, k_rot = base
    batch = pose.shape[:-1]
    cos, sin = np.cos(theta)[..., None], np.sin(theta)[..., None]
    v = cos * j_rot + sin * k_rot  # F_i R_x(θ_i) j (Eq. 2)
    u_cross_v = -sin * j_rot + cos * k_rot  # F_i R_x(θ_i) k
    b = a + params.arm_length * v
    w = (platform.c - b) / params.rod_length
    h = params.arm_length * np.sum(w * u_cross_v, axis=-1)  # Eq. (8)
    assert params.parallelogram_width is not None  # set by FourLimbParameters.__post_init__
    half = 0.5 * params.parallelogram_width * np.stack([-u, u], axis=-2)  # (4, 2, 3)
    return FourLimbConfiguration(
        params=params,
        working_mode=working_mode,
        pose=pose,
        theta=theta,
        a=np.broadcast_to(a, (*batch, 4, 3)),
        u=np.broadcast_to(u, (*batch, 4, 3)),
        b=b,
        v=v,
        c=platform.c,
        w=w,
        h=h,
        s=platform.dc_dphi / params.platform_radius,
        platform_s=platform.platform_s,
        elbow_corners=b[..., None, :] + half,
        platform_corners=platform.c[..., None, :] + half,
        subplatform_limbs=params.subplatform_limbs,
        platform_joint_points=platform.joint_points,
        platform_joint_axis=platform.joint_axis,
        platform_joint_pitches=(
            (-params.lead / (2.0 * np.pi), 0.0) if params.lead is not None else (0.0, 0.0)
        ),
    )


def _describe_failures(mask: np.ndarray, batch: tuple[int, ...], what: str) -> str:
    """'pose index (3,): limbs 1, 2; ...' for the first few failing entries (mask (..., 4))."""
    entries = np.argwhere(mask.any(axis=-1)) if batch else np.zeros((1, 0), dtype=int)
    parts = []
    for index in entries[:5]:
        limbs = ", ".join(str(i + 1) for i in np.flatnonzero(mask[tuple(index)]))
        where = f"{what} index {tuple(int(i) for i in index)}: " if batch else ""
        parts.append(f"{where}limb(s) {limbs}")
    more = f" (and {len(entries) - 5} more)" if len(entries) > 5 else ""
    return "; ".join(parts) + more


def inverse_kinematics(
    params: FourLimbParameters,
    pose: Any,
    *,
    working_mode: Sequence[int] = _DEFAULT_WORKING_MODE,
) -> FourLimbConfiguration:
    """Closed-form inverse kinematics of Eq. (3) (paper 004), vectorised over the pose batch.

    With ``d_i = c_i - a_i``, Eq. (3) reads ``P_i cos θ_i + Q_i sin θ_i = K_i`` where
    ``P_i = d_i·F_i j``, ``Q_i = d_i·F_i k`` (``F_i = R_z(α_i)`` for horizontal axes, item 6) and
    ``K_i = (|d_i|² + b² - l²)/(2b)``. With
    ``ρ_i = hypot(P_i, Q_i)``, ``ψ_i = atan2(Q_i, P_i)`` and ``δ_i = cos⁻¹(K_i/ρ_i)``, the two roots
    are ``θ_i = ψ_i ∓ δ_i``, and ``h_i = (b ρ_i / l) sin(ψ_i - θ_i)`` (Eq. 8), so
    ``θ_i = ψ_i - m_i δ_i`` is the root with ``sgn(h_i) = m_i``.

    Parameters
    ----------
    params : FourLimbParameters
    pose : array_like, shape (..., 4)
        ``(x, y, z, φ)`` in ``params.length_unit`` and radians.
    working_mode : sequence of 4 int
        Sign (+1 or -1) of each ``h_i``; the paper's choice ``(-1, -1, -1, -1)`` by default.

    Returns
    -------
    FourLimbConfiguration

    Raises
    ------
    UnreachablePoseError
        If ``|K_i| > ρ_i`` for some limb (it cannot reach ``C_i``); names the limbs (paper numbering)
        and, for a batch, the pose indices.
    ScrewkitValueError, ScrewkitTypeError
        For a malformed pose or working mode.

    Examples
    --------
    >>> quattro = FourLimbParameters(name="Quattro", platform_kind="articulated_z",
    ...     arm_length=375, rod_length=800, alpha=-np.pi / 4, beta=3 * np.pi / 4,
    ...     platform_radius=80, platform_offset=70, base_radius=275)
    >>> cfg = inverse_kinematics(quattro, [0, 0, -700, 0])
    >>> np.allclose(np.linalg.norm(cfg.c - cfg.b, axis=-1), 800)
    True
    >>> inverse_kinematics(quattro, [0, 0, -2000, 0])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.UnreachablePoseError: Pose (x, y, z, phi) = (0, 0, -2000, 0 rad = 0 deg) is out ...
    """
    _require(params, FourLimbParameters, "params")
    mode = _checked_working_mode(working_mode)
    chi = as_array(pose, "pose", (4,), symbolic=False)
    terms = _ik_terms(params, chi)
    unreachable = ~terms.reachable
    if unreachable.any():
        batch = chi.shape[:-1]
        detail = _describe_failures(unreachable, batch, "pose")
        head = (
            f"{int(unreachable.any(axis=-1).sum())} of {int(np.prod(batch))} poses are"
            if batch
            else "Pose (x, y, z, phi) = ({:g}, {:g}, {:g}, {:g} rad = {:g} deg) is".format(
                *chi.tolist(), math.degrees(float(chi[-1]))
            )
        )
        raise UnreachablePoseError(
            f"{head} out of reach of {params.name} (paper 004 limb numbering; Eq. 3 has no real "
            f"root, |K_i| > hypot(P_i, Q_i)): {detail}."
        )
    psi = np.arctan2(terms.q, terms.p)
    delta = np.arccos(at_reach(terms.k / terms.rho, terms.condition))
    theta = _wrap(psi - np.array(mode, dtype=float) * delta)
    return _assemble(params, chi, theta, mode, terms.platform, terms.base)


class _IKTerms(NamedTuple):
    platform: _Platform
    base: _Base
    p: np.ndarray  # P_i = d_i·F_i j
    q: np.ndarray  # Q_i = d_i·F_i k
    k: np.ndarray  # K_i = (|d_i|² + b² - l²) / (2b)
    rho: np.ndarray  # hypot(P_i, Q_i)
    condition: np.ndarray  # relative size of the rounding error of K_i / ρ_i (at_reach)
    reachable: np.ndarray  # (..., 4) bool


def _ik_terms(params: FourLimbParameters, chi: np.ndarray) -> _IKTerms:
    """Coefficients of ``P_i cos θ_i + Q_i sin θ_i = K_i``, Eq. (3) rewritten (paper 004)."""
    platform = _platform(params, chi)
    base = _base(params)
    d = platform.c - base.a
    big_p = np.sum(d * base.j_rot, axis=-1)
    big_q = np.sum(d * base.k_rot, axis=-1)
    big_k = (np.sum(d * d, axis=-1) + params.arm_length**2 - params.rod_length**2) / (
        2.0 * params.arm_length
    )
    rho = np.hypot(big_p, big_q)
    with np.errstate(divide="ignore", invalid="ignore"):
        cosine = big_k / rho
        condition = (big_k * params.arm_length + params.rod_length**2) / (params.arm_length * rho)
    # a limb stretched or folded exactly to its reach may round to |K_i| a few ulps above ρ_i: at its
    # reach (arccos of ±1, a serial singularity), not out of reach (README, "Tolerance policy")
    reachable = (rho > 0.0) & within_reach(np.where(rho > 0.0, cosine, np.inf), condition)
    return _IKTerms(platform, base, big_p, big_q, big_k, rho, condition, reachable)


def reachable(params: FourLimbParameters, pose: Any) -> np.ndarray:
    """Which poses every limb can reach (Eq. 3 has real roots for all four limbs).

    Parameters
    ----------
    params : FourLimbParameters
    pose : array_like, shape (..., 4)

    Returns
    -------
    (...,) ndarray of bool
        True where :func:`inverse_kinematics` succeeds (in every working mode).

    Examples
    --------
    >>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> reachable(h4, [[0, 0, -700, 0], [0, 0, -2000, 0]])
    array([ True, False])
    """
    _require(params, FourLimbParameters, "params")
    chi = as_array(pose, "pose", (4,), symbolic=False)
    return np.all(_ik_terms(params, chi).reachable, axis=-1)


def _wrap(angle: np.ndarray) -> np.ndarray:
    """Angles in ``[-π, π)``."""
    return (angle + np.pi) % (2.0 * np.pi) - np.pi


def forward_kinematics(
    params: FourLimbParameters,
    theta: Any,
    *,
    working_mode: Sequence[int] = _DEFAULT_WORKING_MODE,
    initial_pose: Any = None,
    rtol: float = 1e-12,
    max_iterations: int = 50,
) -> FourLimbConfiguration:
    """Numerical forward kinematics: Newton's method on Eq. (3) (paper 004), vectorised.

    The residuals ``F_i = |c_i(χ) - b_i(θ_i)|² - l²`` have the Jacobian ``∂F/∂χ = 2 l A`` (Eqs. 6-8),
    so each step solves ``2 l A Δχ = -F`` (pseudo-inverse, so a singular ``A`` does not abort the
    whole batch), halving the step until ``|F|`` decreases.

    Parameters
    ----------
    params : FourLimbParameters
    theta : array_like, shape (..., 4)
        Actuated angles ``θ_i`` in radians.
    working_mode : sequence of 4 int
        Signs of ``h_i`` the assembly must have (default: the paper's ``h_i < 0``).
    initial_pose : array_like, shape (..., 4), optional
        Starting pose, broadcast against the batch. By default the pose whose four parallelograms
        hang straight down (``w_i = -k`` on average) with ``φ = 0``.
    rtol : float
        Convergence when ``max_i |F_i| / l² <= rtol`` (default 1e-12, i.e. rod lengths right to
        about ``rtol·l/2``).
    max_iterations : int
        Newton iterations before giving up (default 50).

    Returns
    -------
    FourLimbConfiguration
        With ``φ`` wrapped to ``[-π, π)`` for articulated platforms (the screw-pair platform is not
        periodic in ``φ``).

    Raises
    ------
    ForwardKinematicsError
        Naming the batch entries that did not converge or converged to another working mode.

    Examples
    --------
    >>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> pose = np.array([50.0, -20.0, -750.0, 0.4])
    >>> fk = forward_kinematics(h4, inverse_kinematics(h4, pose).theta)
    >>> np.allclose(fk.pose, pose)
    True
    """
    _require(params, FourLimbParameters, "params")
    mode = _checked_working_mode(working_mode)
    if not (isinstance(rtol, float | int) and rtol > 0):
        raise ScrewkitValueError(f"Expected `rtol` to be a positive number, got {rtol!r}.")
    if not (isinstance(max_iterations, int) and max_iterations >= 1):
        raise ScrewkitValueError(
            f"Expected `max_iterations` to be a positive integer, got {max_iterations!r}."
        )
    th = as_array(theta, "theta", (4,), symbolic=False)
    batch = th.shape[:-1]
    base = _base(params)
    a, _, j_rot, k_rot = base
    elbows = a + params.arm_length * (
        np.cos(th)[..., None] * j_rot + np.sin(th)[..., None] * k_rot
    )
    if initial_pose is None:
        offsets = _platform(params, np.zeros(4)).c
        start = np.mean(elbows - offsets, axis=-2) - params.rod_length * _K
        chi = np.concatenate([start, np.zeros((*batch, 1))], axis=-1)
    else:
        guess = as_array(initial_pose, "initial_pose", (4,), symbolic=False)
        try:
            chi = np.broadcast_to(guess, (*batch, 4)).copy()
        except ValueError as err:
            raise ScrewkitValueError(
                f"Expected `initial_pose` to broadcast to the batch shape {(*batch, 4)} of "
                f"`theta`, got {guess.shape}."
            ) from err
    scale = params.rod_length**2

    def residual(pose: np.ndarray) -> tuple[np.ndarray, np.ndarray, _Platform]:
        plat = _platform(params, pose)
        d = plat.c - elbows
        return np.sum(d * d, axis=-1) - scale, d, plat

    f, d, plat = residual(chi)
    for _ in range(max_iterations):
        active = np.max(np.abs(f), axis=-1) / scale > rtol
        if not active.any():
            break
        jac = 2.0 * np.concatenate([d, np.sum(d * plat.dc_dphi, axis=-1)[..., None]], axis=-1)
        step = np.where(active[..., None], (np.linalg.pinv(jac) @ f[..., None])[..., 0], 0.0)
        size = np.sum(f * f, axis=-1)
        pending = active.copy()
        fraction = np.ones(batch)
        for _ in range(30):
            trial = chi - fraction[..., None] * step
            f_trial, d_trial, plat_trial = residual(trial)
            better = pending & (np.sum(f_trial * f_trial, axis=-1) < size)
            chi = np.where(better[..., None], trial, chi)
            f = np.where(better[..., None], f_trial, f)
            d = np.where(better[..., None, None], d_trial, d)
            plat = _Platform(*(np.where(_expand(better, new), new, old)
                               for new, old in zip(plat_trial, plat, strict=True)))
            pending &= ~better
            if not pending.any():
                break
            fraction = np.where(pending, 0.5 * fraction, fraction)
    failed = np.max(np.abs(f), axis=-1) / scale > rtol
    if params.platform_kind != "screw_pair":
        chi[..., 3] = _wrap(chi[..., 3])
    config = _assemble(params, chi, _wrap(th), mode, _platform(params, chi), base)
    wrong_mode = ~failed & np.any(np.sign(config.h) != np.array(mode), axis=-1)
    if failed.any() or wrong_mode.any():
        problems = [
            f"{int(mask.sum())} {what}" + (f" (batch indices {_first_indices(mask)})" if batch else "")
            for mask, what in (
                (failed, "did not converge"),
                (wrong_mode, f"converged to an assembly outside working mode {mode}"),
            )
            if mask.any()
        ]
        subject = f"theta={th.tolist()}" if not batch else f"a batch of shape {batch}"
        raise ForwardKinematicsError(
            f"Forward kinematics of {params.name} failed for {subject} (Newton on Eq. 3, "
            f"{max_iterations} iterations, rtol={rtol}): {'; '.join(problems)}. Try an "
            "`initial_pose` near the expected assembly."
        )
    return config


def _first_indices(mask: np.ndarray, count: int = 5) -> str:
    indices = [tuple(int(i) for i in index) for index in np.argwhere(mask)[:count]]
    more = f" and {int(mask.sum()) - count} more" if mask.sum() > count else ""
    return ", ".join(str(i) for i in indices) + more


def _expand(mask: np.ndarray, like: np.ndarray) -> np.ndarray:
    """Reshape a batch mask to broadcast against an array with trailing axes."""
    return mask.reshape(mask.shape + (1,) * (like.ndim - mask.ndim))


# --------------------------------------------------------------------------------------------------
# The joint table and the nominal twists (the family protocol, screwkit.robots.families)
# --------------------------------------------------------------------------------------------------

#: Paper 002's H4 legs l1..l4 as paper 004's limbs (1-based): (1, 4, 2, 3).
PAPER_002_LEGS = {"l1": 1, "l2": 4, "l3": 2, "l4": 3}
#: Names of the sub-platform links and of the joints joining them to the end effector.
SUBPLATFORMS = (("b_I", "R_I"), ("b_II", "R_II"))


def joints(config: FourLimbConfiguration) -> JointTable:
    """The joints of the physical mechanism with their screws over the whole batch of poses.

    Each limb is modelled as paper 002 models the H4's (§4.1, Fig. 2): ``R–(4S)``, an actuated
    revolute joint ``A<i>`` (axis ``u_i`` through ``A_i``) and a parallelogram of two rods with
    **explicit spherical joints** at its four corners ``m, n`` (on the arm) and ``p, q`` (on the
    sub-platform). The closed 4S loops are *not* typed in as virtual chains: the equivalent twist
    graph derives them (:func:`screwkit.graphs.twistgraph.equivalent_twist_graph`). The sub-platforms
    ``b_I`` and ``b_II`` join the end effector by joints ``R_I`` and ``R_II`` (revolute, or helical
    for the screw-pair platforms) on the axes of :class:`FourLimbConfiguration`.

    Parameters
    ----------
    config : FourLimbConfiguration
        From :func:`inverse_kinematics` (any batch shape ``...``).

    Returns
    -------
    JointTable
        Links ``base``, ``arm<i>``, ``rod<i>a``, ``rod<i>b``, ``b_I``, ``b_II``, ``end_effector``;
        joints, in the order of their names, ``A<i>`` (actuated R), ``R_I``, ``R_II``, ``S<i>m``,
        ``S<i>n``, ``S<i>p``, ``S<i>q`` (S); ``dof = 4``; screws ``(..., rows, 6)``.

    Raises
    ------
    ScrewkitTypeError
        If ``config`` is not a :class:`FourLimbConfiguration`.

    Examples
    --------
    >>> h4 = FourLimbParameters(name="H4", platform_kind="articulated_z", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> table = joints(inverse_kinematics(h4, np.zeros((5, 4)) + [0, 0, -700, 0]))
    >>> len(table.specs), table.specs[6].name, table.joint_screws("S1m").shape
    (22, 'S1m', (5, 3, 6))
    >>> G = table.graph(1)
    >>> G.number_of_nodes(), G.number_of_edges(), G.graph["dof"], sorted(G.successors("b_I"))
    (16, 22, 4, ['end_effector'])
    """
    _require(config, FourLimbConfiguration, "config")
    limb_platform = {}
    for (link, _), limbs in zip(SUBPLATFORMS, config.subplatform_limbs, strict=True):
        for limb in limbs:
            limb_platform[limb] = link
    # rows in the order of the joints' names (the analysis core's canonical order, so that it
    # need not permute them): A1..A4, R_I, R_II, then S<i>m, S<i>n, S<i>p, S<i>q per limb, written
    # into one array
    batch = config.batch_shape
    screws = np.empty((*batch, 4 + 2 + 4 * 4 * 3, 6))
    # the revolute twists (u; a × u) written in place: S.revolute_twist's operations without its
    # checks (the axes are the base frames' unit vectors and the platform's unit joint axis)
    screws[..., :4, :3] = config.u
    screws[..., :4, 3:] = cross(config.a, config.u)
    axis = config.platform_joint_axis
    specs = [JointSpec(f"A{i}", "R", "base", f"arm{i}", 1, True) for i in range(1, 5)]
    for k, (link, name) in enumerate(SUBPLATFORMS):
        point, pitch = config.platform_joint_points[..., k, :], config.platform_joint_pitches[k]
        if pitch:
            screws[..., 4 + k, :] = S.helical_twist(axis, point, pitch)
        else:
            screws[..., 4 + k, :3] = axis
            screws[..., 4 + k, 3:] = cross(point, axis)
        specs.append(JointSpec(name, "H" if pitch else "R", link, "end_effector", 1, False))
    spheres = screws[..., 6:, :].reshape(*batch, 4, 4, 3, 6)  # a view: limb, corner m n p q, axis
    _sphere_twists(config.elbow_corners, spheres[..., :2, :, :])
    _sphere_twists(config.platform_corners, spheres[..., 2:, :, :])
    for limb in range(4):
        i, platform = limb + 1, limb_platform[limb]
        specs += [
            JointSpec(f"S{i}m", "S", f"arm{i}", f"rod{i}a", 3, False),
            JointSpec(f"S{i}n", "S", f"arm{i}", f"rod{i}b", 3, False),
            JointSpec(f"S{i}p", "S", f"rod{i}a", platform, 3, False),
            JointSpec(f"S{i}q", "S", f"rod{i}b", platform, 3, False),
        ]
    screws.flags.writeable = False  # fresh: the table takes it without a copy
    return JointTable("base", "end_effector", tuple(specs), screws, dof=4, mobility=4)


def _sphere_twists(centres: np.ndarray, out: np.ndarray) -> None:
    """The unit rotations about ``x, y, z`` through each of ``centres (..., 3)``, written into
    ``out (..., 3, 6)``: the lines ``(e_k; c × e_k)`` of :func:`screwkit.algebra.screw.revolute_twist`
    written out (no validation needed: the directions are the unit axes)."""
    out[...] = 0.0
    x, y, z = centres[..., 0], centres[..., 1], centres[..., 2]
    for k in range(3):
        out[..., k, k] = 1.0
    out[..., 0, 4], out[..., 0, 5] = z, -y  # c × e_x = (0, z, −y)
    out[..., 1, 3], out[..., 1, 5] = -z, x  # c × e_y = (−z, 0, x)
    out[..., 2, 3], out[..., 2, 4] = y, -x  # c × e_z = (y, −x, 0)


def twist_basis(config: FourLimbConfiguration) -> np.ndarray:
    """The end effector's nominal twists over the batch: a Schoenflies basis (user frame).

    Rows, for ``ẋ = 1``, ``ẏ = 1``, ``ż = 1`` and ``φ̇ = 1`` with ``χ = (x, y, z, φ)``: the three
    translations and the rotation about the end effector's own axis of rotation,
    ``config.platform_joint_axis`` (``k`` for the Quattro, H4, Veloce and Ragnar, ``j`` for the
    V4) through the end-effector point ``p`` (:func:`screwkit.core.jacobians.schoenflies_basis`). They
    are the columns of ``A`` in :func:`screwkit.core.jacobians.jacobians_from_wrenches`, in paper 004's
    order (Eq. 7a).

    Parameters
    ----------
    config : FourLimbConfiguration
        From :func:`inverse_kinematics` (any batch shape ``...``).

    Returns
    -------
    numpy.ndarray, shape (..., 4, 6)

    Raises
    ------
    ScrewkitTypeError
        If ``config`` is not a :class:`FourLimbConfiguration`.

    Examples
    --------
    >>> v4 = FourLimbParameters(name="V4", platform_kind="articulated_y", arm_length=375,
    ...     rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80, platform_offset=70,
    ...     base_radius=275)
    >>> twist_basis(inverse_kinematics(v4, [[0, 0, -700, 0], [50, 0, -700, 0.2]]))[1, 3]  # about j
    array([  0.,   1.,   0., 700.,   0.,  50.])
    """
    _require(config, FourLimbConfiguration, "config")
    return schoenflies_basis(config.pose[..., :3], config.platform_joint_axis)


#: The family (:mod:`screwkit.robots.families`).
FAMILY: Family[FourLimbParameters, FourLimbConfiguration] = Family(
    name="four_limb",
    parameters=FourLimbParameters.from_mapping,
    inverse_kinematics=inverse_kinematics,
    joints=joints,
    twist_basis=twist_basis,
    pose_names=("x", "y", "z", "phi"),
    angle_names=("phi",),
    parameter_kinds=dict.fromkeys(
        ("base_radius", "base_points", "arm_length", "rod_length", "platform_radius", "platform_offset",
         "lead", "parallelogram_width"),
        "length",
    )
    | {"alpha": "angle", "beta": "angle", "platform_kind": "number"},
    reachable=reachable,
)
