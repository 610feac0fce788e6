"""The motion type of a twist system: how many translations, how many other freedoms.

``t = dim(T ∩ translations) = order(T) + 3 − order(T + translations)`` and ``r = order(T) − t``,
labelled translations first, ``"3T1R"`` (a Schoenflies motion), ``"3T"``, ``"1T2R"``: the one-word
summary of a platform's twist system (:mod:`screwkit.algebra.screwsystem`), batched over poses.

Examples
--------
>>> from screwkit.algebra.screw import prismatic_twist
>>> motion_type([prismatic_twist([1, 0, 0]), prismatic_twist([0, 1, 0])])
'2T'
"""

from __future__ import annotations

from typing import Any

import numpy as np

from . import backend as B
from .ranks import characteristic_length, screw_rank, unit_rows
from .readable import _COUPLES
from .screwsystem import ScrewSystem, _rows
from .screwvalue import Screw

__all__ = ["motion_type"]

Array = np.ndarray


def _motion_label(translations: int, rotations: int, pitch: float, length_unit: str) -> str:
    """``"3T1R"``, ``"1T2R"``, ``"3T"``, ``"2R"``, ``"1H (pitch 5 mm/rad)"``: translations first, a
    zero count left out, a helical freedom (a finite ``pitch``) with its pitch."""
    if np.isfinite(pitch):
        unit = f" {length_unit or 'length units'}/rad"  # no unit given: said, not left blank
        kind = f"{translations}T1H" if translations else "1H"
        return f"{kind} (pitch {pitch:.4g}{unit})"
    parts = [(translations, "T"), (rotations, "R")]
    return "".join(f"{n}{kind}" for n, kind in parts if n) or "0"


def motion_type(
    twists: Any,
    *,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
    length_unit: str = "",
) -> Any:
    """The motion type of a twist system: its numbers of translations, rotations and screw motions.

    ``t = dim(T ∩ translations) = order(T) + 3 − order(T + translations)`` and ``r = order(T) − t``
    (the freedoms that are not translations). Labelled ``"3T1R"`` (a Schoenflies motion), ``"3T"``,
    ``"1T2R"``, ``"3T3R"``: always translations first (the one spelling used across screwkit); ``"0"``
    for the 0-system. When ``r = 1`` the one other freedom is a screw motion ``(u; m)`` of unit
    direction ``u`` and pitch ``h = u · m`` (``h = s·s0 / s·s``: Hunt 1978, *Kinematic Geometry of
    Mechanisms*, §5), defined modulo the system's translations: adding a translation ``v`` changes
    it by ``u · v``, so a translation with a component along ``u`` makes it a rotation. A pitch above
    ``rtol`` times the length scale is a helical freedom, labelled ``"1H (pitch 5 mm/rad)"`` or
    ``"2T1H (pitch 5 mm/rad)"`` (the pitch in the coordinates' length unit per radian); with ``r ≥ 2``
    the system holds screws of many pitches and its freedoms are counted as ``R``.

    Parameters
    ----------
    twists : ScrewSystem or array_like, shape (..., k, 6)
        A system, or generators (numeric, batched over leading axes; or one symbolic ``(k, 6)``
        array, decided generically; a symbolic helical freedom is counted as ``R``).
    rtol, length_scale
        As in :func:`screwkit.algebra.ranks.screw_rank` (a ScrewSystem uses its own).
    length_unit : str, optional
        The coordinates' length unit, written in a pitch (``"mm"``: ``"pitch 5 mm/rad"``; none given:
        ``"pitch 5 length units/rad"``).

    Returns
    -------
    str, or numpy.ndarray of str over the batch

    Examples
    --------
    >>> from screwkit.algebra.screw import helical_twist, prismatic_twist, revolute_twist
    >>> schoenflies = [*(prismatic_twist(e) for e in np.eye(3)), revolute_twist([0, 0, 1], [1, 2, 0])]
    >>> motion_type(schoenflies), motion_type(ScrewSystem.span(schoenflies[2:]))
    ('3T1R', '1T1R')
    >>> motion_type(np.stack([np.array(schoenflies[:3]), np.array(schoenflies[1:])]))
    array(['3T', '2T1R'], dtype='<U4')
    >>> motion_type([helical_twist([0, 0, 1], [1, 0, 0], 5.0)], length_unit="mm")
    '1H (pitch 5 mm/rad)'
    """
    if isinstance(twists, ScrewSystem):
        rows, rtol, length_scale = twists.basis, twists.rtol, twists.length_scale
    elif isinstance(twists, Screw):
        rows = twists.coords.reshape(1, 6)
    else:
        rows = _rows_batched(twists)
    length_scale = characteristic_length(rows, length_scale, rtol) if rows.size else 1.0
    couples = np.broadcast_to(_COUPLES, (*rows.shape[:-2], 3, 6))
    stacked = np.concatenate(B.promote(rows, np.asarray(couples, dtype=float)), axis=-2)
    order = np.asarray(screw_rank(rows, rtol=rtol, length_scale=length_scale))
    translations = order + 3 - np.asarray(screw_rank(stacked, rtol=rtol, length_scale=length_scale))
    pitches = np.full(order.shape, np.inf)
    if rows.dtype != object and rows.size:
        assert length_scale is not None  # numeric rows have a length (characteristic_length)
        for index in np.ndindex(order.shape):
            if order[index] - translations[index] != 1:
                continue
            pitches[index] = _helical_pitch(
                rows[index], int(translations[index]), rtol=rtol, length_scale=length_scale
            )
    label = np.vectorize(_motion_label, otypes=[str])
    labels = label(translations, order - translations, pitches, length_unit)
    return str(labels) if labels.ndim == 0 else labels


def _helical_pitch(rows: Array, translations: int, *, rtol: float, length_scale: float) -> float:
    """The pitch of the one non-translational freedom of ``rows`` ``(k, 6)`` modulo the system's
    ``translations`` (:func:`motion_type`), or inf when it is zero at ``rtol`` (a rotation).

    In scaled coordinates (moments over ``length_scale``, rows of unit size): the directions
    ``D = U Σ Vᵀ`` have rank 1; ``c = U₀ / σ₀`` gives the system's screw ``(v₀; m)`` of unit
    direction ``v₀``; the combinations in the left null space of ``D`` are the translations, whose
    first ``translations`` principal directions are ``Q``. Adding a translation ``q`` changes the
    pitch by ``v₀ · q``: a translation with a component along ``v₀`` makes a pure rotation of the
    system (pitch 0), else the pitch is ``h = v₀ · m``."""
    scaled = unit_rows(rows, length_scale)
    u, values, vt = np.linalg.svd(scaled[:, :3], full_matrices=True)
    axis = vt[0]
    if translations:
        cancelling = u[:, 1:]  # the combinations whose directions cancel (rank 1: all but the first)
        _, _, shifts = np.linalg.svd(cancelling.T @ scaled[:, 3:])
        if np.linalg.norm(shifts[:translations] @ axis) > rtol:
            return np.inf
    pitch = float(axis @ ((u[:, 0] / values[0]) @ scaled[:, 3:]))
    return pitch * length_scale if abs(pitch) > rtol else np.inf

def _rows_batched(twists: Any) -> Array:
    if isinstance(twists, list | tuple) and twists and all(isinstance(s, Screw) for s in twists):
        return _rows(twists, "twists")
    array = B.as_array(twists, "twists", (6,))
    return array.reshape(1, 6) if array.ndim == 1 else array
