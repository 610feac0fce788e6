"""Paper 004's Table 4 regenerated: the extremes of a transmission index over a region.

:class:`Region` (a box, paper 004's super-ellipsoid of Eq. 19, or the cone-cylinder assumed for
its missing Fig. 6), :func:`index_extremes` (a grid over the region, then a compass search from its
best points) and :func:`table_4` (each (robot, φ) cell pair of Table 4, the paper's values beside
ours, with the cause of every difference; ``screwkit table4``). The indices are
:func:`screwkit.papers.paper_004.transmission`'s, fused kernel or numpy.

Source: paper 004 (Wu, Bai, Caro, JMR 10(5), 2018) (docs/papers.md).

Examples
--------
>>> result = index_extremes(load_mechanism("h4"), grid=5, refine=0)
>>> bool(0 <= result.minimum <= result.maximum <= 1)
True
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .paper_004 import (
    INDEX_NAMES,
    _four_limb_parameters,
    _kernel_arguments,
    _numba_kernels,
    _transmission_numpy,
)

__all__ = [
    "MAX_GRID",
    "MAX_REFINE",
    "TABLE_4",
    "TABLE_4_CONE",
    "TABLE_4_EQ_19",
    "TABLE_4_TOLERANCE",
    "IndexExtremes",
    "Region",
    "Table4Row",
    "index_extremes",
    "table_4",
]

# --------------------------------------------------------------------------------------------------
# Regions and the extremes of an index over a region (Table 4)
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Region:
    """A region of platform positions ``(x, y, z)``: a bounding box and a membership test.

    Build one with :meth:`box`, :meth:`super_ellipsoid` or :meth:`cone_cylinder`.

    Attributes
    ----------
    name : str
    lower, upper : tuple of 3 float
        The bounding box.
    contains : callable
        ``points (..., 3) -> bool (...)``.
    """

    name: str
    lower: tuple[float, float, float]
    upper: tuple[float, float, float]
    contains: Callable[[np.ndarray], np.ndarray]

    @classmethod
    def box(cls, x: tuple[float, float], y: tuple[float, float], z: tuple[float, float]) -> Region:
        """The box ``x × y × z``.

        Parameters
        ----------
        x, y, z : tuple of 2 float
            The bounds along each axis.

        Returns
        -------
        Region

        Examples
        --------
        >>> Region.box((0, 1), (0, 1), (0, 1)).contains(np.array([[0.5, 0.5, 2.0]])).tolist()
        [False]
        """
        lower, upper = (float(x[0]), float(y[0]), float(z[0])), (float(x[1]), float(y[1]), float(z[1]))

        def inside(points: np.ndarray) -> np.ndarray:
            return np.all((points >= np.array(lower) - 1e-9) & (points <= np.array(upper) + 1e-9), axis=-1)

        return cls(f"box {lower}..{upper}", lower, upper, inside)

    @classmethod
    def super_ellipsoid(
        cls, centre: tuple[float, float, float], semi_axes: tuple[float, float, float], exponent: float = 3.0
    ) -> Region:
        """``Σ |(x_k - c_k)/a_k|^e ≤ 1`` (paper 004, Eq. 19 with ``e = 3``).

        Parameters
        ----------
        centre, semi_axes : tuple of 3 float
        exponent : float

        Returns
        -------
        Region

        Examples
        --------
        >>> eq_19 = Region.super_ellipsoid((0, 0, -575), (505, 685, 365))
        >>> eq_19.contains(np.array([[0, 0, -575], [505, 0, -210]])).tolist()
        [True, False]
        """
        c, a = np.array(centre, dtype=float), np.array(semi_axes, dtype=float)

        def inside(points: np.ndarray) -> np.ndarray:
            return np.sum(np.abs((points - c) / a) ** exponent, axis=-1) <= 1.0 + 1e-9

        lower, upper = tuple((c - a).tolist()), tuple((c + a).tolist())
        return cls(f"super-ellipsoid |x/a|^{exponent:g} about {tuple(c.tolist())}, a = {tuple(a.tolist())}",
                   lower, upper, inside)

    @classmethod
    def cone_cylinder(cls, apex_z: float, radius: float, rim_z: float, top_z: float) -> Region:
        """About ``z``: a cone (apex ``(0, 0, apex_z)``, radius ``radius`` at ``rim_z``) below a
        cylinder of that radius up to ``top_z`` (the Table 4 workspace assumed for paper 004's
        missing Fig. 6: the cone of the spiral of Eq. 17, ``-975``, 650, ``-575``, ``-475`` mm).

        Parameters
        ----------
        apex_z, radius, rim_z, top_z : float

        Returns
        -------
        Region

        Examples
        --------
        >>> cone = Region.cone_cylinder(-975, 650, -575, -475)
        >>> cone.contains(np.array([[600, 0, -500], [600, 0, -900]])).tolist()
        [True, False]
        """

        def inside(points: np.ndarray) -> np.ndarray:
            z = points[..., 2]
            limit = np.where(z >= rim_z, radius, radius * (z - apex_z) / (rim_z - apex_z))
            within = np.hypot(points[..., 0], points[..., 1]) <= limit + 1e-9
            return within & (z >= apex_z - 1e-9) & (z <= top_z + 1e-9)

        return cls(f"cone-cylinder (apex z {apex_z:g}, radius {radius:g} from z {rim_z:g} to {top_z:g})",
                   (-radius, -radius, apex_z), (radius, radius, top_z), inside)

    def boundary(self, count: int = 16) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Points of the region's boundary on a latitude-longitude grid about the centre of its box,
        each where the ray from the centre leaves the region (bisection on :attr:`contains`; the
        region must be star-shaped about that centre, as the box, the super-ellipsoid and the
        cone-cylinder are): ``x, y, z`` of shape ``(count + 1, 2 count + 1)``, for a wireframe.

        Parameters
        ----------
        count : int
            Latitudes (``2 count`` longitudes).

        Returns
        -------
        x, y, z : numpy.ndarray, shape (count + 1, 2 count + 1)

        Examples
        --------
        >>> x, y, z = Region.super_ellipsoid((0, 0, 0), (1, 2, 3), 2.0).boundary(8)
        >>> x.shape, bool(np.allclose(x**2 + (y / 2) ** 2 + (z / 3) ** 2, 1.0))
        ((9, 17), True)
        """
        centre = 0.5 * (np.array(self.lower) + np.array(self.upper))
        polar, azimuth = np.meshgrid(
            np.linspace(0.0, np.pi, count + 1), np.linspace(-np.pi, np.pi, 2 * count + 1), indexing="ij"
        )
        sine = np.sin(polar)
        directions = np.stack([sine * np.cos(azimuth), sine * np.sin(azimuth), np.cos(polar)], axis=-1)
        reach = float(np.linalg.norm(np.array(self.upper) - np.array(self.lower)))  # beyond the box
        points = _pulled_inside(self, centre, centre + reach * directions.reshape(-1, 3))
        x, y, z = points.reshape(*polar.shape, 3).transpose(2, 0, 1)
        return x, y, z


