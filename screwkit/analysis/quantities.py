"""The quantities a map, a locus or a path reads over a posed batch, from the posed mechanism.

Quantities (:data:`QUANTITIES`)
-------------------------------
``"verdict"``
    The core's code per pose: bit 1 constraint, 2 actuation, 4 serial (0 regular,
    :attr:`screwkit.core.verdicts.SingularityReport.codes`); ``-1`` where the pose is out of reach.
``"closeness"``, ``"closeness:constraint"``, ``"closeness:actuation"``, ``"closeness:serial"``
    The core's closeness measures (:mod:`screwkit.core.singularity`), ``"closeness"`` their minimum.
``"det_A"``, ``"det_B"``
    Determinants of the forward and inverse Jacobians ``A χ̇ = B θ̇``
    (:class:`screwkit.core.jacobian_matrices.Jacobians`; paper 004 Eq. 6).
``"lti"``, ``"kappa"``, ``"zeta"``
    The local transmission index ``η = min(κ, ζ)`` of paper 004 Eq. (16), its motion index ``κ``
    and force index ``ζ`` (Eq. 15) (:func:`screwkit.papers.paper_004.transmission`; four-limb
    families). A paper's quantity is registered by name (:func:`register_quantity`; ``import
    screwkit`` registers paper 004's), so that the maps call no paper.
``"wrench_lti"``
    The wrench-based local transmission index of any mechanism, a catalog robot or a graph (the
    report's "LTI (wrench-based)"): the least input and output transmission over the actuated joints,
    from the actuation wrenches and the platform twists
    (:attr:`screwkit.robots.posed.PosedMechanism.wrench_transmission`,
    :func:`screwkit.robots.transmission.wrench_transmission`). Paper 004's ``"lti"`` is defined on the
    four-limb geometry only.
``"condition:K"``
    The vector form of the K-th factor of the superbracket (:mod:`screwkit.gca.conditions`), factored
    once at the default pose and evaluated on the wrench diagram's points over the whole batch
    (:meth:`screwkit.robots.posed.PosedMechanism.diagram_points`); a
    :class:`~screwkit.exceptions.DegenerateGeometryError` names the pose where a point of the
    diagram does not exist (e.g. a limb at a serial singularity has no actuation line).

Every value comes from the posed mechanism (:class:`~screwkit.robots.posed.PosedMechanism`, the one
composer over poses): its codes, closeness, Jacobians, diagram points and superbracket.

Examples
--------
>>> values(load_mechanism("h4").at([[0, 0, -750, 0], [0, 0, -800, 0]]), "verdict").tolist()
[0, 0]
"""

from __future__ import annotations

import re
import weakref
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..core.verdicts import LABELS
from ..exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError

__all__ = [
    "CONTRIBUTED", "KINDS", "QUANTITIES", "QuantityDisplay", "checked_condition", "conditions_of", "display",
    "quantity", "register_quantity", "values", "verdict_name",
]

Array = np.ndarray

#: The quantities a map can show (``"condition:K"`` for any K too).
QUANTITIES = (
    "verdict",
    "closeness",
    "closeness:constraint",
    "closeness:actuation",
    "closeness:serial",
    "det_A",
    "det_B",
    "lti",
    "kappa",
    "zeta",
    "wrench_lti",
)
#: The kinds of singularity, by bit of the core's codes.
KINDS = LABELS  # the verdict codes' bits, as the core defines them


def verdict_name(code: int) -> str:
    """The words of a ``"verdict"`` map's code (module docstring).

    Parameters
    ----------
    code : int
        A code of the ``"verdict"`` quantity (``-1``: out of reach).

    Returns
    -------
    str

    Examples
    --------
    >>> [verdict_name(c) for c in (-1, 0, 2, 5)]
    ['out of reach', 'regular', 'actuation', 'constraint+serial']
    """
    if code < 0:
        return "out of reach"
    return "+".join(kind for bit, kind in enumerate(KINDS) if code >> bit & 1) or "regular"


