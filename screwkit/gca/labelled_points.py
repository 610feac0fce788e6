"""Labelled points for evaluation: a mapping ``{label: (..., 4)}`` validated, promoted together
(numeric or exact sympy) and broadcast to one batch shape (:func:`point_arrays`), and 0-d results
returned as scalars (:func:`scalar_result`). The brackets and joins evaluated on them are
:mod:`screwkit.algebra.projective`'s kernels.

Examples
--------
>>> point_arrays({"a": [0, 0, 0, 1]}, "a")["a"]
array([0., 0., 0., 1.])
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitTypeError, ScrewkitValueError

__all__ = [
    "point_arrays",
    "scalar_result",
]


def point_arrays(
    points: Any, labels: Iterable[str], *, symbolic: bool | None = None
) -> dict[str, np.ndarray]:
    """Validate ``points`` (a mapping label -> (..., 4)), promote them together and broadcast.

    Parameters
    ----------
    points : mapping of str to array_like, shape (..., 4)
    labels : iterable of str
        The labels needed.
    symbolic : bool, optional
        Force the symbolic (True) or numeric (False) branch; default: symbolic if any point is.

    Returns
    -------
    dict of str to numpy.ndarray, shape (..., 4)
        The needed points, sorted by label, broadcast to one batch shape.

    Raises
    ------
    ScrewkitTypeError, ScrewkitValueError
        For a missing label, a wrong shape, batch shapes that do not broadcast.

    Examples
    --------
    >>> arrays = point_arrays({"a": [0, 0, 0, 1], "b": [[1, 0, 0, 1], [2, 0, 0, 1]]}, "ab")
    >>> arrays["a"].shape
    (2, 4)
    """
    if not isinstance(points, Mapping):
        raise ScrewkitTypeError(
            f"Expected `points` to be a mapping from labels to points of shape (..., 4), "
            f"got {type(points).__name__}."
        )
    wanted = sorted(set(labels))
    missing = [label for label in wanted if label not in points]
    if missing:
        raise ScrewkitValueError(
            f"Expected `points` to give a point for every label {wanted}, missing {missing}."
        )
    arrays = [
        B.as_array(points[label], f"points[{label!r}]", (4,), symbolic=symbolic) for label in wanted
    ]
    arrays = list(B.promote(*arrays))
    try:
        batch = np.broadcast_shapes(*(a.shape[:-1] for a in arrays))
    except ValueError as err:
        shapes = {label: a.shape for label, a in zip(wanted, arrays, strict=True)}
        raise ScrewkitValueError(
            f"Expected the batch shapes of `points` to broadcast, got {shapes}."
        ) from err
    return {label: np.broadcast_to(a, (*batch, 4)) for label, a in zip(wanted, arrays, strict=True)}


def scalar_result(value: Any) -> Any:
    """A 0-d result as a scalar (numpy float or sympy expression), batches as arrays.

    Parameters
    ----------
    value : object

    Returns
    -------
    object
        ``value[()]`` for a 0-d array, else ``value``.

    Examples
    --------
    >>> scalar_result(np.array(2.0)), scalar_result(np.zeros(2))
    (np.float64(2.0), array([0., 0.]))
    """
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value[()]
    return value
