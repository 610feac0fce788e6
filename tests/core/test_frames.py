"""The two implementations of :mod:`screwkit.core.frames` (numpy and numba) follow one rule.

Both paths run here whatever this process chose: the numpy kernels are called directly
(``_frames._span_numpy`` …) and so are the numba ones (skipped, with the reason, when numba is not
installed). They must give the same orders and the same subspaces on random generators,
rank-deficient and near-deficient ones, zero rows, and batch shapes ``()``, ``(1,)``, ``(3, 4)``:
bit for bit, since the choice between them depends on the batch size.
"""

import importlib.util
import subprocess
import sys

import numpy as np
import pytest

from screwkit.algebra import compiled as C
from screwkit.algebra import reference_frame as RF
from screwkit.core import _closed_forms as CF
from screwkit.core import _closing as CK
from screwkit.core import _kernel_constants as K
from screwkit.core import _limbs as LK
from screwkit.core import _residuals as R
from screwkit.core import frames as F
from screwkit.core._program import Program, frame_program, run_program
from screwkit.core._wrench_pass import canonical

HAS_NUMBA = importlib.util.find_spec("numba") is not None
needs_numba = pytest.mark.skipif(not HAS_NUMBA, reason="numba is not installed (the `fast` extra)")

RTOL = 1e-9
ATOL = 1e-12
BATCHES = [(), (1,), (3, 4)]


def generators(rng, batch, k, rank, *, near=0.0, zero_rows=0):
    """``(*batch, k, 6)`` generators of the given rank (plus ``near`` times noise), with the last
    ``zero_rows`` rows zero, scaled per pose so the threshold follows the largest norm."""
    basis = rng.standard_normal((*batch, rank, 6))
    mix = rng.standard_normal((*batch, k, rank))
    rows = mix @ basis + near * rng.standard_normal((*batch, k, 6))
    if zero_rows:
        rows[..., k - zero_rows :, :] = 0.0
    return rows * rng.uniform(0.1, 10.0, (*batch, 1, 1))


def projector(rows, order):
    """The orthogonal projector on a frame's span: ``(..., 6, 6)``."""
    mask = np.arange(6) < np.asarray(order)[..., None]
    kept = rows * mask[..., None]
    return np.swapaxes(kept, -1, -2) @ kept


def check_frame(rows, order):
    """Orthonormal first ``order`` rows, zero rows after."""
    mask = np.arange(6) < np.asarray(order)[..., None]
    gram = rows @ np.swapaxes(rows, -1, -2)
    expected = np.eye(6) * (mask[..., :, None] & mask[..., None, :])
    np.testing.assert_allclose(gram, expected, atol=ATOL)


CASES = [
    # (k, rank, near, zero_rows)
    (1, 1, 0.0, 0),
    (3, 3, 0.0, 0),
    (6, 6, 0.0, 0),
    (9, 6, 0.0, 0),
    (5, 2, 0.0, 0),  # rank-deficient
    (8, 4, 0.0, 2),  # rank-deficient with zero rows
    (4, 3, 1e-13, 0),  # near-deficient, below the threshold
    (4, 3, 1e-6, 0),  # near-deficient, above it
    (3, 0, 0.0, 3),  # all zero
]


def _span_numba(generators, rtol):
    if not HAS_NUMBA:
        pytest.skip("numba is not installed (the `fast` extra)")
    return F._span_numba(generators, rtol)


@needs_numba
@pytest.mark.parametrize("batch", BATCHES)
@pytest.mark.parametrize(("k", "rank", "near", "zero_rows"), CASES)
def test_span_numba_matches_numpy(rng, batch, k, rank, near, zero_rows):
    work = generators(rng, batch, k, rank, near=near, zero_rows=zero_rows)
    rows_np, order_np = F._span_numpy(work, RTOL)
    rows_nb, order_nb = F._span_numba(work, RTOL)
    assert rows_nb.shape == rows_np.shape == (*batch, 6, 6)
    assert order_nb.shape == order_np.shape == batch
    np.testing.assert_array_equal(order_nb, order_np)
    if near != 1e-6:
        np.testing.assert_array_equal(order_np, np.full(batch, rank))
    check_frame(rows_nb, order_nb)
    np.testing.assert_allclose(projector(rows_nb, order_nb), projector(rows_np, order_np), atol=ATOL)
    assert np.all(rows_nb[..., :, :] * (np.arange(6) >= order_nb[..., None])[..., None] == 0)


@pytest.mark.parametrize("batch", BATCHES)
@pytest.mark.parametrize(("k", "rank", "near", "zero_rows"), CASES)
def test_span_numpy_is_a_frame_of_the_generators(rng, batch, k, rank, near, zero_rows):
    work = generators(rng, batch, k, rank, near=near, zero_rows=zero_rows)
    rows, order = F._span_numpy(work, RTOL)
    check_frame(rows, order)
    if near == 0.0:  # exact rank: the generators lie in the span
        inside = np.einsum("...ks,...st->...kt", work, projector(rows, order))
        np.testing.assert_allclose(inside, work, atol=1e-12 * np.abs(work).max(initial=1.0))


@pytest.mark.parametrize("implementation", ["numpy", "numba"])
def test_span_of_no_generators(implementation):
    kernel = F._span_numpy if implementation == "numpy" else _span_numba
    rows, order = kernel(np.zeros((3, 4, 0, 6)), RTOL)
    assert rows.shape == (3, 4, 6, 6) and order.shape == (3, 4)
    assert not rows.any() and not order.any()


def _complements(frame_rows, order, implementation):
    if implementation == "numpy":
        return F._complement_numpy(frame_rows, order)
    if not HAS_NUMBA:
        pytest.skip("numba is not installed (the `fast` extra)")
    return F._complement_numba(frame_rows, order)


@pytest.mark.parametrize("implementation", ["numpy", "numba"])
@pytest.mark.parametrize("batch", BATCHES)
@pytest.mark.parametrize(("k", "rank", "near", "zero_rows"), CASES)
def test_complement_is_the_orthogonal_complement(rng, implementation, batch, k, rank, near, zero_rows):
    frame = F._span_numpy(generators(rng, batch, k, rank, near=near, zero_rows=zero_rows), RTOL)
    rows, order = _complements(*frame, implementation)
    np.testing.assert_array_equal(order, 6 - frame[1])
    check_frame(rows, order)  # orthonormal, ordered 0..5-order, zeros after
    np.testing.assert_allclose(projector(rows, order) + projector(*frame), np.broadcast_to(np.eye(6), rows.shape), atol=ATOL)


