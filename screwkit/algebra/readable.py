"""The geometry of a readable basis: axes near a point, the frame's axes first, principal screws.

The steps of :meth:`screwkit.algebra.screwsystem.ScrewSystem.readable_basis` (steps 1–4 of its
docstring): on plain ``(k, 6)`` float arrays, the point nearest a system's axes, moments about a
point, orthonormal couples with the frame's axes first, and the candidate screws of finite pitch
(the principal directions of the pitch form, Hunt, *Kinematic Geometry of Mechanisms*, 1978, §12,
and its isotropic directions), best first; then the numeric and symbolic readable bases of a
system, which take the independent candidates (:func:`_pick`; ``system`` is a
:class:`~screwkit.algebra.screwsystem.ScrewSystem`, read through its attributes only). Private to
:mod:`screwkit.algebra.screwsystem`, with the couples along the frame's axes (``_COUPLES``, also read
by :mod:`screwkit.algebra.motion_type`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from . import backend as B
from .ranks import _independent_rows, screw_rank

__all__: list[str] = []

Array = np.ndarray
#: The couples (pure translations) along the frame's axes, as rows.
_COUPLES = np.hstack([np.zeros((3, 3)), np.eye(3)])


def _axes_centre(rows: Array, length: float, rtol: float) -> Array:
    """The point nearest the axes of the rows (least squares of their moments about it,
    ``Σ |m − p × s|²`` over rows of unit size in scaled coordinates, so that a row weighs by its
    direction: couples, and a couple's round-off direction, do not count; the origin for couples
    only). Directions of the normal equations below ``rtol`` are left out (parallel axes: the point
    nearest the origin along them)."""
    sizes = np.linalg.norm(np.hstack([rows[:, :3], rows[:, 3:] / length]), axis=1)
    unit = rows / np.where(sizes > 0, sizes, 1.0)[:, None]
    s, m = unit[:, :3], unit[:, 3:]
    normal = np.sum(s * s) * np.eye(3) - s.T @ s  # Σ (|s|² I − s sᵀ)
    values, vectors = np.linalg.eigh(normal)
    kept = values > rtol
    if not kept.any():
        return np.zeros(3)
    rhs = vectors[:, kept].T @ np.cross(s, m).sum(axis=0)
    return vectors[:, kept] @ (rhs / values[kept])


def _about(rows: Array, point: Array) -> Array:
    """The rows with their moments taken about ``point`` (``m − point × s``; ``-point`` undoes it)."""
    return np.hstack([rows[:, :3], rows[:, 3:] - np.cross(point, rows[:, :3])])


def _orthonormal_couples(rows: Array) -> Array:
    if rows.shape[0] == 0:
        return np.zeros((0, 6))
    moments = np.linalg.svd(rows[:, 3:])[2][: rows.shape[0]]
    return np.hstack([np.zeros_like(moments), moments])


def _axis_first(moments: Array, rtol: float) -> Array:
    """An orthonormal basis of the span of orthonormal rows ``(c, 3)``: the frame's axes it holds
    first (x, y, z), completed by Gram–Schmidt."""
    if moments.shape[0] == 0:
        return moments
    projector = moments.T @ moments
    chosen = [e for e in np.eye(3) if np.linalg.norm(e - projector @ e) <= 1e3 * rtol]
    for row in moments:
        for picked in chosen:
            row = row - (row @ picked) * picked
        if np.linalg.norm(row) > 1e3 * rtol and len(chosen) < moments.shape[0]:
            chosen.append(row / np.linalg.norm(row))
    return np.array(chosen[: moments.shape[0]]).reshape(-1, 3)


def _finite_candidates(basis: Array, couples: Array, near: Array, rtol: float, length: float) -> list[Array]:
    """Candidate screws of finite pitch of a system (``readable_basis`` steps 2–3), best first."""
    directions = basis[:, :3]
    sizes = np.linalg.norm(np.hstack([directions, basis[:, 3:] / length]), axis=1)
    unit = directions / np.where(sizes > 0, sizes, 1.0)[:, None]  # rows of unit scaled size
    _, values, vt = np.linalg.svd(unit)
    rank = int((values > 1e3 * rtol).sum())
    if rank == 0:
        return []
    span = vt[:rank]  # orthonormal basis of the directions D
    # the moment as a linear map of the direction on D (any screw of the system with direction s)
    coefficients = np.linalg.lstsq(directions.T, span.T, rcond=None)[0]  # (order, rank)
    moment_map = basis[:, 3:].T @ coefficients @ span  # (3, 3): s ↦ m(s) for s in D
    projector = couples.T @ couples if couples.size else np.zeros((3, 3))
    form = span @ (moment_map + moment_map.T) @ span.T / 2  # pitch form on D (orthonormal coords)
    values_q, vectors_q = np.linalg.eigh(form)
    tol = 1e3 * rtol * max(float(np.abs(values_q).max(initial=0.0)), length * rtol)
    principal = [span.T @ v for v in vectors_q.T]
    positive = [(lam, span.T @ v) for lam, v in zip(values_q, vectors_q.T, strict=True) if lam > tol]
    negative = [(lam, span.T @ v) for lam, v in zip(values_q, vectors_q.T, strict=True) if lam < -tol]
    isotropic = []
    for k, (lp, p) in enumerate(positive):
        for m, (ln, n) in enumerate(negative):
            if k == 0 or m == 0:
                isotropic += [np.sqrt(-ln) * p + sign * np.sqrt(lp) * n for sign in (1.0, -1.0)]
    axes = [e for e in np.eye(3) if np.linalg.norm(e - span.T @ (span @ e)) <= 1e3 * rtol]
    candidates = []
    for order, s in enumerate([*axes, *isotropic, *principal]):
        s = s / np.linalg.norm(s)
        moment = moment_map @ s
        about = moment - B.cross(near, s) - projector @ (moment - B.cross(near, s))
        pitch = s @ (about + B.cross(near, s))
        feasible = np.linalg.norm(projector @ s)
        if abs(pitch) > rtol * length and feasible > 1e3 * rtol:
            about = about - pitch / (s @ projector @ s) * (projector @ s)
            pitch = 0.0
        screw = np.concatenate([s, about + B.cross(near, s)])
        is_line = abs(s @ screw[3:]) <= 1e3 * rtol * length
        candidates.append((not is_line, order >= len(axes), order, screw))
    candidates.sort(key=lambda c: c[:3])
    return [np.array([c[3] for c in candidates])]


def _pick(candidates: Array, order: int, system: Any) -> Array:
    """The first ``order`` independent candidates. The candidates lie in the system to within the
    snapping of :func:`_axis_first` and :func:`_finite_candidates` (``1e3 rtol``: a frame axis, a
    line), so that is the tolerance of their independence; the system's own ``rtol`` decides where
    that would not give ``order`` rows (a system with a singular value between the two)."""
    picked = np.zeros((0, 6))
    if not system.is_symbolic:
        picked = _independent_rows(candidates, min(1e3 * system.rtol, 1e-3), system.length_scale)
    if picked.shape[0] != order:
        picked = _independent_rows(candidates, system.rtol, system.length_scale)
    if picked.shape[0] != order:
        # a large rtol (1e-3 from the command line) blurs the candidates' decisions, made at 1e3 rtol,
        # until they disagree with the system's order: its own basis is then the readable one (it
        # was an "Internal error" for `screwkit analyze h4 --rtol 1e-3`)
        picked = np.asarray(system.basis)
    if system.is_symbolic:
        return picked
    sizes = np.linalg.norm(picked[:, :3], axis=1)
    moments = np.linalg.norm(picked[:, 3:], axis=1)
    scale = np.where(sizes > system.rtol * moments / float(system.length_scale or 1.0), sizes, moments)
    return picked / scale[:, None]


def _numeric_readable(system: Any, centre: Array) -> Array:
    """:meth:`~screwkit.algebra.screwsystem.ScrewSystem.readable_basis` of a numeric system in its
    own frame (axes placed near ``centre``)."""
    couples = _axis_first(_orthonormal_couples(system.couple_subsystem().basis)[:, 3:], system.rtol)
    finite = _finite_candidates(system.basis, couples, centre, system.rtol, float(system.length_scale or 1.0))
    rows = np.concatenate([np.hstack([np.zeros_like(couples), couples]), *finite]).reshape(-1, 6)
    return _pick(system._stack(rows, system.basis), system.order, system)


def _symbolic_readable(system: Any, near: Any) -> Array:
    """The symbolic readable basis (generic decisions, :mod:`screwkit.algebra.symbolic`): the frame's
    translations where the system holds them; with all three, the other rows become lines
    through ``near`` (the origin by default); else the couple subsystem, then the basis."""
    axes = [row for row in _COUPLES.astype(int) if system.contains(row)]
    stacked = system._stack(system.basis, _COUPLES.astype(int))
    translations = system.order + 3 - int(screw_rank(stacked))
    couples = (
        np.array(axes).reshape(-1, 6) if len(axes) == translations else system.couple_subsystem().basis
    )
    rows = system.basis
    if translations == 3:
        centre = B.as_array(np.zeros(3) if near is None else near, "near", (3,), symbolic=True)
        rows = np.concatenate(
            [rows[:, :3], B.cross(np.broadcast_to(centre, rows[:, :3].shape), rows[:, :3])], axis=1
        )
    return _pick(system._stack(couples, rows), system.order, system)
