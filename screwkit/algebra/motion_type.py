"""The motion type of a twist system: how many translations, how many other freedoms.

``t = dim(T ∩ translations) = order(T) + 3 − order(T + translations)`` and ``r = order(T) − t``,
labelled translations first, ``"3T1R"`` (a Schoenflies motion), ``"3T"``, ``"1T2R"``: the one-word
summary of a platform's twist system (:mod:`screwkit.algebra.screwsystem`), batched over poses.

A single freedom that is not a translation (``r = 1``) is a rotation only when some screw of the
system has pitch zero. Its direction ``s`` is fixed (the directions of ``T`` span one line) and its
moment is fixed up to the translations ``V`` of ``T``; the pitch ``h = s·s0 / s·s`` (Ball 1900, §13;
Hunt, *Kinematic Geometry of Mechanisms*, 1978, §5.3) changes by ``s·v / s·s`` with ``v ∈ V``. So the
freedom is a rotation when ``s`` is not perpendicular to ``V`` or ``h = 0``, else a helical motion
``"H"`` of pitch ``h``: ``"1H (pitch 5 mm/rad)"``, ``"2T1H (pitch …)"``. Two or more freedoms beyond
the translations are labelled ``"R"`` (the pitches within such a system form a range, not one value).

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


def _motion_label(translations: int, rotations: int, pitch: float, unit: str) -> str:
    """``"3T1R"``, ``"1T2R"``, ``"3T"``, ``"2R"``, ``"1H (pitch 5 mm/rad)"``: translations first, a zero
    count left out; ``pitch`` NaN for a rotation."""
    if not np.isnan(pitch):
        return f"{translations or ''}{'T' if translations else ''}1H (pitch {pitch:.6g} {unit}/rad)"
    parts = [(translations, "T"), (rotations, "R")]
    return "".join(f"{n}{kind}" for n, kind in parts if n) or "0"


def _helical_pitches(rows: Array, rtol: float, length: float) -> Array:
    """The pitch of each system's one freedom beyond its translations (module docstring), NaN where
    that freedom is a rotation; ``rows`` (N, k, 6) numeric, each with exactly one such freedom."""
    u, sigma, vt = np.linalg.svd(rows[..., :3])  # the directions span one line: s = vt[0]
    moments = rows[..., 3:] / length
    s = vt[:, 0]
    s0 = np.einsum("nk,nkj->nj", u[:, :, 0], moments) / sigma[:, :1]
    translations = np.einsum("nki,nkj->nij", u[:, :, 1:], moments)  # combinations with no direction
    along = np.abs(np.einsum("nij,nj->ni", translations, s)).max(axis=1, initial=0.0)
    size = np.linalg.norm(translations, axis=2).max(axis=1, initial=0.0)
    pitch = np.einsum("ni,ni->n", s, s0)
    rotation = (along > rtol * np.maximum(size, 1.0)) | (np.abs(pitch) <= rtol)
    return np.where(rotation, np.nan, pitch * length)


def motion_type(
    twists: Any,
    *,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
    length_unit: str = "length units",
) -> Any:
    """The motion type of a twist system: its numbers of translations and other freedoms.

    ``t = dim(T ∩ translations) = order(T) + 3 − order(T + translations)`` and ``r = order(T) − t``
    (the freedoms that are not translations: rotations or screws). Labelled ``"3T1R"`` (a
    Schoenflies motion), ``"3T"``, ``"1T2R"``, ``"3T3R"``: always translations first (the one
    spelling used across screwkit); ``"0"`` for the 0-system. One freedom beyond the translations
    whose screws all have the same nonzero pitch is helical: ``"1H (pitch 5 mm/rad)"``,
    ``"2T1H (pitch …)"`` (module docstring; numeric systems).

    Parameters
    ----------
    twists : ScrewSystem or array_like, shape (..., k, 6)
        A system, or generators (numeric, batched over leading axes; or one symbolic ``(k, 6)``
        array, decided generically).
    rtol, length_scale
        As in :func:`screwkit.algebra.ranks.screw_rank` (a ScrewSystem uses its own). A row whose
        direction is below ``rtol`` times its moment gives no length scale
        (:func:`~screwkit.algebra.ranks.characteristic_length`).
    length_unit : str, default "length units"
        The unit of the coordinates' lengths, named in a helical freedom's pitch.

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
    >>> motion_type([[0, 0, 1, 0, 0, 5]], length_unit="mm")  # a screw freedom of pitch 5 mm/rad
    '1H (pitch 5 mm/rad)'
    """
    if isinstance(twists, ScrewSystem):
        rows, rtol, length_scale = twists.basis, twists.rtol, twists.length_scale
    elif isinstance(twists, Screw):
        rows = twists.coords.reshape(1, 6)
    else:
        rows = _rows_batched(twists)
    length_scale = characteristic_length(rows, length_scale, rtol=rtol) if rows.size else 1.0
    couples = np.broadcast_to(_COUPLES, (*rows.shape[:-2], 3, 6))
    stacked = np.concatenate(B.promote(rows, np.asarray(couples, dtype=float)), axis=-2)
    order = np.asarray(screw_rank(rows, rtol=rtol, length_scale=length_scale))
    translations = order + 3 - np.asarray(screw_rank(stacked, rtol=rtol, length_scale=length_scale))
    pitch = np.full(order.shape, np.nan)
    one = (order - translations == 1) & (not B.is_symbolic(rows))
    if np.any(one):
        batch = np.broadcast_to(np.asarray(rows, dtype=float), (*order.shape, *rows.shape[-2:]))
        pitch[one] = _helical_pitches(batch[one], rtol, float(length_scale or 1.0))
    labels = np.vectorize(_motion_label, otypes=[str])(translations, order - translations, pitch, length_unit)
    return str(labels) if labels.ndim == 0 else labels


def _rows_batched(twists: Any) -> Array:
    if isinstance(twists, list | tuple) and twists and all(isinstance(s, Screw) for s in twists):
        return _rows(twists, "twists")
    array = B.as_array(twists, "twists", (6,))
    return array.reshape(1, 6) if array.ndim == 1 else array
