"""The Python API's own inputs (issue 24): every public entry point refuses what it cannot take at
its boundary, with a screwkit error naming the argument, the expected and the got. Each case below
failed on the code before issue 24: a numpy/networkx/Python error, a message about something else
(None read as NaN, a snapshot's `kind` reported as an unknown field), or a silent acceptance
(strings and booleans read as numbers, an actuated virtual joint) -- all but the last case, the
snapshot loader's own `kind` message, kept as the reference the catalog loader now matches."""

import numpy as np
import pytest

import screwkit as sk
from screwkit.exceptions import (
    CatalogError,
    ScrewkitError,
    ScrewkitTypeError,
    ScrewkitValueError,
    TwistGraphError,
)
from screwkit.gca.brackets import BracketPolynomial
from screwkit.gca.dotted import DottedSum
from screwkit.graphs.joints import Joint
from screwkit.robots.snapshot import snapshot_from_mapping
from tests.test_bad_inputs import SNAPSHOT, changed

_R = sk.revolute("R", [0, 0, 1], [0, 0, 0], actuated=True)
_G = sk.twist_graph("B", "E", [("B", "E", _R)])
_LINE = [0, 0, 1.0, 0, 0, 0]


def _table(batch, actuated=True, kind="R"):
    return sk.JointTable.from_rows("B", "E", [("B", "E", "R", kind, np.zeros((*batch, 1, 6)) + _LINE, actuated)])


