"""A fuzzer of catalog and snapshot files (issue 11): hypothesis mutates valid files (types, shapes,
magnitudes, keys, names, nesting), writes them as TOML text and loads and analyses them. The only
acceptable outcomes are a clean result (finite numbers, known labels) or a ScrewkitError whose message
names the file; never another exception, a NaN, or a hang (each example is small and bounded).

Derandomized (the same examples every run) with small examples: 1,000+ examples in all, a few seconds.
"""

import json
import math
import tomllib
from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from screwkit import analyze, classify
from screwkit.exceptions import ScrewkitError
from screwkit.robots.catalog import mechanism_from_mapping
from screwkit.robots.snapshot import snapshot_from_mapping
from screwkit.robots.toml_fields import load_toml
from tests.toml_text import toml_text

ROOT = Path(__file__).resolve().parents[1]
CATALOG = tomllib.loads((ROOT / "mechanisms" / "h4.toml").read_text())
SNAPSHOT = tomllib.loads((ROOT / "examples" / "planar_3rpr.toml").read_text())
FUZZ = settings(
    max_examples=600, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck), database=None
)

names = st.sampled_from(["name", "type", "value", "unit", "axis", "point", "dof", "kind", "x", "phi_deg", "A1", "a/b", "é", ""])
scalars = st.one_of(
    st.booleans(),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-170, 1e300, -1e300, 1e20, 5e-324, 800.0, 3]),
    st.text(st.characters(blacklist_categories=("Cs",)), max_size=6),
    st.sampled_from(["mm", "m", "deg", "rad", "-", "R", "P", "U", "S", "snapshot", "family", "four_limb"]),
)
values = st.recursive(
    scalars,
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(names, inner, max_size=3)),
    max_leaves=8,
)


def _paths(data, prefix=()):
    """Every path to a value in nested dicts and lists."""
    yield prefix
    if isinstance(data, dict):
        for key, value in data.items():
            yield from _paths(value, (*prefix, key))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            yield from _paths(value, (*prefix, index))


@st.composite
def mutated(draw, base):
    """``base`` with 1-3 mutations: a value replaced, a key deleted or added, a list resized, a
    number scaled by a huge or tiny factor, or a value nested deeply."""
    data = tomllib.loads(toml_text(base))  # a fresh copy
    for _ in range(draw(st.integers(1, 3))):
        paths = [p for p in _paths(data) if p]
        path = draw(st.sampled_from(paths))
        parent = data
        for key in path[:-1]:
            parent = parent[key]
        key = path[-1]
        action = draw(st.sampled_from(["replace", "delete", "add", "scale", "nest", "resize"]))
        if action == "replace":
            parent[key] = draw(values)
        elif action == "delete" and isinstance(parent, dict):
            del parent[key]
        elif action == "add" and isinstance(parent, dict):
            parent[draw(names)] = draw(values)
        elif action == "scale" and isinstance(parent[key], int | float) and not isinstance(parent[key], bool):
            parent[key] = parent[key] * draw(st.sampled_from([1e-200, 1e-9, -1.0, 1e9, 1e200]))
        elif action == "nest":
            parent[key] = [parent[key]] * 1 if draw(st.booleans()) else {"x": parent[key]}
        elif action == "resize" and isinstance(parent[key], list):
            parent[key] = parent[key][: draw(st.integers(0, 2))] + [parent[key][0]] * draw(st.integers(0, 2)) if parent[key] else []
    return data


def _clean(array):
    assert np.all(np.isfinite(np.asarray(array, dtype=float)))


def _accepts(load, data, tmp_path, analyse):
    """Write, load and analyse; return "ok" or "refused"; anything else fails the test."""
    path = tmp_path / "fuzz.toml"
    path.write_text(toml_text(data), encoding="utf-8")
    try:
        loaded = load(load_toml(path), source=str(path))
    except ScrewkitError as err:
        assert str(path) in str(err) and "\n" not in str(err).strip()
        return "refused"
    try:
        analyse(loaded)
    except ScrewkitError:
        return "refused"
    return "ok"


def _analyse_catalog(mechanism):
    posed = mechanism.at()
    verdict = str(posed.verdicts[0])
    assert verdict == "regular" or verdict.endswith("singularity")
    _clean(posed.closeness["constraint"])


def _analyse_snapshot(graph):
    report = classify(graph)
    assert report.verdict == "regular" or report.verdict.endswith("singularity")
    for value in report.closeness.values():
        assert math.isfinite(value)
    text = json.dumps(analyze(graph, superbracket=False).to_dict(), allow_nan=False)  # never a NaN
    assert "Infinity" not in text


@FUZZ
@given(data=mutated(CATALOG))
def test_mutated_catalog_files_load_cleanly_or_are_refused(tmp_path_factory, data):
    _accepts(mechanism_from_mapping, data, tmp_path_factory.mktemp("c"), _analyse_catalog)


@FUZZ
@given(data=mutated(SNAPSHOT))
def test_mutated_snapshot_files_load_cleanly_or_are_refused(tmp_path_factory, data):
    _accepts(snapshot_from_mapping, data, tmp_path_factory.mktemp("s"), _analyse_snapshot)
