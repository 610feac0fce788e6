"""The command line's input and output, shared by its commands (:mod:`screwkit.interface.cli`).

What a command reads: the mechanism it names (a catalog name or a ``.toml`` file, a snapshot told
apart), a pose given in the file's length unit and degrees (checked coordinate by coordinate and
converted to the API's radians), an output path (checked before a long computation); and how it
writes: text that falls back to escapes where standard output cannot encode it, and JSON. A
malformed command line raises :class:`UsageError` (exit status 2).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from ..robots.catalog import list_mechanisms, load_mechanism, unknown_mechanism
from ..robots.toml_fields import MAX_COORDINATE, degrees_to_radians, file_kind, load_toml

__all__ = [
    "UsageError",
    "check_coordinate",
    "check_writable",
    "error_reason",
    "given_pose",
    "json_text",
    "mechanism_over_poses",
    "pose_coordinates",
    "pose_values",
    "print_text",
    "shown_path",
    "target_and_pose",
    "toml_kind",
]


class UsageError(Exception):
    """A malformed command line (exit status 2)."""



def pose_coordinates() -> list[str]:
    """Every family's pose coordinates, then those a snapshot's motion may have
    (:data:`screwkit.core.task_coordinates.COORDINATE_NAMES`): the map command takes one option per
    coordinate."""
    from ..core.task_coordinates import COORDINATE_NAMES
    from ..robots.families import families

    names = families().pose_names()
    return names + [name for name in COORDINATE_NAMES if name not in names]



def given_pose(args: argparse.Namespace, mechanism: Any) -> Any:
    """The --pose in the API's units (the family's angles from degrees to radians)."""
    if args.pose is None:
        return None
    values = pose_values(f"screwkit {args.command}", "--pose", mechanism, args.pose)
    angles = set(mechanism.angle_names)
    pairs = zip(mechanism.pose_names, values, strict=True)
    return np.array([math.radians(v) if n in angles else v for n, v in pairs])



def pose_values(command: str, option: str, mechanism: Any, values: Sequence[float]) -> list[float]:
    """A pose given on the command line (lengths in the file's unit, angles in degrees), checked:
    one finite number per pose coordinate, lengths up to :data:`~screwkit.robots.toml_fields.MAX_COORDINATE`,
    angles up to :data:`~screwkit.robots.toml_fields.MAX_ANGLE_DEGREES`."""
    names = mechanism.pose_names
    if len(values) != len(names) or not all(math.isfinite(v) for v in values):
        expected = " ".join(n.upper() for n in names)
        raise UsageError(
            f"{command}: error: {option} expects {len(names)} finite numbers ({expected}), "
            f"got {' '.join(map(str, values))}"
        )
    for name, value in zip(names, values, strict=True):
        check_coordinate(command, option, mechanism, name, value)
    return list(values)



def check_coordinate(command: str, option: str, mechanism: Any, name: str, value: float) -> None:
    """One pose coordinate from the command line: an angle in degrees up to MAX_ANGLE_DEGREES, a
    length up to MAX_COORDINATE (beyond, squares of coordinates overflow in the inverse kinematics)."""
    if name in mechanism.angle_names:
        try:
            degrees_to_radians(value)
        except ScrewkitValueError as err:
            raise UsageError(f"{command}: error: {option}: {name}: {err}") from err
    elif not abs(value) <= MAX_COORDINATE:
        raise UsageError(
            f"{command}: error: {option}: {name}: expected a length of at most {MAX_COORDINATE:g} "
            f"{mechanism.length_unit} in magnitude, got {value:g}"
        )



def target_and_pose(args: argparse.Namespace) -> tuple[Any, Any]:
    """The mechanism (a :class:`~screwkit.robots.mechanism.Mechanism`, or a snapshot's path) and the pose of
    ``analyze``/``graph``."""
    if args.mechanism.endswith(".toml") and toml_kind(args.mechanism) == "snapshot":
        if args.pose is not None:
            raise UsageError(
                f"screwkit {args.command}: error: {args.mechanism} is a snapshot (one configuration); "
                "--pose does not apply"
            )
        return args.mechanism, None
    if not args.mechanism.endswith(".toml") and args.mechanism.lower() not in list_mechanisms():
        raise UsageError(f"screwkit {args.command}: error: {unknown_mechanism(args.mechanism)}")
    mechanism = load_mechanism(args.mechanism)  # a malformed file is an analysis error (exit 1)
    return mechanism, given_pose(args, mechanism)



def mechanism_over_poses(command: str, name: str) -> Any:
    """A mechanism with a pose space: a catalog robot by name or file, or a snapshot file over its
    motion (loop-closure kinematics from its configuration,
    :func:`screwkit.robots.graph_mechanism.mechanism`)."""
    if name.endswith(".toml"):
        if toml_kind(name) == "snapshot":
            from ..robots.graph_mechanism import mechanism

            return mechanism(name)
    elif name.lower() not in list_mechanisms():
        raise UsageError(f"screwkit {command}: error: {unknown_mechanism(name)}")
    return load_mechanism(name)



def toml_kind(path: str) -> Any:
    return file_kind(load_toml(path))



def check_writable(command: str, option: str, path: str) -> None:
    """Refuse an output path whose folder does not exist (before a long computation, not after)."""
    folder = os.path.dirname(os.path.abspath(path)) if "\0" not in path else ""
    if not os.path.isdir(folder):
        raise UsageError(
            f"{command}: error: {option} {shown_path(path)}: expected a file in an existing folder"
        )
    if os.path.isdir(path):
        raise UsageError(f"{command}: error: {option} {shown_path(path)}: expected a file, got a folder")



def shown_path(path: str) -> str:
    """A path as a message shows it: as given, or quoted with escapes if it holds control characters."""
    return path if path.isprintable() else repr(path)



def error_reason(err: BaseException) -> str:
    """The reason of an OSError (its strerror), or the message of another error."""
    return str(getattr(err, "strerror", None) or err)



def json_text(value: Any, **options: Any) -> str:
    """JSON text (the json module loads for the commands that print JSON)."""
    import json

    return json.dumps(value, **options)



def print_text(text: str) -> None:
    """Print, falling back to escapes where stdout cannot encode a character (ḟ, χ̇, θ̇ on an
    ASCII or Latin-1 terminal) instead of failing."""
    try:
        print(text)
    except UnicodeEncodeError:
        encoding = getattr(sys.stdout, "encoding", None) or "ascii"
        print(text.encode(encoding, errors="backslashreplace").decode(encoding))

