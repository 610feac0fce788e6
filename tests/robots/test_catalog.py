"""The catalog: every [expected] fact of every shipped TOML, snapshot files, and their errors."""

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from screwkit.algebra import screw as S
from screwkit.algebra.screwvalue import Screw
from screwkit.core.singularity import classify
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import CatalogError
from screwkit.robots.catalog import list_mechanisms, load_mechanism, mechanism_from_mapping
from screwkit.robots.snapshot import load_snapshot, snapshot_from_mapping

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def check_fact(mechanism, fact):
    """Evaluate one [expected] fact; return (got, expected).

    Generic facts are evaluated here at the mechanism's default pose; family-specific facts by the
    functions of the ``tests/facts_<family>.py`` modules (``FACTS = {name: check(mechanism, fact)}``).
    """
    name, value = fact["fact"], fact["value"]
    graph = mechanism.twist_graph()
    analysis = wrench_analysis(graph)
    scale = analysis.length_scale
    if name == "platform_twist_order":
        return analysis.platform_twists.order, value
    if name == "constraint_wrenches_are_couples":
        basis = analysis.constraint_wrenches.basis
        return int(S.is_infinite_pitch(basis, length_scale=scale).sum()), value
    if name == "actuation_wrenches_are_lines":
        return int(S.is_zero_pitch(analysis.actuation_wrenches, length_scale=scale).sum()), value
    if name == "regular_at_default_pose":
        return classify(graph).labels == (), value
    if name == "subplatform_limbs":
        limbs = mechanism.configuration().subplatform_limbs
        return [[i + 1 for i in pair] for pair in limbs], value
    for module in FAMILY_FACTS:
        if name in module.FACTS:
            return module.FACTS[name](mechanism, fact)
    raise AssertionError(f"{mechanism.source}: no check for fact {name!r}")


def _family_fact_modules():
    import importlib
    import pkgutil

    here = Path(__file__).resolve().parents[1]
    return [importlib.import_module(f"tests.{info.name}") for info in pkgutil.iter_modules([str(here)])
            if info.name.startswith("facts_")]


FAMILY_FACTS = _family_fact_modules()


FACTS = [
    pytest.param(name, index, id=f"{name}-{fact['fact']}")
    for name in list_mechanisms()
    for index, fact in enumerate(load_mechanism(name).expected)
]


@pytest.mark.parametrize(("name", "index"), FACTS)
def test_expected_fact(name, index):
    mechanism = load_mechanism(name)
    got, expected = check_fact(mechanism, mechanism.expected[index])
    assert got == expected, f"{name}: {mechanism.expected[index]['source']}"


@pytest.mark.parametrize("name", list_mechanisms())
def test_every_entry_documents_its_parameters(name):
    mechanism = load_mechanism(name)
    assert mechanism.sources and mechanism.expected
    for key, entry in mechanism.parameter_sources.items():
        assert entry["unit"] and entry["source"], key


@pytest.mark.parametrize("name", list_mechanisms())
def test_default_pose_lies_in_the_workspace(name):
    mechanism = load_mechanism(name)
    for coordinate, value in zip(mechanism.pose_names, mechanism.default_pose, strict=True):
        low, high = mechanism.workspace[coordinate]
        assert low <= value <= high


@pytest.mark.parametrize("name", sorted(list_mechanisms()))
def test_stated_workspace_box_against_the_inverse_kinematics(name):
    # [workspace] reachable_fraction (default 1) is the share of the box the IK reaches: a box said to
    # be reachable is reachable at its corners and at random poses, a bounding box reaches its stated
    # share of 40 000 uniform draws (binomial sigma <= 0.0025: 0.01 is four of them)
    mechanism = load_mechanism(name)
    low, high = np.array([mechanism.workspace[c] for c in mechanism.pose_names]).T
    draws = np.random.default_rng(11).uniform(low, high, size=(40_000, len(low)))
    if mechanism.reachable_fraction == 1.0:
        corners = np.array(np.meshgrid(*zip(low, high, strict=True), indexing="ij")).reshape(len(low), -1).T
        mechanism.configuration(np.concatenate([corners, draws[:5000]]))  # raises if any is out of reach
        return
    from screwkit.exceptions import UnreachablePoseError
    from screwkit.robots.families.four_limb.kinematics import reachable

    ok = reachable(mechanism.parameters, draws)
    assert abs(ok.mean() - mechanism.reachable_fraction) <= 0.01, ok.mean()
    mechanism.configuration(draws[ok][:5000])  # the IK agrees on the reachable ones ...
    for pose in draws[~ok][:20]:  # ... and refuses the others
        with pytest.raises(UnreachablePoseError, match="out of reach"):
            mechanism.configuration(pose)
    assert mechanism.random_poses(np.random.default_rng(2), 500).shape == (500, len(low))


