"""Paper 004's indices handed on: to the maps (the quantities ``"lti"``, ``"kappa"``, ``"zeta"``) and to
the report (both transmission indices at one pose).

The maps (:mod:`screwkit.analysis`) stand below the papers: ``import screwkit`` registers
:func:`map_values` with :func:`screwkit.analysis.quantities.register_quantity`.
:func:`transmission_summary` is what :func:`screwkit.interface.report.analyze` shows.

Examples
--------
>>> h4 = load_mechanism("h4")
>>> sorted(transmission_summary(h4, h4.default_pose, h4.at()[0].jacobians))
['note', 'paper_004', 'wrench']
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from ..robots.posed import PosedMechanism
from ..robots.transmission import wrench_transmission
from .paper_004 import _is_four_limb, transmission

__all__ = ["MAP_QUANTITIES", "map_values", "transmission_summary"]


#: The map quantities of :mod:`screwkit.analysis.quantities` paper 004 contributes, by the result's field.
MAP_QUANTITIES = {"lti": "lti", "kappa": "input", "zeta": "output"}


def map_values(posed: PosedMechanism, quantity: str) -> np.ndarray:
    """Paper 004's ``η`` (Eq. 16), ``κ`` or ``ζ`` (Eq. 15) over a posed batch, for the maps (the
    quantities ``"lti"``, ``"kappa"``, ``"zeta"`` that ``import screwkit`` registers with
    :func:`screwkit.analysis.quantities.register_quantity`; :func:`transmission`, fused and compiled
    with the ``fast`` extra).

    Parameters
    ----------
    posed : PosedMechanism
        A four-limb mechanism at reachable poses.
    quantity : {"lti", "kappa", "zeta"}

    Returns
    -------
    numpy.ndarray
        Of the batch's shape.

    Raises
    ------
    ScrewkitValueError
        Not a four-limb mechanism.

    Examples
    --------
    >>> h4 = load_mechanism("h4")
    >>> bool(map_values(h4.at([0, 0, -750, 0]), "kappa") == transmission(h4, [0, 0, -750, 0]).input)
    True
    """
    if not _is_four_limb(getattr(posed.mechanism, "parameters", None)):
        raise ScrewkitValueError(
            f"Expected a four-limb mechanism for quantity {quantity!r} (paper 004's index, defined on the "
            f"four-limb geometry: Eqs. 15-16), got family {posed.mechanism.family!r}; the wrench-based "
            "index of any mechanism is quantity 'wrench_lti'."
        )
    return np.asarray(getattr(transmission(posed), MAP_QUANTITIES[quantity]), dtype=float)


def transmission_summary(mechanism: Any, pose: Any, jacobians: Any) -> dict[str, Any]:
    """The transmission indices at one pose, for :func:`screwkit.interface.report.pose_report`.

    ``"wrench"``: :func:`wrench_transmission` (any mechanism with Jacobians; at the elbows for the
    four-limb family), ``"paper_004"``: :func:`transmission` (four-limb family only, else None),
    ``"note"``: what they are or why one is missing.

    Parameters
    ----------
    mechanism : Mechanism
    pose : array_like, shape (n,)
    jacobians : Jacobians or None
        At the pose (None: not computed).

    Returns
    -------
    dict
        ``"wrench"``, ``"paper_004"`` (JSON-ready dicts or None) and ``"note"``.

    Examples
    --------
    >>> h4 = load_mechanism("h4")
    >>> summary = transmission_summary(h4, h4.default_pose, h4.at()[0].jacobians)
    >>> round(min(summary["wrench"]["input"]), 9) == round(summary["paper_004"]["input"], 9)  # κ, derived
    True
    """
    summary: dict[str, Any] = {"wrench": None, "paper_004": None, "note": ""}
    notes = []
    if jacobians is None or jacobians.A.shape[-1] != jacobians.A.shape[-2]:
        notes.append("wrench-based index: needs square Jacobians at the pose")
    else:
        hook = mechanism.family_protocol.application_points
        points = None if hook is None else hook(mechanism.configuration(pose))
        summary["wrench"] = wrench_transmission(jacobians, input_points=points).to_dict()
        notes.append(
            "wrench-based: input ITI_j = |w_j o $_j| / max (at the elbow for the four-limb family), "
            "output OTI_j against the platform twist of actuator j alone, LTI = min "
            "(screwkit.robots.transmission.wrench_transmission)"
        )
    if _is_four_limb(getattr(mechanism, "parameters", None)):
        summary["paper_004"] = transmission(mechanism, pose).to_dict()
        notes.append("paper 004: kappa, zeta (Eq. 15), LTI eta (Eq. 16)")
    summary["note"] = "; ".join(notes)
    return summary