class IndexExtremes(NamedTuple):
    """The extremes of an index over a region at one rotation angle (:func:`index_extremes`).

    Attributes
    ----------
    minimum, maximum : float
    argmin, argmax : numpy.ndarray, shape (4,)
        The poses ``(x, y, z, φ)`` where they are reached.
    points : int
        Grid points inside the region or on its boundary.
    reachable_fraction : float
        The fraction of them the robot reaches (the others are skipped).
    grid_minimum, grid_maximum : float
        The extremes over the grid alone (before refinement).
    """

    minimum: float
    maximum: float
    argmin: np.ndarray
    argmax: np.ndarray
    points: int
    reachable_fraction: float
    grid_minimum: float
    grid_maximum: float


def _index_values(mechanism: Any, index: str, poses: np.ndarray, mode: tuple[int, ...]) -> np.ndarray:
    kernels = _numba_kernels(len(poses))
    if kernels is None:
        kappa, zeta, ok = _transmission_numpy(mechanism, poses, mode)
    else:
        packed = _kernel_arguments(mechanism.parameters, mode)
        kappa, zeta, ok = kernels.transmission(np.ascontiguousarray(poses), *packed)
    values = {"lti": np.minimum(kappa, zeta), "input": kappa, "output": zeta}[index]
    return np.where(ok, values, np.nan)