def quantity(quantity: Any) -> str:
    """A quantity's name checked, its aliases resolved (``"detA"``, ``"detB"``, ``"condition"``).

    Parameters
    ----------
    quantity : str
        One of :data:`QUANTITIES`, an alias, or ``"condition:K"``.

    Returns
    -------
    str
        The quantity's name.

    Raises
    ------
    ScrewkitTypeError, ScrewkitValueError
        Not a string, or an unknown quantity.

    Examples
    --------
    >>> quantity("detA"), quantity("condition")
    ('det_A', 'condition:0')
    """
    if not isinstance(quantity, str):
        raise ScrewkitTypeError(f"Expected `quantity` to be a str, got {type(quantity).__name__}.")
    aliases = {"detA": "det_A", "detB": "det_B", "condition": "condition:0"}
    name = aliases.get(quantity, quantity)
    if name in QUANTITIES:
        return name
    index = name[len("condition:") :]
    if name.startswith("condition:") and index.isascii() and index.isdigit():  # not '²' or '١'
        return name
    raise ScrewkitValueError(
        f"Expected `quantity` to be one of {[*QUANTITIES, 'condition:K']}, got {quantity!r}."
    )

@dataclass(frozen=True)
class QuantityDisplay:
    r"""How a quantity is named on a figure: a label, its symbol, its unit and whether it is signed.

    Attributes
    ----------
    label : str
        In words, e.g. ``"local transmission index"``.
    symbol : str
        matplotlib mathtext, e.g. ``"$\\eta$"``, or plain text (``"det A"``).
    unit : str
        ``""`` for a dimensionless quantity; ``"{length}"`` stands for the map's length unit and
        ``"{length}^{k}"`` for its power ``k`` = the number of angle coordinates (the rotations among
        the nominal twists, each a column of ``A`` whose entries are moments).
    signed : bool
        True for a quantity whose sign matters (drawn with a diverging colour map centred at 0).
    meaning : str
        Its range and what its zero means.
    """

    label: str
    symbol: str
    unit: str = ""
    signed: bool = False
    meaning: str = ""

    def axis_label(self, length_unit: str = "", angle_count: int = 0) -> str:
        r"""The colour-bar or axis label: ``"symbol, label (unit)"``.

        Parameters
        ----------
        length_unit : str, optional
            The map's length unit (for ``{length}`` in :attr:`unit`).
        angle_count : int, optional
            The number of angle coordinates (for ``{k}``).

        Returns
        -------
        str

        Examples
        --------
        >>> display("det_A").axis_label("mm", 1), display("det_A").axis_label("m", 2)[-9:]
        ('det A, determinant of the forward Jacobian (mm)', '(m$^{2}$)')
        >>> display("lti").axis_label()
        '$\\eta$, local transmission index (dimensionless)'
        """
        unit = self.unit.replace("{length}^{k}", "{length}" if angle_count == 1 else "{length}^{k}")
        unit = unit.format(length=length_unit or "length unit", k=angle_count) if unit else "dimensionless"
        unit = re.sub(r"\^(\w+)", r"$^{\1}$", unit)
        return f"{self.symbol}, {self.label} ({unit})"


_CLOSE = "0 at a singularity; a relative distance that may exceed 1"
#: How each quantity is shown (:class:`QuantityDisplay`); :func:`register_quantity` may add to it.
_DISPLAY: dict[str, QuantityDisplay] = {
    "verdict": QuantityDisplay("verdict", "verdict", meaning="bit 1 constraint, 2 actuation, 4 serial"),
    "closeness": QuantityDisplay("closeness to a singularity (minimum of the three)", "$c$", meaning=_CLOSE),
    "closeness:constraint": QuantityDisplay("closeness to a constraint singularity", "$c_c$", meaning=_CLOSE),
    "closeness:actuation": QuantityDisplay("closeness to an actuation singularity", "$c_a$", meaning=_CLOSE),
    "closeness:serial": QuantityDisplay("closeness to a serial singularity", "$c_s$", meaning=_CLOSE),
    "det_A": QuantityDisplay(
        "determinant of the forward Jacobian", "det A", "{length}^{k}", True,
        "0 at a direct (actuation) singularity; rows unit actuation forces",
    ),
    "det_B": QuantityDisplay(
        "determinant of the inverse Jacobian", "det B", "{length}^r, r revolute actuators", True,
        "0 at an inverse (serial) singularity; rows unit actuation forces",
    ),
    "lti": QuantityDisplay("local transmission index", "$\\eta$", meaning="in [0, 1]; 0 at a singularity"),
    "kappa": QuantityDisplay("motion transmission index", "$\\kappa$", meaning="in [0, 1]"),
    "zeta": QuantityDisplay("force transmission index", "$\\zeta$", meaning="in [0, 1]"),
    "wrench_lti": QuantityDisplay(
        "local transmission index (wrench-based)", "LTI", meaning="in [0, 1]; 0 at a singularity"
    ),
}