@needs_numba
@pytest.mark.parametrize("batch", BATCHES)
def test_reciprocal_numba_matches_numpy(rng, batch):
    frame = F._span_numpy(generators(rng, batch, 4, 3), RTOL)
    expected = F._complement_numpy(*frame)
    rows, order = F._complement_numba(*frame, swap=True)
    np.testing.assert_array_equal(order, expected[1])
    np.testing.assert_allclose(projector(F.swapped(rows), order), projector(*expected), atol=ATOL)


@needs_numba
@pytest.mark.parametrize("batch", BATCHES)
@pytest.mark.parametrize("order", [0, 2, 6])
def test_residual_numba_matches_numpy(rng, batch, order):
    frame_rows, _ = F._span_numpy(generators(rng, batch, order, order), RTOL)
    vectors = rng.standard_normal((*batch, 3, 6))
    np.testing.assert_allclose(
        R._residual_numba(vectors, frame_rows), R._residual_numpy(vectors, frame_rows), atol=ATOL
    )


@needs_numba
def test_numba_single_and_batched_are_bit_identical(rng):
    work = generators(rng, (50,), 7, 5, near=1e-10)
    rows, order = F._span_numba(work, RTOL)
    for i in (0, 17, 49):
        one_rows, one_order = F._span_numba(work[i], RTOL)
        assert one_order == order[i] and np.array_equal(one_rows, rows[i])
        assert np.array_equal(F._complement_numba(one_rows, one_order)[0], F._complement_numba(rows, order)[0][i])


def _probe(code, env):
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True,
        env={**__import__("os").environ, **env},
    )
    return result.stdout.split()


def test_screwkit_numba_0_selects_numpy():
    code = (
        "import sys, numpy as np\nfrom screwkit.core import frames as F\n"
        "F.span(np.eye(6)[:2], 1e-9)\nprint(F.backend(), 'numba' in sys.modules)"
    )
    assert _probe(code, {"SCREWKIT_NUMBA": "0"}) == ["numpy", "False"]


@needs_numba
def test_numba_is_the_default_and_imported_lazily():
    # a small call runs numpy without importing numba; a call of COMPILED_MIN_BATCH frames loads it
    code = (
        "import sys, numpy as np, screwkit\nfrom screwkit.core import frames as F\nprint('numba' in sys.modules)\n"
        "F.span(np.eye(6)[:2], 1e-9)\nprint('numba' in sys.modules)\n"
        "F.span(np.zeros((F.COMPILED_MIN_BATCH - 1, 2, 6)), 1e-9)\nprint('numba' in sys.modules)\n"
        "F.span(np.zeros((F.COMPILED_MIN_BATCH, 2, 6)), 1e-9)\nprint('numba' in sys.modules, F.backend())"
    )
    env = {"SCREWKIT_NUMBA": "1"}
    assert _probe(code, env) == ["False", "False", "False", "True", "numba"]


@needs_numba
@pytest.mark.parametrize("batch", [*BATCHES, (40,)])
@pytest.mark.parametrize(("k", "rank", "near", "zero_rows"), [*CASES, (7, 5, 1e-10, 0), (12, 6, 0.0, 0)])
def test_numpy_and_numba_paths_are_bit_identical(rng, batch, k, rank, near, zero_rows):
    # the rule may pick either path by batch size, so they must agree to the last bit (and sign of zero)
    def same(a, b):
        return np.array_equal(a, b) and np.array_equal(np.signbit(a), np.signbit(b))

    work = generators(rng, batch, k, rank, near=near, zero_rows=zero_rows)
    rows, order = F._span_numpy(work, RTOL)
    numba_rows, numba_order = F._span_numba(work, RTOL)
    assert same(rows, numba_rows) and np.array_equal(order, numba_order)
    for swap in (False, True):
        assert same(F._complement_numpy(rows, order, swap=swap)[0], F._complement_numba(rows, order, swap=swap)[0])
    vectors = rng.standard_normal((*batch, 3, 6))
    assert same(R._residual_numpy(vectors, rows), R._residual_numba(vectors, rows))


@needs_numba
def test_paths_agree_on_non_finite_generators():
    work = np.ones((3, 2, 6))
    work[0, 0, 0], work[1, 1, 2] = np.nan, np.inf
    rows, order = F._span_numpy(work, RTOL)
    numba_rows, numba_order = F._span_numba(work, RTOL)
    np.testing.assert_array_equal(order, numba_order)
    np.testing.assert_array_equal(rows, numba_rows)


@needs_numba
def test_both_paths_classify_the_h4_alike():
    # the whole core in each path (a fresh interpreter per path): identical verdicts and orders on
    # generic poses, closeness within round-off
    code = (
        "import numpy as np, screwkit as sk\nfrom screwkit.robots.families.four_limb.kinematics import reachable\n"
        "h4 = sk.load_mechanism('h4'); p = h4.random_poses(np.random.default_rng(3), 600)\n"
        "p = p[reachable(h4.parameters, p)][:400]\nr = sk.classify_table(h4.joints(p))\n"
        "out = {k: np.asarray(getattr(r, k)).tolist() for k in"
        " ('constraint_order', 'global_order', 'serial_flags', 'codes', 'uncontrolled_dof')}\n"
        "out.update({k: np.asarray(v).tolist() for k, v in r.closeness.items()})\nprint(repr(out))"
    )
    import ast

    outputs = [ast.literal_eval(" ".join(_probe(code, {"SCREWKIT_NUMBA": flag}))) for flag in ("0", "1")]
    assert outputs[0].keys() == outputs[1].keys() and outputs[0]
    for key in outputs[0]:
        a, b = np.asarray(outputs[0][key]), np.asarray(outputs[1][key])
        if a.dtype.kind == "f":
            np.testing.assert_allclose(a, b, atol=1e-9, err_msg=key)
        else:
            np.testing.assert_array_equal(a, b, err_msg=key)


# the closed-form rod, the program interpreter and the other compiled loops ---------------------
def sphere_rows(centre, axes):
    """Three unit rotation axes ``axes (3, 3)`` through ``centre``: rows ``(3, 6)``."""
    axes = axes / np.linalg.norm(axes, axis=-1, keepdims=True)
    return np.concatenate([axes, np.cross(centre, axes)], axis=-1)


