"""Roots along lines of samples: one search for the loci and the paths.

A singular surface is rarely hit by a grid or path sample: a grid's labels miss it. Along each
line of samples (grid rows and columns, or a path) screwkit looks for

* sign changes of ``det A`` and ``det B`` (refined by false position),
* local minima of each closeness measure (refined by golden-section search), and
* the edge of the reachable set (refined by bisection on the inverse kinematics),

then keeps a refined pose when the core labels it singular or one of its closeness measures is
below :data:`ACCEPT` (the kind is the core's label there, else the closest measure). The factor is
the superbracket condition with the smallest value there relative to its value at the default pose.
Each step is one batch through the posed mechanism (:meth:`screwkit.robots.mechanism.Mechanism.at`).
Private to :mod:`screwkit.analysis` (:mod:`~screwkit.analysis.loci`, :mod:`~screwkit.analysis.paths`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..exceptions import ScrewkitError
from .poses import CHUNK, reached_batch
from .quantities import KINDS, conditions_of
from .quantities import values as quantity_values

__all__ = ["ACCEPT", "MAX_STEPS", "XTOL"]

Array = np.ndarray

#: A refined pose with a closeness measure below this is a singularity even if the core's rank
#: decision (relative tolerance ``rtol``) did not label it.
ACCEPT = 1e-6
#: Refinement stops when a bracket (in the line's parameter, 0..1) is this narrow ...
XTOL = 4e-16
#: ... or after this many steps (each one batch through the core).
MAX_STEPS = 80
#: Poses of one surface tried for its factor (where the diagram's points exist).
_FACTOR_TRIES = 5
_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0

@dataclass(frozen=True)
class _Samples:
    """What the core says along lines of samples ``(L, n_t)``."""

    ok: Array
    codes: Array
    closeness: dict[str, Array]
    det_A: Array | None
    det_B: Array | None


def _measure(
    mechanism: Any, poses: Array, options: dict[str, Any], rtol: Any, client: Any = None
) -> _Samples:
    """Codes, closeness, det A and det B at API-unit poses ``(..., n)`` (NaN / -1 where out of
    reach), through the core in chunks of :data:`~screwkit.analysis.poses.CHUNK` poses, in process
    or on a Dask ``client`` (the chunks submitted at once; the same numbers)."""
    shape = poses.shape[:-1]
    flat = poses.reshape(-1, poses.shape[-1])
    pieces = [flat[i : i + CHUNK] for i in range(0, len(flat), CHUNK)]
    if client is None:
        parts = [_measured_chunk(mechanism, piece, options, rtol) for piece in pieces]
    else:
        futures = [client.submit(_measured_chunk, mechanism, p, options, rtol, pure=False) for p in pieces]
        parts = [future.result() for future in futures]
    if not parts:
        parts = [_measured_chunk(mechanism, flat, options, rtol)]
    return _samples([np.concatenate([p[n] for p in parts]) for n in range(1, 6)], shape)


def _samples(columns: list[Array], shape: tuple[int, ...]) -> _Samples:
    """:class:`_Samples` of shape ``shape`` from the flat ``ok, codes, closeness (m, 3), det A, det B``
    of :func:`_measured_chunk` (a determinant NaN at every reachable pose: the mechanism has none)."""
    ok, codes, closeness, det_a, det_b = columns

    def det(values: Array) -> Array | None:
        return None if ok.any() and np.isnan(values[ok]).all() else values.reshape(shape)

    return _Samples(
        ok.reshape(shape),
        codes.reshape(shape),
        {k: closeness[:, i].reshape(shape) for i, k in enumerate(KINDS)},
        det(det_a),
        det(det_b),
    )


def _measured_chunk(
    mechanism: Any, poses: Array, options: dict[str, Any], rtol: Any, quantity: str | None = None
) -> tuple[Array, Array, Array, Array, Array, Array]:
    """One chunk of :func:`_measure` at flat poses ``(m, n)``: ``(values, ok, codes, closeness (m, 3),
    det A, det B)``, one posed batch for all (a module-level function, so a Dask worker can run
    it). ``values`` is ``quantity`` (:func:`screwkit.analysis.quantities.values`) over the chunk, the
    codes when None; the determinants NaN where the mechanism has no square Jacobian."""
    ok = np.array(mechanism.reachable(poses, **options), dtype=bool)  # (narrowed by reached_batch)
    codes = np.full(len(poses), -1, dtype=np.int64)
    closeness = np.full((len(poses), len(KINDS)), np.nan)
    det_a, det_b = np.full(len(poses), np.nan), np.full(len(poses), np.nan)
    integer = quantity in (None, "verdict")
    values = np.full(len(poses), -1 if integer else np.nan, dtype=np.int64 if integer else float)
    posed = reached_batch(mechanism, poses, ok, rtol, options)
    if posed is not None:
        _ = posed.joints  # det A and det B need the joint table too: build it once per batch
        codes[ok] = posed.codes
        for i, k in enumerate(KINDS):
            closeness[ok, i] = posed.closeness[k]
        for name, det in (("det_A", det_a), ("det_B", det_b)):
            try:
                det[ok] = getattr(posed.jacobians, name)
            except ScrewkitError:  # no square Jacobian for this mechanism: no sign to follow
                pass
        values[ok] = codes[ok] if quantity is None else quantity_values(posed, quantity)
    return values, ok, codes, closeness, det_a, det_b


@dataclass(frozen=True)
class _Root:
    """A refined pose on line ``line`` at parameter ``t`` (between the line's samples)."""

    line: int
    t: float
    pose: Array
    kind: str
    closeness: float


def _brackets(t: Array, samples: _Samples) -> list[tuple[int, float, float, str, int, int, int]]:
    """``(line, t_low, t_high, method, i_low, i_middle, i_high)`` intervals holding a candidate root,
    from each line's samples: det A and det B sign changes, closeness minima, reach edges and
    samples labelled singular; ``i_*`` are the samples at the ends and in the middle (-1: none)."""
    out = []
    ok = samples.ok
    both = ok[:, :-1] & ok[:, 1:]
    for name in ("det_A", "det_B"):
        det = getattr(samples, name)
        if det is None:
            continue
        with np.errstate(invalid="ignore"):
            change = both & (np.sign(det[:, :-1]) != np.sign(det[:, 1:]))
        for line, i in zip(*np.nonzero(change), strict=True):
            out.append((int(line), float(t[i]), float(t[i + 1]), name, int(i), -1, int(i) + 1))
    for kind in KINDS:
        c = np.where(ok, samples.closeness[kind], np.inf)
        left = np.concatenate([np.full((len(c), 1), np.inf), c[:, :-1]], axis=1)
        right = np.concatenate([c[:, 1:], np.full((len(c), 1), np.inf)], axis=1)
        minimum = ok & (c <= left) & (c <= right) & ((c < left) | (c < right))
        for line, i in zip(*np.nonzero(minimum), strict=True):
            low, high = max(i - 1, 0), min(i + 1, len(t) - 1)
            out.append((int(line), float(t[low]), float(t[high]), "min:" + kind, int(low), int(i), int(high)))
    edge = ok[:, :-1] != ok[:, 1:]
    for line, i in zip(*np.nonzero(edge), strict=True):
        out.append((int(line), float(t[i]), float(t[i + 1]), "edge", int(i), -1, int(i) + 1))
    singular = ok & (samples.codes > 0)
    for line, i in zip(*np.nonzero(singular), strict=True):
        out.append((int(line), float(t[i]), float(t[i]), "sample", int(i), int(i), int(i)))
    return out


def _refine(
    mechanism: Any,
    along: Callable[[Array, Array], Array],
    brackets: list[tuple[int, float, float, str, int, int, int]],
    t_samples: Array,
    samples: _Samples,
    options: dict[str, Any],
    rtol: Any,
    *,
    keep_edges: bool = False,
    client: Any = None,
) -> list[_Root]:
    """Refine every bracket at once and keep the roots the core labels singular or whose closeness
    is below :data:`ACCEPT` (and, with ``keep_edges``, the reach edges that are no singularity, as
    kind ``"unreachable"``).

    ``along(lines, t)`` gives API-unit poses ``(m, n)`` on lines ``lines`` at parameters ``t``.
    Each step is one batch through the core, for all brackets: false position (Illinois) on det A
    for its sign changes, bisection on reachability for reach edges, and for closeness minima a
    golden-section search whose steps are replaced by the apex of the ``|s (t − t₀)|`` fit through
    the bracket when that lands inside (a closeness measure vanishes like the distance to a simple
    root, design of :mod:`screwkit.core.singularity`). Stops when every bracket is narrower than
    :data:`XTOL` or after :data:`MAX_STEPS` steps. With a Dask ``client`` each step's batch runs
    on the cluster (:func:`_measure`). What the lines' ``samples`` already say is read, not
    measured again: the brackets' ends and middles that are samples, and the final pose of a
    bracket that never left its samples (a closeness minimum proved too shallow at once).
    """
    if not brackets:
        return []
    lines = np.array([b[0] for b in brackets])
    method = np.array([b[3] for b in brackets])
    kind_index = np.array([KINDS.index(m[4:]) if m.startswith("min:") else 0 for m in method])
    is_det_b = method == "det_B"
    is_det, is_edge = (method == "det_A") | is_det_b, method == "edge"
    is_min = np.char.startswith(method.astype(str), "min:")
    everyone = np.arange(len(brackets))

    def scored(s: _Samples, which: Array) -> Array:
        """Per bracket ``which`` from its measured samples ``s`` (flat): det A or det B, ±1
        reachability, or its kind's closeness (inf out of reach)."""
        det_a = np.zeros(len(which)) if s.det_A is None else np.nan_to_num(s.det_A)
        det_b = np.zeros(len(which)) if s.det_B is None else np.nan_to_num(s.det_B)
        det = np.where(is_det_b[which], det_b, det_a)
        closeness = np.stack([s.closeness[k] for k in KINDS], axis=-1)[
            np.arange(len(which)), kind_index[which]
        ]
        values = np.where(is_edge[which], np.where(s.ok, 1.0, -1.0), np.where(s.ok, closeness, np.inf))
        return np.where(is_det[which], det, values)

    def score(t: Array, which: Array = everyone) -> Array:
        out = np.full(len(t), np.nan)
        if len(which):
            measured = _measure(mechanism, along(lines[which], t[which]), options, rtol, client)
            out[which] = scored(measured, which)
        return out

    index = np.array([b[4:7] for b in brackets])  # (B, 3): the samples at the ends and the middle
    known = _at_samples(samples, lines[:, None], index)

    def sampled(column: int) -> Array:
        return scored(_flat(known, column), everyone)

    a = np.array([b[1] for b in brackets])
    b = np.array([b[2] for b in brackets])
    fa, fb = sampled(0), sampled(2)
    # a minimum's middle is its sample (inside the bracket: not at a line's end), else the midpoint
    middle_known = (index[:, 1] >= 0) & (
        ((index[:, 0] < index[:, 1]) & (index[:, 1] < index[:, 2])) | (method == "sample")
    )
    m = np.where(middle_known, t_samples[np.maximum(index[:, 1], 0)], 0.5 * (a + b))
    fm = score(m, np.flatnonzero(~middle_known))
    fm[middle_known] = sampled(1)[middle_known]
    side = np.zeros(len(a))  # Illinois: which end was kept last
    for step in range(MAX_STEPS):
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            left, right = (fm - fa) / (m - a), (fb - fm) / (b - m)
            steep = np.nan_to_num(np.maximum(-left, right), nan=np.inf)
            illinois = (a * fb - b * fa) / (fb - fa)
            # a minimum that cannot reach ACCEPT unless the slope doubles within the bracket: no root
            smooth = is_min & (fm - 2.0 * steep * (b - a) > ACCEPT)  # inf - inf: not smooth
        done = ((b - a) <= XTOL) | (is_min & (fm == 0.0)) | smooth
        if done.all():
            break
        # the next point of each bracket
        illinois = np.where(is_det & (illinois > a) & (illinois < b), illinois, 0.5 * (a + b))
        with np.errstate(invalid="ignore", divide="ignore"):
            apex = np.where(-left >= right, m + fm / steep, m - fm / steep)
        golden = np.where(m - a > b - m, m - (1 - _GOLDEN) * (m - a), m + (1 - _GOLDEN) * (b - m))
        use_apex = (
            (step % 3 != 2) & np.isfinite(apex) & (apex > a) & (apex < b) & (np.abs(apex - m) > XTOL / 4)
        )
        trial = np.where(is_det, illinois, np.where(is_edge, 0.5 * (a + b), np.where(use_apex, apex, golden)))
        f = score(trial, np.nonzero(~done)[0])
        # sign brackets: keep the end whose sign differs from the trial's
        same_as_a = np.sign(f) == np.sign(fa)
        new_a = np.where(same_as_a, trial, a)
        new_b = np.where(same_as_a, b, trial)
        new_fa = np.where(same_as_a, f, np.where(is_det & (side == -1), 0.5 * fa, fa))
        new_fb = np.where(same_as_a, np.where(is_det & (side == 1), 0.5 * fb, fb), f)
        new_side = np.where(same_as_a, 1.0, -1.0)
        # minimum brackets: a <= m <= b with f(m) <= f(a), f(b)
        better = f < fm
        above = trial > m
        min_a = np.where(better, np.where(above, m, a), np.where(above, a, trial))
        min_b = np.where(better, np.where(above, b, m), np.where(above, trial, b))
        min_fa = np.where(better, np.where(above, fm, fa), np.where(above, fa, f))
        min_fb = np.where(better, np.where(above, fb, fm), np.where(above, f, fb))
        min_m, min_fm = np.where(better, trial, m), np.where(better, f, fm)
        sign = is_det | is_edge
        keep = done  # a converged bracket stays as it is
        a = np.where(keep, a, np.where(sign, new_a, min_a))
        b = np.where(keep, b, np.where(sign, new_b, min_b))
        fa = np.where(keep, fa, np.where(sign, new_fa, min_fa))
        fb = np.where(keep, fb, np.where(sign, new_fb, min_fb))
        m = np.where(keep | sign, m, min_m)
        fm = np.where(keep | sign, fm, min_fm)
        side = np.where(keep, side, new_side)
    # the refined parameter: an edge's reachable end, det A's end of smaller |det A|, the minimum
    t = np.where(
        is_edge,
        np.where(fa > 0, a, b),
        np.where(is_det, np.where(np.abs(fa) <= np.abs(fb), a, b), m),
    )
    t = np.where(method == "sample", a, t)
    # a bracket whose final parameter is its middle sample: read, not measured again
    stayed = middle_known & (t == t_samples[np.maximum(index[:, 1], 0)])
    moved = np.flatnonzero(~stayed)
    final = _merged(
        _flat(known, 1),
        moved,
        _measure(mechanism, along(lines[moved], t[moved]), options, rtol, client) if moved.size else None,
    )
    poses = along(lines, t)
    roots = []
    for k in range(len(brackets)):
        if not final.ok[k]:
            continue
        measures = {kind: float(final.closeness[kind][k]) for kind in KINDS}
        code = int(final.codes[k])
        labelled = [kind for bit, kind in enumerate(KINDS) if code >> bit & 1]
        smallest = min(measures, key=measures.__getitem__)
        if labelled or measures[smallest] < ACCEPT:
            kind = labelled[0] if labelled else smallest
            roots.append(_Root(int(lines[k]), float(t[k]), poses[k], kind, measures[kind]))
        elif keep_edges and method[k] == "edge":
            roots.append(_Root(int(lines[k]), float(t[k]), poses[k], "unreachable", math.nan))
    return roots


def _at_samples(samples: _Samples, lines: Array, index: Array) -> _Samples:
    """The samples at ``(lines, index)`` (broadcast; index -1 reads a placeholder, never used)."""
    where = (lines, np.maximum(index, 0))
    return _Samples(
        samples.ok[where],
        samples.codes[where],
        {k: v[where] for k, v in samples.closeness.items()},
        None if samples.det_A is None else samples.det_A[where],
        None if samples.det_B is None else samples.det_B[where],
    )


def _flat(samples: _Samples, column: int) -> _Samples:
    """One column of ``(B, 3)`` samples (:func:`_at_samples`)."""
    return _Samples(
        samples.ok[:, column],
        samples.codes[:, column],
        {k: v[:, column] for k, v in samples.closeness.items()},
        None if samples.det_A is None else samples.det_A[:, column],
        None if samples.det_B is None else samples.det_B[:, column],
    )


def _merged(known: _Samples, rest: Array, measured: _Samples | None) -> _Samples:
    """Per bracket: ``measured`` (in order) at the brackets ``rest``, ``known`` elsewhere."""
    if measured is None:
        return known

    def merge(old: Array | None, new: Array | None) -> Array | None:
        if old is None or new is None:  # no square Jacobian: no determinant anywhere
            return None
        out = old.copy()
        out[rest] = new
        return out

    ok, codes = merge(known.ok, measured.ok), merge(known.codes, measured.codes)
    assert ok is not None and codes is not None
    closeness = {k: merge(v, measured.closeness[k]) for k, v in known.closeness.items()}
    return _Samples(
        ok,
        codes,
        {k: v for k, v in closeness.items() if v is not None},
        merge(known.det_A, measured.det_A),
        merge(known.det_B, measured.det_B),
    )


def _factor(mechanism: Any, poses: Array, kind: str, options: dict[str, Any], rtol: Any) -> str | None:
    """The superbracket condition vanishing at API-unit poses ``(k, n)`` of one surface: at the
    first of them (up to :data:`_FACTOR_TRIES`, evaluated as one batch) where the diagram's points
    exist, the condition of that kind with the smallest value relative to its value at the default
    pose. None for a serial singularity (a limb's, not the superbracket's) or when the conditions
    cannot be had for this mechanism."""
    if kind not in ("constraint", "actuation"):
        return None
    try:
        diagram, conditions, labels, reference = conditions_of(mechanism, options)
    except ScrewkitError:
        return None
    candidates = [i for i, label in enumerate(labels) if label == kind and reference[i] != 0]
    tries = np.asarray(poses[:_FACTOR_TRIES], dtype=float)
    tries = tries[mechanism.reachable(tries, **options)]
    if not candidates or not len(tries):
        return None
    points, exists = mechanism.at(tries, rtol=rtol, **options).diagram_points(diagram.points)
    if not exists.any():
        return None
    first = int(np.argmax(exists))
    at = {label: value[first] for label, value in points.items()}
    ratios = [abs(float(conditions[i].evaluate(at)) / reference[i]) for i in candidates]
    return str(conditions[candidates[int(np.argmin(ratios))]].factor)
