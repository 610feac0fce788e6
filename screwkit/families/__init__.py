"""Parametric mechanism families: the one protocol every family goes through (design.md §1a).

A family is four functions and the names of its pose coordinates:

``parameters(mapping, *, source)``
    The family's validated parameters from a catalog file's ``[parameters]`` mapping.
``inverse_kinematics(parameters, poses, **mode)``
    A configuration over poses ``(..., n)`` (batched; ``mode`` picks a working mode).
``joints(configuration)``
    A :class:`~screwkit.joints.JointTable`: the mechanism's structure once, every joint's screws
    over the batch. Everything else (labels, wrench systems, Jacobians, diagrams, reports) comes
    from the analysis core.
``twist_basis(configuration)``
    The platform's nominal twists ``(..., dof, 6)``, one per pose coordinate (the columns of
    ``A`` in :func:`screwkit.jacobians.jacobians_from_wrenches`).

Adding a robot: write those four functions in a module, add a :class:`Family` to
:func:`families` (``CONTRIBUTING.md`` has a worked example), and a catalog file naming it.

Examples
--------
>>> sorted(families())
['four_limb', 'mcgill_smg', 'peppermill', 'planar_3rrp']
>>> families()["planar_3rrp"].pose_names
('x', 'y', 'phi')
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..joints import JointTable

__all__ = ["Family", "families"]


@dataclass(frozen=True)
class Family:
    """A mechanism family: the protocol of the module docstring.

    Attributes
    ----------
    name : str
    parameters, inverse_kinematics, joints, twist_basis : callable
    pose_names, angle_names : tuple of str
        The pose coordinates, and which of them are angles (degrees in files and on the command
        line, radians in the API).

    Examples
    --------
    >>> families()["four_limb"].angle_names
    ('phi',)
    """

    name: str
    parameters: Callable[..., Any]
    inverse_kinematics: Callable[..., Any]
    joints: Callable[[Any], JointTable]
    twist_basis: Callable[[Any], np.ndarray]
    pose_names: tuple[str, ...]
    angle_names: tuple[str, ...]


def _four_limb_joints(config: Any) -> JointTable:
    from .four_limb_graph import four_limb_joints

    rows = [(p, c, name, kind, screws, act) for p, c, name, kind, screws, act in four_limb_joints(config)]
    return JointTable.from_rows("base", "end_effector", rows, dof=4)


def _four_limb_basis(config: Any) -> np.ndarray:
    from ..jacobians import schoenflies_basis

    return schoenflies_basis(config.pose[..., :3], config.platform_joint_axis)


def _planar_joints(config: Any) -> JointTable:
    from .planar_3rrp import LINK_NAMES, limb_joints

    rows, anchors = [], []
    for limb in limb_joints(config):
        for joint in limb:
            parent, child = (LINK_NAMES[link - 1] for link in joint.links)
            rows.append((parent, child, joint.name, joint.kind, joint.screw[..., None, :], joint.actuated))
            if joint.kind == "R":
                anchors.append(joint.point)
    return JointTable.from_rows("base", "platform", rows, dof=3, anchor=np.mean(anchors, axis=0))


def _planar_basis(config: Any) -> np.ndarray:
    x, y = np.moveaxis(config.platform_point, -1, 0)
    rows = np.zeros((*x.shape, 3, 6))
    rows[..., 0, 3] = rows[..., 1, 4] = rows[..., 2, 2] = 1.0
    rows[..., 2, 3], rows[..., 2, 4] = y, -x  # the rotation about z through C: C × k = (y, -x, 0)
    return rows


@functools.cache
def families() -> dict[str, Family]:
    """The families a catalog entry can name, by name (imported on first use).

    Examples
    --------
    >>> families()["mcgill_smg"].pose_names
    ('x', 'y', 'z', 'phi')
    """
    from . import four_limb, mcgill_smg, peppermill, planar_3rrp

    smg = ("x", "y", "z", "phi")
    return {
        "four_limb": Family(
            "four_limb",
            four_limb.FourLimbParameters.from_mapping,
            four_limb.inverse_kinematics,
            _four_limb_joints,
            _four_limb_basis,
            smg,
            ("phi",),
        ),
        "mcgill_smg": Family(
            "mcgill_smg",
            mcgill_smg.McGillParameters.from_mapping,
            mcgill_smg.inverse_kinematics,
            mcgill_smg.joints,
            mcgill_smg.twist_basis,
            smg,
            ("phi",),
        ),
        "peppermill": Family(
            "peppermill",
            peppermill.PeppermillParameters.from_mapping,
            peppermill.inverse_kinematics,
            peppermill.joints,
            peppermill.twist_basis,
            smg,
            ("phi",),
        ),
        "planar_3rrp": Family(
            "planar_3rrp",
            planar_3rrp.Planar3RRPParameters.from_mapping,
            planar_3rrp.Planar3RRPConfiguration.from_pose,
            _planar_joints,
            _planar_basis,
            ("x", "y", "phi"),
            ("phi",),
        ),
    }