def rod_rows(rng, first, second):
    rows = np.concatenate(
        [sphere_rows(first, rng.standard_normal((3, 3))), sphere_rows(second, rng.standard_normal((3, 3)))]
    )
    return rows / np.linalg.norm(rows, axis=-1, keepdims=True)  # unit rows, as the core's


def rod_numba(rows, rtol):
    from screwkit.core import _closed_forms_numba
    out = np.full((6, 6), np.nan)
    if _closed_forms_numba.rod_into(np.ascontiguousarray(rows), rtol, out):
        return out, 1
    return None


@pytest.mark.parametrize("seed", range(5))
def test_rod_is_the_line_through_the_two_centres(seed):
    # expected: the line (d; c1 × d) through the centres, normalised (written here, not the code's)
    rng = np.random.default_rng(seed)
    first, second = rng.uniform(-2, 2, 3), rng.uniform(-2, 2, 3)
    rows = rod_rows(rng, first, second)
    d = second - first
    line = np.concatenate([d, np.cross(first, d)])
    line /= np.linalg.norm(line)
    generic = F._complement_numpy(*F._span_numpy(rows, RTOL))
    implementations = [CF.rod] + ([rod_numba] if HAS_NUMBA else [])
    for implementation in implementations:
        got, order = implementation(rows, RTOL)
        assert int(order) == 1 and np.all(got[1:] == 0)
        np.testing.assert_allclose(got[0] * np.sign(got[0] @ line), line, atol=1e-12)
        # the same system as the generic rule's: SWAP of the complement of the twists' span
        np.testing.assert_allclose(projector(got, order), projector(F.swapped(generic[0]), generic[1]), atol=ATOL)


@pytest.mark.parametrize("case", ["same centre", "axes without a common point", "parallel axes"])
def test_rod_falls_back_to_the_rule_where_the_closed_form_does_not_apply(case):
    rng = np.random.default_rng(7)
    centre = np.array([0.3, -0.2, 0.5])
    rows = rod_rows(rng, centre, centre if case == "same centre" else centre + np.array([0.0, 0.0, 1.0]))
    if case == "axes without a common point":
        rows[1, 3:] += 0.1 * np.cross(rows[1, :3], [1.0, 0, 0])  # the second axis moved off the centre
    if case == "parallel axes":
        rows[:3] = rows[0]
    expected = F._complement_numpy(*F._span_numpy(rows, RTOL))
    got, order = CF.rod(rows, RTOL)
    assert int(expected[1]) != 1  # no single line: the closed form would be wrong here
    np.testing.assert_array_equal(order, expected[1])
    np.testing.assert_allclose(projector(got, order), projector(F.swapped(expected[0]), expected[1]), atol=ATOL)
    if HAS_NUMBA:
        assert rod_numba(rows, RTOL) is None  # the compiled program then spans, as above


@needs_numba
@pytest.mark.parametrize("seed", range(3))
def test_rod_and_unit_screws_numba_and_numpy_are_bit_identical(seed):
    from screwkit.core import _closed_forms_numba
    from screwkit.core import _frames_numba as _frames_numba
    rng = np.random.default_rng(seed)
    batch = [rod_rows(rng, rng.uniform(-2, 2, 3), rng.uniform(-2, 2, 3)) for _ in range(30)]
    batch[3] = rod_rows(rng, np.ones(3), np.ones(3))  # a fallback pose in the batch
    rows = np.array(batch)
    expected = CF.rod(rows, RTOL)
    for i, pose in enumerate(rows):
        out = np.zeros((6, 6))
        if _closed_forms_numba.rod_into(np.ascontiguousarray(pose), RTOL, out):
            assert expected[1][i] == 1 and np.array_equal(out, expected[0][i])
        else:
            assert i == 3 and expected[1][i] == 3
    screws = rng.standard_normal((7, 9, 6)) * rng.uniform(0.1, 100.0, (7, 1, 1))
    screws[2, 4] = 0.0  # a zero row stays zero
    centre, length = rng.standard_normal((7, 3)), rng.uniform(0.5, 5.0, 7)
    from screwkit.algebra import _reference_frame_numba

    compiled = _reference_frame_numba.unit_scaled(screws, centre, length)
    np.testing.assert_array_equal(compiled, RF.unit_scaled(screws, centre, length))  # 7 < 256: numpy
    assert np.all(compiled[2, 4] == 0.0)
    np.testing.assert_allclose(np.linalg.norm(np.delete(compiled.reshape(-1, 6), 22, 0), axis=-1), 1.0)


@needs_numba
def test_compiled_program_matches_the_ops_run_one_by_one(monkeypatch):
    # the numba interpreter against the numpy path's op-by-op run of the same H4 program: bit for
    # bit (frames, orders)
    import screwkit as sk
    from screwkit.algebra.reference_frame import mechanism_frame
    from screwkit.core import _frames_numba as _frames_numba
    from screwkit.graphs.topology import topology

    h4 = sk.load_mechanism("h4")
    table = canonical(h4.joints(h4.random_poses(np.random.default_rng(5), 30)[:20]))
    top = topology(table.base, table.platform, table.specs)
    centre, length = mechanism_frame(table.screws, table.anchor)
    scaled = RF.unit_scaled(table.screws, centre, length)
    requests = (
        *(("twists", i) for i in range(len(top.nodes))),
        *(("wrenches", i) for i in top.legs),
        *(("passive", tuple(plan.siblings)) for plan in top.limbs),
    )
    program = frame_program(top, requests)
    for code in (K.ROD, K.PARALLELOGRAM, K.EXTEND, K.CONTRACT):  # rods, parallelograms, chains: closed forms
        assert code in program.ops[:, 0]
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", _frames_numba)
    compiled = run_program(program, scaled, RTOL, requests)
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", None)
    stepwise = run_program(program, scaled, RTOL, requests)
    assert compiled[0].shape == stepwise[0].shape == (20, len(requests), 6, 6)
    np.testing.assert_array_equal(compiled[1], stepwise[1])
    np.testing.assert_array_equal(compiled[0], stepwise[0])


