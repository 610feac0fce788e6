"""A diagram's constraint lines over a batch: the points and conditions of the per-pose readable bases.

:func:`screwkit.gca.diagram_points.batch_diagram_points` reads the legs' constraint lines through
:func:`screwkit.algebra.readable_bases.readable_bases`. The expected values take the per-pose route
the maps took before: each leg's system at each pose through
:meth:`~screwkit.algebra.screwsystem.ScrewSystem.readable_basis`, one at a time, from the same
frames. On the Delta (a couple per leg, its first coordinate clear: the closed form) and Tsai's
3-UPU as a graph mechanism (one leg's couple in the plane x = 0: its first coordinate is round-off,
whose sign the method's own null spaces decide), over 800 poses with the 3-UPU's platform
down to 1e-9 above its base (where its operation modes meet), the points agree to 1e-12 and the
conditions to 1e-12 of their scale.
"""

import numpy as np
import pytest

import screwkit as sk
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.analysis import quantities as Q
from screwkit.core.wrench_systems import analyze_table
from screwkit.gca import diagram_points as DP

from ..mechanisms import tsai_3upu


def one_at_a_time(rows, orders, *, rtol, length_scale):
    """readable_bases as the maps took it before: the method, system by system."""
    found = np.full(rows.shape, np.nan)
    for i, order in enumerate(orders):
        system = ScrewSystem.from_independent(rows[i, :order], rtol=rtol, length_scale=float(length_scale[i]))
        found[i, :order] = system.readable_basis()
    return found


def delta_poses():
    delta = sk.load_mechanism("delta")
    poses = delta.random_poses(np.random.default_rng(21), 1600)
    return delta, poses[delta.reachable(poses)][:500]


def tsai_poses():
    rng = np.random.default_rng(8)
    heights = np.concatenate([10.0 ** rng.uniform(-9, -1, 150), rng.uniform(0.3, 1.2, 150)])
    poses = np.column_stack([rng.uniform(-0.2, 0.2, 300), rng.uniform(-0.2, 0.2, 300), heights])
    return sk.mechanism(tsai_3upu([0.1, 0.05, 1.0])), poses


@pytest.mark.parametrize("build", [delta_poses, tsai_poses], ids=["delta", "3-UPU graph"])
def test_points_and_conditions_equal_the_per_pose_readable_bases(build, monkeypatch):
    mechanism, poses = build()
    poses = poses[mechanism.reachable(poses)]
    assert len(poses) >= 250
    diagram, conditions, _, _ = Q.conditions_of(mechanism, {})
    analysis = analyze_table(
        mechanism.at(poses).joints, views=False, kept=lambda top: DP.frames_read(diagram.points, top)
    )
    found = DP.batch_diagram_points(diagram.points, analysis)
    monkeypatch.setattr(DP, "readable_bases", one_at_a_time)
    expected = DP.batch_diagram_points(diagram.points, analysis)
    for point in diagram.points:
        np.testing.assert_allclose(found[point.label], expected[point.label], rtol=1e-12, atol=1e-12)
    for condition in conditions:
        value, reference = condition.evaluate(found), condition.evaluate(expected)
        assert np.isfinite(reference).all()
        np.testing.assert_allclose(value, reference, rtol=1e-12, atol=1e-12 * np.abs(reference).max())
