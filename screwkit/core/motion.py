"""Generic configurations of any twist graph: move the mechanism along its own mobility, close its loops.

A twist graph holds one configuration of a mechanism (its joint screws there). Structural facts
(which points of a wrench diagram coincide, which brackets vanish) must be decided at *generic*
configurations of the same mechanism, never at the analysed one, which may be singular
(gca.md §6). This module makes such configurations from the graph alone, so snapshots, graphs
built in Python and catalog robots are treated alike:

1. the graph's product-of-exponentials model (:class:`~screwkit.core.kinematic_model.KinematicModel`:
   every joint's variables zero at the given configuration, a spanning tree placing each link, one
   loop-closure equation per joint off the tree);
2. a random step in the null space of the loop-closure matrix (the joint rates the loops allow,
   docs/architecture.md §5: the platform's own twist system and the legs' internal motions), then Newton's
   method (Gauss–Newton with the pseudo-inverse, the minimum-norm correction) on the loop-closure
   equations brings every loop back together; a few such steps move the mechanism well away from
   where it started;
3. the joints' screws are those the model carries to the new configuration;
4. only configurations in the reference's operation mode are kept
   (:func:`screwkit.core.operation_modes.reference_mode_indices`: the platform's motion type and the
   constraint order as at the reference; where the reference lies where modes meet, the rule of
   :func:`~screwkit.core.operation_modes.reference_mode_indices`): a 3-UPU drawn from its base
   plane reaches its translational and its turning modes.

All configurations of a batch are moved together (arrays with a leading batch axis), and the
result is a :class:`~screwkit.graphs.jointtable.JointTable` over the batch: the analysis core takes it as is.

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> fourbar = twist_graph("ground", "coupler", [
...     ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("crank", "coupler", revolute("B", [0, 0, 1], [1, 0, 0])),
...     ("ground", "rocker", revolute("D", [0, 0, 1], [3, 0, 0])),
...     ("rocker", "coupler", revolute("C", [0, 0, 1], [3, 2, 0]))], dof=1)
>>> table = generic_configurations(fourbar, np.random.default_rng(0), 4)
>>> table.batch_shape
(4,)
"""

from __future__ import annotations

from dataclasses import replace

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitValueError
from ..graphs.jointtable import JointTable
from .kinematic_model import KinematicModel
from .operation_modes import reference_mode_indices
from .wrench_systems import analyze_table

__all__ = ["generic_configurations", "moved_configurations", "newton_closure", "tangent_error"]

Array = np.ndarray

#: Size of one random step (radians, or characteristic lengths), before the loops are closed again.
STEP = 0.25
#: Random steps taken from the given configuration.
STEPS = 3
#: Newton iterations per step, and the loop-closure residual (in characteristic lengths) accepted.
NEWTON_ITERATIONS = 30
CLOSURE_TOL = 1e-11


def _null_space(jacobian: Array, rtol: float = 1e-9) -> Array:
    """Orthonormal null-space bases ``(columns, k)`` of one matrix."""
    if jacobian.shape[0] == 0:
        return np.eye(jacobian.shape[1])
    _, sigma, vt = np.linalg.svd(jacobian)
    rank = int(np.sum(sigma > rtol * max(sigma[0], 1.0)))
    return vt[rank:].T


def _damped_linear(jacobian: Array, residual: Array) -> Array:
    """``(J Jᵀ + λ I)⁻¹ r`` per configuration: ``Jᵀ`` of it is the minimum-norm Gauss–Newton step
    (Levenberg's damping ``λ`` tiny, so that the dependent loop equations of an overconstrained
    mechanism, whose rows repeat, leave the system solvable)."""
    gram = jacobian @ np.swapaxes(jacobian, -1, -2)
    damping = 1e-12 * (np.trace(gram, axis1=-2, axis2=-1)[:, None, None] + 1.0)
    return np.linalg.solve(gram + damping * np.eye(gram.shape[-1]), residual[..., None])[..., 0]


def _damped_solve(jacobian: Array, vectors: Array) -> Array:
    """The multipliers projecting ``vectors`` onto the null space of ``J``: ``(J Jᵀ + λ I)⁻¹ J z``."""
    return _damped_linear(jacobian, np.einsum("bij,bj->bi", jacobian, vectors))


