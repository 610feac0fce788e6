"""The family protocol's optional knowledge (screwkit.robots.families.Family): working modes, default
map axes, actuated values; read by the generic code instead of special cases on family names."""

import dataclasses
import itertools
from pathlib import Path

import numpy as np
import pytest

from screwkit.analysis.poses import DEFAULT_AXIS_COUNT
from screwkit.analysis.workspace import evaluate, grid_map
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families import Family, WorkingModes, families, register


def test_a_working_mode_goes_to_the_familys_own_keyword():
    # the McGill SMG's inverse kinematics takes `mode`, the four-limb family's `working_mode`
    smg = load_mechanism("mcgill_smg")
    assert smg.family_protocol.mode_options((1, 1, -1, -1)) == {"mode": (1, 1, -1, -1)}
    other = (1, -1, -1, 1)  # both elbows flipped
    pose = smg.default_pose[None]
    verdict, ok = evaluate(smg, pose, "verdict", mode=other)
    direct = smg.at(pose, mode=other)
    assert ok.all() and verdict.tolist() == direct.codes.tolist()
    assert not np.allclose(direct.configuration.joint_angles, smg.configuration(pose).joint_angles)


def test_a_malformed_working_mode_names_the_family_meaning():
    with pytest.raises(ScrewkitValueError, match=r"Expected `mode` to be 4 values among \(-1, 1\) \(the signs of h_i"):
        families()["four_limb"].mode_options((1, 1, 1))
    one_mode = dataclasses.replace(families()["four_limb"], working_modes=None)
    with pytest.raises(ScrewkitTypeError, match=r"working mode of the family 'four_limb' \(it has none\)"):
        one_mode.mode_options((1, 1, 1, 1))
    with pytest.raises(ScrewkitTypeError, match="got 'up'"):
        families()["four_limb"].mode_options("up")


@pytest.mark.parametrize(("robot", "axes"), [("h4", ("z", "phi")), ("mcgill_smg", ("x", "y"))])
def test_a_map_without_axes_spans_the_familys_default_axes_over_the_workspace(robot, axes):
    mechanism = load_mechanism(robot)
    assert mechanism.family_protocol.default_map_axes == axes
    small = {"x": None, "y": None}
    result = grid_map(mechanism, "verdict", **small)
    assert (result.x_name, result.y_name) == axes
    for name, values in ((result.x_name, result.x_values), (result.y_name, result.y_values)):
        low, high = mechanism.workspace[name]
        np.testing.assert_allclose(values, np.linspace(low, high, DEFAULT_AXIS_COUNT))


def test_reachable_uses_the_hook_under_the_working_mode_keyword_only(monkeypatch):
    h4 = load_mechanism("h4")
    poses = np.array([[0, 0, -750, 0], [0, 0, -3000, 0]])
    calls = []
    family = h4.family_protocol

    def counting(parameters, chosen):
        calls.append(len(chosen))
        return family.reachable(parameters, chosen)

    monkeypatch.setitem(families()._loaded, "four_limb", dataclasses.replace(family, reachable=counting))
    assert h4.reachable(poses, working_mode=(1, 1, 1, 1)).tolist() == [True, False]
    assert calls == [2]


def _family(**changes):
    base = Family("odd", *[print] * 4, ("x", "y"), ())
    return dataclasses.replace(base, **changes)


@pytest.mark.parametrize(
    ("changes", "error", "match"),
    [
        ({"actuated_values": 3}, ScrewkitTypeError, r"Expected `family.actuated_values` to be callable or None, got int"),
        ({"working_modes": ("working_mode",)}, ScrewkitTypeError, r"`family.working_modes` to be a WorkingModes or None, got tuple"),
        ({"working_modes": WorkingModes("two words", (1,), "m")}, ScrewkitTypeError, r"`family.working_modes.option` to be an identifier"),
        ({"working_modes": WorkingModes("mode", (1,), "")}, ScrewkitTypeError, r"`family.working_modes.meaning` to be a sentence"),
        ({"working_modes": WorkingModes("mode", (0,), "m")}, ScrewkitValueError, r"`family.working_modes.default` to be a non-empty tuple of values among \(-1, 1\), got \(0,\)"),
        ({"working_modes": WorkingModes("mode", (1,), "m", of=2)}, ScrewkitTypeError, r"`family.working_modes.of` to be callable or None, got int"),
        ({"map_axes": ("x", "z")}, ScrewkitValueError, r"`family.map_axes` to be None or two different pose coordinates of \('x', 'y'\), got \('x', 'z'\)"),
        ({"map_axes": ("x", "x")}, ScrewkitValueError, r"two different pose coordinates"),
    ],
)
def test_register_checks_the_optional_fields(changes, error, match):
    with pytest.raises(error, match=match):
        register(_family(**changes))
    assert "odd" not in families()


@pytest.mark.parametrize("name", ["delta", "h4", "mcgill_smg", "peppermill", "planar_3rrp"])
def test_the_mode_read_back_is_the_mode_the_inverse_kinematics_was_given(name):
    """WorkingModes.of reads the mode from the configuration's geometry: for every mode that reaches
    the default pose, it returns that mode (and the default mode is among them)."""
    mechanism = load_mechanism(Path(__file__).resolve().parents[2] / "mechanisms" / f"{name}.toml")
    modes = mechanism.family_protocol.working_modes
    reached = []
    for mode in itertools.product(modes.values, repeat=len(modes.default)):
        options = modes.options(mode)
        if not mechanism.reachable(mechanism.default_pose[None], **options)[0]:
            continue
        found = modes.of(mechanism.configuration(**options))
        assert np.asarray(found).tolist() == list(mode), mode
        reached.append(mode)
    assert modes.default in reached and len(reached) > 1
