"""The compiled kernels of the loop-closure continuation (screwkit.core._newton_numba) against their
numpy twins (the product of exponentials, the loops' residual, one continuation step's Newton
corrector), the whole continuation with and without them, and the spherical joints' secant
predictor that once took Ragnar poses to another working mode.

The kernels do the numpy twins' formulas in another order (a Cholesky factorisation where numpy calls
LAPACK, the Gram matrix summed column by column), so they agree to round-off: 1e-12 in the scaled
frame (characteristic lengths, radians). A whole continuation converges each pose to a residual of
1e-12 from either path: the joint values that the pose determines agree to that residual times the
conditioning, the internal freedoms (a rod's spin about its own axis) only to what the minimum-norm
corrections left them."""

import numpy as np
import pytest

from screwkit.algebra import compiled
from screwkit.algebra.rigid_motions import rotation_matrix
from screwkit.core import loop_closure
from screwkit.core._batched_poe import KERNELS
from screwkit.core.kinematic_model import KinematicModel
from screwkit.core.kinematic_tasks import PoseTask
from screwkit.core.task_coordinates import task_coordinates
from screwkit.graphs.joints import helical, parallelogram, prismatic, revolute, spherical
from screwkit.graphs.twistgraph import twist_graph
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.graph_kinematics import kinematics_of

from ..mechanisms import gough_stewart, gough_stewart_points
from ..robots.test_graph_mechanism import _spherical_centres

kernels = pytest.importorskip("screwkit.core._newton_numba", reason="numba is not installed (the `fast` extra)")

POSES = 300


def _chain():
    """Every kind of column the kernels know: revolute, Π, slider, helical, spherical."""
    return twist_graph("B", "E", [
        ("B", "L1", revolute("R", [0, 0, 1], [0.5, 0, 0])),
        ("L1", "L2", parallelogram("Pa", [1, 0, 0], [0, 0, -1])),
        ("L2", "L3", prismatic("P", [0, 1, 0])),
        ("L3", "L4", helical("H", [0, 1, 1], [0.3, 0, 0], 0.2)),
        ("L4", "E", spherical("S", [0.2, 0.1, -0.3])),
    ], dof=6)


def _rotations(rng, count):
    axes = rng.normal(size=(count, 3))
    return rotation_matrix(axes / np.linalg.norm(axes, axis=1, keepdims=True), rng.uniform(0, np.pi, count))


def _models():
    h4 = KinematicModel(load_mechanism("h4").twist_graph())
    gs = KinematicModel(gough_stewart(*gough_stewart_points()))
    return {
        "h4": (h4, False),
        "h4 pinned": (h4.pinned_model(h4.platform), True),
        "6-UPS pinned": (gs.pinned_model(gs.platform), True),
        "chain": (KinematicModel(_chain()), False),
    }


@pytest.mark.parametrize("name", ["h4", "h4 pinned", "6-UPS pinned", "chain"])
def test_the_compiled_product_of_exponentials_and_loop_residual_equal_the_numpy_twins(name):
    model, pinned = _models()[name]
    rng = np.random.default_rng(3)
    theta = rng.normal(scale=0.6, size=(POSES, model.size))
    keys = [key for key, kind in model.types.items() if kind == "S"]
    offsets = {key: np.tile(np.eye(4), (POSES, 1, 1)) for key in keys}
    for key in keys[::2]:  # some joints turned, some not
        offsets[key][:, :3, :3] = _rotations(rng, POSES)
    placed = None
    if pinned:
        placed = np.tile(np.eye(4), (POSES, 1, 1))
        placed[:, :3, :3], placed[:, :3, 3] = _rotations(rng, POSES), rng.normal(size=(POSES, 3))
    product = model._product
    ours = kernels.evaluate(
        theta,
        np.stack([offsets[key] for key in keys], axis=1) if keys else np.zeros((POSES, 0, 4, 4)),
        np.zeros((1, 4, 4)) if placed is None else placed,
        product.kernel_arrays(keys),
    )
    twins = product.evaluate_numpy(theta, offsets, placed)
    for compiled_part, numpy_part in zip(ours, twins, strict=True):
        assert np.abs(compiled_part - numpy_part).max() < 1e-12
    loops = np.array([
        [product.link_index[model.joints[key][0]], product.link_index[model.joints[key][1]], product.joint_index[key]]
        for key in model.closing
    ], dtype=np.int64).reshape(-1, 3)
    state = model.state(theta, offsets, placed)
    residual = kernels.loop_residual(ours[0], ours[1], loops)
    assert residual.shape == (POSES, 6 * len(model.closing))
    assert np.abs(residual - model.loop_residual(state)).max(initial=0.0) < 1e-12


