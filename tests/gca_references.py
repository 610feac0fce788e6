"""Independent references shared by the tests of screwkit.gca (tests/test_gca_*.py,
tests/gca/test_conditions.py): numpy and exact determinants, the 24-term formula of gca.md §2.1 copied
verbatim and parsed by a regex here (not by gca's parser), random points, and the H4 wrench diagram
of paper 002 (Amine et al., ARK 2010, §5.1, Fig. 4c) with its samplers.
"""

import itertools
import math
import re
from fractions import Fraction

import numpy as np
from hypothesis import strategies as st

from screwkit.gca import (
    BracketMonomial,
    BracketPolynomial,
)

GENERIC = [("a", "b"), ("c", "d"), ("e", "f"), ("g", "h"), ("i", "j"), ("k", "l")]


# gca.md §2.1, copied verbatim; parsed below by a regex of this file (not by gca's parser).
GCA_24 = """
 +[abcd][efgi][hjkl] -[abcd][efgj][hikl] -[abcd][efhi][gjkl] +[abcd][efhj][gikl]
 -[abce][dfgh][ijkl] +[abce][dghi][fjkl] -[abce][dghj][fikl]
 +[abcf][degh][ijkl] -[abcf][dghi][ejkl] +[abcf][dghj][eikl]
 -[abcg][defi][hjkl] +[abcg][defj][hikl] +[abch][defi][gjkl] -[abch][defj][gikl]
 +[abde][cfgh][ijkl] -[abde][cghi][fjkl] +[abde][cghj][fikl]
 -[abdf][cegh][ijkl] +[abdf][cghi][ejkl] -[abdf][cghj][eikl]
 +[abdg][cefi][hjkl] -[abdg][cefj][hikl] -[abdh][cefi][gjkl] +[abdh][cefj][gikl]
"""


TEMPLATE = [
    (1 if sign == "+" else -1, brackets)
    for sign, *brackets in re.findall(r"([+-])\[(\w{4})\]\[(\w{4})\]\[(\w{4})\]", GCA_24)
]


def parity(sequence):
    """+1 / -1 for an even / odd arrangement of distinct items (by counting inversions)."""
    inversions = sum(a > b for a, b in itertools.combinations(sequence, 2))
    return -1 if inversions % 2 else 1


def det4(p, q, r, s):
    return np.linalg.det(np.stack(np.broadcast_arrays(p, q, r, s), axis=-2))


def plucker(p, q):
    """gca.md §1: L(p, q) = (p_w q - q_w p ; p x q)."""
    return np.concatenate(
        [p[..., 3:] * q[..., :3] - q[..., 3:] * p[..., :3], np.cross(p[..., :3], q[..., :3])],
        axis=-1,
    )


def det6(points, lines):
    rows = [plucker(*np.broadcast_arrays(points[x], points[y])) for x, y in lines]
    return np.linalg.det(np.stack(np.broadcast_arrays(*rows), axis=-2))


def template_value(points, lines):
    """The 24 terms of gca.md §2.1 evaluated with numpy determinants."""
    slot = dict(zip("abcdefghijkl", [x for line in lines for x in line], strict=True))
    return sum(
        sign * math.prod(det4(*(points[slot[c]] for c in b)) for b in brackets)
        for sign, brackets in TEMPLATE
    )


def generic_points(rng, shape=(), labels="abcdefghijkl", infinite=""):
    """Random points; the labels in `infinite` get weight 0, the others weight 1."""
    points = {}
    for x in labels:
        xyz = rng.normal(size=(*shape, 3))
        w = np.full((*shape, 1), 0.0 if x in infinite else 1.0)
        points[x] = np.concatenate([xyz, w], axis=-1)
    return points


def stacked(sampler, n, seed):
    rng = np.random.default_rng(seed)
    draws = [sampler(rng) for _ in range(n)]
    return {x: np.stack([d[x] for d in draws]) for x in draws[0]}


