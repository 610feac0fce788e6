"""The batch bookkeeping of a posed mechanism: poses checked, an index resolved to one pose of the
batch, the batch's joint table computed again, its text and HTML forms
(:class:`screwkit.robots.posed.PosedMechanism`).

Examples
--------
>>> flat_index((2, 3), (1, 2))
5
"""

from __future__ import annotations

import weakref
from dataclasses import fields
from typing import Any

import numpy as np

from ..algebra.display import html_section, html_table, number_text
from ..core.jacobian_matrices import UNREACHABLE
from ..core.wrench_systems import WrenchAnalysis
from ..exceptions import ScrewkitIndexError, ScrewkitValueError, UnreachablePoseError
from ..graphs.jointtable import JointTable
from .angles import pose_scale, pose_text
from .pose_reader import pose_array

__all__ = [
    "UNREACHABLE",
    "batch_html",
    "batch_repr",
    "checked_poses",
    "flat_index",
    "joint_table_of",
    "one_pose",
    "per_pose",
    "reachable_part",
    "reached_view",
    "scattered",
]

# UNREACHABLE ("unreachable", screwkit.core.jacobian_matrices): the verdict of a pose out of reach in a
# batch's per-pose views (``verdicts``; its code is ``-1``, its closeness NaN, its redundancy ``-1``) and
# the Gosselin-Angeles type of its Jacobians.

Array = np.ndarray


def checked_poses(mechanism: Any, poses: Any) -> Array:
    """Poses ``(m, n)`` as floats (a single pose as a batch of one; None: the default pose).

    Parameters
    ----------
    mechanism : Mechanism
    poses : array_like, shape (..., n), or None

    Returns
    -------
    numpy.ndarray, shape (..., n)

    Raises
    ------
    ScrewkitTypeError, ScrewkitValueError
        As :func:`~screwkit.robots.pose_reader.pose_array`, or an empty batch.

    Examples
    --------
    >>> checked_poses(load_mechanism("h4"), [0, 0, -750, 0]).shape
    (1, 4)
    """
    if poses is None:
        return np.asarray(mechanism.default_pose, dtype=float)[None]
    array = pose_array(mechanism, poses)
    if array.ndim == 1:
        array = array[None]
    if array.size == 0:  # an empty batch: the analysis core reshapes over a batch of at least one pose
        raise ScrewkitValueError(f"Expected `poses` to hold at least one pose, got shape {array.shape}.")
    return array


def flat_index(shape: tuple[int, ...], index: Any) -> int:
    """The flat (C order) position of the one pose ``index`` picks in a batch of ``shape``.

    Parameters
    ----------
    shape : tuple of int
        The batch shape (not ``()``).
    index : int or tuple of int
        One integer per batch axis.

    Returns
    -------
    int

    Raises
    ------
    ScrewkitIndexError
        If the index is out of range (an IndexError too, so a for loop stops there).
    ScrewkitValueError
        If the index does not pick one pose.

    Examples
    --------
    >>> flat_index((4,), -1)
    3
    >>> flat_index((4,), 4)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitIndexError: Expected `index` to pick one pose ... got 4 (out of range).
    """
    parts = index if isinstance(index, tuple) else (index,)
    if not all(isinstance(i, int | np.integer) and not isinstance(i, bool) for i in parts):
        raise ScrewkitValueError(  # numpy's IndexError for a string is not an index out of range
            f"Expected `index` to pick one pose of the batch of shape {shape}, got {index!r}."
        )
    try:
        flat = np.arange(int(np.prod(shape))).reshape(shape)[index]
    except IndexError as err:
        raise ScrewkitIndexError(
            f"Expected `index` to pick one pose of the batch of shape {shape}, got {index!r} (out of range)."
        ) from err
    except (TypeError, ValueError) as err:
        raise ScrewkitValueError(
            f"Expected `index` to pick one pose of the batch of shape {shape}, got {index!r}."
        ) from err
    if np.ndim(flat) != 0:
        raise ScrewkitValueError(
            f"Expected `index` to pick one pose of the batch of shape {shape}, got {index!r}."
        )
    return int(flat)


def joint_table_of(
    posed: weakref.ref[Any], mechanism: Any, poses: Array, options: dict[str, Any]
) -> JointTable:
    """The joint table of a posed batch: its own (cached) while it lives, else computed again at
    its poses (inverse kinematics, then the family's joints).

    Parameters
    ----------
    posed : weakref.ref to PosedMechanism
    mechanism : Mechanism
    poses : numpy.ndarray, shape (..., n)
    options : dict
        Inverse-kinematics options.

    Returns
    -------
    JointTable

    Examples
    --------
    >>> h4 = load_mechanism("h4")
    >>> poses = np.array([[0.0, 0.0, -750.0, 0.0]])
    >>> joint_table_of(weakref.ref(h4.at(poses)), h4, poses, {}).batch_shape
    (1,)
    """
    alive = posed()
    if alive is not None:
        return alive.joints
    return mechanism.family_protocol.joint_table(mechanism.configuration(poses, **options))


