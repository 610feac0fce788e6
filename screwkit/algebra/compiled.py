"""Compiled kernels and their numpy twins: when numba runs, and the one order of summation.

Every batched kernel of screwkit has a numpy path (vectorized over the batch) and, when numba is
installed (the ``fast`` extra), a compiled per-pose loop in a private ``*_numba`` module beside it.
The analysis kernels do the same floating-point operations in the same order (sums left to right
from ``0.0``, :func:`sum_in_order`; no BLAS call), so they agree bit for bit and the choice never
changes an answer; the loop closure's Newton correctors (:mod:`screwkit.core._newton_numba`,
:mod:`screwkit.core._rod_newton_numba`) factorise differently from their numpy twins and agree to
round-off (≲ 1e-9 in joint values on the H4; the same poses reached), each saying so.
:func:`compiled_kernels` makes that choice with one rule for every compiled path: a module is
imported on the first call over :data:`COMPILED_MIN_BATCH` elements or more, so a single-pose
analysis never pays for numba's import, and once loaded it serves every call. The environment
variable ``SCREWKIT_NUMBA``, read once when this module is imported, forces the choice: ``0`` (or
``false``, ``no``, ``off``) the numpy path, anything else the default (numba if it imports).

Examples
--------
>>> sum_in_order(np.array([[1e16, 1.0, -1e16], [1.0, 2.0, 3.0]]))
array([0., 6.])
>>> COMPILED_MIN_BATCH  # fewest batch elements for which a compiled module is loaded
256
"""

from __future__ import annotations

import importlib
import importlib.util
import os
from types import ModuleType

import numpy as np

__all__ = ["COMPILED_MIN_BATCH", "compiled_kernels", "sum_in_order"]

#: ``SCREWKIT_NUMBA=0`` forces the numpy path (read once, here).
_NUMBA_WANTED = os.environ.get("SCREWKIT_NUMBA", "1").strip().lower() not in {"0", "false", "no", "off"}
_compiled: dict[str, ModuleType | None] = {}

#: Fewest batch elements (frames, or poses) in one kernel call for which a compiled module is loaded:
#: numba's import and cached code cost ≈ 0.5 s once per process, what the numpy kernels take for
#: a few hundred small calls (a single-pose analysis and its sampled superbracket: at most 48 poses
#: × the limbs per call). A chunk of the batched core (256 poses) reaches it; once loaded, a module
#: serves every call.
COMPILED_MIN_BATCH = 256


def compiled_kernels(name: str, size: int) -> ModuleType | None:
    """The numba kernel module ``name`` (dotted) for a call over ``size`` batch elements; None
    for the numpy path.

    One rule for every compiled path: numba if it is installed, ``SCREWKIT_NUMBA`` is not ``0``,
    and the module is already loaded or the call has at least :data:`COMPILED_MIN_BATCH` elements (it
    is then imported, once; a broken numba install falls back to numpy for good). The two paths
    agree bit for bit (the loop closure's correctors: to round-off, module docstring).

    Parameters
    ----------
    name : str
        The dotted name of the kernel module, e.g. ``"screwkit.core._frames_numba"``.
    size : int
        The number of batch elements (frames or poses) of the call.

    Returns
    -------
    module or None
        The imported kernel module, or None when the call runs the numpy path.

    Examples
    --------
    >>> name = "screwkit.algebra._reference_frame_numba"
    >>> compiled_kernels(name, 1) is None or name in _compiled
    True
    """
    if name not in _compiled:
        if size < COMPILED_MIN_BATCH:
            return None
        module = None
        if _NUMBA_WANTED and importlib.util.find_spec("numba") is not None:
            try:
                module = importlib.import_module(name)
            except ImportError:  # a broken numba install: the numpy path, for the whole process
                module = None
        _compiled[name] = module
    return _compiled[name]


def sum_in_order(values: np.ndarray) -> np.ndarray:
    """``Σ_s values[..., s]`` over the last axis, summed left to right from ``0.0``: the compiled
    kernels' loop, operation for operation (numpy's own reductions may add in another order, and
    so differ in the last bits).

    Parameters
    ----------
    values : numpy.ndarray, shape (..., n)
        The terms, summed over the last axis.

    Returns
    -------
    numpy.ndarray, shape (...)
        The sums (zeros when ``n`` is 0).

    Examples
    --------
    >>> sum_in_order(np.array([[1e16, 1.0, -1e16], [1.0, 2.0, 3.0]]))
    array([0., 6.])
    """
    if values.shape[-1] == 0:
        return np.zeros(values.shape[:-1])
    columns = values.reshape(-1, values.shape[-1])  # 2-D views index faster than ``[..., s]``
    total = columns[:, 0] + 0.0
    for s in range(1, columns.shape[1]):
        total += columns[:, s]
    return total.reshape(values.shape[:-1])