# The H4 wrench diagram (paper 002, §5.1, Fig. 4c): a, c finite on the vertical axis Z_I, e, g
# finite on the parallel axis Z_II, b, d, f, h the actuation force directions, i = n1 x n2 and
# k = n3 x n4 (random directions), j = (z, 0); lines ab, cd, ef, gh (forces), ij, kj (couples).
Z = np.array([0.0, 0.0, 1.0])


H4 = [("a", "b"), ("c", "d"), ("e", "f"), ("g", "h"), ("i", "j"), ("k", "j")]


H4_DECLARED = {"finite": "aceg", "infinite": "bdfhijk", "collinear": ["acj", "egj"]}


def h4_sampler(rng):
    a = np.r_[rng.normal(size=3), 1.0]
    e = np.r_[rng.normal(size=3), 1.0]
    points = {"a": a, "c": a + np.r_[rng.normal() * Z, 0.0], "e": e, "j": np.r_[Z, 0.0]}
    points["g"] = e + np.r_[rng.normal() * Z, 0.0]
    for x in "bdfhik":
        points[x] = np.r_[rng.normal(size=3), 0.0]
    return points


def h4_loose_sampler(rng):
    """The H4 diagram without the collinearity of a, c, j and of e, g, j."""
    points = h4_sampler(rng)
    for x in "aceg":
        points[x] = np.r_[rng.normal(size=3), 1.0]
    return points


def vanishing_quads(points, rtol=1e-9):
    """Label 4-sets whose bracket is zero on every sample (relative to the Hadamard bound)."""
    zero = set()
    for quad in itertools.combinations(sorted(points), 4):
        rows = [points[x] for x in quad]
        bound = math.prod(np.linalg.norm(r, axis=-1) for r in rows)
        if np.all(np.abs(det4(*rows)) <= rtol * bound):
            zero.add(quad)
    return zero


def surviving_template_monomials(lines, points):
    """Template monomials (not combined) none of whose brackets vanishes on all samples."""
    zero = vanishing_quads(points)
    slot = dict(zip("abcdefghijkl", [x for line in lines for x in line], strict=True))
    out = []
    for sign, brackets in TEMPLATE:
        labelled = ["".join(slot[c] for c in b) for b in brackets]
        if not any(len(set(b)) < 4 or tuple(sorted(b)) in zero for b in labelled):
            out.append((sign, labelled))
    return out


polynomials = st.lists(
    st.tuples(
        st.integers(-3, 3),
        st.lists(st.lists(st.sampled_from("abcdef"), min_size=4, max_size=4), max_size=3),
    ),
    max_size=4,
)


def build(terms):
    return BracketPolynomial(BracketMonomial(brackets, c) for c, brackets in terms)


def reference_value(terms, points):
    return sum(
        c * math.prod((det4(*(points[x] for x in b)) for b in brackets), start=1.0)
        for c, brackets in terms
    )


H4_SURVIVORS = (  # the 24 terms with the slots of [ab, cd, ef, gh, ij, kj], read off by hand
    "[abcd][efhj][gikj] + [abcf][dghj][eikj] - [abch][defj][gikj]"
    " - [abdf][cghj][eikj] + [abdh][cefj][gikj]"
)


def canonical_dict(terms):
    """{sorted bracket label sets: signed coefficient} computed here (test-local sign rules)."""
    out = {}
    for coefficient, brackets in terms:
        if any(len(set(b)) < 4 for b in brackets):
            continue
        key = tuple(sorted(tuple(sorted(b)) for b in brackets))
        signed = Fraction(coefficient) * math.prod(parity([ord(x) for x in b]) for b in brackets)
        out[key] = out.get(key, 0) + signed
    return {k: v for k, v in out.items() if v}


def module_terms(poly):
    return [(m.coefficient, [b.labels for b in m.brackets]) for m in poly]
