"""Straight paths in pose space checked for singularities: the first crossing, refined.

``samples`` poses along the path go through the posed mechanism as one batch; ``det A`` sign
changes, closeness minima, the reach edge and singular samples are refined
(:mod:`screwkit.analysis.roots`) and the first root is the crossing.

Examples
--------
>>> check_path(load_mechanism("h4"), {"z": -800, "phi": 0}, {"z": -700, "phi": 30}, samples=20,
...            angles="deg").singularity_free
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .poses import _as_dict, _check_mechanism, _options, _pose, _scale
from .roots import _brackets, _factor, _measure, _refine, _Root
from .workspace import _plain

__all__ = ["MAX_PATH_SAMPLES", "Crossing", "PathCheck", "check_path"]

Array = np.ndarray

#: The most samples a path check takes: they go through the core as one batch (≈ 1 GB at 10⁶).
MAX_PATH_SAMPLES = 10**6


@dataclass(frozen=True)
class Crossing:
    """The first singularity met along a path.

    Attributes
    ----------
    parameter : float
        In [0, 1] along the straight segment from start to end (pose coordinates).
    pose : dict
        User units.
    kind : str
        ``"constraint"``, ``"actuation"``, ``"serial"``, or ``"unreachable"`` (the path leaves
        the workspace where no singularity is labelled).
    factor : str or None
    closeness : float
        The kind's closeness there (~0).
    """

    parameter: float
    pose: dict[str, float]
    kind: str
    factor: str | None
    closeness: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "parameter": self.parameter,
            "pose": self.pose,
            "kind": self.kind,
            "factor": self.factor,
            "closeness": _plain(self.closeness),
        }


@dataclass(frozen=True)
class PathCheck:
    """The verdict on a straight path in pose space.

    Attributes
    ----------
    singularity_free : bool
    crossing : Crossing or None
        The first crossing (None when singularity-free).
    start, end : dict
        User units.
    samples : int
    """

    singularity_free: bool
    crossing: Crossing | None
    start: dict[str, float]
    end: dict[str, float]
    samples: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "singularity_free": self.singularity_free,
            "crossing": None if self.crossing is None else self.crossing.to_dict(),
            "start": self.start,
            "end": self.end,
            "samples": self.samples,
        }

    def __str__(self) -> str:
        if self.crossing is None:
            return f"singularity-free ({self.samples} samples, refined)"
        c = self.crossing
        pose = ", ".join(f"{k} = {v:.6g}" for k, v in c.pose.items())
        factor = f", factor {c.factor}" if c.factor else ""
        # an unreachable pose has no closeness (NaN): say so rather than print "nan"
        closeness = f", closeness {c.closeness:.3g}" if math.isfinite(c.closeness) else ""
        where = "the path starts out of reach" if c.kind == "unreachable" and c.parameter == 0 else ""
        text = f"{c.kind} crossing at t = {c.parameter:.9g} ({pose}){factor}{closeness}"
        return f"{text}: {where}" if where else text


def check_path(
    mechanism: Any,
    start: Any,
    end: Any,
    *,
    samples: int = 200,
    mode: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
) -> PathCheck:
    """Check the straight path ``start → end`` (pose coordinates) for singularities.

    ``samples`` poses along it go through the core as one batch; det A sign changes, closeness
    minima, the reach edge and singular samples are refined (module docstring) and the first
    root is the crossing.

    Parameters
    ----------
    mechanism : Mechanism
    start, end : dict or array_like
        User units (angles in radians unless ``angles="deg"``); a dict's missing coordinates take
        the default pose.
    samples : int, default 200
    mode, angles, rtol
        As in :func:`~screwkit.analysis.workspace.grid_map`.

    Returns
    -------
    PathCheck

    Examples
    --------
    >>> check = check_path(load_mechanism("h4"), {"z": -750}, {"z": -5000}, samples=20)
    >>> check.crossing.kind, round(check.crossing.parameter, 4)  # the arms and rods line up
    ('serial', 0.0964)
    """
    _check_mechanism(mechanism)
    if (
        isinstance(samples, bool)
        or not isinstance(samples, int | np.integer)
        or not 2 <= samples <= MAX_PATH_SAMPLES
    ):
        raise ScrewkitValueError(
            f"Expected `samples` to be an integer in 2..{MAX_PATH_SAMPLES:g}, got {samples!r}."
        )
    scale = _scale(mechanism, angles)
    first, last = _pose(mechanism, start, "start", angles), _pose(mechanism, end, "end", angles)
    options = _options(mechanism, mode)
    t = np.linspace(0.0, 1.0, int(samples))
    a, b = first * scale, last * scale

    def along(lines: Array, s: Array) -> Array:
        return a + s[:, None] * (b - a)

    measured = _measure(mechanism, (a + t[:, None] * (b - a))[None], options, rtol)
    roots = _refine(mechanism, along, _brackets(t, measured), options, rtol, keep_edges=True)
    if not measured.ok[0, 0]:
        roots.append(_Root(0, 0.0, a, "unreachable", math.nan))
    crossing = None
    if roots:
        root = min(roots, key=lambda r: r.t)
        factor = _factor(mechanism, root.pose[None], root.kind, options, rtol)
        crossing = Crossing(root.t, _as_dict(mechanism, root.pose / scale), root.kind, factor, root.closeness)
    return PathCheck(
        crossing is None, crossing, _as_dict(mechanism, first), _as_dict(mechanism, last), int(samples)
    )
