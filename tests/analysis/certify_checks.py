"""Checks shared by the certification tests (tests/analysis/test_certify_*.py): a catalog mechanism
with its lengths in metres, the facts two certificates of one region in two length units must share,
and the zeros of an independent |sin| along a line."""

from __future__ import annotations

import numpy as np

from screwkit.robots.catalog import load_toml, mechanism_from_mapping


def in_metres(mechanism):
    """``mechanism`` (a catalog entry in mm) with every length, lists of points included, in metres."""
    data = load_toml(mechanism.source)
    data["mechanism"]["length_unit"] = "m"
    for entry in data["parameters"].values():
        if entry["unit"] == "mm":
            entry["value"] = (np.asarray(entry["value"], dtype=float) / 1000.0).tolist()
            entry["unit"] = "m"
    for key in ("x", "y", "z"):
        data["pose"][key] /= 1000.0
        data["workspace"][key] = [v / 1000.0 for v in data["workspace"][key]]
    data.pop("expected", None)
    return mechanism_from_mapping(data, source=f"{mechanism.name} in metres")


def assert_same_facts(in_mm, in_m, names=("x", "y")):
    """Rounding may split a box in one unit that the other proves free at once (the pavings then
    differ), but the facts agree: no witness of one lies in a free box of the other, the same singular
    sets are met, and the free volumes differ by less than what either leaves singular or undecided."""
    for mine, mine_scale, other, other_scale in ((in_mm, 1.0, in_m, 1e3), (in_m, 1e3, in_mm, 1.0)):
        for box in mine.boxes:
            if box.witness is not None:
                pose = {n: box.witness.pose[n] * mine_scale for n in names}
                assert not any(
                    b.status == "free"
                    and all(b.bounds[n][0] * other_scale <= pose[n] <= b.bounds[n][1] * other_scale for n in names)
                    for b in other.boxes
                )
    labels = [{b.witness.label for b in c.boxes if b.witness is not None} for c in (in_mm, in_m)]
    assert labels[0] == labels[1]
    margin = sum(c.fractions[k] for c in (in_mm, in_m) for k in ("singular", "undecided"))
    assert abs(in_mm.fractions["free"] - in_m.fractions["free"]) <= margin


def zeros_along(function, points):
    """The zeros of a V-shaped ``function >= 0`` (an |sin| between two couples) along the polyline
    ``points (m, n)``: each sampled local minimum below 0.05 refined by 50 ternary-search steps, kept
    when below 1e-6 (a minimum that is no zero is dropped). ``function`` returns None out of reach."""
    values = np.array([9.0 if (v := function(p)) is None else v for p in points])
    found = []
    for k in np.flatnonzero((values[1:-1] < values[:-2]) & (values[1:-1] < values[2:]) & (values[1:-1] < 0.05)):
        low, high = points[k], points[k + 2]
        for _ in range(50):
            m1, m2 = low + (high - low) / 3, high - (high - low) / 3
            if function(m1) < function(m2):
                high = m2
            else:
                low = m1
        zero = (low + high) / 2
        if function(zero) < 1e-6:
            found.append(zero)
    return found
