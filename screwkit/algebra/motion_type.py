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
from .ranks import characteristic_length, screw_rank
from .readable import _COUPLES
from .screwsystem import ScrewSystem, _rows
from .screwvalue import Screw

__all__ = ["motion_type"]

Array = np.ndarray


def _motion_label(translations: int, rotations: int) -> str:
    """``"3T1R"``, ``"1T2R"``, ``"3T"``, ``"2R"``: translations first, a zero count left out."""
    parts = [(translations, "T"), (rotations, "R")]
    return "".join(f"{n}{kind}" for n, kind in parts if n) or "0"


def motion_type(twists: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float | None = None) -> Any:
    """The motion type of a twist system: its numbers of translations and other freedoms.

    ``t = dim(T ∩ translations) = order(T) + 3 − order(T + translations)`` and ``r = order(T) − t``
    (the freedoms that are not translations: rotations or screws). Labelled ``"3T1R"`` (a
    Schoenflies motion), ``"3T"``, ``"1T2R"``, ``"3T3R"``: always translations first (the one
    spelling used across screwkit); ``"0"`` for the 0-system.

    Parameters
    ----------
    twists : ScrewSystem or array_like, shape (..., k, 6)
        A system, or generators (numeric, batched over leading axes; or one symbolic ``(k, 6)``
        array, decided generically).
    rtol, length_scale
        As in :func:`screwkit.algebra.ranks.screw_rank` (a ScrewSystem uses its own).

    Returns
    -------
    str, or numpy.ndarray of str over the batch

    Examples
    --------
    >>> from screwkit.algebra.screw import prismatic_twist, revolute_twist
    >>> schoenflies = [*(prismatic_twist(e) for e in np.eye(3)), revolute_twist([0, 0, 1], [1, 2, 0])]
    >>> motion_type(schoenflies), motion_type(ScrewSystem.span(schoenflies[2:]))
    ('3T1R', '1T1R')
    >>> motion_type(np.stack([np.array(schoenflies[:3]), np.array(schoenflies[1:])]))
    array(['3T', '2T1R'], dtype='<U4')
    """
    if isinstance(twists, ScrewSystem):
        rows, rtol, length_scale = twists.basis, twists.rtol, twists.length_scale
    elif isinstance(twists, Screw):
        rows = twists.coords.reshape(1, 6)
    else:
        rows = _rows_batched(twists)
    length_scale = characteristic_length(rows, length_scale) if rows.size else 1.0
    couples = np.broadcast_to(_COUPLES, (*rows.shape[:-2], 3, 6))
    stacked = np.concatenate(B.promote(rows, np.asarray(couples, dtype=float)), axis=-2)
    order = np.asarray(screw_rank(rows, rtol=rtol, length_scale=length_scale))
    translations = order + 3 - np.asarray(screw_rank(stacked, rtol=rtol, length_scale=length_scale))
    labels = np.vectorize(_motion_label, otypes=[str])(translations, order - translations)
    return str(labels) if labels.ndim == 0 else labels


def _rows_batched(twists: Any) -> Array:
    if isinstance(twists, list | tuple) and twists and all(isinstance(s, Screw) for s in twists):
        return _rows(twists, "twists")
    array = B.as_array(twists, "twists", (6,))
    return array.reshape(1, 6) if array.ndim == 1 else array