@needs_numba
@pytest.mark.parametrize("k", [4, 6, 7, 12, 16])
def test_triangular_keeps_the_singular_values_and_both_paths_are_bit_identical(rng, monkeypatch, k):
    from screwkit.core import _closing_numba
    from screwkit.core import _frames_numba as _frames_numba
    rows = rng.standard_normal((40, k, 6))
    rows[:, ::3] = 0.0  # zero rows, as in stacked frames
    rows[:5] = 0.0  # an all-zero matrix
    rows[5:10, :, 2] = 0.0  # a zero column
    padded = np.concatenate([rows, np.zeros((40, max(6 - k, 0), 6))], axis=1)  # fewer than 6: zero rows added
    compiled = _closing_numba.triangular(np.ascontiguousarray(padded))
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", None)
    np.testing.assert_array_equal(CK.triangular(rows), compiled)
    assert np.all(np.tril(compiled, -1) == 0)  # upper triangular
    np.testing.assert_allclose(
        np.linalg.svd(compiled, compute_uv=False), np.linalg.svd(padded, compute_uv=False), atol=1e-13
    )
    np.testing.assert_array_equal(CK.unpacked(CK.packed(compiled)), compiled)  # the 21 entries say it all


# ---- the fused passes: mechanism frame sums, limb systems, transmissions ---------------------------
def limb_inputs(rng, n, limbs=4):
    """Locked frames of orders 2..5 (a few limbs with an actuated twist inside: serial), their
    passive complements and actuated twists, ``(n, limbs, ...)``."""
    locked = np.zeros((n, limbs, 6, 6))
    order = rng.integers(2, 6, (n, limbs))
    for p in range(n):
        for k in range(limbs):
            q, _ = np.linalg.qr(rng.standard_normal((6, 6)))
            locked[p, k, : order[p, k]] = q.T[: order[p, k]]
    passive = F._complement_numpy(locked, order, swap=True)[0]
    actuated = rng.standard_normal((n, limbs, 6))
    actuated[::5, 1] = locked[::5, 1, 0] * 3.0  # in the locked system: a serial singularity
    return locked, order, passive, actuated


def test_limb_systems_known_values(rng):
    """Against an independent computation: t⊥ = (I − B Bᵀ) t for the orthonormal locked rows B,
    serial iff t⊥ = 0, the free frame spans the locked rows and t, and the direction is the unit
    projection of SWAP t⊥ on the passive rows (reciprocal to every passive-free twist)."""
    locked, order, passive, actuated = limb_inputs(rng, 30)
    perpendicular, serial, free, free_order, direction = LK._limb_systems_numpy(locked, order, passive, actuated, RTOL)
    expected = actuated - np.einsum("...is,...i->...s", locked, np.einsum("...is,...s->...i", locked, actuated))
    np.testing.assert_allclose(perpendicular, expected, atol=1e-12)
    assert serial[::5, 1].all() and serial.sum() == serial[::5, 1].size
    np.testing.assert_array_equal(free_order, order + ~serial)
    for p, k in [(0, 0), (5, 1), (7, 2)]:
        spanned = np.vstack([locked[p, k, : order[p, k]], actuated[p, k]])
        assert np.linalg.matrix_rank(free[p, k, : free_order[p, k]]) == free_order[p, k]
        assert np.linalg.matrix_rank(np.vstack([spanned, free[p, k, : free_order[p, k]]]), 1e-9) == free_order[p, k]
        swap = np.concatenate([perpendicular[p, k, 3:], perpendicular[p, k, :3]])
        target = passive[p, k].T @ (passive[p, k] @ swap)
        if np.linalg.norm(target) > 1e-9:
            np.testing.assert_allclose(direction[p, k], target / np.linalg.norm(target), atol=1e-12)
            locked_twists = locked[p, k, : order[p, k]]  # reciprocal: w ∘ t = w · SWAP t = 0
            np.testing.assert_allclose(locked_twists @ np.concatenate([direction[p, k, 3:], direction[p, k, :3]]),
                                       0.0, atol=1e-12)


@needs_numba
def test_limb_systems_numba_matches_numpy_bit_for_bit(rng):
    from screwkit.core import _limbs_numba
    locked, order, passive, actuated = limb_inputs(rng, 60)
    compiled = _limbs_numba.limb_systems(locked, order, passive, actuated, RTOL, True)
    for got, expected in zip(compiled, LK._limb_systems_numpy(locked, order, passive, actuated, RTOL), strict=True):
        np.testing.assert_array_equal(got, expected)
    single = LK._limb_systems_numpy(locked[7:8], order[7:8], passive[7:8], actuated[7:8], RTOL)
    for got, expected in zip(single, compiled, strict=True):  # a pose's answer is its own
        np.testing.assert_array_equal(got, expected[7:8])


def test_transmissions_known_values():
    """A force along x through (0, 2, 0) and a rotation about z through the origin: the index is
    the moment arm d sin θ = 2 (scaled: L = 1), whatever the force's size; a force and a translation along it: cos 0 = 1; a couple and a
    rotation: 1; a force and a parallel rotation through it: 0 (paper 002 §3, hand values)."""
    force = np.array([3.0, 0, 0, 0, 0, -6.0])  # along x through (0, 2, 0): moment p × f = (0, 0, -2)·3
    rows = np.array([force, [1.0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 5.0], [1.0, 0, 0, 0, 0, 0]])
    twists = np.array([[0, 0, 1.0, 0, 0, 0], [0, 0, 0, 1.0, 0, 0], [0, 0, 1.0, 0, 0, 0], [1.0, 0, 0, 0, 0, 0]])
    wrench, index = LK.transmissions(rows[None], twists[None], RTOL)
    np.testing.assert_allclose(np.linalg.norm(wrench[0], axis=-1), 1.0)
    np.testing.assert_allclose(index[0], [2.0, 1.0, 1.0, 0.0], atol=1e-15)


@needs_numba
def test_transmissions_numba_matches_numpy_bit_for_bit(rng):
    from screwkit.core import _limbs_numba
    raw, twists = rng.standard_normal((50, 4, 6)), rng.standard_normal((50, 4, 6))
    raw[::6, 2] = 0.0  # a zero wrench row: kept zero, index 0
    raw[::4, 1, :3] = 0.0  # couples
    twists[::3, 3, :3] = 0.0  # translations
    compiled = _limbs_numba.transmissions(raw, twists, RTOL)
    numpy = LK.transmissions_numpy(LK.unit_rows(raw), twists, RTOL)
    for got, expected in zip(compiled, numpy, strict=True):
        np.testing.assert_array_equal(got, expected)
    assert (compiled[1][::6, 2] == 0).all() and (compiled[0][::6, 2] == 0).all()