def batch_repr(posed: Any) -> str:
    """A posed mechanism in one line: the mechanism, the pose with its units (a batch: its shape), ``rtol``.

    Parameters
    ----------
    posed : PosedMechanism

    Returns
    -------
    str

    Examples
    --------
    >>> batch_repr(load_mechanism("h4").at([[30, -20, -750, 0.3], [0, 0, -800, 0.1]]))
    "PosedMechanism('H4', shape=(2,), rtol=1e-09)"
    """
    length = "" if posed.length_scale is None else f", length_scale={posed.length_scale:g}"
    m = posed.mechanism
    where = (
        f" at {pose_text(posed.poses, m.pose_names, m.angle_names, m.length_unit)}"
        if posed.shape == ()
        else f", shape={posed.shape}"
    )
    return f"PosedMechanism({m.name!r}{where}, rtol={posed.rtol:g}{length})"


def batch_html(posed: Any) -> str:
    """A posed mechanism for Jupyter: the poses with their units and each pose's verdict as a table
    (the first 20 of a batch); one pose adds its singularity report.

    Parameters
    ----------
    posed : PosedMechanism

    Returns
    -------
    str

    Examples
    --------
    >>> "<table" in batch_html(load_mechanism("h4").at([[0, 0, -750, 0]]))
    True
    """
    m = posed.mechanism
    flat = posed.poses.reshape(-1, len(m.pose_names))
    scale = pose_scale(m.pose_names, m.angle_names, "deg")
    verdicts = np.asarray(posed.verdicts).reshape(-1) if posed.shape != () else [posed.singularity.verdict]
    header = [f"{n} ({'deg' if n in m.angle_names else m.length_unit})" for n in m.pose_names]
    rows = [
        [*(number_text(v, 6) for v in pose / scale), verdict]
        for pose, verdict in zip(flat[:20], verdicts, strict=False)
    ]
    more = f"<p>… {len(flat)} poses in all</p>" if len(flat) > 20 else ""
    body = html_table([*header, "verdict"], rows) + more
    if posed.shape == ():
        body += posed.singularity._repr_html_()
    return html_section(f"{m.name} at {len(flat)} pose(s)", body)


def reachable_part(posed: Any) -> tuple[Array, Any] | None:
    """None when every pose of a posed batch is reached (its ``singularities`` then computed), else
    the flat mask of the reached poses and the posed mechanism at them, flat (None if none is).

    Parameters
    ----------
    posed : PosedMechanism

    Returns
    -------
    tuple (numpy.ndarray of bool, PosedMechanism or None), or None

    Examples
    --------
    >>> mask, reached = reachable_part(load_mechanism("v4").at([[0, 0, -750, 0], [0, 0, -3000, 0]]))
    >>> mask.tolist(), reached.shape
    ([True, False], (1,))
    """
    if not posed.failures_known:
        try:
            _ = posed.singularities
            return None
        except UnreachablePoseError:
            pass
    mask = np.asarray(posed.reachable, dtype=bool).reshape(-1)
    if not mask.any():
        return mask, None
    flat = posed.poses.reshape(-1, posed.poses.shape[-1])[mask]
    return mask, type(posed).create(
        posed.mechanism, flat, rtol=posed.rtol, length_scale=posed.length_scale, options=posed.options
    )


def per_pose(posed: Any, read: Any, fill: Any, dtype: Any) -> Array:
    """A per-pose view of a posed batch, ``fill`` at its poses out of reach (:func:`reachable_part`).

    Parameters
    ----------
    posed : PosedMechanism
    read : callable
        ``read(posed) -> numpy.ndarray`` of the batch shape, for a batch whose poses are all reached.
    fill : object
        The value at a pose out of reach.
    dtype : numpy dtype
        Of the result where a pose is out of reach.

    Returns
    -------
    numpy.ndarray, the batch shape
        What ``read`` gives when every pose is reached.

    Examples
    --------
    >>> posed = load_mechanism("v4").at([[0, 0, -750, 0], [0, 0, -3000, 0]])
    >>> per_pose(posed, lambda p: p.codes, -1, np.int64).tolist()
    [0, -1]
    """
    part = posed.reached_part
    if part is None:
        return read(posed)
    mask, reached = part
    out = np.full(mask.shape, fill, dtype=dtype)
    if reached is not None:
        out[mask] = read(reached)
    return out.reshape(posed.shape)


