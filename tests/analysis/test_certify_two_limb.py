"""Certification of the two-limb Schönflies-motion generators: the McGill SMG (paper 001) and the
Peppermill (paper 000). Checked against independent models written here: each leg's inverse kinematics
by the law of cosines (circle intersection for the Peppermill), det A as the determinant of the 4 x 4
matrix of the velocity relations (McGill: the rows [f_J, -s R f_J.m], [d_J, -s R d_J.m] with
m = de(phi)/dphi, from eliminating the passive rates of each leg, paper 001 Eqs. 7-16; Peppermill:
the rows [a_i, 0], [v_i, (p_i/2pi) v_i.k] of Eq. 44), numpy's determinant rather than a factored form.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.analysis.enclosures import model_of
from tests.analysis import certify_checks as screws
from tests.analysis.certify_checks import assert_same_facts, in_metres

K = np.array([0.0, 0.0, 1.0])
MCGILL = sk.load_mechanism("mcgill_smg")
MILL = sk.load_mechanism("peppermill")
SMG = MCGILL.parameters


def e_of(angle):
    return np.array([-np.sin(angle), np.cos(angle), 0.0])


def mcgill_legs(pose, mode=(1, 1, -1, -1)):
    """Per leg: (e_J, distal direction d_J, cos theta_J2, |O_J3 - O_J0| horizontal), None out of reach."""
    x, y, z, phi = pose
    out = []
    for index, sign in enumerate((1.0, -1.0)):
        pan, elbow = mode[2 * index], mode[2 * index + 1]
        wrist = np.array([x, y, z]) - sign * SMG.radius * e_of(phi) - (SMG.b4 + SMG.b5) * K
        pan_point = np.array([0.0, -sign * SMG.l0 / 2, 0.0])
        offset = (wrist - pan_point) * [1.0, 1.0, 0.0]
        e = pan * offset / np.linalg.norm(offset)
        shoulder = pan_point + sign * SMG.l1 * e
        along, height = (wrist - shoulder) @ e, wrist[2]
        cosine = (along**2 + height**2 - SMG.l2**2 - SMG.l3**2) / (2 * SMG.l2 * SMG.l3)
        if abs(cosine) > 1:
            return None
        distal = elbow * np.arccos(cosine)
        proximal = np.arctan2(height, along) - np.arctan2(SMG.l3 * np.sin(distal), SMG.l2 + SMG.l3 * np.cos(distal))
        direction = np.cos(proximal + distal) * e + np.sin(proximal + distal) * K
        out.append((e, direction, np.cos(proximal), np.linalg.norm(offset)))
    return out


def mcgill_det_a(pose):
    return mcgill_det_a_in(pose, (1, 1, -1, -1))


def mcgill_det_a_in(pose, mode):
    m = np.array([-np.cos(pose[3]), -np.sin(pose[3]), 0.0])
    rows = []
    for (e, d, _, _), sign in zip(mcgill_legs(pose, mode), (1.0, -1.0), strict=True):
        f = np.cross(e, K)
        rows += [np.r_[f, -sign * SMG.radius * f @ m], np.r_[d, -sign * SMG.radius * d @ m]]
    return np.linalg.det(np.array(rows))


def mill_rods(pose, mode=(1, 1)):
    """The unit distal links v_1, v_2 (branch sgn sin lambda_i = mode_i), None out of reach."""
    p = MILL.parameters
    x, y, z, phi = pose
    leads = np.array([p.p1, p.p2]) / (2 * np.pi)
    # limb i in its plane (x_i, y_i): limb 1 (j, k), o_1 = -b0 k; limb 2 (k, i), o_2 = b0 k
    targets = [np.array([y, z + leads[0] * phi + p.b0]), np.array([z + leads[1] * phi - p.b0, x])]
    rods = []
    for i, (target, r, length) in enumerate(zip(targets, (p.r1, p.r2), (p.l1, p.l2), strict=True)):
        distance = np.linalg.norm(target)
        along = (distance**2 + r**2 - length**2) / (2 * distance)
        if r**2 - along**2 < 0:
            return None
        unit = target / distance
        normal = np.array([-unit[1], unit[0]])
        for side in (1.0, -1.0):
            elbow = along * unit + side * np.sqrt(r**2 - along**2) * normal
            v = (target - elbow) / length
            if np.sign(elbow[0] * v[1] - elbow[1] * v[0]) == mode[i]:  # sin lambda = u x v
                rods.append(v)
                break
    v_one = np.array([0.0, rods[0][0], rods[0][1]])  # x_1 = j, y_1 = k
    v_two = np.array([rods[1][1], 0.0, rods[1][0]])  # x_2 = k, y_2 = i
    return v_one, v_two


def mill_det_a(pose):
    p = MILL.parameters
    v_one, v_two = mill_rods(pose)
    rows = [[1.0, 0, 0, 0], [0, 1.0, 0, 0], np.r_[v_one, p.p1 / (2 * np.pi) * v_one[2]],
            np.r_[v_two, p.p2 / (2 * np.pi) * v_two[2]]]
    return np.linalg.det(np.array(rows))


def sign_changes(function, points):
    """Zeros of ``function`` along the polyline ``points (m, n)`` where it changes sign between two
    reachable samples (``function`` None out of reach), each refined by 60 bisection steps."""
    values = [function(q) for q in points]
    found = []
    for k in range(len(points) - 1):
        a, b = values[k], values[k + 1]
        if a is None or b is None or a * b >= 0:
            continue
        low, high = points[k], points[k + 1]
        for _ in range(60):
            middle = 0.5 * (low + high)
            if np.sign(function(middle)) == np.sign(a):
                low = middle
            else:
                high = middle
        found.append(0.5 * (low + high))
    return found


def in_a_free_box(certificate, point, names):
    return any(b.status == "free" and all(b.bounds[n][0] <= point[n] <= b.bounds[n][1] for n in names)
               for b in certificate.boxes)


def surface_outside_free_boxes(certificate, function, lines, names):
    """The zeros of the independent ``function`` along ``lines`` (sign changes): asserts none lies in a
    free box of ``certificate`` (over the coordinates ``names``) and returns how many were found."""
    found = 0
    for line in lines:
        for zero in sign_changes(function, line):
            found += 1
            point = dict(zip(("x", "y", "z", "phi"), zero, strict=True))
            assert not in_a_free_box(certificate, point, names)
    return found


def reachable_poses(mechanism, low, span, count, seed):
    poses = np.asarray(low) + np.random.default_rng(seed).uniform(size=(8 * count, 4)) * np.asarray(span)
    poses = poses[mechanism.reachable(poses)][:count]
    assert len(poses) == count
    return poses


def test_mcgill_functions_are_the_independent_kinematics():
    poses = reachable_poses(MCGILL, [-600.0, -600.0, -1200.0, -3.0], [1200.0, 1200.0, 800.0, 6.0], 300, 1)
    values = model_of(MCGILL).values(poses)
    legs = [mcgill_legs(pose) for pose in poses]
    det_a = np.array([mcgill_det_a(pose) for pose in poses])
    assert det_a.min() < 0 < det_a.max()
    # the enclosed actuation function is det[phi_I, phi_II, k x e(phi)] = -det A / (2R)
    np.testing.assert_allclose(values["actuation"], -det_a / (2 * SMG.radius), rtol=1e-9,
                               atol=1e-12 * np.abs(det_a).max())
    np.testing.assert_allclose(values["serial:2"], [leg[0][3] ** 2 for leg in legs], rtol=1e-12)
    flat = np.array([[(c2 * d[0:2] @ e[0:2]) ** 2 for e, d, c2, _ in leg] for leg in legs])
    parallel = np.array([np.cross(leg[0][0], leg[1][0])[2] ** 2 for leg in legs])
    np.testing.assert_allclose(values["constraint"], flat.sum(axis=1) + parallel, rtol=1e-9, atol=1e-14)


def test_mcgill_slice_certified_with_the_independent_actuation_surface_in_no_free_box():
    region = {"x": (-300.0, 300.0), "y": (-300.0, 300.0), "z": -800.0, "phi": 0.3}
    certificate = sk.certify(MCGILL, region, resolution=4.0)
    assert {"free", "singular", "undecided"} <= {b.status for b in certificate.boxes}
    assert certificate.fractions["free"] > 0.95
    witnesses = [b.witness for b in certificate.boxes if b.witness is not None]
    assert {w.label for w in witnesses} == {"actuation"} and witnesses[0].factor == "[a b d ḟ][c g ḣ i]"
    scale = abs(mcgill_det_a([30.0, -20.0, -800.0, 0.3]))
    for w in witnesses[::10]:
        assert abs(mcgill_det_a([w.pose[n] for n in MCGILL.pose_names])) < 1e-6 * scale
    # paper 001's Eq. (22), phi_I = +-phi_II, is not what vanishes here: the witnesses' phi_J are far
    # from parallel (phi_J = f_J x d_J), the singularity is det[phi_I, phi_II, k x e(phi)] = 0
    sines = []
    for w in witnesses:
        (e_one, d_one, _, _), (e_two, d_two, _, _) = mcgill_legs([w.pose[n] for n in MCGILL.pose_names])
        sines.append(np.linalg.norm(np.cross(np.cross(np.cross(e_one, K), d_one), np.cross(np.cross(e_two, K), d_two))))
    assert min(sines) > 0.1
    lines = [np.stack([np.full(61, x), np.linspace(-300.0, 300.0, 61), np.full(61, -800.0), np.full(61, 0.3)], -1)
             for x in np.linspace(-140.0, 140.0, 8)]  # two curves near y = -290 and y = +290 mm
    zeros = surface_outside_free_boxes(certificate, lambda pose: mcgill_det_a(pose) if mcgill_legs(pose) else None,
                                       lines, ("x", "y"))
    assert zeros >= 8


def test_mcgill_catalog_workspace_certified_free():
    # paper 001, Sec. 4.2: "it is necessary to have a Cartesian workspace free of parallel singularities"
    certificate = sk.certify(MCGILL, dict(MCGILL.workspace), resolution={"x": 10, "y": 10, "z": 10, "phi": 0.05})
    assert certificate.certified_free and certificate.totals["free"] > 100


def mcgill_constraint_orders(pose):
    """From the joint screws (in metres): each leg's constraint order and the plate's. Leg J: the pan
    joint (k through O_J0), the proximal and distal parallelograms (each the intersection of its two
    chains of revolute joints about f_J through the corners O, O + w k, O' + w k, O'), the wrist joint
    (k through O_J4)."""
    config = MCGILL.configuration(np.array([pose]))
    metre = 1e-3
    legs = []
    for leg in range(2):
        f = config.tilt_axis[0, leg]

        def parallelogram(start, end, width, f=f):
            one = np.array([screws.revolute(f, start * metre), screws.revolute(f, end * metre)])
            two = np.array([screws.revolute(f, (start + width * K) * metre), screws.revolute(f, (end + width * K) * metre)])
            return screws.intersection(one, two)

        twists = np.vstack([
            screws.revolute(K, config.pan_point[0, leg] * metre),
            parallelogram(config.shoulder[0, leg], config.elbow[0, leg], SMG.proximal_width),
            parallelogram(config.elbow[0, leg], config.wrist[0, leg], SMG.distal_width),
            screws.revolute(K, config.wrist_joint[0, leg] * metre),
        ])
        legs.append(screws.reciprocal(twists))
    return [len(w) for w in legs], screws.order(np.vstack(legs))


def distal_vertical_height(y):
    """z at which leg I's distal link is vertical (down) for x = 0, phi = 0: O_I3 - O_I1 is then
    (u, w) = (|y - R + l0/2| - l1, ...) in the leg's plane, with w = -sqrt(l2^2 - u^2) - l3."""
    along = abs(y - SMG.radius + SMG.l0 / 2) - SMG.l1
    return -np.sqrt(SMG.l2**2 - along**2) - SMG.l3 + SMG.b4 + SMG.b5


