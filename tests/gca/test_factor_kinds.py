"""Constraint and actuation factors told apart by what happens at their zeros (issue 21 item 3):
screwkit.gca.factor_kinds, and the superbracket analysis of Tsai's 3-UPU, whose constraint couples
contribute their own squared factor to the determinant (the global 6×6 matrix of three leg forces
and three couples is block triangular: det = det(s₁, s₂, s₃)·det(m₁, m₂, m₃), by hand)."""

import numpy as np
import pytest

from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import ScrewkitValueError
from screwkit.gca import simplify_superbracket
from screwkit.gca.conditions import conditions
from screwkit.gca.diagram_placement import diagram_at, graph_sampler
from screwkit.gca.diagram_recipes import wrench_diagram
from screwkit.gca.factor_kinds import vanishing_kind
from screwkit.gca.superbracket_analysis import superbracket_analysis

from .. import mechanisms as M


def plucker_rows(points, lines):
    """Unit Plücker rows (p_w q − q_w p ; p × q), written here independently."""
    rows = []
    for p, q in lines:
        a, b = np.asarray(points[p]), np.asarray(points[q])
        row = np.concatenate([a[3] * b[:3] - b[3] * a[:3], np.cross(a[:3], b[:3])])
        rows.append(row / np.linalg.norm(row))
    return np.array(rows)


def sampler_of(finite, infinite):
    def sampler(rng):
        return {x: np.r_[rng.normal(size=3), 1.0] for x in finite} | {x: np.r_[rng.normal(size=3), 0.0] for x in infinite}

    return sampler


def test_the_roles_say_constraint_the_zeros_say_actuation():
    """Three constraint forces through the vertices p, q, r of a triangle whose sides are the actuation
    lines. [pqru] uses points of constraint lines only, so the roles call it a constraint condition; but
    where it vanishes (u parallel to the plane pqr) the constraint forces stay independent and pu joins
    the plane pencil of pq, rp at p: the six lines are dependent through the actuation lines."""
    lines, finite, infinite = ["pq", "qr", "rp", "pu", "qv", "rw"], "pqr", "uvw"
    roles = ["actuation"] * 3 + ["constraint"] * 3
    result = simplify_superbracket(lines, sampler_of(finite, infinite), finite=finite, infinite=infinite)
    found = conditions(result.factored, finite=finite, infinite=infinite, lines=lines, roles=roles)
    assert [c.label for c in found] == ["constraint"] * 3  # by the roles
    rng = np.random.default_rng(3)
    sample = sampler_of(finite, infinite)(rng)
    pairs = [tuple(line) for line in lines]
    for c in found:
        kind, evidence = vanishing_kind(c, sample, pairs, roles)
        assert kind == "actuation" and "keep rank 3, the actuation wrenches are dependent" in evidence
    # independently: u moved into the plane pqr (its normal component removed)
    normal = np.cross(sample["q"][:3] - sample["p"][:3], sample["r"][:3] - sample["p"][:3])
    u = sample["u"][:3] - normal * (sample["u"][:3] @ normal) / (normal @ normal)
    zero = {**sample, "u": np.r_[u, 0.0]}
    assert abs(found[0].evaluate(zero)) < 1e-12
    assert np.linalg.matrix_rank(plucker_rows(zero, pairs[3:]), tol=1e-9) == 3
    assert np.linalg.matrix_rank(plucker_rows(zero, pairs), tol=1e-9) == 5


