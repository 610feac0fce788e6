"""Helpers shared by the checks of papers 001 and 000 (``tests/paper_001.py``, ``tests/paper_000.py``).

Not the robot model (that is :mod:`screwkit.robots.families.mcgill_smg` and
:mod:`screwkit.robots.families.peppermill`; a paper's own ``A`` and ``B`` are a
:class:`screwkit.core.jacobian_matrices.Jacobians`): the root search that locates singular poses along a path, and the SCARA test cycle both papers describe.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from screwkit.algebra.backend import as_array
from screwkit.exceptions import ScrewkitValueError
from screwkit.robots.two_limb import describe_indices

__all__ = ["bisect_segment", "pick_and_place_cycle"]


def bisect_segment(
    function: Callable[[np.ndarray], np.ndarray],
    start: Any,
    end: Any,
    *,
    iterations: int = 60,
) -> np.ndarray:
    """Locate a sign change of a scalar function on the straight segment from ``start`` to ``end``.

    Bisection on the segment parameter ``t ∈ [0, 1]``, vectorised over leading batch axes;
    60 halvings bring ``t`` to ``2**-60``, below the resolution of a float.

    Parameters
    ----------
    function : callable
        Maps points ``(..., n)`` to values ``(...)`` (e.g. a singularity factor of the pose).
    start, end : (..., n) array_like
        Segment ends; ``function`` must have opposite signs (or a zero) at them.
    iterations : int, default 60

    Returns
    -------
    (..., n) ndarray
        The point of the segment where ``function`` changes sign.

    Raises
    ------
    ScrewkitValueError
        ``function`` has the same strict sign at both ends of some segment.

    Examples
    --------
    >>> bisect_segment(lambda p: p[..., 0] ** 2 - 2.0, [0.0, 5.0], [2.0, 5.0])
    array([1.41421356, 5.        ])
    """
    a = as_array(start, "start", (None,))
    b = as_array(end, "end", (None,))
    a, b = np.broadcast_arrays(a, b)
    fa = np.asarray(function(a))
    fb = np.asarray(function(b))
    same = np.sign(fa) * np.sign(fb) > 0
    if np.any(same):
        raise ScrewkitValueError(
            "Expected `function` to change sign between `start` and `end`, got the same sign at "
            f"both ends at {describe_indices(same)} (values {fa[same][:3]} and {fb[same][:3]})."
        )
    lo = np.zeros(fa.shape)
    hi = np.ones(fa.shape)
    sign_lo = np.sign(fa)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        value = np.asarray(function(a + mid[..., None] * (b - a)))
        move_lo = np.sign(value) == sign_lo
        lo = np.where(move_lo, mid, lo)
        hi = np.where(move_lo, hi, mid)
    t = np.where(fa == 0, 0.0, np.where(fb == 0, 1.0, 0.5 * (lo + hi)))
    return np.asarray(a + t[..., None] * (b - a))


def pick_and_place_cycle(
    start: Any,
    heading: float = 0.0,
    *,
    rise: float = 25.0,
    span: float = 300.0,
    turn: float = -np.pi,
    samples_per_segment: int = 1,
) -> np.ndarray:
    """The SCARA pick-and-place test cycle as a polyline of poses ``(x, y, z, φ)``.

    Paper 001 (Angeles et al. 2006), Sec. 6: "25-mm vertical displacement up, 300-mm horizontal
    displacement with a concomitant 180° turn, 25-mm vertical displacement down", then back with
    the reversed turn; paper 000 (Harada & Angeles 2014), Sec. 1, describes the same cycle and says
    the turn is clockwise on the way out. Neither paper (Fig. 10 of paper 001 is lost in the OCR)
    gives the start pose, the direction of the horizontal segment or a motion law, so ``start`` and
    ``heading`` are the caller's, and the polyline carries no timing. Lengths are in millimetres
    by default; pass ``rise`` and ``span`` in your unit otherwise.

    Parameters
    ----------
    start : (4,) array_like
        The home pose ``(x, y, z, φ)``.
    heading : float, default 0
        Direction of the horizontal segment, angle from the x axis about z (radians).
    rise, span : float, default 25 and 300
        Vertical and horizontal displacements.
    turn : float, default -π
        Rotation during the outbound horizontal segment (negative: clockwise seen from +z).
    samples_per_segment : int, default 1
        Number of equal steps on each of the six segments.

    Returns
    -------
    (6 * samples_per_segment + 1, 4) ndarray
        Starts and ends at ``start``.

    Examples
    --------
    >>> pick_and_place_cycle([0.0, 0.0, -400.0, 0.0]).round(3)
    array([[   0.   ,    0.   , -400.   ,    0.   ],
           [   0.   ,    0.   , -375.   ,    0.   ],
           [ 300.   ,    0.   , -375.   ,   -3.142],
           [ 300.   ,    0.   , -400.   ,   -3.142],
           [ 300.   ,    0.   , -375.   ,   -3.142],
           [   0.   ,    0.   , -375.   ,    0.   ],
           [   0.   ,    0.   , -400.   ,    0.   ]])
    """
    home = as_array(start, "start", (4,))
    if home.shape != (4,):
        raise ScrewkitValueError(f"Expected `start` to have shape (4,), got {home.shape}.")
    if not (isinstance(samples_per_segment, int | np.integer) and samples_per_segment >= 1):
        raise ScrewkitValueError(
            f"Expected `samples_per_segment` to be an integer >= 1, got {samples_per_segment!r}."
        )
    heading, rise, span, turn = (
        float(as_array(v, n)) for v, n in ((heading, "heading"), (rise, "rise"),
                                          (span, "span"), (turn, "turn"))
    )
    up = np.array([0.0, 0.0, rise, 0.0])
    across = np.array([span * np.cos(heading), span * np.sin(heading), 0.0, turn])
    corners = np.cumsum([home, up, across, -up, up, -across, -up], axis=0)
    steps = np.linspace(0.0, 1.0, samples_per_segment + 1)[:-1]
    path = corners[:-1, None, :] + steps[None, :, None] * np.diff(corners, axis=0)[:, None, :]
    return np.concatenate([path.reshape(-1, 4), corners[-1:]], axis=0)
