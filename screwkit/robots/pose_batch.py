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
from typing import Any

import numpy as np

from ..algebra.display import html_section, html_table, number_text
from ..exceptions import ScrewkitIndexError, ScrewkitValueError
from ..graphs.jointtable import JointTable
from .angles import pose_scale, pose_text
from .pose_reader import pose_array

__all__ = ["batch_html", "batch_repr", "checked_poses", "flat_index", "joint_table_of"]

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
