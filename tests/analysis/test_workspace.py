"""Workspace maps, loci and path checks (screwkit.analysis.workspace) against the core and paper 002.

Expected values come from the core called directly (maps pointwise), from paper 002's Eq. (6) and
Eq. (7) computed in tests/robots/test_h4.py from the parallelograms' plane normals (independent of the
code under test), and from plain bisection in the test (tests/mechanisms.bisect_root).
"""

import json
import pathlib

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis import loci as LO
from screwkit.analysis import paths as PA
from screwkit.analysis import quantities as Q
from screwkit.analysis import roots as RT
from screwkit.analysis import workspace as W
from screwkit.interface.cli import main
from screwkit.papers.paper_004 import det_A_closed_form, transmission_indices
from screwkit.robots.catalog import mechanism_from_mapping
from screwkit.robots.families.four_limb.kinematics import reachable
from screwkit.robots.toml_fields import load_toml

from ..mechanisms import bisect_root
from ..robots.test_h4 import normals
from ..singular_surfaces import SCALE, conditions, surface_roots

H4 = sk.load_mechanism("h4")
#: A slice through the constraint and actuation surfaces and the reach edge (x = y = 300 mm).
SLICE = {"x": ("z", -1100.0, -450.0, 9), "y": ("phi", -90.0, 90.0, 7), "fixed": {"x": 300.0, "y": 300.0}}


def api(poses):
    """User units (degrees) to the API's (radians), H4 coordinates (x, y, z, phi)."""
    out = np.array(poses, dtype=float)
    out[..., 3] = np.radians(out[..., 3])
    return out


def grid_poses(m):
    names = H4.pose_names
    z, phi = np.meshgrid(m.x_values, m.y_values)
    out = np.empty((*z.shape, 4))
    for i, name in enumerate(names):
        out[..., i] = {"z": z, "phi": phi}.get(name, m.fixed.get(name))
    return out


# --- maps ----------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "quantity", ["verdict", "closeness", "closeness:actuation", "det_A", "det_B", "lti", "kappa", "zeta"]
)
def test_map_equals_the_core_pointwise(quantity):
    m = W.grid_map(H4, quantity, **SLICE, angles="deg")
    poses = api(grid_poses(m))
    expected_ok = reachable(H4.parameters, poses)
    assert 0 < expected_ok.sum() < expected_ok.size  # the slice reaches beyond the workspace
    np.testing.assert_array_equal(m.reachable, expected_ok)
    posed = H4.at(poses[expected_ok])
    core = {
        "verdict": posed.codes,
        "closeness": np.min([posed.closeness[k] for k in ("constraint", "actuation", "serial")], axis=0),
        "closeness:actuation": posed.closeness["actuation"],
        "det_A": posed.jacobians.det_A,
        "det_B": posed.jacobians.det_B,
        "lti": transmission_indices(posed.configuration).eta,
        "kappa": transmission_indices(posed.configuration).kappa,
        "zeta": transmission_indices(posed.configuration).zeta,
    }[quantity]
    if quantity in (
        "lti",
        "kappa",
        "zeta",
    ):  # the maps use the fused kernel (indices.transmission): equal to round-off
        np.testing.assert_allclose(m.values[expected_ok], core, rtol=1e-12, atol=1e-14)
        core = m.values[expected_ok]
    np.testing.assert_array_equal(m.values[expected_ok], core)
    if quantity == "verdict":
        assert m.values.dtype.kind == "i" and (m.values[~expected_ok] == -1).all()
    else:
        assert np.isnan(m.values[~expected_ok]).all()
    assert m.minimum == core.min() and m.maximum == core.max()
    low = api([m.argmin[n] for n in H4.pose_names])
    assert W.evaluate(H4, low[None], quantity)[0][0] == core.min()
    assert "z in [-1100, -450] mm (9 values)" in m.region and "phi in [-90, 90] deg" in m.region


def test_map_condition_values_change_sign_with_paper_002_eq_6():
    m = W.grid_map(
        H4, "condition:0", x=("z", -560, -470, 4), y=("phi", 60, 90, 4), fixed={"x": 300, "y": 300}, angles="deg")
    ok = m.reachable
    eq6, _ = conditions(api(grid_poses(m))[ok])
    assert (eq6 > 0).any() and (eq6 < 0).any()  # the slice crosses the constraint surface
    # the factor's vector form is Eq. (6) times a positive or a negative factor (its points are
    # normalised differently), never both
    product = np.sign(m.values[ok] * eq6)
    assert (product == product[0]).all() and product[0] != 0


