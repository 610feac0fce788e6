"""Straight paths in pose space checked for singularities: every crossing, refined.

``samples`` poses along the path go through the posed mechanism as one batch; ``det A`` and
``det B`` sign changes, closeness minima, the reach edge and singular samples are refined
(:mod:`screwkit.analysis.roots`): each refined root is a crossing, and a run of consecutive samples
labelled with one kind is one crossing that runs inside that singular set (``until`` its end).

Examples
--------
>>> check_path(load_mechanism("h4"), {"z": -800, "phi": 0}, {"z": -700, "phi": 30}, samples=20,
...            angles="deg").singularity_free
True
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .poses import _as_dict, _check_mechanism, _options, _pose, _scale
from .quantities import KINDS
from .roots import _brackets, _factor, _measure, _refine, _Root
from .workspace import _plain

__all__ = ["MAX_PATH_SAMPLES", "Crossing", "PathCheck", "check_path"]

Array = np.ndarray

#: The most samples a path check takes: they go through the core as one batch (≈ 1 GB at 10⁶).
MAX_PATH_SAMPLES = 10**6


@dataclass(frozen=True)
class Crossing:
    """A singularity met along a path.

    Attributes
    ----------
    parameter : float
        In [0, 1] along the straight segment from start to end (pose coordinates); where a run
        inside a singular set begins.
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
    until: float | None = None
    enclosure: tuple[float, float] | None = None

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
            "until": self.until,
            "enclosure": None if self.enclosure is None else list(self.enclosure),
        }

    def __str__(self) -> str:
        pose = ", ".join(f"{k} = {v:.6g}" for k, v in self.pose.items())
        factor = f", factor {self.factor}" if self.factor else ""
        # an unreachable pose has no closeness (NaN): say so rather than print "nan"
        closeness = f", closeness {self.closeness:.3g}" if math.isfinite(self.closeness) else ""
        if self.until is not None:
            where = f"inside the {self.kind} singular set for t in [{self.parameter:.9g}, {self.until:.9g}]"
            return f"{where} (from {pose}){factor}"
        enclosure = (
            f", t certified in [{self.enclosure[0]:.9g}, {self.enclosure[1]:.9g}]" if self.enclosure else ""
        )
        text = f"{self.kind} crossing at t = {self.parameter:.9g} ({pose}){factor}{closeness}{enclosure}"
        if self.kind == "unreachable" and self.parameter == 0:
            text += ": the path starts out of reach"
        return text


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
    crossings : tuple of Crossing
        Every crossing, in order along the path.
    certified_free : bool or None
        With ``certify=True``: True when proved free of the singularities of the kinds checked
        (:func:`screwkit.analysis.certify.certify_path`), False when not; None without.
    """

    singularity_free: bool
    crossing: Crossing | None
    start: dict[str, float]
    end: dict[str, float]
    samples: int
    crossings: tuple[Crossing, ...] = ()
    certified_free: bool | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "singularity_free": self.singularity_free,
            "crossing": None if self.crossing is None else self.crossing.to_dict(),
            "crossings": [c.to_dict() for c in self.crossings],
            "start": self.start,
            "end": self.end,
            "samples": self.samples,
            "certified_free": self.certified_free,
        }

    def __str__(self) -> str:
        proof = {None: "", True: ", certified", False: ", not certified"}[self.certified_free]
        if not self.crossings:
            return f"singularity-free ({self.samples} samples, refined{proof})"
        return "\n".join(str(c) for c in self.crossings)


def check_path(
    mechanism: Any,
    start: Any,
    end: Any,
    *,
    samples: int = 200,
    mode: Any = None,
    angles: str = "rad",
    rtol: float | None = None,
    certify: bool = False,
) -> PathCheck:
    """Check the straight path ``start → end`` (pose coordinates) for singularities.

    ``samples`` poses along it go through the core as one batch; det A and det B sign changes,
    closeness minima, the reach edge and singular samples are refined (module docstring): every
    root is a crossing, and a run of samples inside a singular set is one crossing with ``until``.

    Parameters
    ----------
    mechanism : Mechanism
    start, end : dict or array_like
        User units (angles in radians unless ``angles="deg"``). An array gives every coordinate of
        ``mechanism.coordinates`` (fewer or more are refused). A dict gives some: by design, the
        coordinates it leaves out keep their value at the reference pose (``mechanism.reference_pose``:
        a catalog robot's default pose, a graph mechanism's reference configuration), at both ends,
        so a path moves only what is given; :attr:`PathCheck.start` and ``end`` hold the whole poses
        used.
    samples : int, default 200
    mode, angles, rtol
        As in :func:`~screwkit.analysis.workspace.grid_map`.
    certify : bool, default False
        Also pave the path with interval arithmetic (:func:`screwkit.analysis.certify.certify_path`,
        the Quattro and the H4): ``certified_free`` says whether it is proved free, and every
        crossing gets the ``enclosure`` of its parameter outside which the path is proved free
        (a certified crossing no sample saw is added).

    Returns
    -------
    PathCheck

    Raises
    ------
    ScrewkitValueError
        For a bad ``samples``, a malformed pose, or ``certify=True`` on a mechanism it does not cover.

    Examples
    --------
    >>> check = check_path(load_mechanism("h4"), {"z": -750}, {"z": -5000}, samples=20)
    >>> check.crossing.kind, round(check.crossing.parameter, 4)  # the arms and rods line up
    ('serial', 0.0964)
    >>> proved = check_path(load_mechanism("quattro"), {"x": -300, "y": -1}, {"x": 300, "y": 1}, certify=True)
    >>> c = proved.crossing
    >>> c.kind, bool(c.enclosure[0] <= c.parameter <= c.enclosure[1]), proved.certified_free
    ('constraint', True, False)
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
    runs = _runs(t, measured.codes[0], measured.ok[0])
    roots = _refine(mechanism, along, _brackets(t, measured), t, measured, options, rtol, keep_edges=True)
    if not measured.ok[0, 0]:
        roots.append(_Root(0, 0.0, a, "unreachable", math.nan))
    step = 1.0 / (len(t) - 1)
    crossings: list[Crossing] = []
    for kind, low, high in runs:
        pose = a + low * (b - a)
        factor = _factor(mechanism, pose[None], kind, options, rtol)
        closeness = float(measured.closeness[kind][0, round(low / step)])
        crossings.append(Crossing(low, _as_dict(mechanism, pose / scale), kind, factor, closeness, high))
    kept: list[_Root] = []
    for root in sorted(roots, key=lambda r: r.t):
        inside_run = any(k == root.kind and lo - step <= root.t <= hi + step for k, lo, hi in runs)
        repeated = any(r.kind == root.kind and abs(r.t - root.t) < 0.5 * step for r in kept)
        if not inside_run and not repeated:
            kept.append(root)
    for root in kept:
        factor = _factor(mechanism, root.pose[None], root.kind, options, rtol)
        crossings.append(
            Crossing(root.t, _as_dict(mechanism, root.pose / scale), root.kind, factor, root.closeness)
        )
    certified_free = None
    if not isinstance(certify, bool):
        raise ScrewkitValueError(f"Expected `certify` to be True or False, got {certify!r}.")
    if certify:
        crossings, certified_free = _certified(mechanism, a, b, scale, crossings, options, rtol)
    crossings.sort(key=lambda c: c.parameter)
    crossing = crossings[0] if crossings else None
    return PathCheck(
        crossing is None,
        crossing,
        _as_dict(mechanism, first),
        _as_dict(mechanism, last),
        int(samples),
        tuple(crossings),
        certified_free,
    )