def display(name: str) -> QuantityDisplay:
    """How a quantity is named on a figure (:class:`QuantityDisplay`); ``"condition:K"`` included.

    Parameters
    ----------
    name : str
        A quantity (:func:`quantity` resolves aliases).

    Returns
    -------
    QuantityDisplay

    Raises
    ------
    ScrewkitValueError
        For an unknown quantity.

    Examples
    --------
    >>> display("condition:1").signed, display("closeness:actuation").symbol
    (True, '$c_a$')
    """
    name = quantity(name)
    if name.startswith("condition:"):
        index = name.split(":")[1]
        return QuantityDisplay(
            "its vector form", f"condition {index}", "{length}^p", True,
            "0 where the condition holds; p: the form's degree in point coordinates",
        )
    return _DISPLAY[name]


#: The quantities of :data:`QUANTITIES` that :func:`register_quantity` provides (a paper's indices).
CONTRIBUTED = ("lti", "kappa", "zeta")

#: Quantities computed outside the stages below this one (a paper's indices), by name: a function
#: ``(posed) -> values`` per pose (:func:`register_quantity`).
_REGISTERED: dict[str, Callable[[Any], Any]] = {}


def register_quantity(
    name: str,
    function: Callable[[Any], Any],
    *,
    label: str | None = None,
    symbol: str | None = None,
    unit: str | None = None,
    signed: bool | None = None,
) -> None:
    """Register how a quantity of :data:`QUANTITIES` is computed over a posed batch, and optionally
    how it is named on figures (:class:`QuantityDisplay`; what is not given is kept).

    The stages above the maps (a paper's analysis, :mod:`screwkit.papers`) contribute their
    quantities this way, so that the maps call them without importing them.

    Parameters
    ----------
    name : str
        One of :data:`QUANTITIES` not computed here (``"lti"``, ``"kappa"``, ``"zeta"``).
    function : callable
        ``function(posed) -> numpy.ndarray`` of the batch's shape.
    label, symbol, unit, signed : optional
        Its display (:class:`QuantityDisplay`), replacing the registered one's fields.

    Returns
    -------
    None

    Examples
    --------
    >>> register_quantity("lti", _REGISTERED["lti"])  # what import screwkit did
    >>> register_quantity("volume", len)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `name` to be one of ('lti', 'kappa', 'zeta'), ...
    """
    if name not in CONTRIBUTED:
        raise ScrewkitValueError(f"Expected `name` to be one of {CONTRIBUTED}, got {name!r}.")
    if not callable(function):
        raise ScrewkitTypeError(f"Expected `function` to be callable, got {type(function).__name__}.")
    _REGISTERED[name] = function
    given: dict[str, Any] = {"label": label, "symbol": symbol, "unit": unit, "signed": signed}
    _DISPLAY[name] = replace(_DISPLAY[name], **{k: v for k, v in given.items() if v is not None})




def checked_condition(mechanism: Any, options: Mapping[str, Any], index: int) -> tuple[Any, tuple[Any, ...]]:
    """The wrench diagram and the superbracket's conditions (:func:`conditions_of`), refusing a
    condition index out of range: what a map of ``"condition:K"`` checks before its poses.

    Parameters
    ----------
    mechanism : Mechanism
    options : mapping
        Inverse-kinematics options (a working mode).
    index : int
        The ``K`` of ``"condition:K"``.

    Returns
    -------
    diagram : WrenchDiagram
    conditions : tuple of Condition

    Raises
    ------
    ScrewkitValueError
        For ``K`` out of range, or a degenerate wrench diagram.

    Examples
    --------
    >>> _, conditions = checked_condition(load_mechanism("h4"), {}, 1)
    >>> len(conditions)
    2
    """
    diagram, conditions, _, _ = conditions_of(mechanism, options)
    if not 0 <= index < len(conditions):
        raise ScrewkitValueError(
            f"Expected `quantity` 'condition:K' with K in 0..{len(conditions) - 1} (the superbracket's "
            f"factors at the default pose), got K = {index}."
        )
    return diagram, conditions


