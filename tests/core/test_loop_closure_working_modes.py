"""The loop closure keeps the working and assembly modes it starts in (screwkit.core._working_modes,
screwkit.core.loop_closure): the orientation it tracks is the sign of a hand-derived determinant, and
Ragnar poses whose way from the reference grazes or crosses a leg's serial singularity come back either
equal to the closed form's working mode or flagged with their reason, never in the other working mode."""

import numpy as np
import pytest

from screwkit.core._working_modes import Orientations
from screwkit.core.kinematic_model import KinematicModel
from screwkit.core.kinematic_tasks import PoseTask
from screwkit.core.loop_closure import _LoopsAndTask, close_loops
from screwkit.core.task_coordinates import task_coordinates
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics
from screwkit.robots.graph_kinematics import kinematics_of

from .test_loop_closure import arm_2r

# Ragnar poses (random_poses, seeds 12-15 of 10,000) where the loop closure at b9f8382 returned one leg in
# the other working mode (the closed form's other root of paper 004's Eq. 3, sgn h_i flipped): the straight
# way from the reference passes within 2-3 degrees of that leg's serial singularity (delta_i -> pi) or
# leaves the reach and comes back.
RAGNAR_POSES_NEAR_A_FOLD = [
    [182.78083641974388, -378.4451972064997, -245.17390533506216, 3.4905427554154347],
    [-252.40993890930116, -362.5992911815509, -290.5627127912711, -3.4466604456696084],
    [-404.82516833467946, 388.86611910682973, -329.54302376044427, -2.366471342432866],
    [-481.50191402078997, -511.66646890009986, -236.2771247237224, -0.23857787947736409],
    [-401.7478162187059, 312.2181653249261, -396.5214294527011, -2.83681424593372],
    [-246.48386876821803, 384.6307111621111, -274.5750063503807, -4.848148257468109],
    [465.65176972065206, -429.47256860513295, -309.2586553516536, -1.5102423783685222],
    [-408.66444625686233, -390.2999148405229, -349.6421236108663, 6.259134875969837],
    [-444.22103625567496, 278.8838478662576, -428.65508357305947, -0.9620199730832386],
    [482.106406602541, 529.0753259815517, -234.27228708810617, 3.9691492318119206],
    [-284.8668204906618, 405.3620275675137, -268.18257854868625, 2.350321966397397],
    [-250.9881512054171, 435.69450176661894, -218.984478134666, -5.835884334748599],
    [365.67094259554415, 398.53429481099306, -326.71316775839887, 5.399625980370541],
]


def test_a_2r_arms_orientation_is_the_sign_of_its_elbow():
    # the end point's Jacobian of a 2R arm with unit links has det = sin(elbow) (Murray, Li & Sastry 1994,
    # §3.4): two configurations are in one working mode exactly when the elbow has one sign
    model = KinematicModel(arm_2r())
    system = _LoopsAndTask(model, PoseTask(model, task_coordinates(model, point=[1, 1, 0], rotations=False)))
    rng = np.random.default_rng(5)
    start, end = rng.uniform(-np.pi, np.pi, (2, 400, 2))
    elbow_start, elbow_end = np.pi / 2 + start[:, 1], np.pi / 2 + end[:, 1]  # the reference's elbow: +90°
    regular = (np.abs(np.sin(elbow_start)) > 1e-3) & (np.abs(np.sin(elbow_end)) > 1e-3)
    start, end, elbow_start, elbow_end = start[regular], end[regular], elbow_start[regular], elbow_end[regular]
    offsets = np.zeros((len(start), 0, 4, 4))
    values = system.task.values
    modes = Orientations(system, start, offsets, values(model.state(start)))
    kept = modes.kept(system, end, offsets, values(model.state(end)), np.ones(len(end), dtype=bool))
    same = np.sign(np.sin(elbow_start)) == np.sign(np.sin(elbow_end))
    assert 100 < same.sum() < len(same) - 100
    assert np.array_equal(kept, same)
    assert set(modes.changed[~kept]) == {"R1, R2"} and set(modes.changed[kept]) == {""}


@pytest.fixture(scope="module")
def ragnar():
    return load_mechanism("ragnar")


@pytest.mark.parametrize("rods", [True, False])
def test_ragnar_poses_near_a_leg_singularity_keep_the_working_mode_or_are_flagged(ragnar, rods):
    # rods=True: the rods' distance equations (screwkit.core._rod_closure, the default); False: every loop
    poses = np.array(RAGNAR_POSES_NEAR_A_FOLD)
    kinematics = kinematics_of(ragnar)
    closed = close_loops(kinematics.model, kinematics.task, kinematics._targets(poses), rods=rods)
    # the closed form's working mode (-1, -1, -1, -1) (paper 004 Eq. 8), its actuated angles from Eq. 3
    expected = inverse_kinematics(ragnar.parameters, poses).theta
    columns = [kinematics.model.joints[name][2][0] for name in kinematics.actuated]
    reference = inverse_kinematics(ragnar.parameters, ragnar.default_pose).theta
    angles = reference + closed.theta[:, columns]
    gap = np.abs((angles - expected + np.pi) % (2 * np.pi) - np.pi).max(axis=1)
    assert np.all(gap[closed.reached] < 1e-9), gap
    # every pose whose straight way from the reference stays in reach (the closed form at 4,001 points of
    # it) is reached; the others may be flagged, each with its reason
    way = np.linspace(0, 1, 4001)[:, None]
    stays = np.array([ragnar.reachable(ragnar.default_pose + way * (pose - ragnar.default_pose)).all()
                      for pose in poses])
    assert stays.sum() == 6 and np.all(closed.reached[stays])
    if rods:  # the rods' continuation: reached exactly where the straight way stays in reach
        assert np.array_equal(closed.reached, stays)
    else:  # every loop's equations get through one pose more (pose 7, in the closed form's mode)
        assert closed.reached.sum() >= 7
    for reason in closed.reasons[~closed.reached]:
        assert "working or assembly mode" in reason or "do not close" in reason
        assert "residual" in reason


@pytest.mark.parametrize(("rods", "pose", "joints"), [(True, 8, "A2, A4, R_II"), (False, 3, "A1, A3")])
def test_a_refused_step_names_the_joints_of_the_leg_group(ragnar, rods, pose, joints):
    kinematics = kinematics_of(ragnar)
    targets = kinematics._targets(np.array(RAGNAR_POSES_NEAR_A_FOLD[pose : pose + 1]))
    closed = close_loops(kinematics.model, kinematics.task, targets, rods=rods)
    assert not closed.reached[0]
    assert "working or assembly mode" in closed.reasons[0] and joints in closed.reasons[0]