@needs_numba
def test_mechanism_frame_numba_matches_numpy_bit_for_bit(rng, monkeypatch):
    from screwkit.algebra import _reference_frame_numba as kernels
    screws = rng.standard_normal((40, 13, 6))
    screws[:, 3, :3] = 0.0  # infinite pitch: ignored
    screws[::4, 5] = screws[::4, 5] * 1e-3
    screws[7, :, :3] = [0, 0, 1.0]  # all axes parallel: not solved directly, left to the numpy path
    screws[9] = np.array([[*e, 0, 0, 0] for e in np.eye(3)] * 4 + [[0, 0, 1.0, 0, 0, 0]])  # concurrent axes
    point, length, direct, scaled = kernels.mechanism_frame(screws, True)
    expected_point, expected_length = RF._frame_numpy(screws, None)
    assert not direct[7] and direct[9] and direct.sum() == 39
    np.testing.assert_array_equal(point[direct], expected_point[direct])
    np.testing.assert_array_equal(length[direct], expected_length[direct])
    monkeypatch.setitem(C._compiled, RF.KERNELS, None)  # the numpy path, whatever ran before
    expected_scaled = RF.unit_scaled(screws, expected_point, expected_length)
    np.testing.assert_array_equal(scaled[direct], expected_scaled[direct])
    np.testing.assert_array_equal(kernels.unit_scaled(screws, expected_point, expected_length), expected_scaled)
    assert length[9] == 1.0  # every axis through the origin: the length rule's fallback (no foot, no point)
    monkeypatch.setitem(C._compiled, RF.KERNELS, kernels)  # the numba pass, pose 7 as numpy
    for got, expected in zip(RF.scaled_frame(screws), (expected_point, expected_length, expected_scaled), strict=True):
        np.testing.assert_array_equal(got, expected)


def test_mechanism_frame_sums_known_values():
    """Two axes, z through (1, 0, 0) and x through (0, 0, 3), and a translation: N = Σ (I − u uᵀ)
    over the two lines, the right side Σ (I − u uᵀ) f with the feet (1, 0, 0) and (0, 0, 3), the
    farthest foot 3 and the spread about the point (1, 0, 3) (on both axes) zero."""
    z_line = np.array([0, 0, 1.0, *np.cross([1.0, 0, 0], [0, 0, 1.0])])
    x_line = np.array([1.0, 0, 0, *np.cross([0, 0, 3.0], [1.0, 0, 0])])
    screws = np.array([[z_line, [0, 0, 0, 0, 1.0, 0], x_line]])
    count, normal, rhs, farthest = RF._frame_sums_numpy(screws)
    assert count.tolist() == [2]
    np.testing.assert_allclose(normal[0], np.diag([1.0, 2.0, 1.0]))
    np.testing.assert_allclose(rhs[0], [1.0, 0, 3.0])
    np.testing.assert_allclose(farthest, [3.0])
    np.testing.assert_allclose(RF._frame_spread_numpy(screws, np.array([[1.0, 0, 3.0]])), [0.0], atol=1e-15)
    np.testing.assert_allclose(RF._frame_spread_numpy(screws, np.array([[1.0, 2.0, 3.0]])), [8.0])


def test_sum_in_order_adds_left_to_right():
    values = np.array([[1e16, 1.0, -1e16, 1.0], [1.0, 1e16, 1.0, -1e16]])
    np.testing.assert_array_equal(C.sum_in_order(values), [1.0, 0.0])  # ((1e16 + 1) − 1e16) + 1 = 1
    assert C.sum_in_order(np.zeros((3, 0))).tolist() == [0.0, 0.0, 0.0]


# ---- closed forms of the program: a joint in series with a node, the 4S parallelogram -------------
def twist_frame(rng, order):
    """A random frame of ``order`` (the rule's span of random generators) and its wrench frame."""
    rows, got = F._span_numpy(rng.standard_normal((max(order, 1), 6)) * (order > 0), RTOL)
    assert int(got) == order
    return rows, got, *F._complement_numpy(rows, got, swap=True)


def rank(rows, tol=1e-9):
    return np.linalg.matrix_rank(np.asarray(rows), tol) if len(rows) else 0


@pytest.mark.parametrize("order", range(6))
@pytest.mark.parametrize("dependent", [False, True])
def test_extend_and_contract_are_the_span_and_its_reciprocal(rng, order, dependent):
    # expected: the rule's span of the frame's rows and the screw, and its reciprocal (the generic
    # ops the closed forms replace), checked by an SVD rank too
    for _ in range(5):
        twists, t_order, wrenches, w_order = twist_frame(rng, order)
        if dependent and order:
            t = rng.standard_normal(order) @ twists[:order]
        else:
            t = rng.standard_normal(6)
        t /= np.linalg.norm(t)  # a unit joint screw, as in scaled coordinates
        spanned = F._span_numpy(np.concatenate([twists[:order], t[None]]), RTOL)
        expected_order = order if dependent and order else order + 1
        assert int(spanned[1]) == expected_order == rank(np.vstack([twists[:order], t]))
        rows, got, decided = CF.extend(twists, t_order, t, RTOL)
        assert bool(decided) and int(got) == expected_order
        check_frame(rows, got)
        np.testing.assert_allclose(projector(rows, got), projector(*spanned), atol=ATOL)
        rows, got, decided = CF.contract(wrenches, w_order, t, RTOL)
        expected = F._complement_numpy(*spanned, swap=True)
        assert bool(decided) and int(got) == 6 - expected_order == int(expected[1])
        check_frame(rows, got)
        np.testing.assert_allclose(projector(rows, got), projector(*expected), atol=ATOL)
        np.testing.assert_allclose(rows[:got] @ F.swapped(t), 0.0, atol=ATOL)  # reciprocal to the screw


@pytest.mark.parametrize(("offset", "decided", "grows"), [(1e-5, True, True), (1e-9, False, None), (1e-13, True, False)])
def test_closed_forms_leave_the_threshold_band_to_the_rule(rng, offset, decided, grows):
    # a screw at distance `offset` from a 3-system: the closed forms decide only clearly off the
    # threshold rtol = 1e-9 (a factor CLOSED_FORM_MARGIN either way), else the caller spans
    twists, t_order, wrenches, w_order = twist_frame(rng, 3)
    outside = F._complement_numpy(twists, t_order)[0][0]  # a unit vector orthogonal to the system
    t = rng.standard_normal(3) @ twists[:3]
    t = t / np.linalg.norm(t) + offset * outside
    for closed, frame, order, change in ((CF.extend, twists, t_order, 1), (CF.contract, wrenches, w_order, -1)):
        _, got, ok = closed(frame, order, t, RTOL)
        assert bool(ok) is decided
        if decided:
            assert int(got) == int(order) + (change if grows else 0)