def _condition_values(mechanism: Any, index: int, posed: Any) -> Array:
    """The ``index``-th superbracket condition at every pose of ``posed``, as one batch: the
    diagram's points over the batch (:meth:`screwkit.robots.posed.PosedMechanism.diagram_points`)
    and the condition's vector form on them
    (:meth:`screwkit.gca.conditions.Condition.evaluate`).

    Raises
    ------
    DegenerateGeometryError
        Where a point of the diagram does not exist at a pose (naming the point and the pose).
    """
    diagram, conditions = checked_condition(mechanism, posed.options, index)
    points, exists = posed.diagram_points(diagram.points)
    if not exists.all():
        i = int(np.argmin(exists))
        point = next(p for p in diagram.points if not np.isfinite(points[p.label][i]).all())
        raise DegenerateGeometryError(
            f"Expected every point of the wrench diagram to exist for {posed.mechanism.name!r}'s "
            f"conditions, got point {point.label} ({point.description}) missing at the pose "
            f"{np.asarray(posed.poses[i]).tolist()} (API units)."
        )
    return np.asarray(conditions[index].evaluate(points), dtype=float).reshape(len(posed))

#: Per mechanism (held weakly: a cache entry dies with its mechanism) and options: the factored
#: superbracket's diagram, conditions, labels and values at the default pose.
_CONDITIONS: weakref.WeakKeyDictionary[Any, dict[tuple[Any, ...], Any]] = weakref.WeakKeyDictionary()


def conditions_of(
    mechanism: Any, options: Mapping[str, Any]
) -> tuple[Any, tuple[Any, ...], tuple[str, ...], Array]:
    """The wrench diagram, superbracket conditions, their labels and their values at the default
    pose (factored once per mechanism and mode, from the posed mechanism's superbracket).

    Parameters
    ----------
    mechanism : Mechanism
    options : mapping
        Inverse-kinematics options (a working mode).

    Returns
    -------
    diagram : WrenchDiagram
    conditions : tuple of Condition
    labels : tuple of str
        ``"constraint"`` or ``"actuation"`` per condition.
    values : numpy.ndarray
        The conditions at the default pose.

    Raises
    ------
    ScrewkitValueError
        If the mechanism's wrench diagram is degenerate.

    Examples
    --------
    >>> diagram, conditions, labels, reference = conditions_of(load_mechanism("h4"), {})
    >>> len(conditions) == len(labels) == len(reference)
    True
    """
    key = tuple(sorted((k, repr(v)) for k, v in options.items()))
    cache = _CONDITIONS.setdefault(mechanism, {})
    if key not in cache:
        pose = mechanism.at(None, **options)[0]
        diagram = pose.diagram
        if diagram.degenerate:
            raise ScrewkitValueError(
                f"Expected a wrench diagram to factor for the conditions, got a degenerate one: "
                f"{'; '.join(diagram.degenerate)}."
            )
        result = pose.superbracket
        cache[key] = (diagram, result.conditions, result.labels, np.array(result.values, dtype=float))
    return cache[key]


def values(posed: Any, quantity: str) -> Array:
    """One quantity over a posed batch of reachable poses, from the posed mechanism.

    Parameters
    ----------
    posed : PosedMechanism
        The poses (all reachable).
    quantity : str
        A checked name (:func:`quantity`).

    Returns
    -------
    numpy.ndarray, shape (m,)
        int64 codes for ``"verdict"``, else float.

    Raises
    ------
    ScrewkitValueError
        A paper's quantity for a mechanism it does not apply to, or a condition index out of range.
    DegenerateGeometryError
        A condition where a point of the wrench diagram does not exist.

    Examples
    --------
    >>> lti = values(load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]]), "lti")
    >>> lti.shape, bool(((0 < lti) & (lti <= 1)).all())
    ((2,), True)
    """
    if quantity == "verdict":
        return np.asarray(posed.codes, dtype=np.int64)
    if quantity == "closeness":
        return np.min(np.stack([np.asarray(posed.closeness[k], dtype=float) for k in KINDS]), axis=0)
    if quantity.startswith("closeness:"):
        return np.asarray(posed.closeness[quantity.split(":")[1]], dtype=float)
    if quantity in ("det_A", "det_B"):
        return np.asarray(getattr(posed.jacobians, quantity), dtype=float)
    if quantity == "wrench_lti":
        return np.asarray(posed.wrench_transmission.lti, dtype=float)
    if quantity in CONTRIBUTED:
        if quantity not in _REGISTERED:  # only when screwkit's own __init__ did not run to its end
            raise ScrewkitValueError(f"Expected quantity {quantity!r} to be registered (register_quantity).")
        return np.asarray(_REGISTERED[quantity](posed), dtype=float)
    return _condition_values(posed.mechanism, int(quantity.split(":")[1]), posed)
