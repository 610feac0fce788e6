"""Transmission indices (screwkit.papers.paper_004*, screwkit.robots.transmission): paper 004's kappa, zeta, LTI over batches, Table 4
regenerated, the wrench/twist-based index, the Ragnar with inclined axes.

Expected values come from the paper (Table 4, in ``tests/paper_004.py``), from hand derivations
written out here (the closed forms of Eqs. 11-16 from the configuration's vectors, the slider-crank's
trigonometry, the virtual coefficient of two screws), or from an independent computation (the
Ragnar's mobility from its constraint couples). Tolerances: 1e-12 where two closed forms of the same
quantity are compared (round-off only); Table 4's 0.002 (3 printed decimals plus the grid, measured
below); hypothesis invariance checks at 1e-9 (products of lengths up to 1e4 in float64).
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.algebra import screw as S
from screwkit.core.jacobians import jacobians_from_wrenches
from screwkit.core.singularity import classify_table
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError
from screwkit.graphs.joints import prismatic, revolute
from screwkit.graphs.twistgraph import twist_graph
from screwkit.interface.cli import main
from screwkit.papers import paper_004 as P4
from screwkit.papers import paper_004_surfaces as S4
from screwkit.papers import paper_004_table4 as T4
from screwkit.robots import transmission as R4
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics, reachable

from ..paper_004 import TABLE_4, spiral_trajectory
from ..strategies import rigid_motions, unit_factors

FOUR_LIMB = ["quattro", "h4", "v4", "veloce", "ragnar"]
PAIRS = {"articulated_z": ((0, 3), (1, 2)), "articulated_y": ((0, 3), (1, 2)), "screw_pair": ((0, 2), (1, 3))}


@pytest.fixture(scope="module")
def robots():
    return {name: load_mechanism(name) for name in FOUR_LIMB}


def workspace_poses(mechanism, count, seed=7, phi_scale=1.0):
    """Random poses of the catalog workspace box, the reachable ones."""
    poses = mechanism.random_poses(np.random.default_rng(seed), count)
    poses[:, 3] *= phi_scale
    return poses[reachable(mechanism.parameters, poses)]


def hand_indices(config):
    """kappa, zeta of Eqs. (11), (13), (15) written out from the configuration's unit vectors."""
    u_cross_v = np.cross(config.u, config.v)
    kappa = np.min(np.abs(np.einsum("...ij,...ij->...i", config.w, u_cross_v)), axis=-1)
    (i1, i2), (j1, j2) = PAIRS[config.params.platform_kind]
    w = config.w
    normal = np.cross(np.cross(w[..., i1, :], w[..., i2, :]), np.cross(w[..., j1, :], w[..., j2, :]))
    zeta = np.abs(np.einsum("...i,...i->...", normal, config.platform_s)) / np.linalg.norm(normal, axis=-1)
    return kappa, zeta