@pytest.mark.parametrize("name", ["v4", "planar_3rrp"])
def test_reachable_agrees_with_the_inverse_kinematics_pose_by_pose(name):
    # the family's vectorised test (four-limb) and the halving route (planar 3-RRP) against one IK
    # call per pose, on draws from a box twice the workspace's size (so both outcomes occur)
    from screwkit.exceptions import UnreachablePoseError

    mechanism = load_mechanism(name)
    low, high = np.array([mechanism.workspace[c] for c in mechanism.pose_names]).T
    middle, half = (low + high) / 2, (high - low)
    draws = np.random.default_rng(5).uniform(middle - half, middle + half, size=(60, len(low)))
    expected = []
    for pose in draws:
        try:
            mechanism.configuration(pose)
            expected.append(True)
        except UnreachablePoseError:
            expected.append(False)
    assert 0 < sum(expected) < len(expected)
    assert mechanism.reachable(draws).tolist() == expected
    assert mechanism.reachable(draws[:0]).shape == (0,)


@pytest.mark.parametrize("width", [20.0, 100.0, 400.0])
def test_h4_results_do_not_depend_on_the_chosen_parallelogram_width(width, rng):
    # the rod spacing d is our choice (neither paper gives it): orders and labels must not move
    h4 = load_mechanism("h4")
    changed = dataclasses.replace(h4, parameters=dataclasses.replace(h4.parameters, parallelogram_width=width))
    for pose in ([0.0, 0.0, -750.0, 0.0], [120.0, -80.0, -700.0, 0.6]):
        reference, report = classify(h4.twist_graph(pose)), classify(changed.twist_graph(pose))
        assert report.labels == reference.labels
        assert (report.constraint_order, report.global_order) == (reference.constraint_order, reference.global_order)
        # the actuation wrenches are the same lines (they lie in the parallelogram planes)
        for a, b in zip(report.analysis.actuation_wrenches, reference.analysis.actuation_wrenches, strict=True):
            assert Screw(a).is_equivalent(Screw(b))


def test_snapshot_example_planar_3rpr():
    graph = load_snapshot(EXAMPLES / "planar_3rpr.toml")
    report = classify(graph)
    assert report.labels == () and report.dof == 3 and report.constraint_order == 3
    # the three actuation wrenches are the leg lines (zero pitch, along the prismatic directions)
    for limb in report.analysis.limbs:
        direction = graph.edges[next((u, v, k) for u, v, k in graph.edges(keys=True) if k == limb.actuated_joint)]
        leg = direction["joint"].screws[0, 3:]
        assert np.linalg.norm(np.cross(limb.actuation_wrench[:3], leg)) < 1e-9


# errors ------------------------------------------------------------------------------------------
def valid_snapshot():
    return {
        "mechanism": {"kind": "snapshot", "name": "slider", "base": "B", "platform": "E"},
        "joints": [{"name": "P1", "type": "P", "parent": "B", "child": "E", "direction": [1.0, 0.0, 0.0]}],
    }


def snapshot_with(**changes):
    data = valid_snapshot()
    data["joints"][0].update(changes)
    return data