def _pulled_inside(region: Region, fallback: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Each target outside the region moved along the segment from the region's centre (the centre
    of its box; ``fallback`` if that is outside) to the last point inside (bisection on the
    membership test), so the search can slide along a curved boundary of a star-shaped region."""
    centre = 0.5 * (np.array(region.lower) + np.array(region.upper))
    if not region.contains(centre[None])[0]:
        centre = fallback
    outside = ~region.contains(targets)
    if not outside.any():
        return targets
    low, high = np.zeros(int(outside.sum())), np.ones(int(outside.sum()))
    delta = targets[outside] - centre
    for _ in range(30):
        middle = 0.5 * (low + high)
        inside = region.contains(centre + middle[:, None] * delta)
        low, high = np.where(inside, middle, low), np.where(inside, high, middle)
    moved = targets.copy()
    moved[outside] = centre + low[:, None] * delta
    return moved


def _refined(
    mechanism: Any, index: str, region: Region, start: np.ndarray, step: np.ndarray, sign: float,
    mode: tuple[int, ...], rounds: int,
) -> tuple[float, np.ndarray]:
    """Compass search from a grid point: the 26 neighbours (pulled back inside the region where they
    leave it), halving the step each round."""
    offsets = np.stack(np.meshgrid(*[np.array([-1.0, 0.0, 1.0])] * 3, indexing="ij"), axis=-1).reshape(-1, 3)
    best = start.copy()
    best_value = sign * float(_index_values(mechanism, index, best[None], mode)[0])
    for _ in range(rounds):
        candidates = _pulled_inside(region, best[:3], best[:3] + offsets * step)
        poses = np.column_stack([candidates, np.full(len(candidates), best[3])])
        values = sign * _index_values(mechanism, index, poses, mode)
        if np.any(np.isfinite(values)):
            pick = int(np.nanargmin(values))
            if values[pick] < best_value:
                best, best_value = poses[pick], float(values[pick])
                continue  # keep the step while the search moves
        step = step / 2.0
    return sign * best_value, best


#: The largest grid (points per axis, ``grid³`` poses) and number of refinement rounds a search over
#: a region takes (:func:`index_extremes`, :func:`table_4`, :mod:`~screwkit.papers.paper_004_surfaces`):
#: 201³ ≈ 8·10⁶ poses and 200 rounds already take minutes; larger values are refused, not run out of
#: memory or time.
MAX_GRID = 201
MAX_REFINE = 200


def _region_grid(
    mechanism: Any, region: Region | None, phi: Any, working_mode: Any, *, grid: Any, refine: Any = 0
) -> tuple[Region, tuple[int, int, int, int], list[np.ndarray]]:
    """The checked region (default: the mechanism's workspace box), working mode and grid axes of a
    search at one rotation ``phi`` (:func:`index_extremes`, :mod:`~screwkit.papers.paper_004_surfaces`)."""
    from ..robots.families.four_limb.kinematics import checked_working_mode

    for name, value, least, most in (("grid", grid, 2, MAX_GRID), ("refine", refine, 0, MAX_REFINE)):
        if not isinstance(value, int | np.integer) or isinstance(value, bool) or not least <= value <= most:
            raise ScrewkitValueError(f"Expected `{name}` to be an integer in {least}..{most}, got {value!r}.")
    from ..robots.toml_fields import MAX_ANGLE_RADIANS

    numeric = isinstance(phi, int | float | np.integer | np.floating)
    if not numeric or not abs(float(phi)) <= MAX_ANGLE_RADIANS:
        raise ScrewkitValueError(
            f"Expected `phi` to be a finite number of at most {MAX_ANGLE_RADIANS:g} in magnitude (radians), "
            f"got {phi!r}."
        )
    if region is None:
        box = mechanism.workspace
        region = Region.box(box["x"], box["y"], box["z"])
    elif not isinstance(region, Region):
        raise ScrewkitTypeError(f"Expected `region` to be a Region, got {type(region).__name__}.")
    mode = checked_working_mode((-1, -1, -1, -1) if working_mode is None else working_mode)
    axes = [np.linspace(lo, hi, int(grid)) for lo, hi in zip(region.lower, region.upper, strict=True)]
    return region, mode, axes


def index_extremes(
    mechanism: Any,
    index: str = "lti",
    region: Region | None = None,
    *,
    phi: float = 0.0,
    grid: int = 41,
    refine: int = 12,
    working_mode: Any = None,
) -> IndexExtremes:
    """The minimum and maximum of a transmission index over a region at one rotation ``φ``.

    A ``grid``³ grid over the region's bounding box (its points outside the region moved onto the
    region's boundary; points out of reach skipped), then ``refine`` rounds of a compass search
    from the best grid points (the 26 neighbours, pulled back onto the region's boundary where they
    leave it; the step halves when no neighbour improves, and stays while the search moves).
    Paper 004 reports Table 4 ("the max-/minimum LTI within the operational workspace") without
    saying how it searched; :func:`table_4` compares.

    Parameters
    ----------
    mechanism : Mechanism
        A four-limb catalog mechanism.
    index : {"lti", "input", "output"}
        η (Eq. 16), κ or ζ (Eq. 15).
    region : Region, optional
        Default: the box of the mechanism's ``[workspace]``.
    phi : float
        Rotation of the platform, radians.
    grid : int
        Points per axis (at least 2).
    refine : int
        Rounds of local refinement (0: the grid's values).
    working_mode : sequence of 4 int, optional

    Returns
    -------
    IndexExtremes

    Raises
    ------
    ScrewkitValueError
        Unknown index, a bad grid or refine count, a non-finite ``phi``, or no reachable grid point.

    Examples
    --------
    >>> result = index_extremes(load_mechanism("quattro"), region=Region.cone_cylinder(-975, 650, -575, -475),
    ...                         grid=21, refine=0)
    >>> round(result.maximum, 3), result.points
    (1.0, 8921)
    """
    _four_limb_parameters(mechanism)  # a four-limb mechanism, or the message naming the family
    if index not in INDEX_NAMES:
        raise ScrewkitValueError(f"Expected `index` to be one of {INDEX_NAMES}, got {index!r}.")
    region, mode, axes = _region_grid(mechanism, region, phi, working_mode, grid=grid, refine=refine)
    points = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    # the box's points outside the region, pulled onto its boundary: a boundary sampling as fine as
    # the grid (extremes often sit on the boundary, between the grid's points)
    points = np.unique(_pulled_inside(region, points[0], points).round(9), axis=0)
    poses = np.column_stack([points, np.full(len(points), float(phi))])
    values = _index_values(mechanism, index, poses, mode)
    reached = np.isfinite(values)
    if not reached.any():
        raise ScrewkitValueError(
            f"No point of the {grid}^3 grid over {region.name} is reachable by {mechanism.name} at "
            f"phi = {math.degrees(phi):g} deg."
        )
    step = np.array([(hi - lo) / (grid - 1) for lo, hi in zip(region.lower, region.upper, strict=True)])
    low_at, high_at = int(np.nanargmin(values)), int(np.nanargmax(values))
    low, low_pose = _refined(mechanism, index, region, poses[low_at], step / 2, 1.0, mode, refine)
    high, high_pose = _refined(mechanism, index, region, poses[high_at], step / 2, -1.0, mode, refine)
    return IndexExtremes(low, high, low_pose, high_pose, len(points), float(reached.mean()),
                         float(values[low_at]), float(values[high_at]))


# --------------------------------------------------------------------------------------------------
# Paper 004's Table 4, regenerated
# --------------------------------------------------------------------------------------------------

#: The Table 4 workspace of the Quattro, H4, V4 and Veloce: paper 004's Fig. 6 is missing from the
#: text, so this is an assumption (the cone on which the spiral of Eq. 17 lies, capped by a
#: cylinder: the Quattro's 1300 mm x 500 mm envelope), the one the catalog's facts use.
TABLE_4_CONE = Region.cone_cylinder(-975.0, 650.0, -575.0, -475.0)
#: The Ragnar's super-ellipsoid, paper 004 Eq. (19).
TABLE_4_EQ_19 = Region.super_ellipsoid((0.0, 0.0, -575.0), (505.0, 685.0, 365.0), 3.0)

_CONE_NOTE = (
    "paper 004's workspace (Fig. 6) is missing from the text; over the assumed cone-cylinder the "
    "extreme differs, so the paper's workspace differs from it"
)
#: Why a minimum over a region that reaches beyond the robot's reach is not a converged number.
_BEYOND_REACH_NOTE = (
    "the assumed region reaches just beyond the robot's reach ({share:.3%} of the {grid}^3 grid is out "
    "of reach); near that boundary a limb is stretched and kappa -> 0 (a type-1 singularity), so the "
    "minimum over the region is 0 in the limit and our value only says how close the grid comes (a "
    "finer grid gives less); the paper's workspace (Fig. 6, missing) evidently stays inside the reach"
)
_RAGNAR_MIN_NOTE = (
    "part of Eq. (19) is out of reach with the printed b, l and A_i (e.g. (0, 0, -250): "
    "|C_1 - A_1| = 376 mm < l - b = 425 mm), so the paper's Ragnar dimensions differ; over the "
    "reachable part the minimum sits at the reach boundary (a type-1 singularity)"
)
_RAGNAR_MAX_NOTE = (
    "the axis inclination (45 deg) is inferred from this table's phi = 0 maximum (ragnar.toml); with "
    "it the phi = 360 deg maximum is not the paper's, so the real Ragnar differs in more than eps"
)


class Table4Row(NamedTuple):
    """One cell pair of paper 004's Table 4, the paper's values beside ours.

    Attributes
    ----------
    robot, mechanism : str
        The paper's row name and the catalog entry.
    phi_deg : float
    region : str
    paper_min, paper_max : float
    ours : IndexExtremes
    notes : dict of str to str
        ``"min"``/``"max"``: why ours differs from the paper's (only where it does).
    """

    robot: str
    mechanism: str
    phi_deg: float
    region: str
    paper_min: float
    paper_max: float
    ours: IndexExtremes
    notes: dict[str, str]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
        """
        return {
            "robot": self.robot, "mechanism": self.mechanism, "phi_deg": self.phi_deg, "region": self.region,
            "paper": {"min": self.paper_min, "max": self.paper_max},
            "ours": {"min": self.ours.minimum, "max": self.ours.maximum,
                     "argmin": self.ours.argmin.tolist(), "argmax": self.ours.argmax.tolist(),
                     "points": self.ours.points, "reachable_fraction": self.ours.reachable_fraction},
            "notes": self.notes,
        }


#: Table 4 of paper 004: (row, catalog entry, φ in degrees, region, η_min, η_max, why a min / max
#: may differ). Values as printed; the Veloce's φ = 360° column is for h = 20 mm (its catalog lead).
TABLE_4: tuple[tuple[str, str, float, str, float, float, str, str], ...] = (
    ("Quattro", "quattro", 0.0, "cone", 0.380, 1.0, _CONE_NOTE, _CONE_NOTE),
    ("Quattro", "quattro", 45.0, "cone", 0.173, 0.750, _CONE_NOTE, _CONE_NOTE),
    ("H4", "h4", 0.0, "cone", 0.031, 0.917, _CONE_NOTE, _CONE_NOTE),
    ("H4", "h4", 45.0, "cone", 0.0, 0.847, _CONE_NOTE, _CONE_NOTE),
    ("Veloce", "veloce", 0.0, "cone", 0.287, 1.0, _CONE_NOTE, _CONE_NOTE),
    ("Veloce", "veloce", 360.0, "cone", 0.268, 0.999, _CONE_NOTE, _CONE_NOTE),
    ("V4", "v4", 0.0, "cone", 0.008, 0.872, _CONE_NOTE, _CONE_NOTE),
    ("V4", "v4", 45.0, "cone", 0.0, 0.804, _CONE_NOTE, _CONE_NOTE),
    ("Ragnar", "ragnar", 0.0, "eq_19", 0.238, 0.892, _RAGNAR_MIN_NOTE, _RAGNAR_MAX_NOTE),
    ("Ragnar", "ragnar", 360.0, "eq_19", 0.175, 0.885, _RAGNAR_MIN_NOTE, _RAGNAR_MAX_NOTE),
)

#: Agreement with a Table 4 value: the paper prints 3 decimals; a 41³ grid moves the extremes by
#: up to about 1e-3 (tests/papers/test_paper_004.py measures it).
TABLE_4_TOLERANCE = 0.002


def table_4(*, grid: int = 41, refine: int = 12, robots: Any = None) -> list[Table4Row]:
    """Paper 004's Table 4 regenerated: each (robot, φ) cell pair, the paper's and ours.

    Parameters
    ----------
    grid, refine : int
        As :func:`index_extremes`.
    robots : iterable of str, optional
        Catalog names to include (default all five).

    Returns
    -------
    list of Table4Row
        A note explains each value that differs from the paper's by more than
        :data:`TABLE_4_TOLERANCE`: the grid (when the paper's value lies between our grid value and
        our refined one), or the known cause (the missing workspace figure, the Ragnar's data).

    Examples
    --------
    >>> row = table_4(grid=21, refine=0, robots=["veloce"])[0]
    >>> row.robot, row.paper_max, round(row.ours.maximum, 2)
    ('Veloce', 1.0, 1.0)
    """
    from ..robots.catalog import load_mechanism

    wanted = None if robots is None else set(robots)
    regions = {"cone": TABLE_4_CONE, "eq_19": TABLE_4_EQ_19}
    rows = []
    for robot, name, phi_deg, region, low, high, low_note, high_note in TABLE_4:
        if wanted is not None and name not in wanted:
            continue
        mechanism = load_mechanism(name)
        ours = index_extremes(mechanism, "lti", regions[region], phi=math.radians(phi_deg), grid=grid,
                              refine=refine)
        notes = {}
        for key, paper, refined, on_grid, cause in (
            ("min", low, ours.minimum, ours.grid_minimum, low_note),
            ("max", high, ours.maximum, ours.grid_maximum, high_note),
        ):
            if abs(refined - paper) <= TABLE_4_TOLERANCE:
                continue
            if key == "min" and ours.reachable_fraction < 1 and cause == _CONE_NOTE:
                cause = _BEYOND_REACH_NOTE.format(share=1 - ours.reachable_fraction, grid=grid)
            low_end, high_end = min(refined, on_grid), max(refined, on_grid)
            between = low_end - TABLE_4_TOLERANCE <= paper <= high_end + TABLE_4_TOLERANCE
            notes[key] = (
                f"the extreme lies between grid points: our {grid}^3 grid gives {on_grid:.3f}, the refined "
                f"value is {refined:.3f}; the paper's {paper:.3f} lies between (a grid value: its grid is "
                "not given)" if between else cause
            )
        rows.append(Table4Row(robot, name, phi_deg, regions[region].name, low, high, ours, notes))
    return rows
