"""Checks of the parameters every analysis takes: tolerances, length scales, rotations.

Each returns the checked value (or None) and raises an error naming the argument and the accepted
range otherwise: a relative tolerance in ``[0, MAX_RTOL]`` (:func:`checked_rtol`), a length scale
in ``[MIN_LENGTH_SCALE, 1 / MIN_LENGTH_SCALE]`` (:func:`checked_length_scale`), a rotation matrix
(:func:`check_rotation`).

Examples
--------
>>> checked_rtol(1e-6), checked_length_scale(25.0)
(1e-06, 25.0)
"""

from __future__ import annotations

from typing import Any, Literal, overload

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .backend import is_symbolic

__all__ = [
    "MAX_RTOL",
    "MIN_FLOAT_RTOL",
    "MIN_LENGTH_SCALE",
    "check_rotation",
    "checked_length_scale",
    "checked_rtol",
]

Array = np.ndarray


def check_rotation(rotation: Array, name: str = "rotation") -> None:
    """Refuse numeric matrices ``(..., 3, 3)`` that are not proper rotations (``RᵀR = I`` to 1e-9,
    ``det R > 0``). Symbolic matrices are taken as given: their entries may obey relations the
    symbols do not state (``c² + s² = 1`` for ``c``, ``s`` standing for a cosine and a sine), and
    proving trigonometric identities costs up to a second a matrix.

    Parameters
    ----------
    rotation : numpy.ndarray, shape (..., 3, 3)
        The matrices (symbolic ones are taken as given).
    name : str, default "rotation"
        The argument's name in the error message.

    Raises
    ------
    ScrewkitValueError
        Naming the argument and the determinant.

    Examples
    --------
    >>> import sympy
    >>> c, s = sympy.symbols("c s")
    >>> check_rotation(np.eye(3)), check_rotation(np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]))
    (None, None)
    >>> check_rotation(np.diag([1.0, 1, -1]))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `rotation` to be a proper rotation ..., got det = -1.0.
    """
    if is_symbolic(rotation):
        return
    product = np.swapaxes(rotation, -1, -2) @ rotation
    if not (np.allclose(product, np.eye(3), atol=1e-9) and np.all(np.linalg.det(rotation) > 0)):
        raise ScrewkitValueError(
            f"Expected `{name}` to be a proper rotation matrix (R^T R = I, det R = +1), "
            f"got det = {np.linalg.det(rotation)}."
        )


@overload
def checked_length_scale(value: Any, *, allow_none: Literal[False] = False) -> float: ...


@overload
def checked_length_scale(value: Any, *, allow_none: Literal[True]) -> float | None: ...


def checked_length_scale(value: Any, *, allow_none: bool = False) -> float | None:
    """Validate a characteristic length: a number in [:data:`MIN_LENGTH_SCALE`, 1 /
    :data:`MIN_LENGTH_SCALE`] (or None where a default exists).

    Parameters
    ----------
    value : object
        The candidate length.
    allow_none : bool, default False
        Whether None (derive the length from the data) is accepted.

    Returns
    -------
    float or None

    Examples
    --------
    >>> checked_length_scale(2)
    2.0
    >>> checked_length_scale(0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `length_scale` to be a positive ..., got 0.
    """
    if value is None and allow_none:
        return None
    ok = isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool)
    if not (ok and np.isfinite(value) and MIN_LENGTH_SCALE <= value <= 1 / MIN_LENGTH_SCALE):
        expected = f"a positive finite number in [{MIN_LENGTH_SCALE:g}, {1 / MIN_LENGTH_SCALE:g}]"
        raise ScrewkitValueError(
            f"Expected `length_scale` to be {expected}{' or None' if allow_none else ''}, got {value!r}."
        )
    return float(value)


#: The smallest characteristic length accepted, and its inverse the largest, in length units:
#: moments are divided by it, and coordinates are at most 1e100 (README, input rules).
MIN_LENGTH_SCALE = 1e-100


#: The coarsest relative tolerance accepted for a rank or zero decision. Beyond it the decisions
#: of a system and of its reciprocal stop agreeing: at ``rtol = 0.3`` the H4's default pose reads
#: a 3T3R platform and a global wrench system of order 3 (a 4-DOF robot), and coarser values give
#: negative freedom counts; up to 0.1 every catalog robot keeps a consistent 3T1R (2T1R) platform.
MAX_RTOL = 0.1


#: The finest relative tolerance the command line accepts (its analyses are in floats). Below it a
#: rank decision reads round-off as rank: at ``rtol = 0`` the H4's default pose reads a constraint +
#: serial singularity of constraint order 0/2, at 1e-16 a 1T3R platform; at 1e-14 the McGill SMG's
#: verdicts differ from those at the default 1e-9 on 58 of 2,000 random workspace poses, at 1e-13 no
#: catalog robot's do. 1e-12 keeps a factor of 10 from that edge. (The API keeps ``[0, MAX_RTOL]``:
#: ``rtol = 0`` is exact for sympy rows.)
MIN_FLOAT_RTOL = 1e-12


def checked_rtol(value: Any, name: str = "rtol") -> float:
    """A relative tolerance: a real number in ``[0, MAX_RTOL]`` (:data:`MAX_RTOL` = 0.1).

    Parameters
    ----------
    value : object
        The candidate tolerance.
    name : str, default "rtol"
        The argument's name in the error message.

    Returns
    -------
    float

    Examples
    --------
    >>> checked_rtol(1e-6)
    1e-06
    >>> checked_rtol(0.5)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `rtol` to be a number in [0, 0.1], got 0.5.
    """
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ScrewkitTypeError(f"Expected `{name}` to be a number in [0, {MAX_RTOL:g}], got {value!r}.")
    if not 0 <= float(value) <= MAX_RTOL:
        raise ScrewkitValueError(f"Expected `{name}` to be a number in [0, {MAX_RTOL:g}], got {value!r}.")
    return float(value)