def closed_numba(name, frame, order, t):
    from screwkit.core import _closed_forms_numba
    out = np.full((6, 6), np.nan)
    got = getattr(_closed_forms_numba, f"{name}_into")(frame, int(order), t, RTOL, out, np.empty(6), np.empty(6))
    return out, got


@needs_numba
def test_extend_and_contract_numba_match_numpy_bit_for_bit(rng):
    cases = []
    for order in range(7):
        twists, t_order, wrenches, w_order = twist_frame(rng, order)
        for offset in (1.0, 1e-9, 1e-13, 0.0):  # clear, the band, negligible, exact
            t = (rng.standard_normal(order) @ twists[:order]) if order else np.zeros(6)
            t = t + offset * rng.standard_normal(6)
            cases.append((twists, t_order, wrenches, w_order, t * rng.uniform(0.5, 2.0)))
    for name, closed, frame, order in (("extend", CF.extend, 0, 1), ("contract", CF.contract, 2, 3)):
        batch = [np.array([c[k] for c in cases]) for k in (frame, order, 4)]
        rows, got, decided = closed(*batch, RTOL)
        assert decided.any() and not decided.all()  # both kinds of pose in the batch
        for i, case in enumerate(cases):
            out, pose_order = closed_numba(name, case[frame], case[order], case[4])
            assert (pose_order >= 0) == decided[i]
            if decided[i]:
                assert pose_order == got[i] and np.array_equal(out, rows[i])


def parallelogram_points(rng, side=1.0, tilt=0.0):
    """Centres m, n, p, q of a 4S parallelogram (mn ∥ pq, mp ∥ nq), the second rod turned by
    ``tilt`` radians about the plane's normal (not a parallelogram unless 0)."""
    m = rng.uniform(-1, 1, 3)
    rod, across = rng.standard_normal(3), rng.standard_normal(3)
    n = m + side * across / np.linalg.norm(across)
    normal = np.cross(rod, across)
    normal /= np.linalg.norm(normal)
    turned = rod * np.cos(tilt) + np.cross(normal, rod) * np.sin(tilt)
    return m, n, m + rod, n + turned


def parallelogram_rods(rng, m, n, p, q):
    """The two rods' wrench frames by the closed-form rod (order 1 each)."""
    frames = [CF.rod(rod_rows(rng, a, b), RTOL) for a, b in ((m, p), (n, q))]
    assert all(int(order) == 1 for _, order in frames)
    return frames


@pytest.mark.parametrize("seed", range(6))
def test_parallelogram_is_the_span_of_the_rods_and_its_reciprocal(seed):
    # expected: the rule's span of the two rods' lines and its reciprocal (the generic ops), and
    # paper 002 §4.1's bases, written here from the four centres, checked by rank
    rng = np.random.default_rng(seed)
    m, n, p, q = parallelogram_points(rng)
    rods = parallelogram_rods(rng, m, n, p, q)
    wrenches, w_order, twists, t_order, decided = CF.parallelogram(*rods, RTOL)
    assert bool(decided) and int(w_order) == 2 and int(t_order) == 4
    check_frame(wrenches, w_order)
    check_frame(twists, t_order)
    spanned = F._span_numpy(np.concatenate([rods[0][0], rods[1][0]]), RTOL)
    reciprocal = F._complement_numpy(*spanned, swap=True)
    np.testing.assert_allclose(projector(wrenches, w_order), projector(*spanned), atol=ATOL)
    np.testing.assert_allclose(projector(twists, t_order), projector(*reciprocal), atol=ATOL)
    np.testing.assert_allclose(wrenches[:2] @ F.swapped(twists[:4]).T, 0.0, atol=ATOL)  # reciprocal
    s_mp, s_mn = (p - m) / np.linalg.norm(p - m), (n - m) / np.linalg.norm(n - m)
    normal = np.cross(s_mn, s_mp) / np.linalg.norm(np.cross(s_mn, s_mp))
    paper_wrenches = [np.r_[s_mp, np.cross(p, s_mp)], np.r_[np.zeros(3), np.cross(s_mp, s_mn)]]
    paper_twists = [
        np.r_[s_mp, np.cross(p, s_mp)],
        np.r_[s_mn, np.cross(n, s_mn)],
        np.r_[np.zeros(3), normal],
        np.r_[np.zeros(3), np.cross(s_mp, normal)],
    ]
    assert rank(paper_wrenches) == 2 and rank(paper_twists) == 4  # the paper's claims hold by rank
    assert rank(np.vstack([paper_wrenches, wrenches[:2]])) == 2  # the same systems as the closed form's
    assert rank(np.vstack([paper_twists, twists[:4]])) == 4
    np.testing.assert_allclose(np.array(paper_wrenches) @ F.swapped(np.array(paper_twists)).T, 0.0, atol=1e-12)


@pytest.mark.parametrize(
    ("side", "tilt", "decided", "atol"),
    [
        (1e-4, 0.0, True, 1e-10),  # close rods, clearly apart: the closed form (conditioning ~ eps/side)
        (1e-12, 0.0, False, ATOL),  # coincident to the rule: one line, the fallback
        (1.0, 1e-14, True, 1e-12),  # parallel to round-off
        (1.0, 1e-6, False, ATOL),  # not a parallelogram: the fallback
    ],
)
def test_parallelogram_near_degenerate(side, tilt, decided, atol):
    rng = np.random.default_rng(11)
    rods = parallelogram_rods(rng, *parallelogram_points(rng, side, tilt))
    got = CF.parallelogram(*rods, RTOL)
    assert bool(got[4]) is decided
    spanned = F._span_numpy(np.concatenate([rods[0][0], rods[1][0]]), RTOL)
    if decided:
        assert int(spanned[1]) == 2
        np.testing.assert_allclose(projector(got[0], got[1]), projector(*spanned), atol=atol)
        np.testing.assert_allclose(projector(got[2], got[3]), projector(*F._complement_numpy(*spanned, swap=True)), atol=atol)


