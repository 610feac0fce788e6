"""Marching tetrahedra (screwkit.analysis.isosurface): surfaces of known fields -- a plane (exact), a sphere
(vertices on it by linear interpolation to the grid's second order, and exactly after bisection;
area and closedness), NaN corners dropped, nothing where the field keeps its sign."""

from __future__ import annotations

from collections import Counter

import numpy as np

from screwkit.analysis.isosurface import zero_surface

AXES = [np.linspace(-1.3, 1.3, 27)] * 3
POINTS = np.stack(np.meshgrid(*AXES, indexing="ij"), axis=-1)


RADIUS = 0.97  # no grid point on the sphere: no degenerate triangle


def sphere(points):
    return np.sum(points * points, axis=-1) - RADIUS**2


def test_an_oblique_plane_is_exact():
    normal = np.array([1.0, 2.0, -2.0]) / 3.0
    triangles = zero_surface(AXES, POINTS @ normal - 0.2)
    assert len(triangles) > 100
    np.testing.assert_allclose(triangles @ normal, 0.2, rtol=0, atol=1e-12)


def test_a_sphere_linear_then_bisected():
    values = sphere(POINTS)
    linear = zero_surface(AXES, values)
    radius = np.linalg.norm(linear, axis=-1)
    spacing = AXES[0][1] - AXES[0][0]
    assert np.all(radius <= RADIUS + 1e-12) and np.all(radius >= RADIUS - spacing**2)  # chords inside
    exact = zero_surface(AXES, values, sphere)
    np.testing.assert_allclose(np.linalg.norm(exact, axis=-1), RADIUS, rtol=0, atol=1e-12)
    edges = exact[:, 1:] - exact[:, :1]
    area = 0.5 * np.linalg.norm(np.cross(edges[:, 0], edges[:, 1]), axis=-1).sum()
    assert abs(area - 4 * np.pi * RADIUS**2) < 0.01 * 4 * np.pi * RADIUS**2
    # closed, without cracks: every edge is shared by exactly two triangles
    _, index = np.unique(exact.reshape(-1, 3).round(9), axis=0, return_inverse=True)
    corners = index.reshape(-1, 3)
    counts = Counter(tuple(sorted((t[a], t[b]))) for t in corners for a, b in ((0, 1), (1, 2), (0, 2)))
    assert set(counts.values()) == {2}


def test_nan_corners_drop_their_tetrahedra_and_no_crossing_gives_nothing():
    values = sphere(POINTS)
    values[POINTS[..., 0] > 0.0] = np.nan
    half = zero_surface(AXES, values, sphere)
    assert len(half) and np.all(half[..., 0] <= 0.0 + 1e-12)
    assert zero_surface(AXES, sphere(POINTS) + 10.0).shape == (0, 3, 3)
