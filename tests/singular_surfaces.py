"""Poses on and near the H4's singular surfaces, found by root search (test helpers, not tests).

Three surfaces of the catalog H4 (``sk.load_mechanism("h4")``, poses ``(x, y, z)`` in mm and
``phi`` in rad):

* ``"constraint"``: the roots of paper 002's Eq. (6), ``(s12 × s34)·z = 0``;
* ``"actuation"``: the roots of paper 002's Eq. (7);
* ``"serial"``: the edge of the reachable set, where a limb's arm and rods line up (Eq. 3 of paper
  004 has a double root, ``h_i = b w_i·(u_i × v_i) = 0``, Eq. 8): the limb's actuated twist lies in
  the span of its other twists. Only its inner side exists (the outer side is out of reach).

Both conditions come from :func:`tests.robots.test_h4.paper_002_conditions` (computed there from the
parallelograms' plane normals, independently of the code under test).

**Where the roots are.** The catalog workspace (``h4.workspace``: |x|, |y| ≤ 350 mm, −1000 ≤ z ≤
−550 mm, |φ| ≤ 45°) holds none of the three surfaces: at ~2·10⁵ poses drawn in it, Eq. (6) < 0,
Eq. (7) > 0 and every pose is reachable but ~1 %. So each search segment *starts* at a random
catalog-workspace pose (``h4.random_poses``) and *ends* at a reachable pose beyond it
(:func:`tests.robots.test_h4.random_poses` with ``edge=True``: |x|, |y| ≤ 400 mm, z ≤ −500 mm,
|φ| ≤ 90°) where the condition has the other sign (for ``"serial"``: an unreachable pose of a
wider box). The sign change nearest the start on a 101-point grid of the segment (evaluated for
all segments at once) is refined by bisection on the segment's parameter
(:func:`tests.mechanisms.bisect_root`, to ``xtol = 1e-15``: machine precision).

**Distances.** ``d`` is relative to the **workspace size**: the pose at distance ``d`` on side
``±1`` of a root ``r`` is ``r ± d·(SCALE ⊙ e)``, where ``SCALE`` = the catalog workspace's extents
``(700 mm, 700 mm, 450 mm, π/2 rad)`` and ``e`` the unit direction of the segment in coordinates
divided by ``SCALE`` (side +1 points towards the segment's end). So ``d`` is a Euclidean distance
in workspace-scaled coordinates along the segment; the distance from the surface itself is
``d·|e·n|`` (``n`` the surface's unit normal in the same coordinates), stored as
``normal_distance``. In mm, ``d = 1e-6`` is ≈ 0.5 nm … 0.7 nm along the segment.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import screwkit as sk
from screwkit.robots.families.four_limb.kinematics import reachable

from .mechanisms import bisect_root
from .robots.test_h4 import paper_002_conditions
from .robots.test_h4 import random_poses as edge_poses

H4 = sk.load_mechanism("h4")
LOW, HIGH = (np.array(v, dtype=float) for v in zip(*(H4.workspace[c] for c in H4.pose_names), strict=True))
#: The catalog workspace's extents: the unit of the relative distances.
SCALE = HIGH - LOW
#: Relative distances from each root: 1e-12, 1e-11, ..., 1e-4.
DISTANCES = 10.0 ** np.arange(-12, -3)
SURFACES = ("constraint", "actuation", "serial")
_GRID = np.linspace(0.0, 1.0, 101)


def conditions(poses):
    """Paper 002's Eq. (6) and Eq. (7) at reachable poses ``(..., 4)`` (batched IK)."""
    eq6, eq7, _, _ = paper_002_conditions(H4.configuration(poses))
    return eq6, eq7


def surface_function(surface, poses):
    """The function whose sign changes across ``surface``: Eq. (6), Eq. (7), or ±1 reachable."""
    poses = np.asarray(poses, dtype=float)
    if surface == "serial":
        return np.where(reachable(H4.parameters, poses), 1.0, -1.0)
    return conditions(poses)[SURFACES.index(surface)]


@dataclass(frozen=True)
class Roots:
    """Roots of one surface: ``poses`` and unit segment ``directions`` (scaled coordinates), (k, 4)."""

    surface: str
    poses: np.ndarray
    directions: np.ndarray
    normals: np.ndarray  # unit normals of the surface (scaled coordinates); NaN for "serial"


def _stops(rng, surface, count):
    """Poses beyond the catalog workspace on the far side of ``surface``."""
    if surface == "serial":
        wide = rng.uniform([-500, -500, -1150, -np.pi / 2], [500, 500, -400, np.pi / 2], (40 * count, 4))
        return wide[~reachable(H4.parameters, wide)]
    candidates = edge_poses(rng, 200 * count, edge=True)
    values = surface_function(surface, candidates)
    far_side = values > 0 if surface == "constraint" else values < 0  # the workspace has Eq.6<0, Eq.7>0
    return candidates[far_side]


