"""The one pass of the batched core: a joint table's wrench systems over its batch (private).

For a mechanism's joint table, with its structure analysed once (:mod:`screwkit.graphs.topology`):
the frames of one program (:mod:`screwkit.core._program`), the limbs' actuation wrenches
(:mod:`screwkit.core._limbs`, made lines by :mod:`screwkit.core.line_search`; a compound leg
analysed as a whole where a limb's own wrench fails, :mod:`screwkit.core._compound_legs`), and the
closing steps (:mod:`screwkit.core._closing`). :func:`wrench_pass` returns the fields of a
:class:`~screwkit.core.wrench_systems.WrenchAnalysis` (the module docstring of
:mod:`screwkit.core.wrench_systems` states what they are).

Examples
--------
>>> from screwkit.graphs.jointtable import JointTable
>>> checked_lengths(2, (3,))
array([2., 2., 2.])
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..algebra.checks import MIN_LENGTH_SCALE, checked_length_scale
from ..algebra.reference_frame import scaled_frame, unit_scaled
from ..exceptions import ScrewkitValueError, TwistGraphError
from ..graphs.jointtable import JointTable
from ..graphs.topology import Topology, topology
from . import _closing as CK
from . import _limbs as LK
from . import _residuals as R
from . import frames as F
from ._compound_legs import apart_from_legs, compound_legs, coupled_limbs, leg_of, leg_residuals
from ._leg_weights import spanned_spines, weighted_legs
from ._program import Evaluation, Frame, Request, stacked
from .line_search import LINE_RTOL, line_search, nearest_lines

__all__ = [
    "actuated_screws", "canonical", "checked_dof", "checked_lengths", "limb_frame", "scalar", "wrench_pass",
]

Array = np.ndarray


def limb_frame(frame: Frame, k: int) -> Frame:
    """Limb ``k``'s frame from :func:`~screwkit.core._program.stacked` frames.

    Parameters
    ----------
    frame : tuple of numpy.ndarray
        Stacked frames.
    k : int
        A limb.

    Returns
    -------
    tuple of numpy.ndarray
    """
    return frame[0][..., k, :, :], frame[1][..., k]


def canonical(table: JointTable) -> JointTable:
    """The table with its joints sorted by name: every route to the same mechanism (a family's
    table, a graph's, a graph rebuilt from a table) then runs the same arithmetic in the same order,
    bit for bit; its screws C-contiguous, so that a pose's sums run in one order whatever the batch
    it is in (a strided reduction adds in another).

    Parameters
    ----------
    table : JointTable

    Returns
    -------
    JointTable
        The table itself when already so.
    """
    order = sorted(range(len(table.specs)), key=lambda k: table.specs[k].name)
    if order == list(range(len(order))) and table.screws.flags.c_contiguous:
        return table
    starts = list(itertools.accumulate((spec.dof for spec in table.specs), initial=0))
    rows = [r for k in order for r in range(starts[k], starts[k + 1])]
    specs = tuple(table.specs[k] for k in order)
    screws = np.ascontiguousarray(table.screws[..., rows, :])
    return JointTable(
        table.base, table.platform, specs, screws, table.dof, table.anchor, table.mobility, table.free
    )


def checked_dof(dof: Any, table: JointTable, top: Topology) -> int:
    """The nominal mobility: ``dof``, else the table's, else the number of actuated joints (at most 6:
    a first guess, settled by :func:`screwkit.core.mobility.settled_dof`).

    Parameters
    ----------
    dof : int or None
    table : JointTable
    top : Topology

    Returns
    -------
    int

    Raises
    ------
    TwistGraphError
        If it is not an integer in 0..6.
    """
    nominal = dof if dof is not None else (table.dof if table.dof is not None else min(len(top.limbs), 6))
    if not B.is_dof(nominal):
        raise TwistGraphError(f"Expected `dof` to be an integer in 0..6, got {nominal!r}.")
    return int(nominal)


def checked_lengths(value: Any, batch: tuple[int, ...]) -> Array | None:
    """A given characteristic length as an array of the batch shape (None: derive it).

    Parameters
    ----------
    value : float, array_like or None
    batch : tuple of int

    Returns
    -------
    numpy.ndarray or None

    Raises
    ------
    ScrewkitValueError
        If a length is not positive and finite in the allowed range, or the shape does not broadcast.

    Examples
    --------
    >>> checked_lengths(2, (3,))
    array([2., 2., 2.])
    >>> checked_lengths([1.0, -1.0], (2,))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `length_scale` to be positive finite numbers in ...
    """
    if value is None or np.ndim(value) == 0:
        checked = checked_length_scale(value, allow_none=True)
        return None if checked is None else np.full(batch, checked)
    try:
        lengths = np.array(np.broadcast_to(np.asarray(value, dtype=float), batch))
    except (TypeError, ValueError) as err:
        got = repr(value) if isinstance(value, str) else f"shape {np.shape(value)}"
        raise ScrewkitValueError(
            f"Expected `length_scale` to be a positive number or an array of the batch shape {batch}, "
            f"got {got}."
        ) from err
    smallest = MIN_LENGTH_SCALE
    if not np.all(np.isfinite(lengths) & (lengths >= smallest) & (lengths * smallest <= 1)):
        raise ScrewkitValueError(
            f"Expected `length_scale` to be positive finite numbers in [{smallest:g}, {1 / smallest:g}], "
            f"got {lengths}."
        )
    return lengths


def actuated_screws(top: Topology, screws: Array) -> Array:
    """Each limb's actuated joint's screw with the limb's sign ``(..., n, 6)`` (one gather).

    Parameters
    ----------
    top : Topology
    screws : numpy.ndarray, shape (..., rows, 6)

    Returns
    -------
    numpy.ndarray, shape (..., n, 6)
    """
    columns = [top.columns[plan.index] for plan in top.limbs]
    signs = np.array([float(plan.sign) for plan in top.limbs])
    gathered = screws[..., columns, :]  # a new array: signed in place (no second one)
    gathered *= signs[:, None]
    return gathered


def scalar(value: Any) -> Any:
    """A 0-d array as a Python scalar, anything else unchanged.

    Parameters
    ----------
    value : object

    Returns
    -------
    object
    """
    array = np.asarray(value)
    return array.item() if array.ndim == 0 else value


def _checked_kept(keys: Iterable[str], top: Topology) -> tuple[str, ...]:
    """The frames a lean pass keeps (``kept`` of :func:`wrench_pass`): each ``"constraint"``,
    ``"leg{k}:W"`` of a leg or, for a series-parallel tree, ``"node{i}"`` of a node.

    Parameters
    ----------
    keys : iterable of str
    top : Topology

    Returns
    -------
    tuple of str
        Without repeats, in order.

    Raises
    ------
    ScrewkitValueError
        Naming a key that is none of these.

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointSpec
    >>> top = topology("B", "E", (JointSpec("R1", "R", "B", "E", 1, True),))
    >>> _checked_kept(["node0", "constraint", "node0"], top)
    ('node0', 'constraint')
    >>> _checked_kept(["node1"], top)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `kept` to name frames among [...], got 'node1'.
    """
    legs = 1 if top.network else len(top.legs)
    nodes = 0 if top.network else len(top.nodes)
    allowed = ["constraint", *(f"leg{k}:W" for k in range(legs)), *(f"node{i}" for i in range(nodes))]
    keys = tuple(dict.fromkeys(keys))
    for key in keys:
        if key not in allowed:
            raise ScrewkitValueError(f"Expected `kept` to name frames among {allowed}, got {key!r}.")
    return keys


def wrench_pass(
    table: JointTable,
    *,
    dof: Any,
    rtol: float,
    length_scale: Any,
    views: bool,
    kept: Callable[[Topology], Iterable[str]] | None = None,
) -> dict[str, Any]:
    """The wrench systems of a joint table over its batch: the fields of a
    :class:`~screwkit.core.wrench_systems.WrenchAnalysis` (the one pass under
    :func:`~screwkit.core.wrench_systems.analyze_table`, which documents the arguments).

    Parameters
    ----------
    table : JointTable
    dof : int or None
    rtol : float
        Already checked.
    length_scale : float, array_like or None
    views : bool
    kept : callable, optional
        Without the views: ``kept(topology)`` names further frames to keep.

    Returns
    -------
    dict
        The keyword arguments of the analysis.

    Examples
    --------
    >>> line = [0, 0, 1.0, 0, 0, 0]
    >>> table = JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[line]] * 2, True)])
    >>> wrench_pass(table, dof=None, rtol=1e-9, length_scale=None, views=False)["constraint_order"]
    array([5, 5])
    """
    table = canonical(table)
    top = topology(table.base, table.platform, table.specs)
    nominal = checked_dof(dof, table, top)
    batch = table.batch_shape
    screws = table.screws
    given_length = checked_lengths(length_scale, batch)
    wanted = () if views or kept is None else _checked_kept(kept(top), top)
    if given_length is None:  # the frame's own length, with the scaled screws in the same pass
        centre, length, scaled = scaled_frame(screws, table.anchor)
        assert scaled is not None
    else:  # the reference point as derived, the given length
        centre, _, _ = scaled_frame(screws, table.anchor, scale=False)
        length = given_length
        scaled = unit_scaled(screws, centre, length)
    requests: tuple[Request, ...] = ()
    if not top.network:  # every frame the analysis needs, in one program
        assert top.root is not None
        requests = (
            ("twists", top.root),
            ("wrenches", top.root),  # the constraint system (paper 002 Eq. 3), spanned by the legs'
            *((("twists", i) for i in top.legs) if views else ()),
            *(("wrenches", i) for i in top.legs),
            *(("sum", tuple(plan.siblings)) for plan in top.limbs),
            *(("passive", tuple(plan.siblings)) for plan in top.limbs),
            *((("twists", i) for i in range(len(top.nodes))) if views else ()),
            *(("twists", int(key[4:])) for key in wanted if key.startswith("node")),
            *(("wrenches", i) for _, nodes in spanned_spines(top) for n, c in nodes for i in (n, *c)),
        )
        requests = tuple(dict.fromkeys(requests))
    core = Evaluation(top, scaled, rtol, requests)
    frames: dict[str, Frame] = {}
    leg_block: Array | None = None
    if top.network:
        platform = core.network(tuple(range(len(top.specs))))
        leg_wrenches = [F.reciprocal(*platform)]
        leg_twists = [platform]
    else:
        assert top.root is not None
        platform = core.twists(top.root)
        leg_twists = [core.twists(i) for i in top.legs] if views else []
        leg_wrenches = [core.wrenches(i) for i in top.legs]
        leg_block = core.stacked([("wrenches", i) for i in top.legs])[0]  # a view of the program's block
    constraint = F.reciprocal(*platform) if top.network or top.root is None else core.wrenches(top.root)
    legs = leg_block if leg_block is not None else np.stack([w[0] for w in leg_wrenches], axis=-3)
    n = len(top.limbs)
    free: tuple[Array | None, Array]
    if n and top.network:  # each limb's sub-network by loop closure
        lockeds, frees, perpendiculars, serials, twists = [], [], [], [], []
        for plan in top.limbs:
            twist = plan.sign * core.joint_rows(plan.index)[..., 0, :]
            lockeds.append(core.network(plan.network_edges, locked=plan.index))
            frees.append(core.network(plan.network_edges))
            perpendiculars.append(R.residual(twist[..., None, :], lockeds[-1][0])[..., 0, :])
            serials.append(frees[-1][1] == lockeds[-1][1])
            twists.append(twist)
        serial = np.stack(serials, axis=-1)
        actuated = np.stack(twists, axis=-2)
        perpendicular = np.stack(perpendiculars, axis=-2)
        locked, free = stacked(lockeds), stacked(frees)
        passive = F.reciprocal(*locked)
        direction = LK.actuation_directions(passive[0], perpendicular)
    elif n:  # the limbs on an axis of their own (..., n, ...), their locked systems from the program
        locked = core.stacked([("sum", tuple(plan.siblings)) for plan in top.limbs])
        passive = core.stacked([("passive", tuple(plan.siblings)) for plan in top.limbs])
        actuated = actuated_screws(top, scaled)
        coupled = coupled_limbs(top)
        serial, order, direction, wrench, transmissions, own_residuals, not_line = LK.limb_wrenches(
            locked[0], locked[1], passive[0], actuated, legs, np.array(coupled, dtype=np.int64),
            np.array([leg_of(top, k) for k in coupled], dtype=np.int64), rtol, LINE_RTOL,
        )  # in one pass; the free rows only for the views, else where a line is searched
        free_rows = LK.limb_systems(locked[0], locked[1], passive[0], actuated, rtol)[2] if views else None
        free = (free_rows, order)
        del free_rows  # held by `free` alone, freed with it
    if n:
        # the limbs' constraint systems (reciprocal to `free`): kept for the views, else computed only
        # where an actuation wrench is searched for a line (nearest_lines; at a few poses, if any)
        limb_constraint: Frame | None = None
        if views:
            assert free[0] is not None
            limb_constraint = F.reciprocal(free[0], free[1])

        def limb_constraints_at(where: Array) -> Array:
            if limb_constraint is not None:
                return limb_constraint[0][where]
            if free[0] is not None:
                return F.reciprocal(free[0][where], free[1][where])[0]
            at = (locked[0][where], locked[1][where], passive[0][where], actuated[where])
            rows = LK.limb_systems(*at, rtol)[2]
            assert rows is not None
            return F.reciprocal(rows, free[1][where])[0]

        if top.network:
            lines = nearest_lines(direction, limb_constraints_at, 6 - free[1])
            wrench, transmissions = LK.transmissions(lines, actuated, rtol)
            residuals = leg_residuals(top, wrench, legs)
        else:  # where a direction is no line: the line found (nearest_lines), its wrench again
            residuals = own_residuals if coupled else None
            searched = not_line & (6 - free[1] > 0)
            if searched.any():
                lines = direction.copy()
                lines[searched] = line_search(
                    direction[searched], limb_constraints_at(searched), (6 - free[1])[searched]
                )
                again = searched.any(axis=-1)
                wrench[again], transmissions[again] = LK.transmissions(lines[again], actuated[again], rtol)
                if residuals is not None:
                    residuals[again] = leg_residuals(top, wrench[again], legs[again])
        branch, locked_legs = wrench, None
        compound = compound_legs(
            top, scaled, rtol, leg_wrenches, actuated, (wrench, serial, transmissions), residuals
        )
        if compound is not None:
            serial, wrench, branch, transmissions, locked_legs = compound
        wrench_rows = np.where(serial[..., None], 0.0, wrench)
        if compound is not None:  # the replaced limbs' wrenches measured again
            residuals = leg_residuals(top, wrench_rows, legs)
        elif residuals is not None:  # a serial limb's row is zero, and so is its residual (exactly)
            residuals = np.where(serial[..., coupled_limbs(top), None], 0.0, residuals)
        for k in range(n):
            frames[f"limb{k}:passive"] = limb_frame(passive, k)  # the Jacobians' rows at serial singularities
            if views:
                assert free[0] is not None and limb_constraint is not None
                frames[f"limb{k}:T"] = limb_frame((free[0], free[1]), k)
                frames[f"limb{k}:W"] = limb_frame(limb_constraint, k)
        del free, limb_constraint  # (..., n, 6, 6) each: not alive while the closeness inputs are built
    else:
        serial, transmissions = np.zeros((*batch, 0), dtype=bool), np.zeros((*batch, 0))
        wrench_rows = branch = np.zeros((*batch, 0, 6))
        locked_legs, residuals = None, None
    # the global frame; the legs' stacked constraint wrenches as six rows with their singular
    # values (CK.triangular: two 6×6 SVDs instead of (6 legs + n) × 6 ones), their singular values on
    # demand (WrenchAnalysis.closeness); the actuation rows in the user's frame
    apart = apart_from_legs(top, wrench_rows, residuals)
    global_rows, global_order, constraint_factor, actuation_factor, actuation_rows = CK.closing(
        constraint[0], wrench_rows, legs, apart, serial, centre, length, rtol
    )
    global_frame = (global_rows, global_order)
    if not top.network and spanned_spines(top):  # legs weighed by their branches' independence
        weighted = weighted_legs(core, legs, spanned_spines(top))
        constraint_factor = CK.packed(CK.triangular(np.reshape(weighted, (*batch, -1, 6))))
    closeness_factors = {"constraint": constraint_factor, "actuation": actuation_factor}
    if locked_legs is not None:  # where a compound leg was analysed as a whole
        locked_legs.add_to(global_frame, constraint, wrench_rows, rtol)
    frames["platform"] = platform  # the Jacobians' nominal twists are checked against it
    if views:  # else recomputed for the one pose that asks (WrenchAnalysis._add_views)
        frames.update(constraint=constraint, uncontrolled=F.reciprocal(*global_frame))
        frames["global"] = global_frame
    if views and not top.network:  # every node's twists, for the per-pose series-parallel tree
        for index in range(len(top.nodes)):
            frames[f"node{index}"] = core.twists(index)
    if wanted:  # what kept() named, out of the frames computed above or in the program
        known = {"constraint": constraint, **{f"leg{k}:W": w for k, w in enumerate(leg_wrenches)}}
        frames.update({key: known[key] if key in known else core.twists(int(key[4:])) for key in wanted})
    if views:
        for k, (twist_frame, wrench_frame) in enumerate(zip(leg_twists, leg_wrenches, strict=True)):
            frames[f"leg{k}:T"] = twist_frame
            frames[f"leg{k}:W"] = wrench_frame
    if locked_legs is None:  # every branch row is its actuation wrench: the same array (read only)
        user_branches = actuation_rows
    else:
        size = CK.unit_size(F.from_scaled(wrench_rows, centre, length), length)
        user_branches = np.where(serial[..., None], 0.0, F.from_scaled(branch, centre, length) / size)
    return dict(
        table_source=table,
        topology=top,
        rtol=rtol,
        dof=nominal,
        reference_point=centre,
        length_scale=scalar(length),
        platform_order=scalar(platform[1]),
        constraint_order=scalar(constraint[1]),
        global_order=scalar(global_frame[1]),
        serial=serial,
        transmissions=transmissions,
        actuation_rows=actuation_rows,
        branch_rows=user_branches,
        actuated_twists=actuated_screws(top, screws),
        frames=frames,
        closeness_factors=closeness_factors,
        free=table.free,
    )