def test_mcgill_constraint_orders_from_the_joint_screws():
    # both distal links vertical, legs' planes parallel (x = 0): the plate keeps one couple
    assert mcgill_constraint_orders([0.0, 0.0, distal_vertical_height(0.0), 0.0]) == ([1, 1], 1)
    # leg I flat only: leg II still exerts both couples, nothing is singular
    one_flat = [0.0, -20.0, distal_vertical_height(-20.0), 0.0]
    assert mcgill_constraint_orders(one_flat) == ([1, 2], 2)
    assert model_of(MCGILL).values([one_flat])["constraint"][0] > 1e-4  # the enclosed function: not 0
    assert mcgill_constraint_orders([30.0, -20.0, -790.0, 0.17]) == ([2, 2], 2)


def test_mcgill_constraint_zero_where_both_distal_links_are_vertical_in_parallel_planes():
    # x = y = 0, phi = 0: both legs in the plane x = 0; O_J3 - O_J1 = (-150 mm along e_J, w): the distal
    # link is vertical (down) when w = -sqrt(l2^2 - 150^2) - l3
    height = distal_vertical_height(0.0)
    pose = np.array([0.0, 0.0, height, 0.0])
    legs = mcgill_legs(pose)
    assert all(abs(d[2] + 1.0) < 1e-12 for _, d, _, _ in legs)
    model = model_of(MCGILL)
    assert abs(model.values(pose[None])["constraint"][0]) < 1e-20
    assert MCGILL.at(pose[None]).codes[0] & 1  # the core's verdict: constraint
    aside = pose + np.array([1.0, 0.0, 0.0, 0.0])  # the legs' planes no longer parallel
    assert model.values(aside[None])["constraint"][0] > 1e-8 and not MCGILL.at(aside[None]).codes[0] & 1
    certificate = sk.certify(MCGILL, {"x": (-2.0, 2.0), "y": (-2.0, 2.0), "z": height, "phi": 0.0},
                             kinds=("constraint",), resolution=0.5)
    assert not in_a_free_box(certificate, {"x": 0.0, "y": 0.0}, ("x", "y"))


