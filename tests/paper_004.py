"""Paper 004's test path (Wu, Bai, Caro 2018, Sec. 5.1): the spiral of Eqs. (17)-(18) along which the
paper reports the Quattro's pressure angles. Used by the tests that check those reports
(``tests/robots/test_families_four_limb.py``, ``tests/facts_four_limb.py``)."""

from __future__ import annotations

import numpy as np

from screwkit.exceptions import ScrewkitValueError

__all__ = ["TABLE_4", "spiral_trajectory"]


def spiral_trajectory(n: int) -> np.ndarray:
    """The Quattro test path of Eqs. (17)-(18) (paper 004), in mm and radians.

    ``x = 650ρ cos ϑ``, ``y = 650ρ sin ϑ``, ``z = -975 + 500ρ``, ``φ = πρ - π/2`` with
    ``ρ = ϑ/(4π)`` and ``ϑ`` evenly spaced on ``[0, 4π]`` (both ends included).

    Parameters
    ----------
    n : int
        Number of poses, at least 2.

    Returns
    -------
    (n, 4) ndarray

    Examples
    --------
    >>> spiral_trajectory(3).round(6)
    array([[    0.      ,     0.      ,  -975.      ,    -1.570796],
           [  325.      ,    -0.      ,  -725.      ,     0.      ],
           [  650.      ,    -0.      ,  -475.      ,     1.570796]])
    """
    if not isinstance(n, int | np.integer) or isinstance(n, bool) or n < 2:
        raise ScrewkitValueError(f"Expected `n` to be an integer >= 2, got {n!r}.")
    vartheta = np.linspace(0.0, 4.0 * np.pi, int(n))
    rho = vartheta / (4.0 * np.pi)
    return np.stack(
        [
            650.0 * rho * np.cos(vartheta),
            650.0 * rho * np.sin(vartheta),
            -975.0 + 500.0 * rho,
            np.pi * rho - np.pi / 2.0,
        ],
        axis=-1,
    )


#: Paper 004, Table 4 ("The min-/maximum LTI within the operational workspace"), as printed:
#: ``{(robot, phi in degrees): (eta_min, eta_max)}``; the Veloce's and the Ragnar's phi = 360 deg
#: column is for h = 20 mm.
TABLE_4 = {
    ("Quattro", 0.0): (0.380, 1.0),
    ("Quattro", 45.0): (0.173, 0.750),
    ("H4", 0.0): (0.031, 0.917),
    ("H4", 45.0): (0.0, 0.847),
    ("Veloce", 0.0): (0.287, 1.0),
    ("Veloce", 360.0): (0.268, 0.999),
    ("V4", 0.0): (0.008, 0.872),
    ("V4", 45.0): (0.0, 0.804),
    ("Ragnar", 0.0): (0.238, 0.892),
    ("Ragnar", 360.0): (0.175, 0.885),
}
