"""What a reader of papers 002 and 004 checks on a figure: symbols and units, a diverging map centred
at zero for a signed quantity with its zero level, equal scale for spatial slices, legends off the
data, a one-category verdict map that says so, the wrench diagram with no line hidden."""

from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

from screwkit import load_mechanism
from screwkit.analysis.quantities import QUANTITIES, display
from screwkit.interface.plot import (
    DIVERGING_CMAP,
    SEQUENTIAL_CMAP,
    plot_map,
    plot_singularity_surfaces,
    plot_verdicts,
)
from screwkit.interface.plot_diagrams import plot_wrench_diagram, plot_wrench_diagram_schematic


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _map(quantity, values, units=None):
    x, y = np.linspace(-300.0, 300.0, 31), np.linspace(-200.0, 200.0, 21)
    gx, gy = np.meshgrid(x, y)
    return SimpleNamespace(
        quantity=quantity,
        x_name="x",
        x_values=x,
        y_name="y",
        y_values=y,
        values=values(gx, gy),
        reachable=np.ones(gx.shape, bool),
        fixed={"z": -750.0, "phi": 0.0},
        units=units or {"x": "mm", "y": "mm", "z": "mm", "phi": "deg"},
    )


def test_every_quantity_has_a_symbol_a_label_and_says_if_signed():
    for name in QUANTITIES:
        shown = display(name)
        assert shown.label and shown.symbol and shown.meaning
    assert display("lti").symbol == r"$\eta$"  # paper 004's η, Eq. (16)
    assert display("det_A").signed and display("det_B").signed and display("condition:2").signed
    assert not display("lti").signed and not display("closeness").signed
    assert "exceed 1" in display("closeness:actuation").meaning  # the closeness measures can exceed 1


def test_a_signed_map_is_diverging_centred_at_zero_with_its_zero_level():
    ax = plot_map(_map("det_A", lambda x, y: (np.hypot(x, y) - 150.0) / 10.0))
    filled = next(c for c in ax.collections if getattr(c, "filled", False))
    assert filled.get_cmap().name == DIVERGING_CMAP
    assert filled.norm.vcenter == 0.0 and filled.norm.vmin == -filled.norm.vmax
    bold = [c for c in ax.collections if not getattr(c, "filled", True) and list(c.levels) == [0.0]]
    assert len(bold) == 1  # the zero level, drawn once
    colour_bar = ax.figure.axes[-1]
    assert colour_bar.get_ylabel() == "det A, determinant of the forward Jacobian (mm)"  # one rotation: mm¹
    assert ax.get_aspect() == 1.0  # x and y both in mm: equal scale
    legend = ax.get_legend()
    assert legend is not None and legend.get_bbox_to_anchor().y0 < ax.get_window_extent().y0  # below the axes


def test_an_unsigned_map_is_sequential_and_an_angle_axis_is_not_equal_scale():
    units = {"x": "mm", "y": "deg", "z": "mm", "phi": "deg"}
    ax = plot_map(_map("closeness", lambda x, y: np.hypot(x, y) / 400.0, units))
    filled = next(c for c in ax.collections if getattr(c, "filled", False))
    assert filled.get_cmap().name == SEQUENTIAL_CMAP
    assert ax.get_aspect() == "auto"
    assert ax.figure.axes[-1].get_ylabel().endswith("(dimensionless)")


def test_a_verdict_map_of_one_category_says_so():
    ax = plot_verdicts(_map("verdict", lambda x, y: np.zeros(x.shape, int)))
    assert ax.get_title().startswith("every reachable grid pose regular")
    two = plot_verdicts(_map("verdict", lambda x, y: (x > 0).astype(int) * 2))
    assert two.get_title().startswith("verdicts")


def _diagram_with_a_repeated_line():
    # two legs of a Gough-Stewart-like diagram along the same line (points a, b, c collinear), one
    # more line elsewhere: the second is the first line again and must not be hidden behind it
    coordinates = {
        "a": np.array([0.0, 0.0, 0.0, 1.0]),
        "b": np.array([1.0, 0.0, 0.0, 1.0]),
        "c": np.array([2.0, 0.0, 0.0, 1.0]),
        "d": np.array([0.0, 1.0, 0.0, 1.0]),
        "e": np.array([0.0, 0.0, 1.0, 0.0]),
    }
    return SimpleNamespace(
        points=[SimpleNamespace(label=k, at_infinity=v[3] == 0) for k, v in coordinates.items()],
        lines=(("a", "b"), ("b", "c"), ("d", "e")),
        line_names=("leg 1", "leg 2", "leg 3"),
        roles=("actuation",) * 3,
        coordinates=coordinates,
        degenerate=(),
        line_text=lambda: "[ab, bc, de]",
    )


