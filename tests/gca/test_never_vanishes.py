"""A factor that never vanishes is said so alike in the text, the LaTeX and the JSON (issue 21 item 4):
the planar 3-RRP's [hijg] (its constraint couples: the same lines at every pose) once printed as
"constraint: [hijg] = 0" in LaTeX."""

import numpy as np

from screwkit.interface.cli import main
from screwkit.interface.report import analyze
from screwkit.robots.catalog import load_mechanism


def test_planar_3rrp_never_vanishing_factor_everywhere(capsys):
    report = analyze("planar_3rrp")
    result = report.superbracket
    index = [str(c.factor) for c in result.conditions].index("[hijg]")
    # independently: the bracket of the four points has one magnitude on fresh reachable configurations
    _, sampler = load_mechanism("planar_3rrp").wrench_diagram()
    rng = np.random.default_rng(5)
    sizes = [abs(np.linalg.det(np.stack([sampler(rng)[x] for x in "hijg"]))) for _ in range(5)]
    assert np.ptp(sizes) <= 1e-9 * max(sizes) and min(sizes) > 0
    assert result.constant[index]
    assert result.to_dict()["conditions"][index]["never_vanishes"] is True
    rows = result.to_latex().splitlines()
    assert rows[2 + index].startswith(r"\text{never vanishes}:\quad [hijg] \neq 0 &\iff")
    assert not any("[hijg] = 0" in row for row in rows)
    assert "[hijg] never vanishes on this mechanism" in str(report)
    assert main(["analyze", "planar_3rrp", "--latex"]) == 0
    assert capsys.readouterr().out.rstrip("\n") == result.to_latex()