def test_map_chunks_and_json_and_npz(tmp_path):
    whole = W.grid_map(H4, "closeness", **SLICE, angles="deg")
    chunked = W.grid_map(H4, "closeness", **SLICE, chunk=5, angles="deg")
    np.testing.assert_array_equal(whole.values, chunked.values)
    data = json.loads(whole.to_json())
    assert {"region", "minimum", "maximum", "argmin", "argmax", "values", "units"} <= set(data)
    assert data["units"] == {"x": "mm", "y": "mm", "z": "mm", "phi": "deg"}
    flat = [v for row in data["values"] for v in row]
    assert flat.count(None) == int((~whole.reachable).sum())
    saved = np.load(whole.save(tmp_path / "m.npz"))
    np.testing.assert_array_equal(saved["reachable"], whole.reachable)
    assert json.loads(str(saved["summary"]))["argmin"] == whole.argmin


def test_dask_local_cluster_gives_the_in_process_result():
    distributed = pytest.importorskip("distributed")
    plain = W.grid_map(H4, "verdict", **SLICE, chunk=10, angles="deg")
    with (
        distributed.LocalCluster(
            n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        remote = W.grid_map(H4, "verdict", **SLICE, chunk=10, client=client, angles="deg")
        closeness = W.grid_map(H4, "closeness", **SLICE, chunk=7, client=client, angles="deg")
        swept = W.sweep([H4, metres()], "lti", **SLICE, chunk=6, client=client, angles="deg")
    np.testing.assert_array_equal(remote.values, plain.values)
    for remote_map, plain_map in zip(swept, W.sweep([H4, metres()], "lti", **SLICE, angles="deg"), strict=True):
        np.testing.assert_array_equal(remote_map.values, plain_map.values)
        np.testing.assert_array_equal(remote_map.reachable, plain_map.reachable)
    np.testing.assert_array_equal(remote.reachable, plain.reachable)
    np.testing.assert_array_equal(closeness.values, W.grid_map(H4, "closeness", **SLICE, angles="deg").values)


def metres():
    """The H4 with every length in metres (lengths / 1000)."""
    data = load_toml(H4.source)
    data["mechanism"]["length_unit"] = "m"
    for entry in data["parameters"].values():
        if entry["unit"] == "mm":
            entry["value"] /= 1000.0
            entry["unit"] = "m"
    for key in ("x", "y", "z"):
        data["pose"][key] /= 1000.0
        data["workspace"][key] = [v / 1000.0 for v in data["workspace"][key]]
    return mechanism_from_mapping(data, source="h4 in metres")


def test_sweep_is_one_map_per_mechanism():
    maps = W.sweep([H4, sk.load_mechanism("quattro")], "det_A", x=("z", -900, -600, 3), y=("phi", -20, 20, 2), angles="deg")
    for m, mechanism in zip(maps, (H4, sk.load_mechanism("quattro")), strict=True):
        alone = W.grid_map(mechanism, "det_A", x=("z", -900, -600, 3), y=("phi", -20, 20, 2), angles="deg")
        np.testing.assert_array_equal(m.values, alone.values)
        assert m.mechanism == mechanism.name
    with pytest.raises(sk.ScrewkitTypeError, match="Expected `mechanisms` to be a non-empty sequence"):
        W.sweep([], "verdict", angles="deg")


def test_maps_and_crossings_do_not_depend_on_the_length_unit():
    h4_m = metres()
    mm = W.grid_map(H4, "closeness", **SLICE, angles="deg")
    metre_slice = {"x": ("z", -1.1, -0.45, 9), "y": SLICE["y"], "fixed": {"x": 0.3, "y": 0.3}}
    m = W.grid_map(h4_m, "closeness", **metre_slice, angles="deg")
    np.testing.assert_array_equal(m.reachable, mm.reachable)
    np.testing.assert_allclose(m.values[m.reachable], mm.values[mm.reachable], rtol=1e-7, atol=1e-12)
    np.testing.assert_array_equal(
        W.grid_map(h4_m, "verdict", **metre_slice, angles="deg").values, W.grid_map(H4, "verdict", **SLICE, angles="deg").values
    )
    start, end = {"x": 300, "y": 300, "z": -800, "phi": -80}, {"x": 300, "y": 300, "z": -800, "phi": 0}
    in_mm = PA.check_path(H4, start, end, samples=30, angles="deg")
    in_m = PA.check_path(
        h4_m, {**start, "x": 0.3, "y": 0.3, "z": -0.8}, {**end, "x": 0.3, "y": 0.3, "z": -0.8}, samples=30, angles="deg")
    assert in_mm.crossing.kind == "actuation"
    assert in_mm.crossing.kind == in_m.crossing.kind
    assert abs(in_mm.crossing.parameter - in_m.crossing.parameter) < 1e-9


# --- loci ----------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def slice_loci():
    return {locus.kind: locus for locus in LO.loci(H4, **SLICE, angles="deg")}


def test_loci_lie_on_paper_002_surfaces_and_the_verdict_changes_across(slice_loci):
    found = slice_loci
    assert {"constraint", "actuation", "serial"} <= set(found)
    grid = api(grid_poses(W.grid_map(H4, "verdict", **SLICE, angles="deg")))
    ok = reachable(H4.parameters, grid)
    scale = {
        k: np.abs(v).max() for k, v in zip(("constraint", "actuation"), conditions(grid[ok]), strict=True)
    }
    for kind, equation in (("constraint", 0), ("actuation", 1)):
        locus = found[kind]
        assert len(locus.points) >= 3
        poses = api(
            np.column_stack(
                [np.full(len(locus.points), 300.0), np.full(len(locus.points), 300.0), locus.points]
            )
        )
        values = conditions(poses)[equation]
        assert np.abs(values).max() < 1e-9 * scale[kind], kind  # on the surface (paper 002 Eq. 6 / 7)
        assert locus.closeness.max() < RT.ACCEPT
        bit = 1 << ("constraint", "actuation").index(kind)
        assert (H4.at(poses).codes & bit).all()
        # across: a step of 1e-4 of the workspace along z or phi flips the equation's sign, and the
        # core calls both sides regular
        flipped = np.zeros(len(poses), dtype=bool)
        for axis in (2, 3):
            step = np.zeros(4)
            step[axis] = 1e-4 * SCALE[axis]
            below, above = poses - step, poses + step
            both = reachable(H4.parameters, below) & reachable(H4.parameters, above)
            change = np.zeros(len(poses), dtype=bool)
            change[both] = np.sign(conditions(below[both])[equation]) != np.sign(
                conditions(above[both])[equation]
            )
            if change.any():
                assert (H4.at(below[change]).codes & bit == 0).all()
                assert (H4.at(above[change]).codes & bit == 0).all()
            flipped |= change
        assert flipped.all()
    assert found["constraint"].factor.count("[") == 1  # paper 002 Eq. (6): one bracket
    assert found["actuation"].factor.count("[") == 2  # Eq. (7): a product of two brackets
    assert found["serial"].factor is None


def vertical_parallelogram(poses, tolerance=1e-9):
    """Poses where some limb's parallelogram plane contains the vertical (n_i · z = 0)."""
    normal_z = normals(H4.configuration(poses))[..., 2]
    return (np.abs(normal_z) < tolerance).any(axis=-1)


#: Found by the loci: a pose where limb 1's parallelogram plane is vertical (n_1 · z ~ 1e-17).
VERTICAL_PLANE_POSE = np.array([300.0, 300.0, -473.8000726, np.radians(30.0)])


def test_the_loci_find_where_limb_1s_parallelogram_plane_is_vertical():
    assert vertical_parallelogram(VERTICAL_PLANE_POSE[None], 1e-6)[0]


def test_core_calls_the_vertical_parallelogram_pose_regular():
    # limb 1's own actuation force cannot meet R_I's axis there; its compound leg is analysed as a
    # whole (screwkit.core._compound_legs.compound_legs, tests/core/test_compound_legs.py)
    cfg = H4.configuration(VERTICAL_PLANE_POSE)
    assert abs(det_A_closed_form(cfg)) > 40 and abs(conditions(VERTICAL_PLANE_POSE)[1]) > 40
    assert (np.abs(cfg.h) > 200).all()
    assert H4.at(VERTICAL_PLANE_POSE[None]).codes[0] == 0


def test_surfaces_stack_slices_onto_paper_002_surfaces():
    found = {
        surface.kind: surface
        for surface in LO.surfaces(
            H4, x=("z", -1100, -450, 6), y=("phi", -90, 90, 4), z=("x", 250, 300, 2), fixed={"y": 300}, angles="deg")
    }
    assert {"constraint", "actuation"} <= set(found)
    for kind, equation in (("constraint", 0), ("actuation", 1)):
        surface = found[kind]
        assert surface.names == ("z", "phi", "x") and set(surface.points[:, 2]) == {250.0, 300.0}
        poses = api(
            np.column_stack(
                [surface.points[:, 2], np.full(len(surface.points), 300.0), surface.points[:, :2]]
            )
        )
        values = np.abs(conditions(poses)[equation])
        reference = np.abs(conditions(api([[275.0, 300.0, -800.0, 0.0]]))[equation]).max()
        assert values.max() < 1e-9 * reference, kind
    with pytest.raises(
        sk.ScrewkitValueError, match=r"Expected `fixed` not to set the region's axes, got \['x'\]"
    ):
        LO.surfaces(H4, fixed={"x": 0}, angles="deg")


def test_serial_locus_is_the_reach_edge(slice_loci):
    locus = slice_loci["serial"]
    poses = api(
        np.column_stack([np.full(len(locus.points), 300.0), np.full(len(locus.points), 300.0), locus.points])
    )
    assert reachable(H4.parameters, poses).all()
    outward = poses.copy()
    outward[:, 2] -= 1e-6  # 1 nm further down or up: the edge is within it on one side
    inward = poses.copy()
    inward[:, 2] += 1e-6
    assert (~reachable(H4.parameters, outward) | ~reachable(H4.parameters, inward)).all()


# --- paths ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("surface", ["constraint", "actuation"])
def test_path_across_a_surface_finds_the_bisected_root(rng, surface):
    roots = surface_roots(rng, surface, 6)
    equation = ("constraint", "actuation").index(surface)
    for root, direction in zip(roots.poses[:3], roots.directions[:3], strict=True):
        start = root - 0.013 * SCALE * direction
        end = root + 0.021 * SCALE * direction
        t_samples = np.linspace(0, 1, 40)
        samples = start + t_samples[:, None] * (end - start)
        assert reachable(H4.parameters, samples).all()
        assert (H4.at(samples).codes == 0).all()  # the labels at the samples miss the crossing

        def along(t, start=start, end=end):
            return float(conditions(start + t * (end - start))[equation])

        expected = bisect_root(along, 0.0, 1.0)
        check = PA.check_path(H4, start, end, samples=40, angles="rad")
        assert not check.singularity_free
        assert check.crossing.kind == surface
        assert abs(check.crossing.parameter - expected) < 1e-9
        assert check.crossing.closeness < RT.ACCEPT
        pose = np.array([check.crossing.pose[n] for n in H4.pose_names])
        np.testing.assert_allclose(pose, start + check.crossing.parameter * (end - start), rtol=1e-12)


def test_path_inside_the_catalog_box_is_singularity_free():
    start = {"x": -250.0, "y": -250.0, "z": -900.0, "phi": -40.0}
    end = {"x": 300.0, "y": 250.0, "z": -600.0, "phi": 40.0}
    dense = api(np.linspace([*start.values()], [*end.values()], 2000))
    eq6, eq7 = conditions(dense)  # independently: no sign change of Eq. (6) or (7) on the path
    assert (eq6 < 0).all() and (eq7 > 0).all() and reachable(H4.parameters, dense).all()
    check = PA.check_path(H4, start, end, samples=50, angles="deg")
    assert check.singularity_free and check.crossing is None
    assert check.start == start and check.end == end


def test_path_leaving_the_reach_reports_the_serial_edge():
    check = PA.check_path(H4, {"z": -750.0}, {"z": -5000.0}, samples=20, angles="deg")

    def inside(t):
        return 1.0 if reachable(H4.parameters, [0, 0, -750.0 - 4250.0 * t, 0])[()] else -1.0

    assert check.crossing.kind == "serial"
    assert abs(check.crossing.parameter - bisect_root(inside, 0.0, 1.0)) < 1e-12


# --- the command line ----------------------------------------------------------------------------


def test_cli_map_writes_json_and_npz(tmp_path, capsys):
    out = tmp_path / "map.json"
    argv = [
        "map",
        "h4",
        "--quantity",
        "closeness",
        "--z",
        "-1100",
        "-450",
        "--phi",
        "-90",
        "90",
        "--x",
        "300",
        "--y",
        "300",
        "--grid",
        "5",
        "--out",
        str(out),
    ]
    assert main(argv) == 0
    data = json.loads(out.read_text())
    assert data["quantity"] == "closeness" and len(data["values"]) == 5 and len(data["values"][0]) == 5
    assert data["argmin"]["x"] == 300 and "region" in data
    assert "minimum" in capsys.readouterr().out
    npz = tmp_path / "map.npz"
    assert main([*argv[:-1], str(npz)]) == 0
    assert np.load(npz)["values"].shape == (5, 5)
    assert (
        main(
            [
                "map",
                "h4",
                "--quantity",
                "verdict",
                "--z",
                "-900",
                "-600",
                "3",
                "--phi",
                "-10",
                "10",
                "2",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    assert np.array(json.loads(out.read_text())["values"]).shape == (2, 3)


def test_cli_path_json(capsys):
    argv = ["path", "h4", "--from", "300", "300", "-800", "-80", "--to", "300", "300", "-800", "0", "--json"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["singularity_free"] is False and data["crossing"]["kind"] == "actuation"
    assert data["crossing"]["pose"]["z"] == -800 and -80 < data["crossing"]["pose"]["phi"] < 0
    assert {"parameter", "pose", "kind", "factor", "closeness"} <= set(data["crossing"])
    assert main(["path", "h4", "--from", "0", "0", "-800", "0", "--to", "0", "0", "-700", "20"]) == 0
    assert "singularity-free" in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv, message",
    [
        (["map", "h4", "--quantity", "lti", "--z", "-900", "-600", "--out", "a.json"], "exactly two ranges"),
        (
            ["map", "h4", "--quantity", "bogus", "--z", "-900", "-600", "--phi", "0", "1", "--out", "a.json"],
            "--quantity",
        ),
        (
            ["map", "h4", "--quantity", "lti", "--z", "-900", "-600", "--phi", "0", "1", "--out", "a.txt"],
            ".npz, .json or .png",
        ),
        (
            ["map", "h4", "--quantity", "lti", "--z", "-900", "--phi", "0", "1", "2", "3", "--out", "a.json"],
            "--phi",
        ),
        (
            ["map", "nope", "--quantity", "lti", "--z", "-9", "-6", "--phi", "0", "1", "--out", "a.json"],
            "unknown mechanism",
        ),
        (
            ["map", "h4", "--quantity", "lti", "--z", "-9", "-6", "--theta", "0", "1", "--out", "a.json"],
            "--theta",
        ),
        (["path", "h4", "--from", "0", "0", "-800", "--to", "0", "0", "-700", "0"], "--from expects 4"),
        (
            ["path", "h4", "--from", "0", "0", "-800", "0", "--to", "0", "0", "-700", "0", "--samples", "1"],
            "--samples",
        ),
    ],
)
def test_cli_bad_arguments(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    assert message in capsys.readouterr().err


# --- errors ---------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"quantity": "speed"}, "Expected `quantity` to be one of"),
        ({"x": ("q", 0, 1, 3)}, "Expected `x`'s name among the pose coordinates"),
        ({"x": ("z", 0, 1)}, "Expected `x` to be (name, low, high, count)"),
        ({"x": ("z", 1, 0, 3)}, "Expected `x` low < high, got 1 and 0"),
        ({"x": ("z", 0, 1, 1)}, "Expected `x` count to be an integer in 2..1e+08, got 1"),
        ({"x": ("phi", 0, 1, 3)}, "Expected `x` and `y` over different coordinates"),
        ({"fixed": {"phi": 0}}, "Expected `fixed` not to set the map's axes, got ['phi']"),
        ({"fixed": {"w": 0}}, "Expected the keys of `fixed` among"),
        ({"fixed": {"x": float("nan")}}, "Expected `fixed['x']` to be finite"),
        ({"chunk": 0}, "Expected `chunk` to be a positive integer, got 0"),
        ({"angles": "grad"}, "Expected `angles` to be 'deg' or 'rad', got 'grad'"),
        ({"client": object()}, "Expected `client` to be a dask.distributed Client"),
        ({"quantity": "condition:7"}, "K in 0..1"),
    ],
)
def test_grid_map_errors(kwargs, message):
    arguments = {"quantity": "verdict", "x": ("z", -900, -600, 2), "y": ("phi", -10, 10, 2), "angles": "deg",
                 **kwargs}
    quantity = arguments.pop("quantity")
    with pytest.raises(sk.ScrewkitError) as info:
        W.grid_map(H4, quantity, **arguments)
    assert message in str(info.value)


def test_other_errors():
    with pytest.raises(sk.ScrewkitValueError, match="four-limb mechanism for quantity 'lti'"):
        W.grid_map(sk.load_mechanism("planar_3rrp"), "lti", x=("x", -1, 1, 2), y=("y", -1, 1, 2), angles="deg")
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected `samples` to be an integer in 2\.\.1e\+06, got 1\.$"):
        PA.check_path(H4, {}, {"z": -700}, samples=1, angles="deg")
    # 10^9 samples would be one 10^9-pose batch (a MemoryError): refused before any work
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected `samples` to be an integer in 2\.\.1e\+06, got 1000000000\.$"):
        PA.check_path(H4, {}, {"z": -700}, samples=10**9, angles="deg")
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected `start` to have shape \(4,\)"):
        PA.check_path(H4, [0, 0, -700], {"z": -700}, angles="deg")
    with pytest.raises(sk.ScrewkitTypeError, match="Expected `end\\['z'\\]` to be a number"):
        PA.check_path(H4, {}, {"z": "low"}, angles="deg")
    with pytest.raises(sk.ScrewkitTypeError, match="Expected `mode` to be None"):
        PA.check_path(H4, {}, {"z": -700}, mode="up", angles="deg")
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected `path` to end in \.npz, \.json or \.png"):
        W.grid_map(H4, "verdict", x=("z", -900, -600, 2), y=("phi", -10, 10, 2), angles="deg").save("m.csv")


def test_png_through_screwkit_plot(tmp_path):
    pytest.importorskip("matplotlib")
    plot = pytest.importorskip("screwkit.interface.plot")
    for quantity in ("verdict", "lti"):
        m = W.grid_map(H4, quantity, x=("z", -900, -600, 4), y=("phi", -30, 30, 3), angles="deg")
        written = plot.save_map_png(m, tmp_path / f"{quantity}.png")
        assert written == tmp_path / f"{quantity}.png" and written.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_png_without_the_plot_extra_says_what_to_install(tmp_path):
    # a map is data: it writes .npz and .json itself; a .png is drawn by screwkit.interface.plot
    # (the plot extra), which its refusal names, with what to install
    m = W.grid_map(H4, "verdict", x=("z", -900, -600, 2), y=("phi", -10, 10, 2), angles="deg")
    with pytest.raises(sk.ScrewkitValueError, match=r"plot\.save_map_png draws it \(pip install 'screwkit\[plot\]'\)"):
        m.save(tmp_path / "m.png")
    assert not (tmp_path / "m.png").exists()


def test_progress_line_on_request(capsys):
    W.grid_map(H4, "verdict", x=("z", -900, -600, 4), y=("phi", -10, 10, 3), chunk=5, progress=True, angles="deg")
    err = capsys.readouterr().err
    assert "12/12" in err.replace(" ", "")  # tqdm's bar or the plain line, both count the poses
    W.grid_map(H4, "verdict", x=("z", -900, -600, 4), y=("phi", -10, 10, 3), chunk=5, progress=False, angles="deg")
    assert capsys.readouterr().err == ""


def test_angles_are_radians_by_default_like_the_rest_of_the_api():
    # docs/architecture.md §3: the Python API takes radians; angles="deg" is the CLI's and the TOML files' unit
    in_degrees = W.grid_map(H4, "det_A", x=("z", -900, -600, 3), y=("phi", -30, 30, 3), angles="deg")
    in_radians = W.grid_map(H4, "det_A", x=("z", -900, -600, 3), y=("phi", -np.pi / 6, np.pi / 6, 3))
    np.testing.assert_allclose(in_radians.values, in_degrees.values, rtol=1e-12)
    np.testing.assert_allclose(in_radians.y_values, np.radians(in_degrees.y_values), rtol=1e-15)


@pytest.mark.parametrize("call", [
    lambda g: W.grid_map(g, "verdict"),
    lambda g: PA.check_path(g, {}, {}),
    lambda g: W.evaluate(g, [[0, 0, 0, 0]], "verdict"),
    lambda g: LO.loci(g, x=("z", -900, -600, 3), y=("phi", -0.5, 0.5, 3)),
])
def test_a_twist_graph_is_refused_with_a_pointer_to_its_mechanism(call):
    graph = H4.twist_graph()
    with pytest.raises(sk.ScrewkitTypeError, match=r"Expected `mechanism` to be a Mechanism .* got "
                                                   r"MultiDiGraph \(a twist graph is one configuration: "
                                                   r"screwkit.mechanism\(graph\) gives its motion"):
        call(graph)


def test_cli_verdict_map_names_its_codes(tmp_path, capsys):
    # a new user read "minimum 0 ... maximum 0" and integer codes with no key: the text now says which
    # verdicts were found and the JSON carries the codes' words (bits: constraint 1, actuation 2, serial 4)
    out = tmp_path / "verdicts.json"
    argv = ["map", "h4", "--quantity", "verdict", "--x", "300", "--y", "300", "--z", "-1100", "-450",
            "--phi", "-90", "90", "--grid", "9", "--out", str(out)]
    assert main(argv) == 0
    printed = capsys.readouterr().out
    saved = json.loads(out.read_text())
    assert saved["codes"]["0"] == "regular" and saved["codes"]["6"] == "actuation+serial"
    assert saved["codes"]["-1"] == "out of reach"
    codes = {v for row in saved["values"] for v in row if v is not None}
    if codes == {0}:  # every sample regular: the text must not say "regular 100 %" when loci lie between
        singular = [locus for locus in saved["loci"] if locus["kind"] != "reach"]
        assert bool(singular) == ("read regular, but the slice holds the singular loci" in printed)
        assert bool(singular) != ("regular 100.0%" in printed)
        if singular:
            return
    line = next(ln for ln in printed.splitlines() if "verdicts of the reachable poses" in ln)
    for code in codes:
        assert Q.verdict_name(code) in line
    assert sum(float(p.split()[-1].rstrip("%")) for p in line.split(": ", 1)[1].split(", ")) == pytest.approx(100, abs=0.2)


def test_condition_map_says_which_factor_it_shows(tmp_path, capsys):
    # a new user could not tell which factor `condition:1` was: the map, its JSON and the CLI say it
    # (the H4's factors of paper 002: [gikj], the constraint one, and the actuation product)
    shown = W.grid_map(H4, "condition:0", x=("z", -1000, -600, 3), y=("phi", -30, 30, 3), angles="deg")
    assert shown.meaning.startswith("constraint factor [gikj] (vector form ")
    assert json.loads(shown.to_json())["meaning"] == shown.meaning
    out = tmp_path / "c.json"
    argv = ["map", "h4", "--quantity", "condition:1", "--z", "-1000", "-600", "--phi", "-30", "30",
            "--grid", "3", "--out", str(out)]
    assert main(argv) == 0
    assert "  actuation factor [a b d ḟ][c g ḣ j] (vector form " in capsys.readouterr().out
    assert W.grid_map(H4, "lti", x=("z", -1000, -600, 2), y=("phi", 0, 1, 2), angles="deg").meaning == ""


def test_register_quantity_errors():
    # the maps read a paper's quantities by name (import screwkit registers paper 004's)
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected `name` to be one of \('lti', 'kappa', 'zeta'\), got 'volume'"):
        Q.register_quantity("volume", len)
    with pytest.raises(sk.ScrewkitTypeError, match="Expected `function` to be callable, got str"):
        Q.register_quantity("lti", "eta")


def test_the_maps_read_paper_004_through_the_posed_mechanism():
    # "lti" over a posed batch is paper 004's eta at those poses, computed from the posed mechanism
    poses = np.array([[0.0, 0.0, -750.0, 0.0], [30.0, -20.0, -750.0, 0.3]])
    values, ok = W.evaluate(H4, poses, "lti")
    # exact on the numpy path; once an earlier batch of >= 256 poses has loaded paper 004's compiled
    # kernel (screwkit.papers._lti_numba), it agrees with the numpy path to 1e-12 (tests/papers/test_paper_004_numba.py)
    np.testing.assert_allclose(values, transmission_indices(H4.configuration(poses)).lti, rtol=0, atol=1e-12)
    assert ok.all()


def test_quantity_constants_have_one_home():
    """The maps' verdict bits are the core's labels, and paper 004's quantity names are written once
    (register_quantity, the maps' early refusal and the package's registration read them)."""
    from screwkit.analysis import quantities
    from screwkit.core import verdicts

    assert quantities.KINDS is verdicts.LABELS
    sources = [pathlib.Path(m.__file__).read_text(encoding="utf-8")
               for m in (sk, quantities, sk.workspace)]
    assert sum(s.count('("lti", "kappa", "zeta")') for s in sources) == 1


# the wrench-based transmission index over poses, for a graph mechanism (issue 19) ----------------------
def _planar_3rpr_output_transmission(base, platform, pose):
    """A 3-RPR's wrench-based LTI, derived by hand: each prismatic actuator's input transmission is 1
    (its force lies along its own sliding); with the other two legs held, the platform turns about the
    meet P of their lines, so leg j's output transmission is the cosine between the leg and the
    velocity of its platform joint C_j, which is normal to C_j − P (Wang, Wu & Liu 2010's pressure
    angle). The LTI is the least of them."""
    centre = platform.mean(axis=0)
    c, s = np.cos(pose[2]), np.sin(pose[2])
    moved = (platform - centre) @ np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]]) + [pose[0], pose[1], 0]
    legs = (moved - base) / np.linalg.norm(moved - base, axis=1)[:, None]
    cosines = []
    for j in range(3):
        k, m = [i for i in range(3) if i != j]
        a, _ = np.linalg.solve(np.array([legs[k, :2], -legs[m, :2]]).T, base[m, :2] - base[k, :2])
        arm = moved[j, :2] - (base[k, :2] + a * legs[k, :2])
        cosines.append(abs(legs[j, :2] @ [-arm[1], arm[0]]) / np.linalg.norm(arm))
    return min(cosines)


def test_a_graph_mechanisms_map_of_the_wrench_based_transmission_index():
    from ..mechanisms import PLANAR_BASE, PLANAR_PLATFORM, planar_3rpr

    robot = sk.mechanism(planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM))
    x0, y0, _ = robot.reference_pose
    result = W.grid_map(robot, "wrench_lti", x=("x", x0 - 0.1, x0 + 0.1, 3), y=("y", y0, y0 + 0.1, 2),
                        fixed={"phi": 0.2}, loci=False)
    expected = [[_planar_3rpr_output_transmission(PLANAR_BASE, PLANAR_PLATFORM, (x, y, 0.2))
                 for x in result.x_values] for y in result.y_values]
    np.testing.assert_allclose(result.values, expected, rtol=1e-9)
    # paper 004's LTI is defined on the four-limb geometry: refused, naming the index that applies
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected a four-limb mechanism for quantity 'lti' "
                       r"\(paper 004's index.*got family 'loop_closure'; the wrench-based index of any "
                       r"mechanism is quantity 'wrench_lti'\.$"):
        W.grid_map(robot, "lti", x=("x", x0 - 0.1, x0 + 0.1, 2), y=("y", y0, y0 + 0.1, 2), loci=False)