@needs_numba
def test_parallelogram_numba_matches_numpy_bit_for_bit(rng):
    from screwkit.core import _closed_forms_numba
    cases = [parallelogram_points(rng) for _ in range(20)]
    cases += [parallelogram_points(rng, 1e-12), parallelogram_points(rng, 1.0, 1e-6)]  # two fallbacks
    rods = [parallelogram_rods(rng, *case) for case in cases]
    first = (np.array([r[0][0] for r in rods]), np.array([r[0][1] for r in rods]))
    second = (np.array([r[1][0] for r in rods]), np.array([r[1][1] for r in rods]))
    wrenches, _, twists, _, decided = CF.parallelogram(first, second, RTOL)
    assert decided[:20].all() and not decided[20:].any()
    for i in range(len(rods)):
        out = np.full((2, 6, 6), np.nan)
        ok = _closed_forms_numba.parallelogram_into(first[0][i], 1, second[0][i], 1, RTOL, out[0], out[1])
        assert ok == decided[i]
        if ok:
            assert np.array_equal(out[0], wrenches[i]) and np.array_equal(out[1], twists[i])


@needs_numba
def test_compiled_program_falls_back_alike(monkeypatch):
    # a hand-made program (a 3-joint chain's twists, their wrenches; a fourth screw added by EXTEND
    # and CONTRACT; two rods' PARALLELOGRAM) over poses where every closed form applies, where the
    # screw lies in the threshold band, and where the rods are not a parallelogram: the compiled
    # interpreter and the numpy path's op-by-op run agree bit for bit, and with the generic ops
    from screwkit.core import _frames_numba as _frames_numba
    rng = np.random.default_rng(3)
    poses = []
    for k in range(12):
        chain = rng.standard_normal((3, 6))
        chain /= np.linalg.norm(chain, axis=-1, keepdims=True)
        fourth = rng.standard_normal(6) if k % 3 == 0 else chain[0] + chain[1] + 1e-9 * rng.standard_normal(6)
        points = parallelogram_points(rng, 1.0, 1e-6 if k % 4 == 1 else 0.0)
        rods = np.concatenate([rod_rows(rng, points[0], points[2]), rod_rows(rng, points[1], points[3])])
        poses.append(np.concatenate([chain, fourth[None] / np.linalg.norm(fourth), rods]))
    scaled = np.array(poses)
    J, S = K.JOINT_ROWS, K.SLOT_ROWS
    ops = [
        (K.SPAN, 0, 0, 1),  # slot 0: the chain's twists
        (K.RECIPROCAL, 1, 0, 0),  # slot 1: their wrenches
        (K.EXTEND, 2, 1, 2),  # slot 2: with the fourth screw
        (K.CONTRACT, 3, 3, 3),  # slot 3: the wrenches of that (falling back on slot 0's rows)
        (K.ROD, 4, 6, 2),
        (K.ROD, 5, 8, 2),
        (K.PARALLELOGRAM, 6, 10, 2),
        (K.COMPANION, 7, 6, 0),
    ]
    sources = [
        (J, 0, 3),  # the span
        (J, 3, 1), (S, 0, 3),  # EXTEND
        (J, 3, 1), (S, 1, 6), (S, 0, 3),  # CONTRACT
        (J, 4, 3), (J, 7, 3),  # a rod
        (J, 10, 3), (J, 13, 3),  # another
        (S, 4, 6), (S, 5, 6),  # the two rods in parallel
    ]  # fmt: skip
    requests = tuple(("slot", i) for i in (2, 3, 6, 7))
    program = Program(
        np.array(ops, dtype=np.int64), np.array(sources, dtype=np.int64), {r: r[1] for r in requests}, (3, 3, 2, 3, 6, 6, 6, 7)
    )
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", _frames_numba)
    compiled = run_program(program, scaled, RTOL, requests)
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", None)
    stepwise = run_program(program, scaled, RTOL, requests)
    np.testing.assert_array_equal(compiled[1], stepwise[1])
    np.testing.assert_array_equal(compiled[0], stepwise[0])
    chain = F._span_numpy(scaled[:, :3], RTOL)[0][:, :3]  # in the band: the rule on the fallback's rows
    decided = CF.extend(F._span_numpy(scaled[:, :3], RTOL)[0], 3, scaled[:, 3], RTOL)[2]
    assert decided[::3].all() and not decided[1::3].any()  # both kinds of pose
    np.testing.assert_array_equal(stepwise[1][:, 0], F._span_numpy(np.concatenate([scaled[:, 3:4], chain], 1), RTOL)[1])
    chains = F._span_numpy(scaled[:, :4], RTOL)
    clear = slice(0, None, 3)  # the fourth screw well off the chain's system: closed forms
    np.testing.assert_array_equal(stepwise[1][clear, 0], chains[1][clear])
    np.testing.assert_array_equal(stepwise[1][:, 1], 6 - stepwise[1][:, 0])
    np.testing.assert_allclose(
        projector(stepwise[0][clear, 0], stepwise[1][clear, 0]), projector(*chains)[clear], atol=ATOL
    )
    reciprocal = F._complement_numpy(chains[0][clear], chains[1][clear], swap=True)
    np.testing.assert_allclose(projector(stepwise[0][clear, 1], stepwise[1][clear, 1]), projector(*reciprocal), atol=ATOL)
    rods = [CF.rod(scaled[:, 4 + 6 * r : 10 + 6 * r], RTOL) for r in range(2)]
    lines = F._span_numpy(np.concatenate([rods[0][0], rods[1][0]], axis=-2), RTOL)
    np.testing.assert_array_equal(stepwise[1][:, 2], lines[1])
    np.testing.assert_allclose(projector(stepwise[0][:, 2], stepwise[1][:, 2]), projector(*lines), atol=1e-9)