def _normal(surface, pose, step=1e-7):
    """Unit normal of the surface at ``pose`` in scaled coordinates (central differences)."""
    if surface == "serial":
        return np.full(4, np.nan)
    shifts = np.eye(4) * step * SCALE
    gradient = (surface_function(surface, pose + shifts) - surface_function(surface, pose - shifts)) / (2 * step)
    return gradient / np.linalg.norm(gradient)


def surface_roots(rng, surface, count):
    """``count`` roots of ``surface`` on random segments from the catalog workspace outwards."""
    stops = _stops(rng, surface, count)
    assert len(stops), f"no pose beyond the workspace on the far side of the {surface} surface"
    starts = H4.random_poses(rng, 20 * count)
    starts = starts[reachable(H4.parameters, starts)]
    stops = stops[rng.integers(0, len(stops), len(starts))]
    paths = starts[:, None, :] + _GRID[:, None] * (stops - starts)[:, None, :]  # (m, 101, 4)
    if surface == "serial":
        ok = np.ones(len(starts), dtype=bool)  # the path leaves the reachable set somewhere
    else:
        ok = reachable(H4.parameters, paths).all(axis=1)
    starts, stops, paths = starts[ok][: 2 * count], stops[ok][: 2 * count], paths[ok][: 2 * count]
    values = surface_function(surface, paths)
    changes = np.sign(values[:, :-1]) != np.sign(values[:, 1:])
    first = np.argmax(changes, axis=1)
    found = changes.any(axis=1)
    roots, directions, normals = [], [], []
    for start, stop, k in zip(starts[found], stops[found], first[found], strict=True):

        def along(t, start=start, stop=stop):
            return float(surface_function(surface, start + t * (stop - start)))

        t = bisect_root(along, _GRID[k], _GRID[k + 1])
        root = start + t * (stop - start)
        for _ in range(10_000):  # keep a serial root reachable: step back from the edge by ulps of t
            if surface != "serial" or reachable(H4.parameters, root):
                break
            t = np.nextafter(t, 0.0)
            root = start + t * (stop - start)
        direction = (stop - start) / SCALE
        roots.append(root)
        directions.append(direction / np.linalg.norm(direction))
        normals.append(_normal(surface, root))
        if len(roots) == count:
            break
    assert len(roots) == count, f"found {len(roots)} of {count} roots of the {surface} surface"
    return Roots(surface, np.array(roots), np.array(directions), np.array(normals))


@dataclass(frozen=True)
class NearSurfacePoses:
    """Poses near surface roots, flat arrays of one length.

    ``surface`` (str), ``root`` (index into the roots), ``side`` (±1, +1 towards the segment's end;
    ``"serial"`` only −1, inside the reach), ``distance`` (relative to the workspace size, along the
    segment), ``normal_distance`` (first order, from the surface; NaN for ``"serial"``).
    """

    poses: np.ndarray
    surface: np.ndarray
    root: np.ndarray
    side: np.ndarray
    distance: np.ndarray
    normal_distance: np.ndarray

    def __len__(self):
        return len(self.poses)

    def select(self, mask):
        return NearSurfacePoses(*(getattr(self, f)[mask] for f in self.__dataclass_fields__))

    @staticmethod
    def concatenate(parts):
        fields = NearSurfacePoses.__dataclass_fields__
        return NearSurfacePoses(*(np.concatenate([getattr(p, f) for p in parts]) for f in fields))


def near_surface_poses(roots, distances=DISTANCES):
    """Poses at every relative distance on both sides (only inside for ``"serial"``) of every root."""
    sides = np.array([-1.0]) if roots.surface == "serial" else np.array([-1.0, 1.0])
    k, s, d = np.meshgrid(np.arange(len(roots.poses)), sides, distances, indexing="ij")
    k, s, d = k.ravel(), s.ravel(), d.ravel()
    poses = roots.poses[k] + (s * d)[:, None] * roots.directions[k] * SCALE
    cosine = np.abs(np.einsum("ij,ij->i", roots.directions[k], roots.normals[k]))
    return NearSurfacePoses(
        poses=poses,
        surface=np.full(len(k), roots.surface),
        root=k,
        side=s,
        distance=d,
        normal_distance=d * cosine,
    )


def all_near_surface_poses(rng, count_per_surface, surfaces=SURFACES, distances=DISTANCES):
    """Near-surface poses of every surface (``count_per_surface`` roots each), and the roots."""
    roots = {surface: surface_roots(rng, surface, count_per_surface) for surface in surfaces}
    near = NearSurfacePoses.concatenate([near_surface_poses(r, distances) for r in roots.values()])
    assert all(reachable(H4.parameters, r.poses).all() for r in roots.values())
    assert reachable(H4.parameters, near.poses).all()
    return near, roots