def test_peppermill_functions_are_the_independent_kinematics():
    poses = reachable_poses(MILL, [-600.0, -600.0, -700.0, -6.0], [1200.0, 1200.0, 700.0, 12.0], 300, 2)
    values = model_of(MILL).values(poses)
    det_a = np.array([mill_det_a(pose) for pose in poses])
    assert det_a.min() < 0 < det_a.max()
    np.testing.assert_allclose(values["actuation"], det_a, rtol=1e-9, atol=1e-12 * np.abs(det_a).max())
    assert (values["constraint"] == 1.0).all()
    # no constraint singularity: each limb exerts the couple along a_i x k (module docstring); the core
    # reads the constraint system nominal at every one of these poses
    assert not (MILL.at(poses).codes & 1).any()


def mill_constraint_systems(pose):
    """From the joint screws (in metres): each limb's constraint wrenches. Limb i: the C joint along a_i
    through o_i (a turn and a slide), the R joints about a_i through B_i and P_i, the H joint about k
    through C with pitch -p_i/2pi."""
    config, p, metre = MILL.configuration(np.array([pose])), MILL.parameters, 1e-3
    out = []
    for i, lead in enumerate((p.p1, p.p2)):
        a = config.drive_axis[0, i]
        twists = np.vstack([
            screws.revolute(a, config.drive_point[0, i] * metre), np.r_[np.zeros(3), a],
            screws.revolute(a, config.elbow[0, i] * metre), screws.revolute(a, config.wrist[0, i] * metre),
            np.r_[K, np.cross(config.platform_point[0] * metre, K) - lead / (2 * np.pi) * metre * K],
        ])
        out.append(screws.reciprocal(twists))
    return out