# maps and paths over poses partly out of reach of a graph mechanism ----------------------------------
def _five_bar_end_point():
    """A five-bar (base joints A1 = (0, 0), A2 = (1, 0); proximal links of length 1; distal links of
    length √0.89 meeting at C = (0.5, 1.8)) whose task is the point C: it reaches the points within
    1 + √0.89 of both base joints."""
    from ..robots.test_graph_mechanism import five_bar

    return sk.mechanism(five_bar(), task=("distal1", [0.5, 1.8, 0]))


FIVE_BAR_REACH = 1.0 + np.sqrt(0.89)


def test_a_graph_mechanisms_map_and_path_over_poses_out_of_reach():
    robot = _five_bar_end_point()
    result = W.grid_map(robot, "verdict", x=("x", 0.3, 0.7, 3), y=("y", 1.6, 2.0, 3), loci=False)
    xs, ys = np.meshgrid(result.x_values, [1.6, 1.8, 2.0])
    within = (np.hypot(xs, ys) < FIVE_BAR_REACH) & (np.hypot(xs - 1.0, ys) < FIVE_BAR_REACH)
    assert 0 < within.sum() < within.size
    np.testing.assert_array_equal(result.reachable, within)
    assert (result.values[~within] == -1).all() and (result.values[within] == 0).all()
    closeness = W.grid_map(robot, "closeness", x=("x", 0.3, 0.7, 3), y=("y", 1.6, 2.0, 3), loci=False)
    assert np.isnan(closeness.values[~within]).all() and np.isfinite(closeness.values[within]).all()
    # straight up from C the path leaves the reach where C is 1 + √0.89 from both base joints
    path = PA.check_path(robot, [0.5, 1.8], [0.5, 4.0], samples=30)
    edge = np.sqrt(FIVE_BAR_REACH**2 - 0.25)
    assert abs(path.crossing.pose["y"] - edge) < 1e-6 and path.crossing.kind in ("unreachable", "serial")


