"""Maps show their slice's singular sets (issue 22, item 1): loci found between the samples, in the
API, the JSON, the PNG and the CLI's text; a slice inside a singular set says so."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis.workspace import grid_map
from screwkit.interface.cli import main
from tests.four_limb_reference import QUATTRO, eq7_actuation, geometry

QUATTRO_M = sk.load_mechanism("quattro")
SLICE = {"x": ("x", -400, 400, 50), "y": ("y", -400, 400, 50)}


def test_quattro_map_shows_the_y_zero_constraint_curve_no_sample_hits():
    # 50 values per axis put no sample on y = 0 (the catalog's constraint_singular_poses: the plane
    # y = 0 at phi = 0, by the mirror symmetry y -> -y): every sample reads regular, the loci do not
    m = grid_map(QUATTRO_M, "verdict", fixed={"z": -750, "phi": 0}, angles="deg", **SLICE)
    assert np.all(m.values == 0)
    (locus,) = [locus for locus in m.loci if locus.kind != "reach"]
    assert locus.kind == "constraint" and locus.factor
    assert np.all(np.abs(locus.points[:, 1]) < 1e-6)
    assert locus.points[:, 0].min() == -400 and locus.points[:, 0].max() == 400
    saved = m.to_dict()["loci"]
    assert {"kind", "factor", "points"} <= set(saved[0]) and saved[0]["kind"] == "constraint"


def test_quattro_map_at_phi_90_shows_the_actuation_curve():
    # at phi = 90 deg every sample reads regular; the actuation loci found between them make paper
    # 002's Eq. (7), evaluated on an independent model, vanish
    m = grid_map(QUATTRO_M, "verdict", fixed={"z": -750, "phi": 90}, angles="deg", **SLICE)
    kinds = {locus.kind for locus in m.loci}
    assert {"constraint", "actuation"} <= kinds
    actuation = next(locus for locus in m.loci if locus.kind == "actuation")
    for x, y in actuation.points[:: max(1, len(actuation.points) // 5)]:
        value = eq7_actuation(geometry(QUATTRO, [x, y, -750, math.pi / 2]))
        scale = abs(eq7_actuation(geometry(QUATTRO, [x + 30, y + 30, -750, math.pi / 2])))
        assert abs(value) < 1e-6 * scale
    assert np.all(m.values == 0)  # every sample reads regular: the loci are between them


def test_cli_map_never_says_regular_100_over_a_singular_curve(tmp_path, capsys):
    out = tmp_path / "m.json"
    argv = ["map", "quattro", "--quantity", "verdict", "--x", "-400", "400", "--y", "-400", "400",
            "--z", "-750", "--phi", "0", "--out", str(out), "--no-progress"]
    assert main(argv) == 0
    printed = capsys.readouterr().out
    assert "regular 100" not in printed
    assert "constraint singularity" in printed and "read regular, but the slice holds" in printed
    saved = json.loads(out.read_text())
    assert [locus["kind"] for locus in saved["loci"]] == ["constraint"]


def test_slice_inside_a_singular_set_says_so(capsys, tmp_path):
    m = grid_map(QUATTRO_M, "verdict", x=("x", -300, 300, 7), y=("z", -850, -650, 5),
                 fixed={"y": 0, "phi": 0}, angles="deg")
    assert m.inside == ("constraint",)
    argv = ["map", "quattro", "--quantity", "verdict", "--x", "-300", "300", "7", "--z", "-850", "-650", "5",
            "--y", "0", "--phi", "0", "--out", str(tmp_path / "m.json"), "--no-progress"]
    assert main(argv) == 0
    assert "the whole slice lies inside the constraint singular set" in capsys.readouterr().out


def test_png_draws_the_loci(tmp_path):
    pytest.importorskip("matplotlib")
    from screwkit.interface.plot import plot_verdicts

    m = grid_map(QUATTRO_M, "verdict", fixed={"z": -750, "phi": 0}, angles="deg",
                 x=("x", -400, 400, 12), y=("y", -400, 400, 12))
    ax = plot_verdicts(m, loci=m.loci)
    assert any("constraint locus" in t.get_text() for t in ax.get_legend().get_texts())
    from screwkit.interface.plot import save_map_png

    assert save_map_png(m, tmp_path / "m.png").stat().st_size > 0


def test_loci_can_be_left_out_and_the_flag_is_checked():
    m = grid_map(QUATTRO_M, "verdict", fixed={"z": -750, "phi": 0}, angles="deg", loci=False,
                 x=("x", -400, 400, 4), y=("y", -400, 400, 4))
    assert m.loci == () and m.to_dict()["loci"] == []
    with pytest.raises(sk.ScrewkitTypeError, match="`loci` to be True or False"):
        grid_map(QUATTRO_M, "verdict", loci="yes")


def test_path_reports_every_crossing():
    check = sk.check_path(QUATTRO_M, {"x": -300, "y": -300, "z": -750, "phi": 90},
                          {"x": 300, "y": 300, "z": -750, "phi": 90}, angles="deg")
    assert [c.kind for c in check.crossings] == ["actuation", "constraint", "actuation"]
    assert check.crossing is check.crossings[0]
    assert len(str(check).splitlines()) == 3


def test_loci_on_a_dask_local_cluster_are_the_in_process_loci():
    # the map's chunks (samples for the loci included) and every refinement step on an in-process
    # LocalCluster: the same values and the same loci, point for point, as the plain path
    distributed = pytest.importorskip("distributed")
    slice_ = {"x": ("x", -400, 400, 12), "y": ("y", -400, 400, 11), "fixed": {"z": -750, "phi": 90}}
    plain = grid_map(QUATTRO_M, "closeness", angles="deg", **slice_)
    alone = sk.loci(QUATTRO_M, angles="deg", **slice_)
    with (
        distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None)
        as cluster,
        distributed.Client(cluster) as client,
    ):
        remote = grid_map(QUATTRO_M, "closeness", angles="deg", chunk=25, client=client, **slice_)
        remote_alone = sk.loci(QUATTRO_M, angles="deg", client=client, **slice_)
    assert {locus.kind for locus in plain.loci} >= {"constraint", "actuation"}
    np.testing.assert_array_equal(remote.values, plain.values)
    for found in (remote.loci, alone, remote_alone):
        assert [(lo.kind, lo.factor) for lo in found] == [(lo.kind, lo.factor) for lo in plain.loci]
        for mine, theirs in zip(found, plain.loci, strict=True):
            np.testing.assert_array_equal(mine.points, theirs.points)
    with pytest.raises(sk.ScrewkitTypeError, match="`client`"):
        sk.loci(QUATTRO_M, angles="deg", client=object(), **slice_)