@pytest.mark.parametrize("name", ["h4", "6-UPS"])
def test_one_compiled_corrector_step_equals_the_numpy_twin(name):
    """From the reference, the first continuation step towards poses a quarter step away: theta,
    offsets, residual sizes and corrections of both paths (the 6-UPS's blocks are square and regular;
    the H4's are singular (a parallelogram's loops hold a dependent equation), damped: the
    corrections agree to the damping's round-off, the closed loops to the tolerance)."""
    if name == "h4":
        kinematics = kinematics_of(load_mechanism("h4"))
        model, task = kinematics.model, kinematics.task
    else:
        model = KinematicModel(gough_stewart(*gough_stewart_points()))
        task = PoseTask(model, task_coordinates(model), complete=True)
    system = loop_closure._PinnedLoops(model, task)
    rng = np.random.default_rng(5)
    start = task.values(model.state(np.zeros((1, model.size))))
    target = start + rng.uniform(-0.06, 0.06, size=(POSES, start.shape[1])) * np.any(start != 0, axis=0)
    if name == "6-UPS":
        target = start + rng.uniform(-0.06, 0.06, size=(POSES, start.shape[1]))
    tolerance = np.tile(loop_closure.LAST_TOLERANCES, (POSES, 1))
    working = np.ones(POSES, dtype=bool)
    working[::7] = False  # resting poses stay as they are
    runs = []
    for step in (system.newton, super(loop_closure._PinnedLoops, system).newton):
        theta = np.zeros((POSES, model.size))
        offsets = np.tile(np.eye(4), (POSES, len(system.spherical), 1, 1))
        runs.append((theta, offsets, *step(theta, offsets, target, tolerance, working)))
    (theta_c, offsets_c, *out_c), (theta_n, offsets_n, *out_n) = runs
    for theta, offsets in ((theta_c, offsets_c), (theta_n, offsets_n)):
        assert np.all(theta[~working] == 0.0)
        closed = system.pinned.state(theta, system.offsets_of(offsets), task.displacement(target))
        assert np.abs(system.pinned.loop_residual(closed)[working]).max() < 1e-9  # closed on the way
    if name == "6-UPS":
        assert np.abs(theta_c - theta_n).max() < 1e-12
        assert np.abs(offsets_c - offsets_n).max() < 1e-12
        for compiled_part, numpy_part in zip(out_c, out_n, strict=True):
            assert np.abs(compiled_part - numpy_part).max() < 1e-12
    else:  # the joint values the pose determines (the hinges'), and the jump measure
        hinges = [i for i, column in enumerate(model.columns) if model.types[column.joint] == "R"]
        assert np.abs(theta_c[:, hinges] - theta_n[:, hinges]).max() < 1e-10
        assert np.abs(out_c[1] - out_n[1]).max() < 1e-6


def test_the_continuation_reaches_the_same_configurations_without_numba(monkeypatch):
    kinematics = kinematics_of(load_mechanism("h4"))
    poses = load_mechanism("h4").random_poses(np.random.default_rng(2), POSES)
    targets = kinematics._targets(poses)
    fast = loop_closure.close_loops(kinematics.model, kinematics.task, targets)
    monkeypatch.setitem(compiled._compiled, KERNELS, None)  # the numpy twins
    plain = loop_closure.close_loops(kinematics.model, kinematics.task, targets)
    assert fast.reached.all() and plain.reached.all()
    hinges = [i for i, column in enumerate(kinematics.model.columns) if kinematics.model.types[column.joint] == "R"]
    assert np.abs(fast.theta[:, hinges] - plain.theta[:, hinges]).max() < 1e-10
    centres = [
        _spherical_centres(closed.state.current[:, columns] * 1.0)
        for closed in (fast, plain)
        for columns in [kinematics.model.joints["S1m"][2]]
    ]
    assert np.abs(centres[0] - centres[1]).max() < 1e-10


def test_the_spherical_secant_keeps_ragnar_poses_in_their_working_mode():
    """Two Ragnar poses whose straight way passes close to a leg's serial singularity (the second's
    leaves the reach), each asked 128 times (a batch: numba's path, where they were found): predicting
    the spherical joints by the secant in the second pass's short steps too, where any correction is
    accepted, took both to the other elbow branch (S1m's centre 436 and 349 mm away from the closed
    form's); with the secant in the first pass only, the whole correction from the predicted point
    counted, the first is reached in its working mode and the second is flagged or reached in it."""
    robot = load_mechanism("ragnar")
    poses = np.array([
        [406.51642906163147, 507.4067908207528, -233.64454084078704, 1.1809730502495315],
        [408.46310792779923, 445.4721407067368, -266.9239207584569, -1.1233149454584384],
    ])
    kinematics = kinematics_of(robot)
    repeated = np.repeat(poses, compiled.COMPILED_MIN_BATCH // 2, axis=0)
    closed = loop_closure.close_loops(kinematics.model, kinematics.task, kinematics._targets(repeated))
    way = robot.default_pose + np.linspace(0, 1, 4000)[:, None] * (poses[0] - robot.default_pose)
    assert robot.reachable(way).all() and closed.reached[0]
    ours = kinematics.model.joint_table(closed.state, kinematics.reference)
    reference = robot.joints(repeated)
    gap = _spherical_centres(ours.joint_screws("S1m")) - _spherical_centres(reference.joint_screws("S1m"))
    assert np.abs(gap[closed.reached]).max() < 1e-6  # mm