def one_pose(posed: Any, index: Any) -> Any:
    """One pose of a posed batch (:meth:`PosedMechanism.__getitem__
    <screwkit.robots.posed.PosedMechanism.__getitem__>`): its row of the batch's joint table, or of the
    reached poses' when some are out of reach; a pose out of reach gets its reason, which its views raise.

    Parameters
    ----------
    posed : PosedMechanism
        A batch (not one pose).
    index : int or tuple of int

    Returns
    -------
    PosedMechanism
        Of shape ``()``.

    Examples
    --------
    >>> posed = load_mechanism("v4").at([[0, 0, -750, 0], [0, 0, -3000, 0]])
    >>> one_pose(posed, 0).singularity.verdict, one_pose(posed, 1).reachable.tolist()
    ('regular', False)
    """
    flat = flat_index(posed.shape, index)
    fields = {"mechanism": posed.mechanism, "poses": posed.poses[index], "rtol": posed.rtol,
              "length_scale": posed.length_scale, "options": posed.options}
    try:
        table = None if posed.failures_known else posed.joints
    except UnreachablePoseError:
        table = None
    if table is not None:  # the batch's row: no new inverse kinematics
        one = type(posed)(**fields, _batch=(posed, flat))
        one.__dict__["joints"] = table[index]
        return one
    mask, reached = posed.reached_part
    if not mask[flat]:  # out of reach: its views raise the reason (its own inverse kinematics' message)
        if not posed.failures_known:
            return type(posed)(**fields)
        reason = posed.failures[tuple(int(i) for i in np.unravel_index(flat, posed.shape))]
        return type(posed)(**fields, _failures={(): reason})
    row = int(np.count_nonzero(mask[:flat]))  # its row among the reached poses
    one = type(posed)(**fields, _batch=(reached, row))
    one.__dict__["joints"] = reached.joints[row]
    return one


def scattered(values: Any, mask: Array, shape: tuple[int, ...], fill: Any) -> Array:
    """Values of the reached poses of a batch (a first axis over them) put back at their poses, ``fill``
    at the poses out of reach.

    Parameters
    ----------
    values : array_like, shape (k, ...)
        One row per reached pose, in the batch's flat (C) order.
    mask : numpy.ndarray of bool, shape (m,)
        The flat mask of the reached poses (``k`` of them).
    shape : tuple of int
        The batch shape (``m`` poses).
    fill : object
        The value at a pose out of reach (NaN, False, ``-1``).

    Returns
    -------
    numpy.ndarray
        Of shape ``shape + values.shape[1:]``.

    Examples
    --------
    >>> scattered(np.array([[1.0, 2.0]]), np.array([False, True]), (2,), np.nan).tolist()
    [[nan, nan], [1.0, 2.0]]
    """
    rows = np.asarray(values)
    out = np.full((mask.size, *rows.shape[1:]), fill, dtype=np.result_type(rows, np.asarray(fill)))
    out[mask] = rows
    return out.reshape(*shape, *rows.shape[1:])


def reached_view(posed: Any, view: str) -> Any:
    """A whole-batch view of a batch some of whose poses are out of reach: each reached pose's value as
    in a batch of the reached poses alone, NaN (False for a flag) at the others; what covers the reached
    poses only is left out (the Jacobians' ``analysis``: ``posed[i]`` has a pose's).

    Parameters
    ----------
    posed : PosedMechanism
        A batch with a pose out of reach (:func:`reachable_part` not None).
    view : {"jacobians", "wrench_transmission"}
        The view: a frozen dataclass of arrays over the batch
        (:class:`~screwkit.core.jacobian_matrices.Jacobians`, whose type reads ``"unreachable"`` at a
        pose out of reach, or :class:`~screwkit.robots.transmission.Transmission`, whose ``reachable``
        is False there).

    Returns
    -------
    Jacobians or Transmission
        Over the batch's shape.

    Raises
    ------
    UnreachablePoseError
        If no pose of the batch is in reach.

    Examples
    --------
    >>> posed = load_mechanism("v4").at([[0, 0, -750, 0], [0, 0, -3000, 0]])
    >>> reached_view(posed, "jacobians").types.tolist()
    ['regular', 'unreachable']
    >>> reached_view(posed, "wrench_transmission").reachable.tolist()
    [True, False]
    """
    mask, reached = posed.reached_part
    if reached is None:
        raise UnreachablePoseError(
            f"Expected some pose of the batch in reach for `{view}`, got none of {mask.size} "
            f"(posed.failures has the reasons)."
        )
    value = getattr(reached, view)

    def spread(item: Any) -> Any:
        if isinstance(item, WrenchAnalysis):  # the reached poses' only
            return None
        if isinstance(item, dict):
            return {key: spread(np.asarray(entry)) for key, entry in item.items()}
        if isinstance(item, np.ndarray):
            return scattered(item, mask, posed.shape, False if item.dtype == bool else np.nan)
        return item

    return type(value)(**{f.name: spread(getattr(value, f.name)) for f in fields(value)})