def test_a_constraint_factor_is_one_whose_zeros_drop_the_constraint_order():
    """Tsai's 3-UPU as lines: legs ab, cd, ef and the couples as the triangle of lines at infinity gh,
    gi, hi: det(m₁, m₂, m₃) = det(g, h, i)² (gca.md §5.2 triangle of infinite lines)."""
    lines, finite, infinite = ["ab", "cd", "ef", "gh", "gi", "hi"], "ace", "bdfghi"
    roles = ["actuation"] * 3 + ["constraint"] * 3
    result = simplify_superbracket(lines, sampler_of(finite, infinite), finite=finite, infinite=infinite)
    found = conditions(result.factored, finite=finite, infinite=infinite, lines=lines, roles=roles)
    sample = sampler_of(finite, infinite)(np.random.default_rng(5))
    kinds = [vanishing_kind(c, sample, [tuple(x) for x in lines], roles)[0] for c in found]
    assert sorted(zip(kinds, [c.multiplicity for c in found], strict=True)) == [("actuation", 1), ("constraint", 2)]
    # g in the plane of h and i: the three couples are one line at infinity (rank 1)
    h, i = sample["h"][:3], sample["i"][:3]
    zero = {**sample, "g": np.r_[0.3 * h - 1.7 * i, 0.0]}
    assert np.linalg.matrix_rank(plucker_rows(zero, [tuple(x) for x in lines[3:]]), tol=1e-9) == 1


def test_vanishing_kind_wants_a_role_per_line():
    lines, finite, infinite = ["ab", "cd", "ef", "gh", "gi", "hi"], "ace", "bdfghi"
    result = simplify_superbracket(lines, sampler_of(finite, infinite), finite=finite, infinite=infinite)
    (first, *_) = conditions(result.factored, finite=finite, infinite=infinite)
    with pytest.raises(ScrewkitValueError, match="one role per line"):
        vanishing_kind(first, sampler_of(finite, infinite)(np.random.default_rng(0)), [("a", "b")], [])


def upu_position(rng):
    return np.array([rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(0.8, 1.2)])


def test_tsai_3upu_constraint_factor_separated_at_its_constraint_singularity():
    """The couples m_i ∝ (d_i·ρ_i) ρ_i + d_z z (ρ_i radial, d_i = p + (r_p − r_b) ρ_i the leg
    direction): det(m₁, m₂, m₃) = z sin 120° (α₁α₂ + α₂α₃ + α₃α₁), α_i = p·ρ_i − 1/2 (by hand), which
    vanishes at p = (±1, 0, z). There the design's factored form (the diagram chosen at a regular
    pose, its points sampled over the translational motion) keeps the constraint factor, squared and
    labelled constraint, ≈ 0, while the actuation factor is not."""
    reference = wrench_diagram(wrench_analysis(M.tsai_3upu([0.05, 0.1, 1.0])))
    sampler = graph_sampler(reference.points, lambda r: M.tsai_3upu(upu_position(r)))
    for singular in ([1.0, 0.0, 1.0], [-1.0, 0.0, 0.7]):
        assert abs(np.linalg.det(M.tsai_constraint_couples(singular)[:, 3:])) < 1e-12  # independent
        result = superbracket_analysis(diagram_at(reference, wrench_analysis(M.tsai_3upu(singular))), sampler)
        by_kind = {c.label: (c, v, z) for c, v, z in zip(result.conditions, result.values, result.vanishing, strict=True)}
        assert sorted(by_kind) == ["actuation", "constraint"]
        constraint, value, vanishes = by_kind["constraint"]
        assert constraint.multiplicity == 2 and vanishes and abs(value) < 1e-12
        assert "constraint lines gh, gi, hi drop from rank 3 to 1" in constraint.evidence
        _, value, vanishes = by_kind["actuation"]
        assert not vanishes and abs(value) > 0.1
    # away from it, along x at z = 1, the constraint factor's zero is where the couples' determinant
    # changes sign, and only there
    xs = np.linspace(0.6, 1.4, 5)
    values = []
    for x in xs:
        result = superbracket_analysis(diagram_at(reference, wrench_analysis(M.tsai_3upu([x, 0.0, 1.0]))), sampler)
        values.append(next(v for c, v in zip(result.conditions, result.values, strict=True) if c.label == "constraint"))
    independent = [np.linalg.det(M.tsai_constraint_couples([x, 0.0, 1.0])[:, 3:]) for x in xs]
    small = np.abs(values) < 1e-9 * np.max(np.abs(values))
    assert xs[small].tolist() == [1.0] and abs(independent[2]) < 1e-12
    assert all(abs(d) > 1e-3 for k, d in enumerate(independent) if k != 2)
