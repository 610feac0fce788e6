"""The two implementations of :mod:`screwkit._frames` (numpy and numba) follow one rule.

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

from screwkit import _frames as F

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
        F._residual_numba(vectors, frame_rows), F._residual_numpy(vectors, frame_rows), atol=ATOL
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
        "import sys, numpy as np\nfrom screwkit import _frames as F\n"
        "F.span(np.eye(6)[:2], 1e-9)\nprint(F.backend(), 'numba' in sys.modules)"
    )
    assert _probe(code, {"SCREWKIT_NUMBA": "0"}) == ["numpy", "False"]


@needs_numba
def test_numba_is_the_default_and_imported_lazily():
    # a small call runs numpy without importing numba; a call of COMPILED_MIN_BATCH frames loads it
    code = (
        "import sys, numpy as np, screwkit\nfrom screwkit import _frames as F\nprint('numba' in sys.modules)\n"
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
    assert same(F._residual_numpy(vectors, rows), F._residual_numba(vectors, rows))


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
        "import numpy as np, screwkit as sk\nfrom screwkit.families.four_limb import reachable\n"
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
    from screwkit import _frames_numba

    out = np.full((6, 6), np.nan)
    if _frames_numba.rod_into(np.ascontiguousarray(rows), rtol, out):
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
    implementations = [F.rod] + ([rod_numba] if HAS_NUMBA else [])
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
    got, order = F.rod(rows, RTOL)
    assert int(expected[1]) != 1  # no single line: the closed form would be wrong here
    np.testing.assert_array_equal(order, expected[1])
    np.testing.assert_allclose(projector(got, order), projector(F.swapped(expected[0]), expected[1]), atol=ATOL)
    if HAS_NUMBA:
        assert rod_numba(rows, RTOL) is None  # the compiled program then spans, as above


@needs_numba
@pytest.mark.parametrize("seed", range(3))
def test_rod_and_unit_screws_numba_and_numpy_are_bit_identical(seed):
    from screwkit import _frames_numba

    rng = np.random.default_rng(seed)
    batch = [rod_rows(rng, rng.uniform(-2, 2, 3), rng.uniform(-2, 2, 3)) for _ in range(30)]
    batch[3] = rod_rows(rng, np.ones(3), np.ones(3))  # a fallback pose in the batch
    rows = np.array(batch)
    expected = F.rod(rows, RTOL)
    for i, pose in enumerate(rows):
        out = np.zeros((6, 6))
        if _frames_numba.rod_into(np.ascontiguousarray(pose), RTOL, out):
            assert expected[1][i] == 1 and np.array_equal(out, expected[0][i])
        else:
            assert i == 3 and expected[1][i] == 3
    screws = rng.standard_normal((7, 9, 6)) * rng.uniform(0.1, 100.0, (7, 1, 1))
    screws[2, 4] = 0.0  # a zero row stays zero
    centre, length = rng.standard_normal((7, 3)), rng.uniform(0.5, 5.0, 7)
    compiled = _frames_numba.unit_scaled(screws, centre, length)
    np.testing.assert_array_equal(compiled, F.unit_scaled(screws, centre, length))  # 7 < 256: numpy
    assert np.all(compiled[2, 4] == 0.0)
    np.testing.assert_allclose(np.linalg.norm(np.delete(compiled.reshape(-1, 6), 22, 0), axis=-1), 1.0)


@needs_numba
def test_compiled_program_matches_the_ops_run_one_by_one(monkeypatch):
    # the numba interpreter against the numpy path's op-by-op run of the same H4 program: bit for
    # bit (frames, orders)
    import screwkit as sk
    from screwkit import _frames_numba
    from screwkit import wrenches as W
    from screwkit.topology import topology
    from screwkit.twistgraph import mechanism_frame

    h4 = sk.load_mechanism("h4")
    table = W._canonical(h4.joints(h4.random_poses(np.random.default_rng(5), 30)[:20]))
    top = topology(table.base, table.platform, table.specs)
    centre, length = mechanism_frame(table.screws, table.anchor)
    scaled = F.unit_scaled(table.screws, centre, length)
    requests = (
        *(("twists", i) for i in range(len(top.nodes))),
        *(("wrenches", i) for i in top.legs),
        *(("passive", tuple(plan.siblings)) for plan in top.limbs),
    )
    program = W._program(top, requests)
    assert W.ROD in program.ops[:, 0]  # the parallelograms' rods in closed form
    monkeypatch.setitem(F._compiled, "_frames_numba", _frames_numba)
    compiled = W._run(program, scaled, RTOL, requests)
    monkeypatch.setitem(F._compiled, "_frames_numba", None)
    stepwise = W._run(program, scaled, RTOL, requests)
    assert compiled[0].shape == stepwise[0].shape == (20, len(requests), 6, 6)
    np.testing.assert_array_equal(compiled[1], stepwise[1])
    np.testing.assert_array_equal(compiled[0], stepwise[0])


@needs_numba
@pytest.mark.parametrize("k", [4, 6, 7, 12, 16])
def test_triangular_keeps_the_singular_values_and_both_paths_are_bit_identical(rng, monkeypatch, k):
    from screwkit import _frames_numba

    rows = rng.standard_normal((40, k, 6))
    rows[:, ::3] = 0.0  # zero rows, as in stacked frames
    rows[:5] = 0.0  # an all-zero matrix
    rows[5:10, :, 2] = 0.0  # a zero column
    padded = np.concatenate([rows, np.zeros((40, max(6 - k, 0), 6))], axis=1)  # fewer than 6: zero rows added
    compiled = _frames_numba.triangular(np.ascontiguousarray(padded))
    monkeypatch.setitem(F._compiled, "_frames_numba", None)
    np.testing.assert_array_equal(F.triangular(rows), compiled)
    assert np.all(np.tril(compiled, -1) == 0)  # upper triangular
    np.testing.assert_allclose(
        np.linalg.svd(compiled, compute_uv=False), np.linalg.svd(padded, compute_uv=False), atol=1e-13
    )
    np.testing.assert_array_equal(F.unpacked(F.packed(compiled)), compiled)  # the 21 entries say it all
