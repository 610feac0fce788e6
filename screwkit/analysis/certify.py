"""Certified singularity-free regions and paths. One algorithm: branch and bound over boxes of
pose space.

A box of pose space is enclosed (:mod:`screwkit.analysis.enclosures`, interval
arithmetic with outward rounding and the mean-value form, :mod:`screwkit.analysis.intervals`) and

* ``"free"`` when every limb provably reaches every pose of it (``g_i > 0``) and no function of the
  requested kinds can vanish in it (a proof);
* ``"unreachable"`` when some limb provably reaches no pose of it (``g_i < 0`` over it);
* ``"singular"`` when, at the resolution, two points of the box carry certified opposite signs of
  one function that is continuous over the box (the box proved reachable, or for ``g_i`` the other
  limbs' ``g_j > 0``): by the intermediate value theorem it vanishes on the segment between them,
  and the witness is that segment, refined by bisection;
* ``"undecided"`` at the resolution otherwise (a touching zero, or an enclosure still too wide);

else it is split (at :data:`SPLIT` of its width) across the coordinate widest relative to its
resolution. Each box's fate depends
on the box alone, so the boxes of one bisection level can run anywhere: with a Dask ``client``
each level's boxes are evaluated in chunks on the cluster, with the same result as in process. A
run stopped by ``max_boxes`` returns the decided boxes and the rest as ``"undecided"`` (never a
false ``"free"``).

Examples
--------
>>> c = certify(load_mechanism("quattro"), {"x": (100, 200), "y": (100, 200), "z": -750, "phi": 0},
...             resolution=10)
>>> c.certified_free, c.totals["singular"], c.totals["undecided"]
(True, 0, 0)
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from ..robots.angles import angle_factor
from .enclosures import model_of
from .intervals import Enclosure, mean_value
from .poses import _check_mechanism, _options

__all__ = [
    "DEFAULT_MAX_BOXES",
    "KINDS",
    "MAX_BOXES",
    "RESOLUTION_DIVISIONS",
    "STATUSES",
    "Certificate",
    "CertifiedBox",
    "PathInterval",
    "Witness",
    "certify",
    "certify_path",
]

Array = np.ndarray

#: The kinds of singularity a certificate can exclude.
KINDS = ("constraint", "actuation", "serial")
#: A range is split down to this fraction of its width unless ``resolution`` says otherwise.
RESOLUTION_DIVISIONS = 256.0
#: A box's status.
STATUSES = ("free", "singular", "undecided", "unreachable")
#: Boxes evaluated by default before a run stops (the rest returned undecided) ...
DEFAULT_MAX_BOXES = 200_000
#: ... and the most a caller may ask for (memory: ~1 kB a box in a level).
MAX_BOXES = 10**7
#: Bisection steps refining a witness's segment (the bracket shrinks by 2**-WITNESS_STEPS; a model
#: may ask for fewer: ``witness_steps``).
WITNESS_STEPS = 30
#: Where a box is split (a fraction of its width, off the middle: a symmetric region's plane of
#: symmetry, often singular, then falls inside boxes, where a sign change shows it, not on edges).
SPLIT = 15 / 32
#: Boxes evaluated at once (bounded memory), in process or per Dask task.
TASK_BOXES = 8192


@dataclass(frozen=True)
class Witness:
    """A certified singular pose: a function of one kind changes sign between two poses of a box.

    Attributes
    ----------
    pose : dict of str to float
        The middle of the refined bracket (user units): within ``bracket`` of a zero.
    label : str
        ``"constraint"``, ``"actuation"`` or ``"serial"``.
    factor : str or None
        The superbracket factor of that kind (None for serial).
    statement : str
        The function that vanishes and what that means.
    bracket : tuple of two dict
        Poses with certified opposite signs of the function: a zero lies on the segment.
    """

    pose: dict[str, float]
    label: str
    factor: str | None
    statement: str
    bracket: tuple[dict[str, float], dict[str, float]]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "pose": self.pose,
            "label": self.label,
            "factor": self.factor,
            "statement": self.statement,
            "bracket": list(self.bracket),
        }


@dataclass(frozen=True)
class CertifiedBox:
    """One box of a certificate.

    Attributes
    ----------
    status : str
        One of :data:`STATUSES`.
    bounds : dict of str to tuple of float
        The box's ``(lo, hi)`` per free coordinate (user units).
    witness : Witness or None
        For ``"singular"``.
    """

    status: str
    bounds: dict[str, tuple[float, float]]
    witness: Witness | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "status": self.status,
            "bounds": {k: list(v) for k, v in self.bounds.items()},
            "witness": None if self.witness is None else self.witness.to_dict(),
        }


@dataclass(frozen=True)
class Certificate:
    """The paving of a region of pose space (:func:`certify`).

    Attributes
    ----------
    mechanism : str
    region : dict of str to tuple of float
        The free coordinates' ranges (user units).
    fixed : dict of str to float
        The other coordinates (user units).
    kinds : tuple of str
    resolution : dict of str to float
    boxes : tuple of CertifiedBox
        Sorted by their lower corners.
    totals : dict of str to int
        Boxes per status.
    fractions : dict of str to float
        Share of the region's volume per status.
    capped : bool
        The run stopped at ``max_boxes`` (the undecided rest included).
    evaluated : int
        Boxes evaluated.
    angles : str
    """

    mechanism: str
    region: dict[str, tuple[float, float]]
    fixed: dict[str, float]
    kinds: tuple[str, ...]
    resolution: dict[str, float]
    boxes: tuple[CertifiedBox, ...]
    totals: dict[str, int]
    fractions: dict[str, float]
    capped: bool
    evaluated: int
    angles: str = "rad"
    lows: Array = field(default_factory=lambda: np.zeros((0, 0)), repr=False)
    highs: Array = field(default_factory=lambda: np.zeros((0, 0)), repr=False)

    @property
    def certified_free(self) -> bool:
        """bool: Every box is free (the whole region is proved free of the kinds)."""
        return self.totals["free"] == len(self.boxes)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "mechanism": self.mechanism,
            "region": {k: list(v) for k, v in self.region.items()},
            "fixed": self.fixed,
            "kinds": list(self.kinds),
            "resolution": self.resolution,
            "angles": self.angles,
            "certified_free": self.certified_free,
            "totals": self.totals,
            "fractions": self.fractions,
            "capped": self.capped,
            "evaluated": self.evaluated,
            "boxes": [box.to_dict() for box in self.boxes],
        }

    def to_json(self, **kwargs: Any) -> str:
        """:meth:`to_dict` as a JSON string.

        Parameters
        ----------
        **kwargs
            Passed to :func:`json.dumps`.

        Returns
        -------
        str

        Examples
        --------
        >>> c = certify(load_mechanism("h4"), {"x": (0, 50), "y": (100, 150), "z": -800, "phi": 0.3},
        ...             resolution=25)
        >>> json.loads(c.to_json())["totals"]["free"] >= 1
        True
        """
        return json.dumps(self.to_dict(), **kwargs)

    def __str__(self) -> str:
        region = ", ".join(f"{k} in [{lo:g}, {hi:g}]" for k, (lo, hi) in self.region.items())
        fixed = ", ".join(f"{k} = {v:g}" for k, v in self.fixed.items())
        head = f"{self.mechanism}: {region}" + (f", {fixed}" if fixed else "") + f" ({self.angles})"
        shares = ", ".join(f"{s} {self.totals[s]} boxes ({self.fractions[s]:.2%})" for s in STATUSES)
        verdict = (
            f"certified free of {', '.join(self.kinds)} singularities"
            if self.certified_free
            else "not certified free"
        )
        labels = sorted({b.witness.label for b in self.boxes if b.witness is not None})
        found = f"; singular sets met: {', '.join(labels)}" if labels else ""
        cap = "; stopped at the box cap" if self.capped else ""
        return f"{head}\n  {verdict}: {shares}{found}{cap}"


def _checked_kinds(kinds: Any) -> tuple[str, ...]:
    if isinstance(kinds, str) or not isinstance(kinds, Sequence) or not kinds:
        raise ScrewkitTypeError(f"Expected `kinds` to be a non-empty sequence among {KINDS}, got {kinds!r}.")
    unknown = [k for k in kinds if k not in KINDS]
    if unknown:
        raise ScrewkitValueError(f"Expected `kinds` among {KINDS}, got {unknown}.")
    return tuple(k for k in KINDS if k in kinds)


def _real(value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ScrewkitTypeError(f"Expected `{what}` to be a number, got {value!r}.")
    if not math.isfinite(float(value)):
        raise ScrewkitValueError(f"Expected `{what}` to be finite, got {value!r}.")
    return float(value)


@dataclass(frozen=True)
class _Problem:
    """A paving problem in API units: pose = base + coef · u over boxes in ``u``."""

    model: Any  # what screwkit.analysis.enclosures.model_of gives
    base: Array  # (4,) pose at u = 0
    coef_lo: Array  # (4, k) enclosure of the affine map
    coef_hi: Array
    kinds: tuple[str, ...]
    resolution: Array  # (k,)


def _poses(problem: _Problem, lo: Array, hi: Array, gradient: bool) -> list[Enclosure]:
    """The pose coordinates over boxes ``[lo, hi]`` in ``u`` (``(B, k)``)."""
    variables = Enclosure.variables(lo, hi, gradient=gradient)
    out = []
    for j in range(len(problem.base)):
        value = Enclosure.constant(float(problem.base[j]), variables[0])
        for i, u in enumerate(variables):
            c_lo, c_hi = float(problem.coef_lo[j, i]), float(problem.coef_hi[j, i])
            if c_lo == c_hi == 0.0:
                continue
            term = (
                u * c_lo
                if c_lo == c_hi
                else u * Enclosure.constant(0.5 * (c_lo + c_hi), u, relative=_half_width(c_lo, c_hi))
            )
            value = value + term
        out.append(value)
    return out


def _half_width(lo: float, hi: float) -> float:
    centre = 0.5 * (lo + hi)
    return float(np.nextafter((hi - lo) / abs(centre), np.inf)) if centre else 0.0


def _functions(problem: _Problem) -> list[str]:
    """The functions enclosed: the reach functions and those of the requested kinds that the model
    has (a kind it has none of cannot occur: e.g. a planar mechanism's constraint wrenches)."""
    names = [f"serial:{i}" for i in range(1, problem.model.limbs + 1)]
    has = problem.model.functions()
    return names + [k for k in ("constraint", "actuation") if k in problem.kinds and k in has]


def _enclose(problem: _Problem, lo: Array, hi: Array) -> dict[str, Enclosure]:
    """Mean-value enclosures of the functions over the boxes."""
    centre = 0.5 * (lo + hi)
    centre = np.clip(centre, lo, hi)
    radius = np.nextafter(np.maximum(centre - lo, hi - centre), np.inf)
    singular = any(k in problem.kinds for k in ("constraint", "actuation"))
    if hasattr(problem.model, "evaluate_points"):  # it encloses boxes in its own centred forms
        found = problem.model.evaluate(_poses(problem, lo, hi, False), singular=singular)
        return {name: found[name] for name in _functions(problem)}
    over = problem.model.evaluate(_poses(problem, lo, hi, True), singular=singular)
    at = problem.model.evaluate(_poses(problem, centre, centre, False), singular=singular)
    return {name: mean_value(at[name], over[name], radius) for name in _functions(problem)}


def _signs(problem: _Problem, points: Array, boxes: tuple[Array, Array]) -> dict[str, Array]:
    """Certified signs (+1, -1, 0 unknown) of the functions at points ``(P, k)``, each in its box
    (``(P, k)`` bounds: a loop-closure model evaluates a point on its box's branch)."""
    poses = _poses(problem, points, points, False)
    if hasattr(problem.model, "evaluate_points"):
        values = problem.model.evaluate_points(poses, _poses(problem, boxes[0], boxes[1], False))
    else:
        values = problem.model.evaluate(poses)
    return {
        name: np.where(values[name].lo > 0, 1, np.where(values[name].hi < 0, -1, 0))
        for name in _functions(problem)
    }


def _step(problem: _Problem, lo: Array, hi: Array) -> tuple[Array, Array, Array, Array]:
    """One level for boxes ``(B, k)``: status codes (0 free, 1 singular, 2 undecided, 3 unreachable,
    -1 split), the witness function's index in :func:`_functions` (-1 none) and the bracket
    ``(B, 2, k)``, and the refined zero ``(B, k)``: a pure function of the boxes (any chunking gives
    the same answer)."""
    names = _functions(problem)
    enc = _enclose(problem, lo, hi)
    limbs = problem.model.limbs
    reach = [enc[f"serial:{i}"] for i in range(1, limbs + 1)]
    reachable = np.all([g.lo > 0 for g in reach], axis=0)
    unreachable = np.any([g.hi < 0 for g in reach], axis=0)
    clear = reachable.copy()
    for kind in ("constraint", "actuation"):
        if kind in enc:
            clear &= enc[kind].excludes_zero()
    small = np.all(hi - lo <= problem.resolution, axis=1)
    status = np.where(clear, 0, np.where(unreachable, 3, np.where(small, 2, -1)))
    which = np.full(len(lo), -1)
    bracket = np.zeros((len(lo), 2, lo.shape[1]))
    zero = np.zeros_like(lo)
    look = np.flatnonzero(status == 2)
    if look.size:
        k = lo.shape[1]
        corners = np.array(np.meshgrid(*([[0.0, 1.0]] * k), indexing="ij")).reshape(k, -1).T
        fractions = np.vstack([np.full((1, k), 0.5), corners])  # the centre and the corners
        points = lo[look, None, :] + fractions[None] * (hi - lo)[look, None, :]  # (L, P, k)
        signs = _signs(problem, points.reshape(-1, k), (np.repeat(lo[look], fractions.shape[0], axis=0),
                                                          np.repeat(hi[look], fractions.shape[0], axis=0)))
        count = fractions.shape[0]
        others_positive = {
            i: np.all([reach[j].lo[look] > 0 for j in range(limbs) if j != i], axis=0) for i in range(limbs)
        }
        for index, name in enumerate(names):
            if name.startswith("serial:"):
                if "serial" not in problem.kinds:
                    continue
                allowed = others_positive[int(name[-1]) - 1]
            else:
                allowed = reachable[look]
            sign = signs[name].reshape(len(look), count)
            plus, minus = sign == 1, sign == -1
            found = allowed & plus.any(axis=1) & minus.any(axis=1) & (which[look] < 0)
            for row in np.flatnonzero(found):
                box = look[row]
                which[box] = index
                bracket[box, 0] = points[row, np.argmax(plus[row])]
                bracket[box, 1] = points[row, np.argmax(minus[row])]
        proved = look[which[look] >= 0]
        status[proved] = 1
        if proved.size:
            zero[proved] = _refined(problem, bracket[proved], which[proved], (lo[proved], hi[proved]))
    return status, which, bracket, zero


def _refined(problem: _Problem, bracket: Array, which: Array, boxes: tuple[Array, Array]) -> Array:
    """Bisection on each bracket's segment (its function positive at the first end) in its box."""
    names = _functions(problem)
    plus, minus = bracket[:, 0].copy(), bracket[:, 1].copy()
    for _ in range(getattr(problem.model, "witness_steps", WITNESS_STEPS)):
        middle = 0.5 * (plus + minus)
        signs = _signs(problem, middle, boxes)
        value = np.choose(which, [signs[n] for n in names])
        positive, negative = value == 1, value == -1
        plus = np.where(positive[:, None], middle, plus)
        minus = np.where(negative[:, None], middle, minus)
        if not (positive | negative).any():
            break
    return 0.5 * (plus + minus)


def _pave(
    problem: _Problem, lo: Array, hi: Array, *, max_boxes: int = DEFAULT_MAX_BOXES, client: Any = None
) -> tuple[list[tuple[Array, Array, int, int, Array, Array]], int, bool]:
    """Branch and bound from boxes ``[lo, hi]`` (``(B, k)`` in ``u``) to the resolution: the decided
    boxes ``(lo, hi, status, function index, bracket, zero)`` (status 0..3), the boxes evaluated and
    whether the run stopped before a level that would take them beyond ``max_boxes`` (the rest
    then undecided). With a Dask ``client`` each level's boxes are evaluated on the cluster in
    chunks of :data:`TASK_BOXES` (in process too: bounded memory)."""
    decided: list[tuple[Array, Array, int, int, Array, Array]] = []
    evaluated, capped = 0, False
    while len(lo):
        if evaluated + len(lo) > max_boxes:
            capped = True
            for a, b in zip(lo, hi, strict=True):
                decided.append((a, b, 2, -1, np.zeros((2, lo.shape[1])), np.zeros(lo.shape[1])))
            break
        evaluated += len(lo)
        pieces = [(lo[i : i + TASK_BOXES], hi[i : i + TASK_BOXES]) for i in range(0, len(lo), TASK_BOXES)]
        if client is None:
            parts = [_step(problem, a, b) for a, b in pieces]
        else:
            futures = [client.submit(_step, problem, a, b, pure=False) for a, b in pieces]
            parts = [f.result() for f in futures]
        status, which, bracket, zero = (np.concatenate([p[n] for p in parts]) for n in range(4))
        for i in np.flatnonzero(status >= 0):
            decided.append((lo[i], hi[i], int(status[i]), int(which[i]), bracket[i], zero[i]))
        split = np.flatnonzero(status < 0)
        lo, hi = lo[split], hi[split]
        axis = np.argmax((hi - lo) / problem.resolution, axis=1)
        rows = np.arange(len(lo))
        middle = lo[rows, axis] + SPLIT * (hi[rows, axis] - lo[rows, axis])
        left_hi, right_lo = hi.copy(), lo.copy()
        left_hi[rows, axis] = middle
        right_lo[rows, axis] = middle
        lo, hi = np.vstack([lo, right_lo]), np.vstack([left_hi, hi])
    return decided, evaluated, capped


def certify(
    mechanism: Any,
    region: Mapping[str, Any],
    *,
    kinds: Sequence[str] = KINDS,
    resolution: Any = None,
    client: Any = None,
    angles: str = "rad",
    mode: Any = None,
    max_boxes: int = DEFAULT_MAX_BOXES,
) -> Certificate:
    """Prove boxes of a region of pose space free of singularities, or singular with a witness.

    Branch and bound (module docstring) over interval enclosures of the closed-form conditions
    (:mod:`screwkit.analysis.enclosures`; covered: :data:`~screwkit.analysis.enclosures.COVERED`).

    Parameters
    ----------
    mechanism : Mechanism
    region : mapping
        Pose coordinate name to ``(lo, hi)`` (a range) or one value (fixed); coordinates not named
        take the default pose.
    kinds : sequence of str, default all of :data:`KINDS`
        The singularities to exclude (reach is always required of a free box).
    resolution : float or mapping, optional
        The box width below which a box is not split (absolute, in the coordinates' units): a
        mapping per coordinate (those it leaves out: the default); or one number, which applies to
        every range when the ranges are all lengths or all angles, and to the lengths only when they
        mix both (a length and an angle do not compare: each angle range then gets the default).
        Default: 1/:data:`RESOLUTION_DIVISIONS` of each range. :attr:`Certificate.resolution` holds
        the widths used.
    client : dask.distributed.Client, optional
        Evaluate the boxes on this cluster (the same result).
    angles : {"rad", "deg"}
        The unit of angles in ``region`` and ``resolution`` (and in the result).
    mode : mapping or sequence, optional
        The working mode (default the catalog's).
    max_boxes : int, default DEFAULT_MAX_BOXES
        Evaluated boxes before the run stops (the rest undecided).

    Returns
    -------
    Certificate

    Raises
    ------
    ScrewkitValueError
        For a mechanism not covered, an unknown coordinate or kind, an empty or inverted range, a
        resolution that is not positive, no range at all, or ``max_boxes`` outside 1..MAX_BOXES.
    ScrewkitTypeError
        For arguments of the wrong type.

    Examples
    --------
    >>> c = certify(load_mechanism("quattro"), {"x": (-400, 400), "y": (-400, 400), "z": -750, "phi": 0},
    ...             resolution=25)
    >>> sorted({b.witness.label for b in c.boxes if b.status == "singular"})  # y = 0 at phi = 0
    ['constraint']
    >>> all(abs(b.witness.pose["y"]) < 1e-6 for b in c.boxes if b.status == "singular")
    True
    """
    _check_mechanism(mechanism)
    factor = angle_factor(angles)
    options = _options(mechanism, mode)
    model = model_of(mechanism, options)
    chosen = _checked_kinds(kinds)
    if (
        isinstance(max_boxes, bool)
        or not isinstance(max_boxes, int | np.integer)
        or not 1 <= max_boxes <= MAX_BOXES
    ):
        raise ScrewkitValueError(
            f"Expected `max_boxes` to be an integer in 1..{MAX_BOXES:g}, got {max_boxes!r}."
        )
    if not isinstance(region, Mapping):
        raise ScrewkitTypeError(
            f"Expected `region` to be a dict of coordinate to (lo, hi) or value, got {region!r}."
        )
    names = tuple(mechanism.pose_names)
    unknown = [k for k in region if k not in names]
    if unknown:
        raise ScrewkitValueError(f"Expected `region` over the coordinates {list(names)}, got {unknown}.")
    angle_names = set(mechanism.angle_names)
    scale = np.array([factor if n in angle_names else 1.0 for n in names])
    default = np.asarray(mechanism.default_pose, dtype=float)
    base = default.copy()
    ranges: dict[str, tuple[float, float]] = {}
    fixed: dict[str, float] = {}
    for name in names:
        given = region.get(name)
        if given is None:
            fixed[name] = float(default[names.index(name)] / scale[names.index(name)])
            continue
        if isinstance(given, Sequence) and not isinstance(given, str):
            if len(given) != 2:
                raise ScrewkitValueError(
                    f"Expected `region[{name!r}]` to be (lo, hi) or one value, got {given!r}."
                )
            lo, hi = _real(given[0], f"region[{name!r}][0]"), _real(given[1], f"region[{name!r}][1]")
            if not lo < hi:
                raise ScrewkitValueError(
                    f"Expected `region[{name!r}]` to be a non-empty range lo < hi, got ({lo:g}, {hi:g})."
                )
            ranges[name] = (lo, hi)
        else:
            fixed[name] = _real(given, f"region[{name!r}]")
            base[names.index(name)] = fixed[name] * scale[names.index(name)]
    if not ranges:
        raise ScrewkitValueError(
            f"Expected `region` to give at least one range (lo, hi), got {dict(region)!r}."
        )
    free = [names.index(n) for n in ranges]
    step = _resolutions(resolution, ranges, mechanism.angle_names)
    for i in free:
        base[i] = 0.0
    # the box in API units (radians), rounded outward so that it holds the box the caller gave
    exact = np.array([scale[i] == 1.0 for i in free])
    low = np.array([ranges[names[i]][0] * scale[i] for i in free])
    high = np.array([ranges[names[i]][1] * scale[i] for i in free])
    low = np.where(exact, low, np.nextafter(low, -np.inf))
    high = np.where(exact, high, np.nextafter(high, np.inf))
    problem = _Problem(
        model,
        base,
        np.eye(len(names))[:, free],
        np.eye(len(names))[:, free],
        chosen,
        np.array([step[names[i]] * scale[i] for i in free]),
    )
    decided, evaluated, capped = _pave(
        problem, low[None], high[None], max_boxes=int(max_boxes), client=client
    )
    user_scale = scale[free]
    full = np.array(base)

    def user_pose(u: Array) -> dict[str, float]:
        pose = full.copy()
        pose[free] = u
        return {n: float(pose[j] / scale[j]) for j, n in enumerate(names)}

    return _certificate(
        mechanism,
        problem,
        decided,
        evaluated,
        capped,
        ranges,
        fixed,
        step,
        angles,
        [names[i] for i in free],
        user_scale,
        user_pose,
        options,
    )


def _resolutions(
    resolution: Any, ranges: Mapping[str, tuple[float, float]], angle_names: Sequence[str]
) -> dict[str, float]:
    """Per range, the width below which a box is not split (user units): what a mapping gives, the
    others 1/:data:`RESOLUTION_DIVISIONS` of their range; one number for every range when the ranges
    are all lengths or all angles, else for the lengths only (a length and an angle do not compare:
    each angle range then gets the default)."""
    out = {n: (hi - lo) / RESOLUTION_DIVISIONS for n, (lo, hi) in ranges.items()}
    if resolution is None:
        return out
    if isinstance(resolution, Mapping):
        unknown = [k for k in resolution if k not in ranges]
        if unknown:
            raise ScrewkitValueError(
                f"Expected `resolution` over the region's ranges {list(ranges)}, got {unknown}."
            )
        out.update({n: _real(v, f"resolution[{n!r}]") for n, v in resolution.items()})
    else:
        value = _real(resolution, "resolution")
        lengths = [n for n in ranges if n not in angle_names]
        out.update(dict.fromkeys(lengths if lengths else ranges, value))
    bad = {n: v for n, v in out.items() if not v > 0}
    if bad:
        raise ScrewkitValueError(f"Expected `resolution` > 0, got {bad}.")
    return out


def _certificate(
    mechanism: Any,
    problem: _Problem,
    decided: list[Any],
    evaluated: int,
    capped: bool,
    ranges: dict[str, tuple[float, float]],
    fixed: dict[str, float],
    step: dict[str, float],
    angles: str,
    free_names: list[str],
    user_scale: Array,
    user_pose: Any,
    options: dict[str, Any],
) -> Certificate:
    """The certificate from the decided boxes (sorted by lower corner), witnesses labelled."""
    from .roots import _factor

    names = _functions(problem)
    statements = problem.model.functions()
    order = sorted(range(len(decided)), key=lambda i: tuple(decided[i][0]))
    lows = np.array([decided[i][0] for i in order]) / user_scale
    highs = np.array([decided[i][1] for i in order]) / user_scale
    factors: dict[str, str | None] = {}
    boxes = []
    for row, i in enumerate(order):
        _, _, status, which, bracket, zero = decided[i]
        witness = None
        if status == 1:
            name = names[which]
            label = name.split(":")[0]
            pose = user_pose(zero)
            if label not in factors:
                # the witness, else the box's centre: where a factor's point degenerates at the zero
                # (the Veloce's s_I = 0) the diagram is read beside it
                centre = user_pose(0.5 * (decided[i][0] + decided[i][1]))
                unit = np.array([angle_factor(angles) if n in mechanism.angle_names else 1.0
                                 for n in mechanism.pose_names])
                api = np.array([[at[n] for n in mechanism.pose_names] for at in (pose, centre)]) * unit
                factors[label] = _factor(mechanism, api, label, options, None)
            witness = Witness(
                pose, label, factors[label], statements[name], (user_pose(bracket[0]), user_pose(bracket[1]))
            )
        bounds = {n: (float(lows[row, j]), float(highs[row, j])) for j, n in enumerate(free_names)}
        boxes.append(CertifiedBox(STATUSES[status], bounds, witness))
    volume = np.prod(highs - lows, axis=1) if len(lows) else np.zeros(0)
    total = float(volume.sum()) or 1.0
    codes = np.array([STATUSES.index(b.status) for b in boxes], dtype=int)
    totals = {s: int(np.sum(codes == k)) for k, s in enumerate(STATUSES)}
    fractions = {s: float(volume[codes == k].sum() / total) for k, s in enumerate(STATUSES)}
    return Certificate(
        mechanism.name,
        ranges,
        {k: v for k, v in fixed.items() if k not in ranges},
        problem.kinds,
        step,
        tuple(boxes),
        totals,
        fractions,
        capped,
        evaluated,
        angles,
        lows,
        highs,
    )


@dataclass(frozen=True)
class PathInterval:
    """A run of boxes of one status along a path ``start + t (end - start)`` that are not free.

    Attributes
    ----------
    status : str
        ``"singular"``, ``"undecided"`` or ``"unreachable"``.
    enclosure : tuple of float
        ``(t_lo, t_hi)``: outside the runs the path is proved free.
    label : str or None
        The kind whose function changes sign in it (singular runs).
    t : float or None
        The refined zero of that function (singular runs).
    """

    status: str
    enclosure: tuple[float, float]
    label: str | None = None
    t: float | None = None


def certify_path(
    mechanism: Any,
    start: Any,
    end: Any,
    *,
    kinds: Sequence[str] = KINDS,
    mode: Any = None,
    resolution: float = 2.0**-20,
    max_boxes: int = DEFAULT_MAX_BOXES,
) -> tuple[tuple[PathInterval, ...], bool]:
    """Pave the straight path ``start + t (end - start)``, ``t ∈ [0, 1]`` (API units, radians).

    Parameters
    ----------
    mechanism : Mechanism
    start, end : array_like, shape (n,)
        API-unit poses.
    kinds : sequence of str
    mode : mapping or sequence, optional
    resolution : float
        In ``t``.
    max_boxes : int

    Returns
    -------
    intervals : tuple of PathInterval
        The runs of adjacent boxes of one status and label that are not free, in order.
    capped : bool

    Examples
    --------
    >>> runs, _ = certify_path(load_mechanism("quattro"), [-300, -1, -750, 0], [300, 1, -750, 0])
    >>> [(r.status, r.label, round(r.t, 9)) for r in runs]       # y = 0 crossed at t = 1/2
    [('singular', 'constraint', 0.5)]
    """
    _check_mechanism(mechanism)
    options = _options(mechanism, mode)
    model = model_of(mechanism, options)
    chosen = _checked_kinds(kinds)
    a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    step = _real(resolution, "resolution")
    if not step > 0:
        raise ScrewkitValueError(f"Expected `resolution` > 0, got {resolution!r}.")
    difference = b - a
    problem = _Problem(
        model,
        a,
        np.nextafter(difference, -np.inf)[:, None],
        np.nextafter(difference, np.inf)[:, None],
        chosen,
        np.array([step]),
    )
    decided, _, capped = _pave(problem, np.zeros((1, 1)), np.ones((1, 1)), max_boxes=max_boxes)
    names = _functions(problem)
    runs: list[PathInterval] = []
    for lo, hi, status, which, _, zero in sorted(decided, key=lambda d: float(d[0][0])):
        if status == 0:
            continue
        label = names[which].split(":")[0] if status == 1 else None
        last = runs[-1] if runs else None
        if (
            last is not None
            and last.status == STATUSES[status]
            and last.label == label
            and last.enclosure[1] == float(lo[0])
        ):
            runs[-1] = PathInterval(last.status, (last.enclosure[0], float(hi[0])), label, last.t)
        else:
            runs.append(
                PathInterval(
                    STATUSES[status],
                    (float(lo[0]), float(hi[0])),
                    label,
                    float(zero[0]) if status == 1 else None,
                )
            )
    return tuple(runs), capped