def test_the_3d_wrench_diagram_draws_a_repeated_line_offset_with_units():
    ax = plot_wrench_diagram(_diagram_with_a_repeated_line(), length_unit="mm")
    first, second, _ = ax.lines
    assert "the line ab; drawn offset" in second.get_label()
    gap = np.min(np.linalg.norm(np.array(first.get_data_3d()).T - np.array(second.get_data_3d()).T, axis=1))
    assert gap > 0  # not drawn on top of each other
    assert (ax.get_xlabel(), ax.get_zlabel()) == ("x (mm)", "z (mm)")


def test_the_schematic_wrench_diagram_of_the_h4():
    # paper 002 Fig. 4c: a, c, e, g finite; b, d, f, h, i, j, k at infinity; ij and kj lines at infinity
    diagram, _ = load_mechanism("h4").wrench_diagram()
    ax = plot_wrench_diagram_schematic(diagram)
    texts = {t.get_text() for t in ax.texts}
    assert set("abcdefghijk") <= texts
    labels = [line.get_label() for line in ax.lines if not line.get_label().startswith("_")]
    assert labels == [
        f"{''.join(line)}: {name}" for line, name in zip(diagram.lines, diagram.line_names, strict=True)
    ]
    border = [np.hypot(*t.xy) for t in ax.texts if t.get_text() in "bdfhijk" and t.get_text()]
    finite = [np.hypot(*t.xy) for t in ax.texts if t.get_text() in ("a", "c", "e", "g")]
    assert np.allclose(border, 1.0) and max(finite) < 1.0  # points at infinity on the border circle
    places = [tuple(np.round(t.xy, 6)) for t in ax.texts if t.get_text() in list("bdfhijk")]
    assert len(set(places)) == 7  # seven distinct points at infinity, none on top of another


def test_singularity_surfaces_have_units_on_their_axes():
    triangles = np.array([[[0, 0, -800], [100, 0, -800], [0, 100, -750]]], dtype=float)
    region = SimpleNamespace(lower=(-200, -200, -900), upper=(200, 200, -600), name="box")  # no wireframe
    surface = SimpleNamespace(triangles=triangles, fixed={"phi": 0.5}, mechanism="H4", region=region)
    ax = plot_singularity_surfaces([surface], wireframe=0)
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("x (mm)", "y (mm)", "z (mm)")


def test_the_map_command_gives_a_verdict_map_its_shares_not_extrema(capsys, tmp_path):
    from screwkit.interface.cli import main

    out = tmp_path / "v.json"
    argv = ["map", "h4", "--quantity", "verdict", "--z", "-900", "-600", "3", "--phi", "-10", "10", "3"]
    assert main([*argv, "--out", str(out), "--no-progress"]) == 0
    text = capsys.readouterr().out
    assert "regular 100.0%" in text and "minimum" not in text and "maximum" not in text
    assert main(["map", "h4", "--quantity", "lti", *argv[4:], "--out", str(out), "--no-progress"]) == 0
    assert "mm, phi = " in capsys.readouterr().out  # extrema where they occur, with units


def test_a_registered_quantity_brings_its_display():
    from screwkit.analysis import quantities as Q

    before = Q.display("kappa")
    try:
        Q.register_quantity("kappa", Q._REGISTERED["kappa"], symbol="$\\kappa_m$", unit="")
        assert Q.display("kappa").symbol == "$\\kappa_m$" and Q.display("kappa").label == before.label
    finally:
        Q._DISPLAY["kappa"] = before


def test_the_3d_view_is_one_where_no_line_hides_another():
    from screwkit.interface.plot_diagrams import VIEWS_3D, _clearest_view

    # matplotlib's default view looks along this direction: a line shifted along it hides behind the first
    elev, azim = np.radians(VIEWS_3D[0])
    along = np.array([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)])
    first = np.linspace([0.0, 0.0, 0.0], [1.0, -1.0, 0.5], 30)
    second = first + 2.0 * along
    third = np.linspace([0.0, 1.0, 0.0], [0.0, 1.0, 1.0], 30)
    chosen = _clearest_view([first, second, third])
    assert chosen != VIEWS_3D[0]
    assert _clearest_view([first, third]) == VIEWS_3D[0]  # nothing hidden: the default view stays