CASES = [
    # numbers are numbers: None, strings, booleans, complex numbers are named, not read as NaN or 1.0
    (lambda: sk.Screw(None), ScrewkitTypeError, r"^Expected `coords` to be an array of numbers, got None\.$"),
    (lambda: sk.ScrewSystem.span(None), ScrewkitTypeError, r"^Expected `screws` to be an array of numbers, got None\.$"),
    (lambda: sk.Screw(["1", "0", "0", "0", "0", "0"]), ScrewkitTypeError, r"Expected `coords` to be an array of real numbers, got strings: \['1', '0'"),
    (lambda: sk.Screw([True, False, False, False, False, False]), ScrewkitTypeError, r"Expected `coords` to be an array of real numbers, got booleans"),
    (lambda: sk.Screw([1, 0, 0, 0, 0, True]), ScrewkitTypeError, r"Expected `coords` to be an array of real numbers, got bool True at flat index 5"),
    (lambda: sk.Screw([1, 0, 0, 0, 0, None]), ScrewkitTypeError, r"got None at flat index 5"),
    (lambda: sk.Screw([1j, 0, 0, 0, 0, 0]), ScrewkitTypeError, r"Expected `coords` to be an array of real numbers, got complex numbers"),
    (lambda: sk.Screw(np.ones(6, dtype=bool)), ScrewkitTypeError, r"got booleans"),
    (lambda: sk.ScrewSystem.span(np.eye(6, dtype=bool)), ScrewkitTypeError, r"Expected `screws` to be an array of real numbers, got booleans"),
    (lambda: sk.revolute("R", None, [0, 0, 0]), ScrewkitTypeError, r"Expected `direction` to be an array of numbers, got None"),
    (lambda: sk.revolute("R", [0, 0, 1], [0, 0, "1"]), ScrewkitTypeError, r"Expected `point` to be an array of real numbers, got strings"),
    (lambda: sk.helical("H", [0, 0, 1], [0, 0, 0], True), ScrewkitTypeError, r"Expected `pitch` to be an array of numbers, got the boolean True"),
    (lambda: sk.join(None, [0, 0, 0, 1]), ScrewkitTypeError, r"Expected `p` to be an array of numbers, got None"),
    (lambda: sk.analyze("h4", [True, 0, -750, 0]), ScrewkitTypeError, r"Expected `pose` to be an array of real numbers, got bool True at flat index 0"),
    (lambda: sk.load_mechanism("h4").at(["0", "0", "-750", "0"]), ScrewkitTypeError, r"Expected `poses` to be an array of real numbers, got strings"),
    (lambda: sk.classify_poses(_G, {"R": np.ones((2, 1, 6), dtype=bool)}), ScrewkitTypeError, r"Expected `screws\['R'\]` to be an array of real numbers, got booleans"),
    (lambda: sk.JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[["0", "0", "1", "0", "0", "0"]]], True)]), ScrewkitTypeError, r"Expected `screws of joint 'R'` to be an array of real numbers, got strings"),
    (lambda: Joint.from_dict({"name": "R", "type": "R", "screws": [["0", "0", "1", "0", "0", "0"]]}), ScrewkitValueError, r"Joint 'R': expected numeric screws"),
    (lambda: Joint.from_dict({"name": "R", "type": "R", "screws": [_LINE], "actuated": "no"}), ScrewkitTypeError, r"Joint 'R': expected `actuated` to be True or False, got 'no'"),
    (lambda: Joint.from_dict(5), ScrewkitTypeError, r"Expected `data` to be a dict of joint fields, got int"),
    # link names: hashable, not None, not a boolean, not NaN (networkx's own errors do not leak)
    (lambda: sk.twist_graph("B", ["E"], [("B", ["E"], _R)]), TwistGraphError, r"Expected the platform link to be a hashable link name .*got list \['E'\]"),
    (lambda: sk.twist_graph("B", None, [("B", None, _R)]), TwistGraphError, r"Expected the platform link to be a hashable link name .*got NoneType None"),
    (lambda: sk.twist_graph("B", "E", [("B", "E", _R), ("E", {"x": 1}, sk.revolute("R2", [0, 0, 1], [1, 0, 0]))]), TwistGraphError, r"Expected the child link of joint 'R2' to be a hashable link name .*got dict"),
    (lambda: sk.twist_graph("B", "E", [(True, "E", _R)]), TwistGraphError, r"Expected the parent link of joint 'R' to be a hashable link name .*other than None, a boolean or NaN, got bool True"),
    (lambda: sk.twist_graph("B", "E", 5), TwistGraphError, r"Expected `joints` to be an iterable of \(parent, child, Joint\) triples, got int"),
    (lambda: sk.classify(_with_base(["B"])), TwistGraphError, r"Expected graph attribute 'base' to be a hashable link name .*got list"),
    (lambda: sk.JointTable.from_rows("B", None, [("B", None, "R", "R", [[_LINE]], True)]), TwistGraphError, r"Expected the table's platform link to be a hashable link name .*got NoneType None"),
    (lambda: sk.JointTable.from_rows("B", "E", [("B", ["E"], "R", "R", [[_LINE]], True)]), TwistGraphError, r"Expected the child link of joint 'R' to be a hashable link name .*got list"),
    (lambda: sk.JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[_LINE]], "yes")]), ScrewkitTypeError, r"Joint 'R': expected `actuated` to be True or False, got 'yes'"),
    (lambda: sk.JointTable.from_rows("B", "E", [("B", "E", "R", "X", [[_LINE]], True)]), ScrewkitValueError, r"Joint 'R': expected `type` to be one of \[.*\], got 'X'"),
    (lambda: sk.JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[_LINE]], True), ("B", "E", "R", "R", [[_LINE]], False)]), ScrewkitValueError, r"Duplicate joint name 'R'"),
    (lambda: sk.JointTable.from_rows("B", "E", [("B", "E", "R")]), ScrewkitTypeError, r"Expected `rows` of \(parent, child, name, type, screws, actuated\), got \('B', 'E', 'R'\)"),
    # empty batches: refused by the table, as the posed path refuses them
    (lambda: sk.classify_poses(_G, {"R": np.zeros((0, 1, 6))}), ScrewkitValueError, r"^Expected `screws` to hold at least one configuration, got batch shape \(0,\)\.$"),
    (lambda: sk.classify_poses(_G, {"R": np.zeros((2, 0, 1, 6))}), ScrewkitValueError, r"got batch shape \(2, 0\)"),
    (lambda: sk.classify_table(_table((0,))), ScrewkitValueError, r"Expected `screws` to hold at least one configuration"),
    (lambda: sk.analyze_table(_table((0,))), ScrewkitValueError, r"Expected `screws` to hold at least one configuration"),
    # virtual joints: never actuated, and `virtual` exactly for the virtual types
    (lambda: Joint("V", "vR", [_LINE], actuated=True, virtual=True), ScrewkitValueError, r"Joint 'V': expected a virtual joint .* not to be actuated, got actuated = True"),
    (lambda: Joint("V", "vR", [_LINE]), ScrewkitValueError, r"Joint 'V': expected `virtual` = True exactly for the virtual types vR, vP, vH, got type 'vR' with virtual = False"),
    (lambda: Joint("V", "R", [_LINE], virtual=True), ScrewkitValueError, r"got type 'R' with virtual = True"),
    (lambda: sk.classify_table(_table((2,), kind="vR")), ScrewkitValueError, r"Joint 'R': expected an actuated joint to be a one-freedom joint that is not virtual, got a vR joint"),
    # the bracket-polynomial parser: screwkit errors, not ZeroDivisionError or Python's digit limit
    (lambda: BracketPolynomial.parse("1/0 [abcd]"), ScrewkitValueError, r"Expected `text` to hold coefficients with non-zero denominators, got '1/0'"),
    (lambda: DottedSum.parse("[abcd] - 3/0 [abce]"), ScrewkitValueError, r"non-zero denominators, got '3/0'"),
    (lambda: BracketPolynomial.parse("1" * 5000 + " [abcd]"), ScrewkitValueError, r"Expected `text` to hold coefficients of at most 1000 digits, got one of 5000 digits"),
    (lambda: DottedSum.parse("[abcd] + 1/" + "7" * 5000 + " [abce]"), ScrewkitValueError, r"at most 1000 digits, got one of 5000 digits"),
    # a file's kind: refused with a message about `kind`, not about a field the other kind has
    (lambda: sk.load_mechanism(str(_snapshot_file("snapshoot"))), CatalogError, r"\[mechanism\]: field `kind`: expected 'family' \(a catalog entry\) or 'snapshot' \(a snapshot file\), got 'snapshoot'"),
    (lambda: sk.analyze(str(_snapshot_file("Snapshot"))), CatalogError, r"field `kind`: expected 'family' \(a catalog entry\) or 'snapshot' \(a snapshot file\), got 'Snapshot'"),
    (lambda: sk.load_mechanism(str(_snapshot_file("snapshot"))), CatalogError, r"field `kind`: expected 'family' here, got 'snapshot'; a snapshot file loads with load_snapshot"),
    (lambda: snapshot_from_mapping(changed(SNAPSHOT, lambda d: d["mechanism"].update(kind="family"))), CatalogError, r"field `kind`: expected 'snapshot', got 'family'"),
]