def _certified(
    mechanism: Any,
    a: Array,
    b: Array,
    scale: Array,
    crossings: list[Crossing],
    options: dict[str, Any],
    rtol: Any,
) -> tuple[list[Crossing], bool]:
    """The sampled crossings with the enclosures of the certified paving, and the certified
    crossings no sample saw."""
    from .certify import certify_path

    runs, capped = certify_path(mechanism, a, b, mode=options or None)
    out = []
    for c in crossings:
        holding = [r for r in runs if r.enclosure[0] <= c.parameter <= r.enclosure[1]]
        until = c.until if c.until is not None else c.parameter
        spans = [r for r in runs if r.enclosure[0] <= until and c.parameter <= r.enclosure[1]]
        enclosure = None
        if holding or spans:
            chosen = holding or spans
            enclosure = (min(r.enclosure[0] for r in chosen), max(r.enclosure[1] for r in chosen))
        out.append(dataclasses.replace(c, enclosure=enclosure))
    for run in runs:
        seen = any(
            c.enclosure is not None
            and c.enclosure[0] <= run.enclosure[0] <= run.enclosure[1] <= c.enclosure[1]
            for c in out
        )
        if run.status == "singular" and not seen and run.t is not None and run.label is not None:
            pose = a + run.t * (b - a)
            measured = _measure(mechanism, pose[None, None], options, rtol)
            factor = _factor(mechanism, pose[None], run.label, options, rtol)
            out.append(Crossing(run.t, _as_dict(mechanism, pose / scale), run.label, factor,
                                float(measured.closeness[run.label][0, 0]), None, run.enclosure))
    return out, not runs and not capped


def _runs(t: Array, codes: Array, ok: Array) -> list[tuple[str, float, float]]:
    """``(kind, t_first, t_last)`` for each run of two or more consecutive reachable samples labelled
    with one kind of singularity: the path runs inside that singular set there."""
    out = []
    for bit, kind in enumerate(KINDS):
        flagged = np.concatenate([[False], ok & (codes >= 0) & (codes >> bit & 1 == 1), [False]])
        edges = np.flatnonzero(np.diff(flagged.astype(np.int8)))
        for first, stop in zip(edges[::2], edges[1::2], strict=True):
            if stop - first >= 2:
                out.append((kind, float(t[first]), float(t[stop - 1])))
    return out