@pytest.mark.parametrize(
    ("data", "message"),
    [
        ({}, r"f\.toml: \[mechanism\]: expected a table \[mechanism\], got nothing"),
        ({"mechanism": {"kind": "family"}}, r"field `kind`: expected 'snapshot', got 'family'"),
        ({"mechanism": {**valid_snapshot()["mechanism"], "dof": 9}, "joints": valid_snapshot()["joints"]},
         r"field `dof`: expected an integer in 0\.\.6, got 9"),
        ({"mechanism": valid_snapshot()["mechanism"]}, r"expected at least one \[\[joints\]\] table"),
        (snapshot_with(type="Q"), r"joint 'P1': field `type`: expected one of \['C', 'H', 'P', 'Pa', 'R', 'S', 'U'\], got 'Q'"),
        (snapshot_with(direction=[1.0, 0.0]), r"joint 'P1': field `direction`: expected a list of 3 numbers"),
        (snapshot_with(direction=["1", 0.0, 0.0]), r"joint 'P1': field `direction`: expected a finite number, got '1'"),
        (snapshot_with(direction=[0.0, 0.0, 0.0]), r"joint 'P1': Expected `direction` to be a non-zero direction"),
        (snapshot_with(actuated="yes"), r"joint 'P1': field `actuated`: expected true or false, got 'yes'"),
        (snapshot_with(axis=[0.0, 0.0, 1.0]), r"joint 'P1' \(P joint\): unknown field `axis`"),
        (snapshot_with(type="R"), r"joint 'P1' \(R joint\): unknown field `direction`"),
        ({**valid_snapshot(), "joints": [{"name": "S1", "type": "S", "parent": "B", "child": "E"}]},
         r"joint 'S1': field `center`: missing"),
        ({**valid_snapshot(), "joints": [{"name": "S1", "type": "S", "parent": "B", "child": "E",
                                          "center": [0.0, 0.0, 0.0], "actuated": True}]},
         r"joint 'S1': field `actuated`: a S joint has several freedoms"),
        (snapshot_with(child="X"), r"f\.toml: Expected every link connected to the base 'B', got unconnected links \['E'\]"),
        ({**valid_snapshot(), "joints": [valid_snapshot()["joints"][0], valid_snapshot()["joints"][0]]},
         r"f\.toml: Duplicate joint name 'P1'"),
        ({**valid_snapshot(), "joints": [{"type": "P"}]}, r"\[\[joints\]\] #1: field `name`: expected a non-empty string"),
    ],
)
def test_snapshot_errors_name_file_joint_and_field(data, message):
    with pytest.raises(CatalogError, match=message):
        snapshot_from_mapping(data, source="f.toml")


def catalog_entry():
    return {
        "mechanism": {"kind": "family", "name": "H", "family": "four_limb", "length_unit": "mm"},
        "parameters": {key: dict(entry) for key, entry in load_mechanism("h4").parameter_sources.items()},
        "pose": {"x": 0.0, "y": 0.0, "z": -750.0, "phi_deg": 0.0},
        "workspace": {"x": [-1.0, 1.0], "y": [-1.0, 1.0], "z": [-800.0, -700.0], "phi_deg": [-1.0, 1.0]},
    }


def test_catalog_entry_round_trip():
    assert mechanism_from_mapping(catalog_entry(), source="c.toml").default_pose[2] == -750.0


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda d: d["mechanism"].update(family="six_limb"), r"c\.toml: \[mechanism\]: field `family`: expected one of \[[^]]*'four_limb'[^]]*\], got 'six_limb'"),
        (lambda d: d["mechanism"].update(length_unit=3), r"\[mechanism\]: field `length_unit`: expected one of \[.km., .m., .*\], got 3"),
        (lambda d: d["mechanism"].update(sources="paper"), r"field `sources`: expected a list of strings"),
        (lambda d: d["parameters"].update(rod_length=800.0), r"\[parameters\.rod_length\]: expected a table with `value`, `unit` and `source`"),
        (lambda d: d["parameters"]["rod_length"].pop("source"), r"\[parameters\.rod_length\]: field `source`: expected a non-empty string"),
        (lambda d: d["parameters"]["rod_length"].update(typo=1), r"\[parameters\.rod_length\]: unknown field `typo`"),
        (lambda d: d["parameters"]["alpha"].update(value="zero"), r"\[parameters\.alpha\]: field `value`: expected a finite number, got 'zero'"),
        (lambda d: d["parameters"]["rod_length"].update(value=-800.0), r"c\.toml: \[parameters\].*rod_length"),
        (lambda d: d["pose"].pop("phi_deg"), r"\[pose\]: field `phi_deg`: missing"),
        (lambda d: d["workspace"].update(z=[-700.0, -800.0]), r"\[workspace\]: field `z`: expected low < high"),
        (lambda d: d.update(expected=[{"fact": "x", "value": 1}]), r"\[\[expected\]\] #1: field `source`: expected a non-empty string"),
        (lambda d: d.update(expected=[{"fact": "x", "source": "s"}]), r"\[\[expected\]\] #1: field `value`: missing"),
    ],
)
def test_catalog_errors_name_file_and_field(change, message):
    data = catalog_entry()
    change(data)
    with pytest.raises(CatalogError, match=message):
        mechanism_from_mapping(data, source="c.toml")


def test_error_malformed_toml(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[mechanism\nname = 1\n")
    with pytest.raises(CatalogError, match=r"bad\.toml: not valid TOML"):
        load_snapshot(path)


def test_error_unknown_mechanism():
    with pytest.raises(CatalogError, match=r"unknown mechanism 'h5': expected one of \[[^]]*'h4'[^]]*\] or a path"):
        load_mechanism("h5")