def _with_base(base):
    graph = _G.copy()
    graph.graph["base"] = base
    return graph


def _snapshot_file(kind):
    """The planar 3-RPR snapshot example with another `kind` (in a temporary directory)."""
    import tempfile
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "examples" / "planar_3rpr.toml").read_text()
    assert 'kind = "snapshot"' in text
    path = Path(tempfile.mkdtemp()) / "kinded.toml"
    path.write_text(text.replace('kind = "snapshot"', f'kind = "{kind}"'))
    return path


@pytest.mark.parametrize(("call", "error", "message"), CASES)
def test_the_api_refuses_at_its_boundary(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_every_case_is_a_screwkit_error():
    assert all(issubclass(error, ScrewkitError) for _, error, _ in CASES)


def test_link_names_may_be_strings_integers_and_tuples():
    """The documented policy (docs/errors.md): any hashable name but None, booleans and NaN."""
    for base, platform in (("B", "E"), (0, 1), (("a", 0), ("a", 1))):
        graph = sk.twist_graph(base, platform, [(base, platform, _R)])
        assert sk.classify(graph).verdict == "regular"


def test_algebra_kernels_answer_empty_batches_with_empty_results():
    """The other half of the empty-batch policy: kernels map over a batch, so an empty batch of
    screws has empty answers (the analyses refuse one, above)."""
    assert sk.Screw(np.zeros((0, 6))).shape == (0,)
    assert sk.ScrewSystem.span(np.zeros((0, 6))).order == 0
    assert sk.ScrewSystem.span([]).order == 0