@needs_numba
def test_closing_numba_matches_numpy_bit_for_bit(rng, monkeypatch):
    # the core's last steps (global span, closeness triangles, user-frame actuation rows) in one
    # compiled pass against the numpy path's separate kernels; and against independent values: the
    # rank of the stacked rows, the triangles' singular values, the rows moved back by hand
    from screwkit.core import _frames_numba as _frames_numba
    n, limbs = 40, 4
    constraint = np.zeros((n, 6, 6))
    constraint[:, :2] = F._span_numpy(rng.standard_normal((n, 2, 6)), RTOL)[0][:, :2]
    wrenches = LK.unit_rows(rng.standard_normal((n, limbs, 6)))
    wrenches[::5, 2] = wrenches[::5, 0]  # a repeated row: the global order drops
    wrenches[3, 1, :3] = 0.0  # a couple
    legs = np.zeros((n, 2, 6, 6))
    legs[:, :, 0] = LK.unit_rows(rng.standard_normal((n, 2, 6)))
    apart = LK.unit_rows(rng.standard_normal((n, limbs, 6)))
    serial = rng.random((n, limbs)) < 0.2
    centre, length = rng.standard_normal((n, 3)), rng.uniform(0.5, 3.0, n)
    arguments = (constraint, wrenches, legs, apart, serial, centre, length, RTOL)
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", None)
    expected = CK.closing(*arguments)
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", _frames_numba)
    compiled = CK.closing(*arguments)
    for got, want in zip(compiled, expected, strict=True):
        np.testing.assert_array_equal(got, want)
    stacked = np.concatenate([constraint[:, :2], wrenches], axis=1)
    assert [rank(m) for m in stacked] == expected[1].tolist()
    assert (expected[1][::5] == 5).all() and (expected[1][1::5] == 6).all()
    values = np.linalg.svd(np.concatenate([CK.unpacked(expected[2]), apart], axis=1), compute_uv=False)
    np.testing.assert_allclose(
        np.linalg.svd(CK.unpacked(expected[3]), compute_uv=False),
        np.linalg.svd(np.concatenate([legs.reshape(n, 12, 6), apart], axis=1), compute_uv=False),
        atol=1e-12,
    )
    np.testing.assert_allclose(values, np.linalg.svd(CK.unpacked(expected[3]), compute_uv=False), atol=1e-12)
    moved = np.concatenate([wrenches[..., :3], wrenches[..., 3:] * length[:, None, None]
                            + np.cross(centre[:, None, :], wrenches[..., :3])], axis=-1)
    forces = np.linalg.norm(moved[..., :3], axis=-1)
    size = np.where(forces > 1e-9 * np.linalg.norm(moved[..., 3:], axis=-1) / length[:, None], forces,
                    np.linalg.norm(moved[..., 3:], axis=-1))
    np.testing.assert_allclose(expected[4], np.where(serial[..., None], 0.0, moved / size[..., None]), atol=1e-12)
    assert np.all(expected[4][serial] == 0.0)


@needs_numba
def test_residuals_against_frames_match_residual_bit_for_bit(rng, monkeypatch):
    # each vector against its own frame of a strided stack, as residual() one frame at a time
    from screwkit.core import _frames_numba as _frames_numba
    block = np.zeros((30, 5, 6, 6))
    for f in range(5):
        block[:, f, : f + 1] = F._span_numpy(rng.standard_normal((30, f + 1, 6)), RTOL)[0][:, : f + 1]
    frames = block[:, 1:4]  # strided, as the program's block
    vectors = rng.standard_normal((30, 4, 6))
    which = np.array([2, 0, 2, 1])
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", None)
    expected = R.residuals_against(vectors, frames, which)
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", _frames_numba)
    np.testing.assert_array_equal(R.residuals_against(vectors, frames, which), expected)
    for j, f in enumerate(which):
        np.testing.assert_array_equal(expected[:, j], R._residual_numpy(vectors[:, j : j + 1], frames[:, f])[:, 0])
        np.testing.assert_allclose(np.einsum("pis,ps->pi", frames[:, f], expected[:, j]), 0.0, atol=1e-12)


@needs_numba
def test_limb_wrenches_one_pass_matches_the_steps_bit_for_bit(rng, monkeypatch):
    # the fused pass against its steps run one by one (limb systems, line test, transmissions,
    # leg residuals), numba and numpy alike
    from screwkit.core import _frames_numba as _frames_numba
    locked, order, passive, actuated = limb_inputs(rng, 50)
    passive[3, 2, :, 3:] += 0.5 * passive[3, 2, :, :3]  # a pitched direction: no line
    legs = np.zeros((50, 2, 6, 6))
    legs[:, :, 0] = LK.unit_rows(rng.standard_normal((50, 2, 6)))
    coupled, leg_of = np.array([0, 3, 1]), np.array([1, 1, 0])
    arguments = (locked, order, passive, actuated, legs, coupled, leg_of, RTOL, 1e-6)
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", None)
    expected = LK.limb_wrenches(*arguments)
    _, serial, _, free_order, direction = LK._limb_systems_numpy(locked, order, passive, actuated, RTOL)
    wrench, index = LK.transmissions_numpy(LK.unit_rows(direction), actuated, RTOL)
    steps = (serial, free_order, direction, wrench, index,
             R.residuals_against(wrench[:, coupled], legs, leg_of), LK.not_lines(direction, 1e-6))
    monkeypatch.setitem(C._compiled, "screwkit.core._frames_numba", _frames_numba)
    compiled = LK.limb_wrenches(*arguments)
    for got, via_numpy, step in zip(compiled, expected, steps, strict=True):
        np.testing.assert_array_equal(got, via_numpy)
        np.testing.assert_array_equal(via_numpy, step)
    assert expected[0].any() and expected[6].any() and not expected[6].all()  # serial limbs, a non-line


def test_not_lines_is_the_pitch_criterion(rng):
    # Independent of the kernel: a line (s; r × s) has s·m = 0 exactly in exact arithmetic; a helical
    # screw (s; r × s + h s) has s·m = h |s|², so it is "not a line" iff |h| |s| > line_rtol |w|
    # (|w| the whole row's norm). Couples (s = 0) have s·m = 0 and count as lines at infinity.
    from screwkit.algebra import screw as S
    directions = rng.standard_normal((200, 3))
    points = rng.uniform(-10, 10, (200, 3))
    lines = S.line(directions, points)
    assert not LK.not_lines(lines, 1e-6).any()
    assert not LK.not_lines(S.couple(directions), 1e-6).any()
    for pitch, expected in ((1e-3, True), (-1e-3, True), (1e-12, False)):
        helices = S.helical_twist(directions, points, pitch)
        size = np.linalg.norm(helices[:, :3], axis=1)
        by_hand = np.abs(pitch) * size > 1e-6 * np.linalg.norm(helices, axis=1)
        assert (by_hand == expected).all()
        np.testing.assert_array_equal(LK.not_lines(helices, 1e-6), by_hand)
