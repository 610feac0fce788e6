"""The closed-form model of Clavel's Delta robot for certification (:class:`DeltaModel`).

Examples
--------
>>> sorted(DeltaModel.of(load_mechanism("delta")).functions())
['actuation', 'constraint', 'serial:1', 'serial:2', 'serial:3']
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .intervals import Enclosure
from .limb_enclosures import (
    Vector,
    _ClosedFormModel,
    _Constant,
    _constants,
    _cross,
    _cross_constant,
    _dot,
    _family_mode,
    _relative,
    _sum,
)

__all__ = ["DeltaModel"]

_DELTA_STATEMENTS = {
    "constraint": "(n_1 x n_2).n_3 = 0, n_i = w_i x u_i: the parallelograms' constraint couples are "
    "dependent, the platform may turn (Clavel 1990: each parallelogram keeps its orientation)",
    "actuation": "det[w_1; w_2; w_3] = 0 (Williams 2015, velocity kinematics): the rods' forces are "
    "dependent",
    "serial": "P_i^2 + Q_i^2 - K_i^2 = 0 (Williams 2015, inverse kinematics; h_i = sigma_i (b/l) sqrt "
    "of it): leg {i} at its reach, det B = 0",
}


@dataclass(frozen=True)
class DeltaModel(_ClosedFormModel):
    """The closed-form model of Clavel's Delta robot (:mod:`screwkit.robots.families.delta`), for
    enclosures: three arm-and-parallelogram legs to a translating platform.

    Leg ``i`` is the four-limb family's limb with ``F j = r_i`` (the leg's radial direction),
    ``F k = -k``, the actuated point ``a_i = R r_i`` and the platform point ``c_i = p + r r_i``, so
    ``d_i = p + (r - R) r_i`` (Williams 2015, inverse kinematics). The certified functions:
    ``serial:i`` (``h_i = σ_i (b/l) √g_i``: reach and det B, as for the four-limb family),
    ``actuation`` ``det[w_1; w_2; w_3]`` (Williams 2015, velocity kinematics ``A ṗ = B θ̇``, the
    rows of ``A`` the unit rods) and ``constraint`` ``(n_1 × n_2)·n_3`` with ``n_i = w_i × u_i``,
    the couple a parallelogram exerts (it keeps the platform's orientation, Clavel 1990): the
    three couples dependent leave the platform a rotation.

    Attributes
    ----------
    name : str
    pose_names : tuple of str
        ``("x", "y", "z")``.
    arm, rod : float
        ``b`` and ``l``.
    working_mode : tuple of int
        ``σ_i`` (+1 elbows out).
    base : tuple
        Constants ``d_i - p``, ``u_i``, ``F j``, ``F k`` (3 rows of 3 each).
    limbs : int
        3.

    Examples
    --------
    >>> model = DeltaModel.of(load_mechanism("delta"))
    >>> values = model.values([[0.0, 0.0, -1000.0], [1143.5, 0.0, -1000.0]])
    >>> bool(abs(values["actuation"][0]) > 0.1 and abs(values["actuation"][1]) < 1e-3)
    True
    """

    name: str
    pose_names: tuple[str, ...]
    arm: float
    rod: float
    working_mode: tuple[int, int, int]
    base: tuple[list[list[_Constant]], ...]
    limbs: int = 3
    statements: ClassVar[dict[str, str]] = _DELTA_STATEMENTS

    @classmethod
    def of(cls, mechanism: Any, options: Mapping[str, Any] | None = None) -> DeltaModel:
        """The model of a Delta catalog mechanism.

        Parameters
        ----------
        mechanism : Mechanism
            Of the ``delta`` family.
        options : mapping, optional
            Inverse-kinematics options (``mode``: three signs ``σ_i``).

        Returns
        -------
        DeltaModel

        Raises
        ------
        ScrewkitValueError
            For another family, or options other than a mode of three signs.

        Examples
        --------
        >>> DeltaModel.of(load_mechanism("delta")).working_mode
        (1, 1, 1)
        """
        from ..robots.families.delta import ACTUATED_AXES, DEFAULT_MODE, RADIAL_DIRECTIONS

        mode = _family_mode(mechanism, options, "delta", DEFAULT_MODE)
        params = mechanism.parameters
        radial, axes = RADIAL_DIRECTIONS, ACTUATED_AXES  # the catalog's leg layout, u_i = k × r_i
        base = (
            _constants((params.platform_radius - params.base_radius) * radial, exact=False),
            _constants(axes, exact=False),
            _constants(radial, exact=False),
            _constants(np.tile([0.0, 0.0, -1.0], (3, 1)), exact=True),
        )
        return cls(
            mechanism.name,
            tuple(mechanism.pose_names),
            float(params.arm_length),
            float(params.rod_length),
            (mode[0], mode[1], mode[2]),
            base,
        )

    def evaluate(self, pose: list[Enclosure], *, singular: bool = True) -> dict[str, Enclosure]:
        """Enclose every function of ``functions()`` over a batch of boxes of pose space.

        Parameters
        ----------
        pose : list of 3 Enclosure
            ``x, y, z`` over the boxes.
        singular : bool, default True
            Also the constraint and actuation functions (else the reach functions only).

        Returns
        -------
        dict of str to Enclosure

        Examples
        --------
        >>> model = DeltaModel.of(load_mechanism("delta"))
        >>> at = Enclosure.variables(np.array([[0.0, 0.0, -1000.0]]), np.array([[10.0, 10.0, -990.0]]))
        >>> bool(model.evaluate(at)["actuation"].excludes_zero()[0])
        True
        """
        offsets, u_rows, _, _ = self.base
        ds: list[Vector] = [
            [
                _sum(pose[k], None if offsets[i][k].value == 0 else type(pose[k]).constant(
                    offsets[i][k].value, pose[k], relative=_relative(offsets[i][k])))
                for k in range(3)
            ]
            for i in range(3)
        ]
        out, w = self._limb_functions(ds, singular)
        if singular:
            actuation = _dot(_cross(w[0], w[1]), w[2])
            normals = [_cross_constant(rod_i, u_rows[i]) for i, rod_i in enumerate(w)]
            constraint = _dot(_cross(normals[0], normals[1]), normals[2])
            assert actuation is not None and constraint is not None
            out["actuation"], out["constraint"] = actuation, constraint
        return out