def test_a_paths_dict_keeps_the_reference_value_of_what_it_leaves_out():
    # the documented fill: a dict's missing coordinates take the reference pose's values (here a graph
    # mechanism's reference configuration), shown in the result; an array must give every coordinate
    from ..mechanisms import PLANAR_BASE, PLANAR_PLATFORM, planar_3rpr

    robot = sk.mechanism(planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM))
    x0, y0, phi0 = robot.reference_pose.tolist()
    path = PA.check_path(robot, {"x": x0 - 0.05}, {"x": x0 + 0.05}, samples=5)
    assert path.start == {"x": x0 - 0.05, "y": y0, "phi": phi0}
    assert path.end == {"x": x0 + 0.05, "y": y0, "phi": phi0}
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected `end` to have shape \(3,\), got \(2,\) "
                       r"\(one pose of coordinates x, y, phi\)\.$"):
        PA.check_path(robot, [x0, y0, phi0], [x0, y0])


def test_a_pose_its_own_batch_does_not_reach_is_marked_out_of_reach():
    # a graph mechanism may reach a pose in a larger batch only (seeded starts): the map's batch of the
    # reachable poses is then the judge. Here `reachable` claims every pose; the batch reaches two of three
    catalog = sk.load_mechanism("v4")

    class Overreaching:  # the V4 whose reach test says yes to every pose
        def __getattr__(self, name):
            return getattr(catalog, name)

        def reachable(self, poses, **options):
            return np.ones(len(poses), dtype=bool)

    v4 = Overreaching()
    poses = np.array([[0.0, 0.0, -750.0, 0.0], [0.0, 0.0, -5000.0, 0.0], [30.0, -20.0, -750.0, 0.3]])
    expected = catalog.at(poses[[0, 2]]).codes
    for measure in (
        lambda: W.evaluate(v4, poses, "verdict"),
        lambda: RT._measured_chunk(v4, poses, {}, None)[:2],
    ):
        values, reachable = measure()
        assert reachable.tolist() == [True, False, True]
        assert values.tolist() == [int(expected[0]), -1, int(expected[1])]