def generic_configurations(
    graph: nx.MultiDiGraph,
    rng: np.random.Generator,
    count: int,
    *,
    joint_key: str = "joint",
    rtol: float = 1e-9,
    same_mode: bool = True,
) -> JointTable:
    """``count`` random configurations of the graph's mechanism, reached by moving it (module docstring).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph at one (any, even singular) configuration.
    rng : numpy.random.Generator
    count : int
        Configurations wanted; those whose loops Newton's method could not close are dropped.
    joint_key : str
    rtol : float, default 1e-9
        The data's precision, relative: loop-closure rates whose singular value is at most ``rtol``
        times the largest are motions, and a loop closed to ``rtol`` characteristic lengths is closed
        (an overconstrained linkage given with rounded coordinates moves at its data's precision).
    same_mode : bool, default True
        Keep only the configurations in the reference's operation mode (module docstring, step 4);
        False keeps every mode reached.

    Returns
    -------
    JointTable
        Batch shape ``(k,)`` with ``k <= count`` (fewer where other modes were reached), the graph's
        joints (same names, types, actuation).

    Raises
    ------
    ScrewkitValueError
        If the mechanism cannot move (its loops admit no joint motion), or no loop could be closed.

    Examples
    --------
    >>> graph = load_mechanism("planar_3rrp").twist_graph()
    >>> table = generic_configurations(graph, np.random.default_rng(0), 3)
    >>> table.batch_shape, bool(np.allclose(table.screws[0], table.screws[1]))
    ((3,), False)
    """
    model = KinematicModel(graph, joint_key)
    theta = moved_configurations(model, rng, count, rtol)
    reference = JointTable.from_graph(graph, joint_key=joint_key)
    table = model.joint_table(model.state(theta), reference)
    if not same_mode:
        return table
    rank_rtol = max(rtol, B.DEFAULT_RTOL)
    kept = reference_mode_indices(analyze_table(_with_free(table, reference), rtol=rank_rtol, views=False),
                                  analyze_table(reference, rtol=rank_rtol, views=False))
    return model.joint_table(model.state(theta[kept]), reference)


def newton_closure(
    model: KinematicModel,
    theta: Array,
    iterations: int = NEWTON_ITERATIONS,
    largest_step: float = np.inf,
    *,
    tolerance: float = CLOSURE_TOL,
) -> tuple[Array, Array]:
    """Joint values ``(B, n)`` moved onto the loop-closure equations by Gauss–Newton's minimum-norm
    correction (Nocedal & Wright, *Numerical Optimization*, 2006, §10.3), at most ``iterations``
    times or until every loop is closed to ``tolerance``; and each row's largest residual.

    Parameters
    ----------
    model : KinematicModel
    theta : numpy.ndarray, shape (B, n)
    iterations : int, default :data:`NEWTON_ITERATIONS`
    largest_step : float, optional
        A correction whose largest joint variable exceeds this (radians or characteristic lengths)
        is shortened to it, keeping its direction (a step bound, as a trust region's: Nocedal &
        Wright §4.1): far from the solution set the full step overshoots, and without the bound most
        random assemblies of a spatial linkage stall at a nonzero residual.
    tolerance : float, default :data:`CLOSURE_TOL`
        The largest residual (characteristic lengths) at which the iterations stop; 0 runs all of
        them (to round-off, where a configuration's first-order motions are read: :func:`tangent_error`).

    Returns
    -------
    theta : numpy.ndarray, shape (B, n)
    residual : numpy.ndarray, shape (B,)
        Zero for a mechanism without loops.

    Raises
    ------
    ScrewkitValueError
        If ``theta`` is not of shape ``(B, n)``, ``n`` the model's joint variables.

    Examples
    --------
    >>> model = KinematicModel(load_mechanism("planar_3rrp").twist_graph())
    >>> theta, residual = newton_closure(model, np.full((2, model.size), 0.1))
    >>> bool(np.all(residual < CLOSURE_TOL))
    True
    """
    theta = _checked_theta(model, theta)
    if len(theta) == 0:
        return theta.copy(), np.zeros(0)
    for _ in range(iterations):
        state = model.state(theta)
        residual = model.loop_residual(state)
        if residual.shape[1] == 0 or np.max(np.abs(residual)) < tolerance:
            break
        jacobian = model.loop_jacobian(state)
        step = np.einsum("bji,bj->bi", jacobian, _damped_linear(jacobian, residual))
        largest = np.max(np.abs(step), axis=1, keepdims=True)
        theta = theta - step * np.minimum(1.0, largest_step / np.where(largest > 0, largest, 1.0))
    residual = model.loop_residual(model.state(theta))
    return theta, (np.max(np.abs(residual), axis=1) if residual.shape[1] else np.zeros(theta.shape[0]))


