"""Family facts of the four-limb catalog entries (paper 004), evaluated by tests/robots/test_catalog.py.

``FACTS = {fact name: check(mechanism, fact) -> (got, expected)}``; ``test_catalog`` asserts
``got == expected``. Expected values are the TOML's (the paper's numbers); where a fact carries a
``tolerance`` the expected side is a :func:`pytest.approx`. A fact may list ``not_reproduced`` values:
paper numbers we do *not* reproduce (the TOML says why). For those the check asserts that our value
differs from the paper's by more than the tolerance, so a better reading of the paper shows up as a
failing test instead of being forced to match.

Regions for Table 4 (paper 004's Fig. 6, the workspace, is missing from the OCR text):

* ``"cone"``: the solid of revolution about ``z`` bounded below by the cone on which the spiral of
  Eq. (17) lies (apex ``(0, 0, -975)``, radius 650 mm at ``z = -575``) and above by a cylinder of
  radius 650 mm up to ``z = -475`` (the Quattro's 1300 mm x 500 mm envelope); a 61 x 61 x 41 grid
  plus 721 points on the top rim. The same assumption as ``tests/robots/test_families_four_limb.py``.
* ``"eq_19"``: the Ragnar's super-ellipsoid of Eq. (19) on a 41^3 grid.

Unreachable grid points are skipped.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import lru_cache
from typing import Any

import numpy as np
import pytest

from screwkit.algebra import screw as S
from screwkit.core.singularity import classify_table
from screwkit.core.wrenches import wrench_analysis
from screwkit.papers.paper_004 import (
    force_pressure_angle,
    four_limb_jacobians,
    motion_pressure_angles,
    transmission_indices,
)
from screwkit.robots.families.four_limb.joints import joints
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics, reachable

from .paper_004 import spiral_trajectory

K = np.array([0.0, 0.0, 1.0])
SEED = 20261121


# -------------------------------------------------------------------------------------------------
# Helpers
# -------------------------------------------------------------------------------------------------


def region_points(region: str) -> np.ndarray:
    """Grid points (x, y, z) of a Table 4 region (module docstring), shape (n, 3)."""
    if region == "cone":
        x = np.linspace(-650.0, 650.0, 61)
        z = np.linspace(-975.0, -475.0, 41)
        gx, gy, gz = np.meshgrid(x, x, z, indexing="ij")
        radius = np.where(gz >= -575.0, 650.0, 650.0 * (gz + 975.0) / 400.0)
        inside = np.hypot(gx, gy) <= radius + 1e-9
        angles = np.linspace(0.0, 2.0 * math.pi, 721)
        rim = np.column_stack([650.0 * np.cos(angles), 650.0 * np.sin(angles), np.full(721, -475.0)])
        return np.concatenate([np.column_stack([gx[inside], gy[inside], gz[inside]]), rim])
    if region == "eq_19":
        gx, gy, gz = np.meshgrid(
            np.linspace(-505.0, 505.0, 41),
            np.linspace(-685.0, 685.0, 41),
            np.linspace(-940.0, -210.0, 41),
            indexing="ij",
        )
        inside = np.abs(gx / 505) ** 3 + np.abs(gy / 685) ** 3 + np.abs((gz + 575) / 365) ** 3 <= 1 + 1e-9
        return np.column_stack([gx[inside], gy[inside], gz[inside]])
    raise AssertionError(f"unknown Table 4 region {region!r}: expected 'cone' or 'eq_19'")


def random_configuration(mechanism, count: int, seed: int = SEED):
    """The configuration at random reachable poses of the mechanism's workspace box."""
    poses = mechanism.random_poses(np.random.default_rng(seed), count)
    return mechanism.configuration(poses[reachable(mechanism.parameters, poses)])


def batch_labels(config) -> list[tuple[str, ...]]:
    """Labels of :func:`screwkit.core.singularity.classify_table` over a batched configuration (vectorized)."""
    return classify_table(joints(config)).labels.ravel().tolist()