# -------------------------------------------------------------------------------------------------
# transmission(): paper 004's closed forms over a batch, numba and numpy
# -------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", FOUR_LIMB)
def test_transmission_is_paper_004_closed_form(robots, name):
    mechanism = robots[name]
    poses = workspace_poses(mechanism, 200)
    result = P4.transmission(mechanism, poses.reshape(-1, 1, 4)[: 2 * (len(poses) // 2)].reshape(-1, 2, 4))
    kappa, zeta = hand_indices(mechanism.configuration(poses[: 2 * (len(poses) // 2)]))
    np.testing.assert_allclose(result.input.ravel(), kappa, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.output.ravel(), zeta, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(result.lti, np.minimum(result.input, result.output))
    assert result.lti.shape == (len(poses) // 2, 2) and result.reachable.all() and not result.per_joint


@pytest.mark.parametrize("name", FOUR_LIMB)
@pytest.mark.parametrize("mode", [(-1, -1, -1, -1), (1, -1, 1, 1)])
def test_numba_and_numpy_paths_agree(robots, name, mode):
    kernels = pytest.importorskip("screwkit.papers._lti_numba")
    mechanism = robots[name]
    rng = np.random.default_rng(3)
    low, high = zip(*(mechanism.workspace[c] for c in mechanism.pose_names), strict=True)
    poses = rng.uniform(np.array(low) * 1.3, np.array(high) * 1.3, size=(400, 4))  # some out of reach
    params = mechanism.parameters
    fast = kernels.transmission(poses, *P4._kernel_arguments(params, mode))
    plain = P4._transmission_numpy(mechanism, poses, mode)
    assert 0 < fast[2].sum() < len(poses)
    np.testing.assert_array_equal(fast[2], plain[2])
    np.testing.assert_allclose(fast[0], plain[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast[1], plain[1], rtol=0, atol=1e-12)


def test_transmission_of_a_posed_mechanism(robots):
    quattro = robots["quattro"]
    poses = np.array([[0.0, 0.0, -800.0, 0.0], [100.0, -50.0, -700.0, 0.4]])
    posed = quattro.at(poses)
    direct = P4.transmission(quattro, poses)
    np.testing.assert_array_equal(P4.transmission(posed).lti, direct.lti)
    assert P4.transmission(quattro).lti.shape == ()  # the default pose
    other = P4.transmission(quattro.at(poses, working_mode=(1, -1, -1, -1)))  # the posed batch's mode
    np.testing.assert_array_equal(other.output, P4.transmission(quattro, poses, working_mode=(1, -1, -1, -1)).output)
    assert not np.allclose(other.output, direct.output)


def test_transmission_unreachable_poses(robots):
    veloce = robots["veloce"]
    poses = [[0.0, 0.0, -800.0, 0.0], [0.0, 0.0, -3000.0, 0.0]]
    with pytest.raises(UnreachablePoseError, match=r"1 of 2 poses are out of reach of Veloce.*pose index \(1,\)"):
        P4.transmission(veloce, poses)
    result = P4.transmission(veloce, poses, unreachable="nan")
    assert result.reachable.tolist() == [True, False]
    assert np.isnan(result.lti[1]) and np.isfinite(result.lti[0])
    assert json.loads(json.dumps(result.to_dict()))["lti"] == [pytest.approx(float(result.lti[0])), None]


def test_transmission_errors(robots):
    with pytest.raises(ScrewkitValueError, match=r"four-limb family.*'planar_3rrp'.*wrench_transmission"):
        P4.transmission(load_mechanism("planar_3rrp"), [0.0, 0.0, 0.0])
    with pytest.raises(ScrewkitValueError, match="Expected `unreachable` to be one of"):
        P4.transmission(robots["h4"], unreachable="skip")
    with pytest.raises(ScrewkitValueError, match="Expected `poses` to be None"):
        P4.transmission(robots["h4"].at(), [0, 0, -700, 0])
    with pytest.raises(ScrewkitValueError, match=r"shape \(\.\.\., 4\)"):
        P4.transmission(robots["h4"], [0, 0, -700])
    with pytest.raises(ScrewkitValueError, match="finite"):
        P4.transmission(robots["h4"], [0, 0, np.nan, 0])
    with pytest.raises(ScrewkitValueError, match="working_mode"):
        P4.transmission(robots["h4"], working_mode=(1, 1, 0, 1))
    with pytest.raises(ScrewkitValueError, match="four-limb family"):
        P4.transmission(load_mechanism("planar_3rrp").at())


def test_paper_spiral_reports_hold_through_the_batch_api(robots):
    # Sec. 5.1: along the spiral of Eqs. (17)-(18) mu_i in [0, 65 deg] (kappa >= cos 65 deg) and
    # sigma = 0 (zeta = 1) where phi = 0 (ours: the midpoint of an odd sampling)
    result = P4.transmission(robots["quattro"], spiral_trajectory(2001))
    assert result.input.min() >= math.cos(math.radians(65.0))
    assert result.output[1000] == pytest.approx(1.0, abs=1e-12)


# -------------------------------------------------------------------------------------------------
# Regions, index_extremes and Table 4
# -------------------------------------------------------------------------------------------------


def test_regions_by_hand():
    eq_19 = T4.Region.super_ellipsoid((0.0, 0.0, -575.0), (505.0, 685.0, 365.0))
    # |x/505|^3 + ... = 1 on the boundary: (505 * 0.5^(1/3), 685 * 0.5^(1/3), -575) is on it
    edge = np.array([505.0 * 0.5 ** (1 / 3), 685.0 * 0.5 ** (1 / 3), -575.0])
    assert eq_19.contains(np.array([edge * [0.999, 0.999, 1.0], edge * [1.001, 1.001, 1.0]])).tolist() == [
        True,
        False,
    ]
    cone = T4.TABLE_4_CONE  # apex (0, 0, -975), radius 650 at z = -575 and up to -475
    assert cone.contains(np.array([[325.0, 0.0, -775.0], [330.0, 0.0, -775.0], [0, 0, -470.0]])).tolist() == [
        True,
        False,
        False,
    ]
    box = T4.Region.box((0, 1), (0, 2), (0, 3))
    assert box.lower == (0.0, 0.0, 0.0) and box.upper == (1.0, 2.0, 3.0)


def test_index_extremes_errors(robots):
    h4 = robots["h4"]
    with pytest.raises(ScrewkitValueError, match="Expected `index` to be one of"):
        T4.index_extremes(h4, "eta")
    with pytest.raises(ScrewkitValueError, match=r"Expected `grid` to be an integer in 2\.\.201, got 1"):
        T4.index_extremes(h4, grid=1)
    # a grid of 10^9 poses or 10^9 refinement rounds: refused at once, not a MemoryError or hours of work
    with pytest.raises(ScrewkitValueError, match=r"Expected `grid` to be an integer in 2\.\.201, got 1000"):
        T4.index_extremes(h4, grid=1000)
    with pytest.raises(ScrewkitValueError, match=r"Expected `refine` to be an integer in 0\.\.200, got -1"):
        T4.index_extremes(h4, refine=-1)
    with pytest.raises(ScrewkitValueError, match=r"Expected `refine` to be an integer in 0\.\.200, got 1000000000"):
        T4.table_4(refine=10**9, robots=["h4"])
    with pytest.raises(ScrewkitValueError, match="Expected `phi` to be a finite number"):
        T4.index_extremes(h4, phi=float("nan"))
    with pytest.raises(ScrewkitTypeError, match="Expected `region` to be a Region"):
        T4.index_extremes(h4, region=(0, 1))
    with pytest.raises(ScrewkitValueError, match="No point of the 3\\^3 grid"):
        T4.index_extremes(h4, region=T4.Region.box((-1, 1), (-1, 1), (5000, 5001)), grid=3)


def test_index_extremes_are_attained_and_bound_the_grid(robots):
    quattro = robots["quattro"]
    result = T4.index_extremes(quattro, "input", T4.TABLE_4_CONE, phi=0.3, grid=15, refine=6)
    at = P4.transmission(quattro, np.stack([result.argmin, result.argmax]))
    assert at.input.tolist() == pytest.approx([result.minimum, result.maximum], abs=1e-12)
    assert result.minimum <= result.grid_minimum and result.maximum >= result.grid_maximum
    assert T4.TABLE_4_CONE.contains(np.stack([result.argmin[:3], result.argmax[:3]])).all()
    assert result.argmin[3] == result.argmax[3] == 0.3


def test_region_boundary_points():
    box = T4.Region.box((0, 1), (0, 2), (0, 3))
    x, y, z = box.boundary(6)
    points = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    on_a_face = np.isclose(points, box.lower, atol=1e-6) | np.isclose(points, box.upper, atol=1e-6)
    assert x.shape == (7, 13) and on_a_face.any(axis=1).all() and box.contains(points).all()
    cone = T4.TABLE_4_CONE
    points = np.stack(cone.boundary(8), axis=-1).reshape(-1, 3)
    centre = np.array([0.0, 0.0, -725.0])  # the centre of its box
    assert cone.contains(points).all() and not cone.contains(centre + (points - centre) * 1.001).any()


# -------------------------------------------------------------------------------------------------
# Actuation singularity surfaces (Sec. 5.3, Figs. 14-16)
# -------------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def surfaces(robots):
    """Figs. 14-16's pairs of angles (degrees), both signs, over the assumed workspace, grid 12."""
    angles = {"quattro": (75, 90), "h4": (60, 90), "v4": (45, 90)}
    return {
        (name, sign * angle): S4.actuation_singularity_surface(
            robots[name], math.radians(sign * angle), T4.TABLE_4_CONE, grid=12
        )
        for name, pair in angles.items()
        for angle in pair
        for sign in (1, -1)
    }


def test_actuation_surface_is_where_det_a_and_zeta_vanish(robots, surfaces):
    for (name, degrees), surface in surfaces.items():
        if not len(surface.triangles):
            continue
        vertices = surface.triangles.reshape(-1, 3)
        poses = np.column_stack([vertices, np.full(len(vertices), math.radians(degrees))])
        config = robots[name].configuration(poses)
        det_a = np.linalg.det(P4.four_limb_jacobians(config).A)  # the 4x4 determinant, not Eq. (12)
        assert np.max(np.abs(det_a)) < 1e-9, (name, degrees)  # |A| ~ 10 mm in the workspace
        # where w_I x w_II is not ~0 (Fig. 5a, b: |A| = 0 with sigma undefined), zeta = 0 (Fig. 5c, d)
        w = config.w
        (i1, i2), (j1, j2) = PAIRS[config.params.platform_kind]
        normal = np.cross(np.cross(w[:, i1], w[:, i2]), np.cross(w[:, j1], w[:, j2]))
        defined = np.linalg.norm(normal, axis=-1) > 1e-6
        zeta = P4.transmission(robots[name], poses).output  # the kernel: an independent path
        assert defined.mean() > 0.99 and np.max(zeta[defined]) < 1e-6, (name, degrees)
        assert T4.TABLE_4_CONE.contains(surface.triangles.mean(axis=1)).all()
        assert surface.fixed == {"phi": math.radians(degrees)} and surface.mechanism == robots[name].name
        assert surface.kind == "actuation" and surface.points.shape[1:] == (3,)


def test_actuation_surfaces_grow_with_the_rotation_as_paper_004_says(surfaces, robots):
    # Sec. 5.3: "the singularity surfaces of the robots become larger with the increasing rotation
    # angle"; the Quattro "still admits a large singularity-free workspace" at +-75 deg; and at phi = 0
    # none (Table 4: eta_min = 0.380 > 0 over the workspace)
    for name, (low, high) in {"quattro": (75, 90), "h4": (60, 90), "v4": (45, 90)}.items():
        for sign in (1, -1):
            assert surfaces[(name, sign * high)].area > surfaces[(name, sign * low)].area > 0
    assert surfaces[("quattro", 75)].area < 0.01 * surfaces[("quattro", 90)].area
    flat = S4.actuation_singularity_surface(robots["quattro"], 0.0, T4.TABLE_4_CONE, grid=12)
    assert flat.triangles.shape == (0, 3, 3) and flat.area == 0.0


def test_quattro_surfaces_at_plus_and_minus_phi_are_mirror_images(robots, surfaces):
    # the mirror y -> -y swaps limbs 1 <-> 4 and 2 <-> 3 of Table 1 and turns phi into -phi, so the
    # -phi locus mirrored lies on the +phi locus
    mirrored = surfaces[("quattro", -90)].triangles.reshape(-1, 3) * [1.0, -1.0, 1.0]
    poses = np.column_stack([mirrored, np.full(len(mirrored), math.pi / 2)])
    det_a = np.linalg.det(P4.four_limb_jacobians(robots["quattro"].configuration(poses)).A)
    assert len(mirrored) > 1000 and np.max(np.abs(det_a)) < 1e-9


def test_actuation_surface_errors(robots):
    h4 = robots["h4"]
    # a catalog name, as sk.analyze takes it (a new user's trial): the message says how to load it
    with pytest.raises(sk.ScrewkitTypeError, match=r"got the string 'h4'; load it first: sk\.load_mechanism\('h4'\)"):
        S4.actuation_singularity_surface("h4", 0.0)
    with pytest.raises(sk.ScrewkitTypeError, match=r"got the string 'h4'"):
        sk.transmission("h4", [0.0, 0.0, -800.0, 0.0])
    with pytest.raises(ScrewkitValueError, match=r"Expected `grid` to be an integer in 2\.\.201, got 1"):
        S4.actuation_singularity_surface(h4, 0.0, grid=1)
    # the surface's marching tetrahedra hold the whole grid: 201 took 16 GB (a new user's trial)
    with pytest.raises(ScrewkitValueError, match=r"Expected `grid` to be an integer in 2\.\.64 for a surface, got 201"):
        S4.actuation_singularity_surface(h4, 0.0, grid=201)
    with pytest.raises(ScrewkitValueError, match="Expected `phi` to be a finite number"):
        S4.actuation_singularity_surface(h4, float("inf"))
    with pytest.raises(ScrewkitTypeError, match="Expected `region` to be a Region, got tuple"):
        S4.actuation_singularity_surface(h4, 0.0, (0, 1))
    with pytest.raises(ScrewkitValueError, match="four-limb family"):
        S4.actuation_singularity_surface(load_mechanism("planar_3rrp"), 0.0)
    with pytest.raises(ScrewkitValueError, match="working_mode"):
        S4.actuation_singularity_surface(h4, 0.0, working_mode=(1, 1))
    default = S4.actuation_singularity_surface(h4, 0.0, grid=4)  # the catalog workspace box
    assert default.region.lower == tuple(h4.workspace[c][0] for c in "xyz")


@pytest.fixture(scope="module")
def table():
    return {(row.robot, row.phi_deg): row for row in T4.table_4()}


def test_table_4_holds_the_papers_values(table):
    assert {(r[0], r[2]): (r[4], r[5]) for r in T4.TABLE_4} == TABLE_4


#: Table 4 cells we reproduce within 0.002 (the refined extremes over the assumed workspace).
REPRODUCED = [
    ("Quattro", 0.0, "min"), ("Quattro", 0.0, "max"), ("Quattro", 45.0, "max"),
    ("H4", 0.0, "max"), ("H4", 45.0, "min"),
    ("Veloce", 0.0, "min"), ("Veloce", 0.0, "max"), ("Veloce", 360.0, "min"), ("Veloce", 360.0, "max"),
    ("V4", 0.0, "min"), ("V4", 0.0, "max"), ("V4", 45.0, "min"),
    ("Ragnar", 0.0, "max"),  # the value eps = 45 deg was inferred from (ragnar.toml)
]
#: Cells where the paper's value lies between our 41^3 grid value and the refined one.
BETWEEN_GRID_AND_REFINED = [("H4", 45.0, "max"), ("V4", 45.0, "max")]
#: Cells not reproduced (the paper's workspace figure is missing; the Ragnar's printed data).
NOT_REPRODUCED = [
    ("Quattro", 45.0, "min"), ("H4", 0.0, "min"),
    ("Ragnar", 0.0, "min"), ("Ragnar", 360.0, "min"), ("Ragnar", 360.0, "max"),
]


def test_table_4_cells_are_all_classified():
    assert sorted(REPRODUCED + BETWEEN_GRID_AND_REFINED + NOT_REPRODUCED) == sorted(
        (robot, phi, key) for robot, phi in TABLE_4 for key in ("min", "max")
    )


@pytest.mark.parametrize(("robot", "phi", "key"), REPRODUCED)
def test_table_4_reproduced(table, robot, phi, key):
    row = table[(robot, phi)]
    paper = TABLE_4[(robot, phi)][0 if key == "min" else 1]
    ours = row.ours.minimum if key == "min" else row.ours.maximum
    assert ours == pytest.approx(paper, abs=0.002) and key not in row.notes


@pytest.mark.parametrize(("robot", "phi", "key"), BETWEEN_GRID_AND_REFINED)
def test_table_4_paper_value_between_grid_and_refined(table, robot, phi, key):
    row = table[(robot, phi)]
    paper = TABLE_4[(robot, phi)][1]
    assert row.ours.grid_maximum < paper < row.ours.maximum
    assert abs(row.ours.maximum - paper) > 0.002 and "between grid points" in row.notes[key]


@pytest.mark.parametrize(("robot", "phi", "key"), NOT_REPRODUCED)
def test_table_4_not_reproduced_is_explained(table, robot, phi, key):
    # the check asserts the difference, so a better reading of the paper shows up as a failure
    row = table[(robot, phi)]
    paper = TABLE_4[(robot, phi)][0 if key == "min" else 1]
    ours = row.ours.minimum if key == "min" else row.ours.maximum
    assert abs(ours - paper) > 0.002
    if (robot, phi, key) == ("H4", 0.0, "min"):
        assert "beyond the robot's reach" in row.notes[key]
    else:
        assert row.notes[key] in (T4._CONE_NOTE, T4._RAGNAR_MIN_NOTE, T4._RAGNAR_MAX_NOTE)


def test_h4_minimum_at_phi_0_is_not_converged_because_the_region_passes_the_reach(table, robots):
    # a new user's trial: 0.016 on the 41^3 grid, 0.001 on 61^3, 0.0007 on 101^3. The assumed cone
    # reaches just past the H4's reach, where a stretched limb's kappa -> 0 (paper 004 Eq. 11), so the
    # infimum is 0; our table says so instead of offering 0.016 as a converged minimum
    row = table[("H4", 0.0)]
    assert row.ours.reachable_fraction < 1
    finer = T4.index_extremes(robots["h4"], "lti", T4.TABLE_4_CONE, phi=0.0, grid=61, refine=12)
    assert finer.minimum < row.ours.minimum / 5
    # the finer minimum sits where a limb is nearly stretched: kappa (not zeta) is the small index
    kappa = sk.transmission(robots["h4"], finer.argmin[None]).kappa.min()
    assert kappa == pytest.approx(finer.minimum, rel=1e-9)


def test_ragnar_eq_19_is_partly_out_of_reach_for_any_inclination(robots):
    # |C_1 - A_1| must lie in [l - b, l + b] = [425, 1175] mm whatever the axis; at (0, 0, -250, 0),
    # inside Eq. (19), C_1 = (100 cos 45, 100 sin 45, -250) and A_1 = (350, 100, 0) (text after Table 4)
    c1, a1 = np.array([100 / math.sqrt(2), 100 / math.sqrt(2), -250.0]), np.array([350.0, 100.0, 0.0])
    assert np.linalg.norm(c1 - a1) < 800.0 - 375.0
    assert T4.TABLE_4_EQ_19.contains(np.array([[0.0, 0.0, -250.0]]))[0]
    params = robots["ragnar"].parameters
    for eps in (-60.0, -20.0, 0.0, 20.0, 45.0, 80.0):
        tilted = dataclasses.replace(params, axis_inclination=math.radians(eps))
        assert not reachable(tilted, [0.0, 0.0, -250.0, 0.0])


# -------------------------------------------------------------------------------------------------
# The Ragnar with inclined actuated axes
# -------------------------------------------------------------------------------------------------


def rotation_axes(config):
    """Independent mobility count: sub-platform I (II) may only turn about n_1 x n_3 (n_2 x n_4)
    with n_i = u_i x w_i its limbs' constraint couples, and the end effector (joined to both by
    joints of axis k) about span(a_I, k) ∩ span(a_II, k): one axis iff det[a_I, a_II, k] != 0."""
    n = np.cross(config.u, config.w)
    a_one, a_two = np.cross(n[..., 0, :], n[..., 2, :]), np.cross(n[..., 1, :], n[..., 3, :])
    k = np.broadcast_to([0.0, 0.0, 1.0], a_one.shape)
    scale = np.linalg.norm(a_one, axis=-1) * np.linalg.norm(a_two, axis=-1)
    return np.linalg.det(np.stack([a_one, a_two, k], axis=-1)) / scale


def test_ragnar_inclined_axes_give_four_dof(robots):
    ragnar = robots["ragnar"]
    assert ragnar.parameters.axis_inclination == pytest.approx(math.pi / 4, abs=1e-15)
    horizontal = dataclasses.replace(ragnar.parameters, axis_inclination=0.0)
    poses = workspace_poses(ragnar, 80, seed=11)
    poses = poses[reachable(horizontal, poses)]
    assert len(poses) > 20
    config = ragnar.configuration(poses)
    np.testing.assert_allclose(config.u[..., 1], 0.0, atol=1e-15)  # parallel to the x-z plane
    np.testing.assert_allclose(np.abs(config.u[..., 2]), math.sin(math.pi / 4), atol=1e-15)
    assert np.abs(rotation_axes(config)).min() > 1e-3
    report = classify_table(ragnar.joints(poses))
    assert np.all(report.constraint_order == 2) and np.all(report.global_order == 6)
    assert np.abs(rotation_axes(inverse_kinematics(horizontal, poses))).max() < 1e-12


@settings(max_examples=25, deadline=None)
@given(x=st.floats(-300, 300), y=st.floats(-400, 400), z=st.floats(-800, -500), phi=st.floats(-1.0, 1.0))
def test_ragnar_mirror_symmetry(x, y, z, phi):
    # eps_i = (eps, -eps, eps, -eps) makes the Ragnar symmetric under x -> -x and y -> -y; at phi = 0
    # the screw-pair platform is symmetric too, so the LTI is even in x and in y
    ragnar = load_mechanism("ragnar")
    poses = np.array([[x, y, z, 0.0], [-x, y, z, 0.0], [x, -y, z, 0.0]])
    result = P4.transmission(ragnar, poses, unreachable="nan")
    if result.reachable.all():
        np.testing.assert_allclose(result.lti[1:], result.lti[0], rtol=0, atol=1e-12)


# -------------------------------------------------------------------------------------------------
# The wrench/twist-based index
# -------------------------------------------------------------------------------------------------


def test_transmission_ratio_by_hand():
    # a force along x through the origin and a screw of pitch h along (cos t, sin t, 0) through
    # r = (0, 0, -d): f.(r x s + h s) = d sin t + h cos t, bounded by sqrt(h^2 + d^2)
    d, theta, h = 2.0, 0.7, 0.5
    force = S.force([1.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    axis = [math.cos(theta), math.sin(theta), 0.0]
    twist = S.helical_twist(axis, [0.0, 0.0, -d], h)  # the common normal is along z
    expected = abs(h * math.cos(theta) + d * math.sin(theta)) / math.hypot(h, d)
    assert float(R4.transmission_ratio(force, twist)) == pytest.approx(expected, abs=1e-12)
    # at a point of application: |f.(v(q) + h_W w)| / (|f| |v(q) + h_W w|), the pressure angle
    q = np.array([0.0, 3.0, 0.0])
    velocity = np.cross(axis, q - [0.0, 0.0, -d]) + h * np.array(axis)
    assert float(R4.transmission_ratio(force, twist, point=q)) == pytest.approx(
        abs(velocity[0]) / np.linalg.norm(velocity), abs=1e-12
    )
    translation, couple = S.prismatic_twist([0.0, 1.0, 1.0]), S.couple([0.0, 0.0, 2.0])
    assert float(R4.transmission_ratio(force, translation)) == pytest.approx(0.0, abs=1e-15)
    assert float(R4.transmission_ratio(S.force([0, 0, 1], [5, 5, 5]), translation)) == pytest.approx(
        1 / math.sqrt(2), abs=1e-12
    )
    assert float(R4.transmission_ratio(couple, twist)) == pytest.approx(0.0, abs=1e-12)  # axis in x-y
    assert float(R4.transmission_ratio(couple, S.revolute_twist([0, 1, 1], [4, 0, 0]))) == pytest.approx(
        1 / math.sqrt(2), abs=1e-12
    )
    assert float(R4.transmission_ratio(couple, translation)) == 0.0


@settings(max_examples=40, deadline=None)
@given(motion=rigid_motions(), factor=unit_factors, seed=st.integers(0, 2**32 - 1))
def test_transmission_ratio_is_frame_and_unit_invariant(motion, factor, seed):
    rotation, translation = motion
    rng = np.random.default_rng(seed)
    wrench = S.helical_twist(rng.normal(size=3), rng.normal(size=3), rng.normal())  # any screw
    twist = S.helical_twist(rng.normal(size=3), rng.normal(size=3), rng.normal())
    point = S.axis(wrench)[0] + 0.3 * rng.normal(size=3)
    before = [float(R4.transmission_ratio(wrench, twist)), float(R4.transmission_ratio(wrench, twist, point=point))]

    def moved(screw):
        scaled = np.concatenate([screw[:3], factor * screw[3:]])  # lengths times factor
        return S.transform(scaled, rotation, factor * translation)

    after = [
        float(R4.transmission_ratio(moved(wrench), moved(twist))),
        float(R4.transmission_ratio(moved(wrench), moved(twist), point=factor * (rotation @ point) + factor * translation)),
    ]
    assert after == pytest.approx(before, abs=1e-9)
    assert all(0.0 <= value <= 1.0 for value in before)


@pytest.mark.parametrize("name", FOUR_LIMB)
def test_wrench_input_index_at_the_elbows_is_kappa(robots, name):
    # derived (wrench_transmission docstring): w_i o $_i = b w_i.(u_i x v_i) and |v(B_i)| = b
    mechanism = robots[name]
    poses = workspace_poses(mechanism, 30, seed=5)
    posed = mechanism.at(poses)
    result = posed.wrench_transmission
    config = posed.configuration
    per_limb = np.abs(np.einsum("...ij,...ij->...i", config.w, np.cross(config.u, config.v)))
    assert posed.jacobians.actuated_joints == ("A1", "A2", "A3", "A4")
    np.testing.assert_allclose(result.input, per_limb, rtol=0, atol=1e-9)
    np.testing.assert_allclose(result.input.min(axis=-1), P4.transmission(posed).input, rtol=0, atol=1e-9)
    assert np.all((result.output >= 0) & (result.output <= 1)) and result.lti.shape == (len(poses),)


@pytest.mark.parametrize("name", ["quattro", "ragnar"])
def test_common_normal_input_index_identity(robots, name):
    # derived: with the common-normal bound ITI_i = |sin(w_i, u_i)| = sqrt(kappa_i^2 + (w_i.v_i)^2)
    mechanism = robots[name]
    posed = mechanism.at(workspace_poses(mechanism, 30, seed=9))
    jac, config = posed.jacobians, posed.configuration
    common = R4.transmission_ratio(jac.wrenches, np.asarray(jac.analysis.actuated_twists))
    kappa_i = np.einsum("...ij,...ij->...i", config.w, np.cross(config.u, config.v))
    along_arm = np.einsum("...ij,...ij->...i", config.w, config.v)
    np.testing.assert_allclose(common, np.hypot(kappa_i, along_arm), rtol=0, atol=1e-9)
    assert np.all(common >= np.abs(kappa_i) - 1e-12)


def slider_crank(theta):
    pin = np.array([math.cos(theta), math.sin(theta), 0.0])
    slider = np.array([pin[0] + math.sqrt(4.0 - pin[1] ** 2), 0.0, 0.0])
    graph = twist_graph("ground", "slider", [
        ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
        ("crank", "coupler", revolute("R1", [0, 0, 1], pin)),
        ("coupler", "slider", revolute("R2", [0, 0, 1], slider)),
        ("ground", "slider", prismatic("P", [1, 0, 0])),
    ], dof=1)
    return jacobians_from_wrenches(wrench_analysis(graph), [[0, 0, 0, 1, 0, 0]]), pin, slider


@pytest.mark.parametrize("theta", [0.3, 1.0, 2.0, -2.5])
def test_wrench_transmission_slider_crank_by_hand(theta):
    # the coupler's force acts along the coupler; input: its cosine with the pin's velocity z x pin;
    # output: its cosine with the slider's path x. The pin is found from the crank's other joint.
    jac, pin, slider = slider_crank(theta)
    coupler = (slider - pin) / np.linalg.norm(slider - pin)
    pin_velocity = np.cross([0.0, 0.0, 1.0], pin)
    result = R4.wrench_transmission(jac)
    assert result.input.tolist() == pytest.approx([abs(coupler @ pin_velocity)], abs=1e-9)
    assert result.output.tolist() == pytest.approx([abs(coupler[0])], abs=1e-9)
    assert float(result.lti) == pytest.approx(min(abs(coupler @ pin_velocity), abs(coupler[0])), abs=1e-9)
    explicit = R4.wrench_transmission(jac, input_points=[pin], output_points=[slider])
    assert explicit.input.tolist() == pytest.approx(result.input.tolist(), abs=1e-12)


def test_wrench_transmission_zero_at_the_singularities():
    jac, _, _ = slider_crank(0.0)  # dead centre: a serial singularity (B = 0)
    assert R4.wrench_transmission(jac).input.tolist() == [0.0]
    # the Quattro's type-2 singularity on the spiral (|A| changes sign near phi = -88.3 deg): OTI -> 0
    quattro = load_mechanism("quattro")
    path = spiral_trajectory(2001)[:80]
    det = np.linalg.det(P4.four_limb_jacobians(quattro.configuration(path)).A)
    k = int(np.flatnonzero(np.sign(det[:-1]) != np.sign(det[1:]))[0])
    lo, hi = path[k], path[k + 1]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if np.sign(np.linalg.det(P4.four_limb_jacobians(quattro.configuration(mid)).A)) == np.sign(det[k]):
            lo = mid
        else:
            hi = mid
    near = quattro.at(np.stack([0.5 * (lo + hi), path[0]])).wrench_transmission
    assert near.output[0].min() < 1e-6 < near.output[1].min()
    assert P4.transmission(quattro, 0.5 * (lo + hi)).output < 1e-6


def test_wrench_transmission_errors():
    jac, pin, _ = slider_crank(1.0)
    with pytest.raises(ScrewkitTypeError, match="Expected `jacobians` to be a Jacobians"):
        R4.wrench_transmission("A")
    with pytest.raises(ScrewkitValueError, match=r"Expected `input_points` to have shape \(\.\.\., 1, 3\)"):
        R4.wrench_transmission(jac, input_points=[pin, pin])


def test_wrench_transmission_for_other_families_and_in_the_report():
    posed = load_mechanism("peppermill").at()
    result = posed.wrench_transmission
    assert result.input.shape == (1, 4) and 0 < float(result.lti[0]) <= 1
    from screwkit.interface.report import analyze

    data = json.loads(json.dumps(analyze("h4", superbracket=False).to_dict()))["transmission"]
    assert min(data["wrench"]["input"]) == pytest.approx(data["paper_004"]["input"], abs=1e-9)
    text = str(analyze("planar_3rrp", superbracket=False))
    assert "transmission (in [0, 1]; 0 at a singularity)" in text and "paper 004" not in text.split(
        "transmission (in")[1]


# -------------------------------------------------------------------------------------------------
# The command line
# -------------------------------------------------------------------------------------------------


def test_cli_table4(capsys):
    assert main(["table4", "--robot", "veloce", "--robot", "ragnar", "--grid", "15", "--refine", "2"]) == 0
    out = capsys.readouterr().out
    assert "Veloce" in out and "Ragnar" in out and "Quattro" not in out
    assert "out of reach with the printed b, l and A_i" in out
    assert main(["table4", "--robot", "veloce", "--grid", "11", "--refine", "0", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [(row["robot"], row["phi_deg"], row["paper"]["max"]) for row in rows] == [
        ("Veloce", 0.0, 1.0),
        ("Veloce", 360.0, 0.999),
    ]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["table4", "--robot", "delta"], "unknown robot 'delta'"),
        (["table4", "--grid", "1"], "expected --grid in 2..201, got 1"),
        (["table4", "--refine", "-2"], "expected --refine in 0..200, got -2"),
    ],
)
def test_cli_table4_usage_errors(capsys, argv, message):
    assert main(argv) == 2
    assert message in capsys.readouterr().err