def tangent_error(model: KinematicModel, theta: Array) -> Array:
    """How far the first-order motions read at nearly closed configurations may turn from the true ones:
    ``‖F‖ / σ²`` per configuration (``F`` the loop residual, ``σ`` the smallest nonzero singular value of
    the loop-closure matrix ``J``, both scaled).

    A configuration closed to a residual ``F`` lies about ``‖J⁺F‖ <= ‖F‖ / σ`` from a true one (one
    Gauss–Newton step), where the loop-closure matrix differs by about that much times its Lipschitz
    constant (about 1 in characteristic lengths: its columns are unit screws, their derivatives Lie
    brackets of them); by Wedin's theorem (P.-Å. Wedin, "Perturbation bounds in connection with
    singular value decomposition", BIT 12, 1972) the null space (the joint rates the loops allow, hence
    the platform's twists) then turns by at most that difference over the gap ``σ``. Away from any
    singular configuration ``σ`` is of order one and the error is the residual's size; next to a
    configuration where operation modes meet ``σ`` is small (the branch's distance from it) and a
    residual of 1e-11 can turn the twists by a few per cent (a 3-UPU configuration 1.7e-5 from its
    transition set, closed to 7e-12, read a helical freedom of pitch -0.016).

    Parameters
    ----------
    model : KinematicModel
    theta : numpy.ndarray, shape (B, n)
        Joint values (e.g. :func:`newton_closure`'s).

    Returns
    -------
    numpy.ndarray, shape (B,)
        Zero for a mechanism without loops; infinite where the loops admit every joint motion to
        first order but do not close.

    Raises
    ------
    ScrewkitValueError
        If ``theta`` is not of shape ``(B, n)`` (``n`` the model's joint variables).

    Examples
    --------
    The H4 at its reference (closed exactly) and with one joint moved off it:

    >>> h4 = KinematicModel(load_mechanism("h4").twist_graph())
    >>> off = np.zeros((2, h4.size))
    >>> off[1, 0] = 1e-6
    >>> error = tangent_error(h4, off)
    >>> float(error[0]), bool(1e-7 < error[1] < 1e-2)
    (0.0, True)
    """
    theta = _checked_theta(model, theta)
    if len(theta) == 0 or not model.closing:
        return np.zeros(len(theta))
    state = model.state(theta)
    residual = np.linalg.norm(model.loop_residual(state), axis=1)
    sigma = np.linalg.svd(model.loop_jacobian(state), compute_uv=False)
    nonzero = sigma > 1e-9 * np.maximum(sigma[:, :1], 1.0)  # the rank rule of _null_space
    smallest = np.min(np.where(nonzero, sigma, np.inf), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        error = residual / smallest**2
    return np.where(residual == 0.0, 0.0, np.where(np.isfinite(smallest), error, np.inf))


def _with_free(table: JointTable, reference: JointTable) -> JointTable:
    """A moved configurations' joint table with the reference's free rotations (a point task's,
    :attr:`JointTable.free <screwkit.graphs.jointtable.JointTable.free>`), which
    :meth:`~screwkit.core.kinematic_model.KinematicModel.joint_table` does not carry: their operation
    modes are read as the reference's (:func:`screwkit.core.operation_modes.operation_modes`)."""
    return replace(table, free=reference.free) if reference.free != table.free else table


def _checked_theta(model: KinematicModel, theta: Array) -> Array:
    """``theta`` as floats of shape ``(B, n)``, or a ScrewkitValueError naming it."""
    theta = np.asarray(theta, dtype=float)
    if theta.ndim != 2 or theta.shape[1] != model.size:
        raise ScrewkitValueError(
            f"Expected `theta` of shape (B, {model.size}) (the model's joint variables), got {theta.shape}."
        )
    return theta


def moved_configurations(
    model: KinematicModel, rng: np.random.Generator, count: int, rtol: float = 1e-9
) -> Array:
    """Joint values of ``count`` configurations reached by moving the mechanism from its reference:
    :data:`STEPS` random steps of :data:`STEP` along the motions its loops allow, each closed again
    (module docstring, step 2); those that did not close are dropped.

    Parameters
    ----------
    model : KinematicModel
    rng : numpy.random.Generator
    count : int
    rtol : float, default 1e-9
        As in :func:`generic_configurations`.

    Returns
    -------
    numpy.ndarray, shape (k, n)
        ``k <= count``.

    Raises
    ------
    ScrewkitValueError
        If ``count`` is not a non-negative integer, the mechanism cannot move, or no loop could be
        closed.

    Examples
    --------
    >>> model = KinematicModel(load_mechanism("planar_3rrp").twist_graph())
    >>> moved_configurations(model, np.random.default_rng(0), 3).shape
    (3, 9)
    """
    n = model.size
    if isinstance(count, bool) or not isinstance(count, int | np.integer) or count < 0:
        raise ScrewkitValueError(f"Expected `count` to be a non-negative integer, got {count!r}.")
    if count == 0:
        return np.zeros((0, n))
    theta = np.zeros((count, n))
    null = _null_space(model.loop_jacobian(model.state(theta[:1]))[0], rtol)
    if null.shape[1] == 0:
        raise ScrewkitValueError(
            "Expected a mechanism that can move (to reach generic configurations), got one whose loops "
            "admit no joint motion."
        )
    ok = np.ones(count, dtype=bool)
    for _ in range(STEPS):
        jacobian = model.loop_jacobian(model.state(theta))
        direction = rng.standard_normal((count, n))
        direction = direction - np.einsum("bji,bj->bi", jacobian, _damped_solve(jacobian, direction))
        theta = theta + STEP * direction / np.max(np.abs(direction), axis=1, keepdims=True)
        theta, residual = newton_closure(model, theta)
        ok &= residual < max(rtol, 1e-9)
    if not np.any(ok):
        raise ScrewkitValueError("Expected loops that close again after a small motion, got none in "
                                 f"{count} tries (Newton's method did not converge).")
    return theta[ok]