def test_peppermill_constraint_from_the_joint_screws_never_loses_a_couple():
    aligned = [30.0, np.sqrt(650.0**2 - 500.0**2), -550.0, 0.0]  # limb 1's links aligned: |q_1| = r + l
    for pose, orders in (([30.0, -20.0, -450.0, 0.5], [1, 1]), (aligned, [2, 1])):
        systems = mill_constraint_systems(pose)
        assert [len(w) for w in systems] == orders and screws.order(np.vstack(systems)) >= 2
        for w, a in zip(systems, MILL.configuration(np.array([pose])).drive_axis[0], strict=True):
            couple = np.r_[np.zeros(3), np.cross(a, K)]  # the couple along a_i x k is in the limb's system
            assert screws.order(np.vstack([w, couple])) == len(w)
    assert MILL.at(np.array([aligned])).codes[0] == 4  # serial only, as the reach function says


def test_peppermill_slice_certified_with_the_independent_actuation_surface_in_no_free_box():
    region = {"x": 30.0, "y": (-600.0, 600.0), "z": (-700.0, 0.0), "phi": 0.5}
    certificate = sk.certify(MILL, region, resolution=5.0)
    assert {"free", "singular", "undecided", "unreachable"} <= {b.status for b in certificate.boxes}
    witnesses = [b.witness for b in certificate.boxes if b.witness is not None]
    actuation = [w for w in witnesses if w.label == "actuation"]
    assert len(actuation) > 20 and actuation[0].factor == "[abfd][eghi] - [abfh][ecdi]"
    for w in actuation[::10]:
        v_one, v_two = mill_rods([w.pose[n] for n in MILL.pose_names])
        assert min(abs(v_one[2]), abs(v_two[2])) < 1e-6  # a distal link horizontal (paper 000, Eq. 48)
    lines = [np.stack([np.full(141, 30.0), np.full(141, y), np.linspace(-700.0, 0.0, 141), np.full(141, 0.5)], -1)
             for y in np.linspace(200.0, 580.0, 6)]  # the surface meets this slice for y in [154, 600] mm
    zeros = surface_outside_free_boxes(certificate, lambda pose: mill_det_a(pose) if mill_rods(pose) else None,
                                       lines, ("y", "z"))
    assert zeros >= 5