def compare(computed: dict[str, Any], fact: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """``(got, expected)`` for a fact with a ``value`` table, a ``tolerance`` and ``not_reproduced``.

    ``computed`` holds our value for every key of ``value`` and ``not_reproduced`` (None: not found).
    """
    tolerance = fact["tolerance"]
    got: dict[str, Any] = {key: computed[key] for key in fact["value"]}
    expected: dict[str, Any] = {
        key: pytest.approx(value, abs=tolerance) for key, value in fact["value"].items()
    }
    for key, paper in fact.get("not_reproduced", {}).items():
        label = f"{key}: ours differs from the paper's {paper}"
        ours = computed[key]
        got[label] = ours is None or abs(ours - paper) > tolerance
        expected[label] = True
    return got, expected


# -------------------------------------------------------------------------------------------------
# Checks
# -------------------------------------------------------------------------------------------------

#: |A| in closed form (paper 004, Eq. 12 and Table 2, corrected where needed), written out here.
CLOSED_FORMS: dict[str, Callable[[Any], np.ndarray]] = {
    "2r (w14 x w23).s": lambda c: (
        2.0
        * c.params.platform_radius
        * np.einsum(
            "...i,...i->...",
            np.cross(np.cross(c.w[..., 0, :], c.w[..., 3, :]), np.cross(c.w[..., 1, :], c.w[..., 2, :])),
            c.platform_s,
        )
    ),
    "-h/(2 pi) (w13 x w24).k": lambda c: (
        -c.params.lead
        / (2.0 * math.pi)
        * np.cross(np.cross(c.w[..., 0, :], c.w[..., 2, :]), np.cross(c.w[..., 1, :], c.w[..., 3, :]))[..., 2]
    ),
}


def check_det_a_closed_form(mechanism, fact):
    """The named closed form equals ``numpy.linalg.det(A)`` (Eq. 6) at random workspace poses."""
    config = random_configuration(mechanism, 60)
    numeric = np.linalg.det(four_limb_jacobians(config).A)
    error = np.abs(CLOSED_FORMS[fact["value"]](config) - numeric).max() / np.abs(numeric).max()
    return (fact["value"] if error <= 1e-9 else f"differs from det A by {error:.2e} (relative)"), fact[
        "value"
    ]


def check_det_a_table_2_as_printed(mechanism, fact):
    """Whether Table 2's entry *as printed* equals det A (at random workspace poses)."""
    config = random_configuration(mechanism, 60)
    w, phi = config.w, config.pose[..., 3]
    kind = mechanism.parameters.platform_kind
    if kind == "articulated_z":  # 2r (w14 x w23)^T s with s = R_z(phi) j (Table 1)
        s = np.stack([-np.sin(phi), np.cos(phi), np.zeros_like(phi)], axis=-1)
        normal = np.cross(np.cross(w[..., 0, :], w[..., 3, :]), np.cross(w[..., 1, :], w[..., 2, :]))
        printed = 2.0 * mechanism.parameters.platform_radius * np.einsum("...i,...i->...", normal, s)
    elif kind == "screw_pair":  # h phi / (2 pi) (w13 x w24)^T k
        normal = np.cross(np.cross(w[..., 0, :], w[..., 2, :]), np.cross(w[..., 1, :], w[..., 3, :]))
        printed = mechanism.parameters.lead * phi / (2.0 * math.pi) * normal[..., 2]
    else:
        raise AssertionError(f"{mechanism.source}: no printed Table 2 form is checked for {kind!r}")
    numeric = np.linalg.det(four_limb_jacobians(config).A)
    return bool(np.abs(printed - numeric).max() <= 1e-9 * np.abs(numeric).max()), fact["value"]


@lru_cache(maxsize=16)
def lti_extremes(source: str, region: str, phi_deg: float, parameters: Any) -> tuple[float, float]:
    """(eta_min, eta_max) of Eq. (16) over a region at one rotation (cached per entry)."""
    grid = region_points(region)
    poses = np.column_stack([grid, np.full(len(grid), math.radians(phi_deg))])
    poses = poses[reachable(parameters, poses)]
    eta = transmission_indices(inverse_kinematics(parameters, poses)).eta
    return float(eta.min()), float(eta.max())


def check_lti_extremes(mechanism, fact):
    """Table 4: the extremes of the LTI over the region at ``value.phi_deg``."""
    phi = fact["value"]["phi_deg"]
    low, high = lti_extremes(mechanism.source, fact["region"], phi, mechanism.parameters)
    return compare({"phi_deg": phi, "eta_min": low, "eta_max": high}, fact)


@lru_cache(maxsize=4)
def spiral_configuration(parameters: Any):
    return inverse_kinematics(parameters, spiral_trajectory(2001))


def check_spiral_sigma_deg_at_phi_zero(mechanism, fact):
    """Sec. 5.1: sigma (Eq. 13) at the pose of the spiral where phi = 0."""
    config = spiral_configuration(mechanism.parameters)
    at_zero = int(np.argmin(np.abs(config.pose[:, 3])))
    assert config.pose[at_zero, 3] == pytest.approx(0.0, abs=1e-12)
    sigma = math.degrees(float(force_pressure_angle(config)[at_zero]))
    return sigma, pytest.approx(fact["value"], abs=fact["tolerance"])


def check_spiral_mu_range_deg(mechanism, fact):
    """Sec. 5.1: every mu_i (Eq. 11) along the spiral lies in the stated range."""
    mu = np.degrees(motion_pressure_angles(spiral_configuration(mechanism.parameters)))
    low, high = fact["value"]
    inside = low <= mu.min() and mu.max() <= high
    return ("within" if inside else f"outside: [{mu.min():.1f}, {mu.max():.1f}] deg"), "within"


def check_spiral_type_2_phi_deg(mechanism, fact):
    """Sec. 5.1: the angles phi where det A (Eq. 6, numerically) changes sign along the spiral."""
    config = spiral_configuration(mechanism.parameters)
    det_a = np.linalg.det(four_limb_jacobians(config).A)
    phi = np.degrees(config.pose[:, 3])
    crossings = np.flatnonzero(np.sign(det_a[:-1]) != np.sign(det_a[1:]))
    roots = phi[crossings] - det_a[crossings] * (phi[crossings + 1] - phi[crossings]) / (
        det_a[crossings + 1] - det_a[crossings]
    )
    targets = {**fact["value"], **fact.get("not_reproduced", {})}
    computed = {
        key: (float(roots[np.argmin(np.abs(roots - target))]) if len(roots) else None)
        for key, target in targets.items()
    }
    return compare(computed, fact)


def _samples(mechanism, coordinate: str, count: int) -> np.ndarray:
    low, high = mechanism.workspace[coordinate]
    return np.linspace(low, high, count)


CANDIDATE_POSES = {
    "z axis": lambda m: np.array(
        [[0.0, 0.0, z, phi] for z in _samples(m, "z", 5) for phi in _samples(m, "phi", 5)]
    ),
    "plane y = 0 at phi = 0": lambda m: np.array(
        [[x, 0.0, z, 0.0] for x in np.linspace(-300.0, 300.0, 7) for z in _samples(m, "z", 5)]
    ),
}


def check_constraint_singular_poses(mechanism, fact):
    """Which families of poses are constraint-singular (labels of :func:`classify_table`).

    ``"everywhere"`` when every one of 150 random workspace poses is; otherwise the candidate
    families (:data:`CANDIDATE_POSES`, reachable poses only) that are constraint-singular throughout,
    plus ``"some random poses"`` if some random workspace pose is.
    """
    flags = ["constraint" in labels for labels in batch_labels(random_configuration(mechanism, 150))]
    if all(flags):
        return ["everywhere"], fact["value"]
    found = []
    for name, build in CANDIDATE_POSES.items():
        poses = build(mechanism)
        poses = poses[reachable(mechanism.parameters, poses)]
        assert len(poses) >= 10, name
        if all("constraint" in labels for labels in batch_labels(mechanism.configuration(poses))):
            found.append(name)
    if any(flags):
        found.append("some random poses")
    return found, fact["value"]


def check_actuation_wrenches_along_parallelograms(mechanism, fact):
    """Sec. 4.1 (Fig. 3a): at the default pose the actuation wrench of limb i is a force along w_i
    in the plane of its parallelogram (through the rod midline, normal u_i x w_i)."""
    config = mechanism.configuration()
    analysis = wrench_analysis(mechanism.twist_graph())
    ok = True
    for limb in analysis.limbs:
        i = int(limb.actuated_joint[1:]) - 1
        point, direction = S.axis(limb.actuation_wrench)
        normal = np.cross(config.u[i], config.w[i])
        ok &= bool(np.linalg.norm(np.cross(direction, config.w[i])) < 1e-9)
        ok &= bool(abs((point - config.b[i]) @ normal) < 1e-9 * mechanism.parameters.rod_length)
        ok &= bool(abs(S.pitch(limb.actuation_wrench)) < 1e-9 * mechanism.parameters.rod_length)
    return ok, fact["value"]


FACTS = {
    "det_A_closed_form": check_det_a_closed_form,
    "det_A_table_2_as_printed": check_det_a_table_2_as_printed,
    "lti_extremes": check_lti_extremes,
    "spiral_sigma_deg_at_phi_zero": check_spiral_sigma_deg_at_phi_zero,
    "spiral_mu_range_deg": check_spiral_mu_range_deg,
    "spiral_type_2_phi_deg": check_spiral_type_2_phi_deg,
    "constraint_singular_poses": check_constraint_singular_poses,
    "actuation_wrenches_along_parallelograms": check_actuation_wrenches_along_parallelograms,
}
