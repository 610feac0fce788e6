"""Screws described as lines for people: a wrench's kind, direction, point and pitch, and a twist's
motion (:func:`describe_wrench`, :func:`describe_twist`), JSON-ready; the report's wrench sections
read them.

Examples
--------
>>> describe_twist(S.revolute_twist([0, 0, 1], [1, 0, 0]), length_scale=1.0)["kind"]
'rotation'
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..algebra import screw as S

__all__ = ["describe_twist", "describe_wrench"]

Array = np.ndarray


def describe_wrench(wrench: Array, *, length_scale: float) -> dict[str, Any]:
    """A wrench as a line: kind, unit direction, a point (the one nearest the origin), pitch.

    Parameters
    ----------
    wrench : numpy.ndarray, shape (6,)
        Screw coordinates ``(f; m_O)``, numeric and nonzero.
    length_scale : float
        The characteristic length of the zero-pitch and infinite-pitch decisions.

    Returns
    -------
    dict
        ``kind`` (``"force (finite line)"``, ``"screw of finite pitch"`` or ``"couple (line at
        infinity)"``), ``direction`` (unit; the moment's for a couple), ``point`` (None for a couple)
        and ``pitch`` (``"inf"`` for a couple), JSON-ready.

    Examples
    --------
    >>> describe_wrench(S.line([0, 0, 2], [1, 0, 5]), length_scale=1.0)["point"]
    [1.0, 0.0, 0.0]
    """
    if S.is_infinite_pitch(wrench, rtol=1e-7, length_scale=length_scale):
        moment = wrench[3:] / np.linalg.norm(wrench[3:])
        return {
            "kind": "couple (line at infinity)",
            "direction": moment.round(12).tolist(),
            "point": None,
            "pitch": "inf",
        }
    point, direction = S.axis(wrench)
    pitch = float(S.pitch(wrench))
    kind = "force (finite line)" if abs(pitch) <= 1e-7 * length_scale else "screw of finite pitch"
    return {
        "kind": kind,
        "direction": direction.round(12).tolist(),
        "point": (point + 0.0).round(9).tolist(),
        "pitch": round(pitch, 12) + 0.0,
    }


def describe_twist(twist: Array, *, length_scale: float) -> dict[str, Any]:
    """A twist as :func:`describe_wrench` does a wrench, named as a motion: translation, rotation
    or screw motion.

    Parameters
    ----------
    twist : numpy.ndarray, shape (6,)
        Screw coordinates ``(ω; v_O)``, numeric and nonzero.
    length_scale : float
        As for :func:`describe_wrench`.

    Returns
    -------
    dict
        As :func:`describe_wrench`, with ``kind`` one of ``"rotation"``, ``"screw motion"`` and
        ``"translation"``.

    Examples
    --------
    >>> describe_twist(S.prismatic_twist([0, 0, 1]), length_scale=1.0)["kind"]
    'translation'
    """
    described = describe_wrench(twist, length_scale=length_scale)
    kinds = {
        "couple (line at infinity)": "translation",
        "force (finite line)": "rotation",
        "screw of finite pitch": "screw motion",
    }
    return {**described, "kind": kinds[described["kind"]]}