def test_peppermill_catalog_workspace_certified_free():
    # paper 000 names no workspace; the catalog's box, every turn of phi in [-2 pi, 2 pi]
    certificate = sk.certify(MILL, dict(MILL.workspace), resolution={"x": 10, "y": 10, "z": 10, "phi": 0.1})
    assert certificate.certified_free


@settings(max_examples=3, deadline=None)
@given(x=st.floats(-300.0, 200.0), y=st.floats(-300.0, 200.0), phi=st.floats(-0.8, 0.8),
       name=st.sampled_from(["mcgill_smg", "peppermill"]))
def test_certificate_is_invariant_under_the_length_unit(x, y, phi, name):
    mechanism = MCGILL if name == "mcgill_smg" else MILL
    z = -800.0 if name == "mcgill_smg" else -450.0
    in_mm = sk.certify(mechanism, {"x": (x, x + 100.0), "y": (y, y + 100.0), "z": z, "phi": phi}, resolution=4.0)
    in_m = sk.certify(in_metres(mechanism), {"x": (x / 1e3, (x + 100.0) / 1e3), "y": (y / 1e3, (y + 100.0) / 1e3),
                                             "z": z / 1e3, "phi": phi}, resolution=4e-3)
    assert_same_facts(in_mm, in_m)


def test_working_modes_reach_the_models_and_bad_modes_are_one_line_errors():
    poses = reachable_poses(MCGILL, [-300.0, -300.0, -900.0, -0.5], [600.0, 600.0, 200.0, 1.0], 50, 3)
    mode = (1, -1, -1, 1)
    values = model_of(MCGILL, {"mode": mode}).values(poses)
    det_a = np.array([mcgill_det_a_in(pose, mode) for pose in poses])
    np.testing.assert_allclose(values["actuation"], -det_a / (2 * SMG.radius), rtol=1e-9)
    for mechanism, bad in ((MCGILL, (1, 1)), (MILL, (1, 1, 1))):
        with pytest.raises(sk.ScrewkitValueError, match="`mode`") as info:
            sk.certify(mechanism, {"x": (-1.0, 1.0)}, mode=bad)
        assert "\n" not in str(info.value)
