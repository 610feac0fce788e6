"""Checks shared by the certification tests (tests/analysis/test_certify_*.py): a catalog mechanism
with its lengths in metres, the facts two certificates of one region in two length units must share,
and the zeros of an independent |sin| along a line."""

from __future__ import annotations

import numpy as np

from screwkit.robots.catalog import load_toml, mechanism_from_mapping


def in_metres(mechanism):
    """``mechanism`` (a catalog entry in mm) with every length, lists of points included, in metres."""
    data = load_toml(mechanism.source)
    data["mechanism"]["length_unit"] = "m"
    for entry in data["parameters"].values():
        if entry["unit"] == "mm":
            entry["value"] = (np.asarray(entry["value"], dtype=float) / 1000.0).tolist()
            entry["unit"] = "m"
    for key in ("x", "y", "z"):
        data["pose"][key] /= 1000.0
        data["workspace"][key] = [v / 1000.0 for v in data["workspace"][key]]
    data.pop("expected", None)
    return mechanism_from_mapping(data, source=f"{mechanism.name} in metres")


def assert_same_facts(in_mm, in_m, names=("x", "y")):
    """Rounding may split a box in one unit that the other proves free at once (the pavings then
    differ), but the facts agree: no witness of one lies in a free box of the other, the same singular
    sets are met, and the free volumes differ by less than what either leaves singular or undecided."""
    for mine, mine_scale, other, other_scale in ((in_mm, 1.0, in_m, 1e3), (in_m, 1e3, in_mm, 1.0)):
        for box in mine.boxes:
            if box.witness is not None:
                pose = {n: box.witness.pose[n] * mine_scale for n in names}
                assert not any(
                    b.status == "free"
                    and all(b.bounds[n][0] * other_scale <= pose[n] <= b.bounds[n][1] * other_scale for n in names)
                    for b in other.boxes
                )
    labels = [{b.witness.label for b in c.boxes if b.witness is not None} for c in (in_mm, in_m)]
    assert labels[0] == labels[1]
    margin = sum(c.fractions[k] for c in (in_mm, in_m) for k in ("singular", "undecided"))
    assert abs(in_mm.fractions["free"] - in_m.fractions["free"]) <= margin


def zeros_along(function, points):
    """The zeros of a V-shaped ``function >= 0`` (an |sin| between two couples) along the polyline
    ``points (m, n)``: each sampled local minimum below 0.05 refined by 50 ternary-search steps, kept
    when below 1e-6 (a minimum that is no zero is dropped). ``function`` returns None out of reach."""
    values = np.array([9.0 if (v := function(p)) is None else v for p in points])
    found = []
    for k in np.flatnonzero((values[1:-1] < values[:-2]) & (values[1:-1] < values[2:]) & (values[1:-1] < 0.05)):
        low, high = points[k], points[k + 2]
        for _ in range(50):
            m1, m2 = low + (high - low) / 3, high - (high - low) / 3
            if function(m1) < function(m2):
                high = m2
            else:
                low = m1
        zero = (low + high) / 2
        if function(zero) < 1e-6:
            found.append(zero)
    return found


class ScrewPairGeometry:
    """An independent model of a screw-pair robot of paper 004 (Ragnar, Veloce): platform points
    ``c_i = p + r R_z(γ_i) i + mod(i, 2) (h φ/2π) k`` (Table 1) and the unit rods of the branch
    ``h_i < 0`` (``w_i·(u_i × v_i) < 0``), by circle-sphere intersection; only the base's points and
    axes (parameters) are read from the catalog."""

    K = np.array([0.0, 0.0, 1.0])
    GAMMA = (2 * np.arange(1, 5) - 1) * np.pi / 4
    ODD = np.array([1.0, 0.0, 1.0, 0.0])  # mod(i, 2): limbs 1, 3 on sub-platform I

    def __init__(self, mechanism, rest_pose):
        frames = mechanism.configuration(np.array([rest_pose]))
        self.a_points, self.axes = frames.a[0], frames.u[0]
        params = mechanism.parameters
        self.arm, self.rod, self.radius = params.arm_length, params.rod_length, params.platform_radius
        self.rise = params.lead / (2 * np.pi)

    def points(self, pose):
        p, phi = np.asarray(pose[:3], dtype=float), float(pose[3])
        radial = np.stack([np.cos(self.GAMMA), np.sin(self.GAMMA), np.zeros(4)], -1)
        return p + self.radius * radial + (self.ODD * self.rise * phi)[:, None] * self.K

    def solve(self, pose):
        """``(c, elbows, rods)`` (each ``(4, 3)``), or None out of reach."""
        c = self.points(pose)
        elbows, rods = [], []
        for i in range(4):
            u, a = self.axes[i], self.a_points[i]
            height = (c[i] - a) @ u
            centre, radius2 = c[i] - height * u, self.rod**2 - height**2
            d = np.linalg.norm(centre - a)
            along = (d**2 + self.arm**2 - radius2) / (2 * d)
            if radius2 < 0 or self.arm**2 - along**2 < 0:
                return None
            e1 = (centre - a) / d
            for side in (1.0, -1.0):
                elbow = a + along * e1 + side * np.sqrt(self.arm**2 - along**2) * np.cross(u, e1)
                w = (c[i] - elbow) / self.rod
                if w @ np.cross(u, (elbow - a) / self.arm) < 0:
                    elbows.append(elbow)
                    rods.append(w)
                    break
        return c, np.array(elbows), np.array(rods)

    def geometry(self, pose):
        """``(c, rods)``, or None out of reach."""
        found = self.solve(pose)
        return None if found is None else (found[0], found[2])

    def det_a(self, pose):
        """det A, rows ``[w_i, w_i·∂c_i/∂φ]``, ``∂c_i/∂φ = mod(i, 2) (h/2π) k`` (paper 004, Eq. 7, Table 1)."""
        _, w = self.geometry(pose)
        return np.linalg.det(np.hstack([w, (self.ODD * self.rise * w[:, 2])[:, None]]))


# Screw systems from joint screws (rows (w; v), ordered as twists; wrenches (f; m)), independent of
# screwkit's wrench code: the rank computations of the certification tests.


def revolute(axis, point):
    return np.concatenate([axis, np.cross(point, axis)])


def reciprocal(rows):
    """An orthonormal basis of the screws reciprocal to ``rows`` (the null space of ``rows`` with their
    halves swapped: (w; v).(f; m) -> v.f + w.m), rank decided at 1e-9 of the largest singular value."""
    swapped = np.hstack([rows[:, 3:], rows[:, :3]])
    _, values, vt = np.linalg.svd(swapped)
    rank = int(np.sum(values > 1e-9 * values[0]))
    return vt[rank:]


def order(rows):
    if len(rows) == 0:
        return 0
    values = np.linalg.svd(rows, compute_uv=False)
    return int(np.sum(values > 1e-9 * values[0]))


def intersection(one, two):
    """The screws in both spans: reciprocal to the reciprocals of both."""
    return reciprocal(np.vstack([reciprocal(one), reciprocal(two)]))
