"""screwkit.interface.plot and plot_diagrams: drawings rendered to files with Agg, checked through the artists they contain.

The maps and loci are small objects built here with the attributes of screwkit.analysis.workspace's
WorkspaceMap and Locus (plot reads attributes only); the diagrams and twist graphs are screwkit's own.
Expected values come from the inputs (how many lines, which labels, which levels), never from a
drawing of the code under test.
"""

import subprocess
import sys
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.contour import ContourSet
from matplotlib.patches import FancyArrowPatch
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

from screwkit import equivalent_twist_graph, load_mechanism, prismatic, revolute, twist_graph
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import (
    DegenerateGeometryError,
    ScrewkitTypeError,
    ScrewkitValueError,
    TwistGraphError,
)
from screwkit.gca.diagram_recipes import wrench_diagram
from screwkit.interface.plot import (
    SURFACE_COLOURS,
    UNREACHABLE_COLOUR,
    VERDICT_COLOURS,
    plot_map,
    plot_singularity_surfaces,
    plot_verdicts,
)
from screwkit.interface.plot_diagrams import plot_twist_graph, plot_wrench_diagram
from screwkit.papers.paper_004_surfaces import actuation_singularity_surface
from screwkit.papers.paper_004_table4 import TABLE_4_CONE, Region


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _map(values=None, reachable=None, x_name="x", y_name="phi"):
    x, y = np.linspace(-1.0, 1.0, 21), np.linspace(-0.5, 0.5, 11)
    grid_x, grid_y = np.meshgrid(x, y)
    if values is None:
        values = 1 - np.hypot(grid_x, grid_y) / 2  # from 1 at the centre to 1 - sqrt(1.25)/2 = 0.44
    if reachable is None:
        reachable = np.hypot(grid_x, grid_y) < 0.9
    return SimpleNamespace(
        quantity="lti", x_name=x_name, x_values=x, y_name=y_name, y_values=y, values=values,
        reachable=reachable, fixed={"z": -800.0, "y": 0.0},
    )


def _locus(kind="constraint", x_name="x", y_name="phi", m=7):
    return SimpleNamespace(kind=kind, factor="[gikj]", x_name=x_name, y_name=y_name,
                           points=np.c_[np.zeros(m), np.linspace(-0.5, 0.5, m)])


def _contour_sets(ax):
    return [c for c in ax.collections if isinstance(c, ContourSet)]


# maps ---------------------------------------------------------------------------------------------
def test_map_contour_levels_and_loci(tmp_path):
    unknown = _locus("actuation", m=3)
    unknown.factor = None  # the factor is not always known
    ax = plot_map(_map(), levels=[0.5, 0.7, 0.9], loci=[_locus(), unknown], degrees=("phi",))
    ax.figure.savefig(tmp_path / "map.png")
    assert (tmp_path / "map.png").stat().st_size > 0
    filled, lines = _contour_sets(ax)
    assert filled.filled and not lines.filled
    assert filled.extend == "both"  # values beyond the levels are coloured, not left blank as unreachable
    assert lines.levels.tolist() == [0.5, 0.7, 0.9]
    # one marker line per locus, its points the locus's, phi drawn in degrees
    constraint, actuation = ax.lines
    assert constraint.get_label() == "constraint locus: [gikj]" and actuation.get_label() == "actuation locus"
    assert np.allclose(constraint.get_ydata(), np.degrees(np.linspace(-0.5, 0.5, 7)))
    assert len(actuation.get_xdata()) == 3
    assert constraint.get_color() != actuation.get_color()
    assert ax.get_xlabel() == "x" and ax.get_ylabel() == "phi (deg)"
    assert ax.get_title() == r"$\eta$, local transmission index at z = -800, y = 0"  # the symbol, not the key
    # contour labels: one text per labelled level segment, each a level's value
    assert {t.get_text() for t in ax.texts} <= {"0.5", "0.7", "0.9"} and ax.texts


def test_map_shows_the_units_of_the_map():
    m = _map()
    m.units = {"x": "mm", "y": "mm", "z": "mm", "phi": "rad"}
    ax = plot_map(m, levels=3)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x (mm)", "phi (rad)")
    assert ax.get_title() == r"$\eta$, local transmission index at z = -800 mm, y = 0 mm"
    assert plot_map(m, levels=3, degrees=("phi",)).get_ylabel() == "phi (deg)"


def test_map_leaves_unreachable_points_blank():
    reachable = np.zeros((11, 21), bool)
    reachable[:, :10] = True  # the left half only
    ax = plot_map(_map(reachable=reachable), levels=[0.6, 0.8])
    assert ax.get_facecolor() == matplotlib.colors.to_rgba(UNREACHABLE_COLOUR)
    (_, lines) = _contour_sets(ax)
    for path in lines.get_paths():  # no contour line reaches into the unreachable half (x > 0)
        assert path.vertices[:, 0].max() <= 0.0 + 1e-12


def test_map_degrees_can_be_off_and_inputs_are_not_changed():
    m = _map()
    before = m.y_values.copy()
    ax = plot_map(m, filled=False, levels=4)  # angles drawn as stored by default
    assert np.array_equal(m.y_values, before)
    assert ax.get_ylabel() == "phi" and len(_contour_sets(ax)) == 1


@pytest.mark.parametrize(
    ("change", "error", "match"),
    [
        ({"values": np.zeros((3, 3))}, ScrewkitValueError, r"shape \(len\(y_values\), len\(x_values\)\) = \(11, 21\), got \(3, 3\)"),
        ({"values": np.full((11, 21), np.nan)}, ScrewkitValueError, "finite value at a reachable grid point"),
        ({"reachable": np.ones((2, 2), bool)}, ScrewkitValueError, "reachable` to have the shape of its values"),
    ],
)
def test_map_errors(change, error, match):
    m = _map()
    for key, value in change.items():
        setattr(m, key, value)
    with pytest.raises(error, match=match):
        plot_map(m)


def test_map_refuses_an_object_without_the_attributes():
    with pytest.raises(ScrewkitTypeError, match=r"Expected `workspace_map` to have x_name.*got dict"):
        plot_map({"values": 1})


def test_map_refuses_a_locus_over_other_axes():
    with pytest.raises(ScrewkitValueError, match=r"loci\[0\] over the map's axes \('x', 'phi'\), got \('z', 'phi'\)"):
        plot_map(_map(), loci=[_locus(x_name="z")])


def test_verdict_map_colours_and_legend(tmp_path):
    codes = np.zeros((11, 21), int)
    codes[5, :] = 2  # a row of actuation singularities
    codes[:, 10] = 1  # a column of constraint singularities
    codes[0, 0] = -1  # unreachable: any value, not in the legend
    reachable = np.ones((11, 21), bool)
    reachable[0, 0] = False
    ax = plot_verdicts(_map(values=codes, reachable=reachable), loci=[_locus()])
    ax.figure.savefig(tmp_path / "verdicts.png")
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts == ["regular", "constraint singularity", "actuation singularity", "constraint locus: [gikj]"]
    (mesh,) = ax.collections
    shown = mesh.get_array()
    assert shown.mask.sum() == 1  # the unreachable cell
    assert np.array_equal(shown.data.reshape(11, 21)[reachable], codes[reachable])
    # each code is drawn in its own colour
    rgba = mesh.to_rgba(np.array([0, 1, 2]))
    assert np.allclose(rgba, [matplotlib.colors.to_rgba(VERDICT_COLOURS[c]) for c in (0, 1, 2)])


def test_verdict_map_accepts_verdict_strings():
    names = np.full((11, 21), "regular", dtype=object)
    names[3, 4] = "actuation + serial singularity"
    ax = plot_verdicts(_map(values=names, reachable=np.ones((11, 21), bool)))
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["regular", "actuation + serial singularity"]
    assert ax.collections[0].get_array().data.reshape(11, 21)[3, 4] == 6


@pytest.mark.parametrize(
    ("values", "match"),
    [
        (np.full((11, 21), "singular", dtype=object), r"verdict codes or verdicts .*got \['singular'\]"),
        (np.full((11, 21), 9), r"codes in 0..7 .*got \[9\]"),
    ],
)
def test_verdict_map_errors(values, match):
    with pytest.raises(ScrewkitValueError, match=match):
        plot_verdicts(_map(values=values))


# the wrench diagram -------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def h4_diagram():
    return wrench_diagram(wrench_analysis(load_mechanism("h4").twist_graph([30.0, -20.0, -750.0, 0.3])))


def test_wrench_diagram_artists(h4_diagram, tmp_path):
    ax = plot_wrench_diagram(h4_diagram)
    ax.figure.savefig(tmp_path / "diagram.png")
    labels = [line.get_label() for line in ax.lines]
    assert labels == [f"{''.join(pair)}: {n}" for pair, n in zip(h4_diagram.lines, h4_diagram.line_names, strict=True)]
    assert len({line.get_color() for line in ax.lines}) == 6
    texts = {t.get_text().strip() for t in ax.texts}
    finite, infinite = set(h4_diagram.finite), set(h4_diagram.infinite)
    assert texts == finite | {f"{k}∞" for k in infinite}
    arrows = [c for c in ax.collections if isinstance(c, Line3DCollection)]
    assert len(arrows) == len(infinite) == 7


def test_wrench_diagram_geometry(h4_diagram):
    ax = plot_wrench_diagram(h4_diagram, radius=200.0)
    coords = h4_diagram.coordinates
    finite = np.array([coords[k][:3] for k in h4_diagram.finite])
    centre = finite.mean(axis=0)
    ab, *_, ij, kj = ax.lines
    # the actuation line ab passes through a, along the direction b, and ends on the sphere
    ends = np.array(ab.get_data_3d()).T
    assert np.allclose(np.linalg.norm(ends - centre, axis=1), 200.0)
    a, b = coords["a"][:3], coords["b"][:3]
    assert np.allclose(np.cross(ends[1] - ends[0], b), 0, atol=1e-9 * 400)
    assert np.allclose(np.cross(a - ends[0], b), 0, atol=1e-9 * 400)
    # the line at infinity ij: a circle of radius 200 in the plane of the directions i and j
    circle = np.array(ij.get_data_3d()).T
    normal = np.cross(coords["i"][:3], coords["j"][:3])
    assert np.allclose(np.linalg.norm(circle - centre, axis=1), 200.0)
    assert np.allclose((circle - centre) @ normal, 0, atol=1e-9)
    assert ij.get_linestyle() == kj.get_linestyle() == "--" and ab.get_linestyle() == "-"


def test_wrench_diagram_line_through_two_finite_points():
    diagram = SimpleNamespace(
        lines=(("a", "b"),), line_names=("actuation P",), roles=("actuation",), degenerate=(),
        coordinates={"a": np.array([0.0, 0, 0, 1]), "b": np.array([2.0, 0, 0, 1])},
        line_text=lambda: "[ab]",
    )
    ax = plot_wrench_diagram(diagram)
    (line,) = ax.lines
    xs, ys, zs = line.get_data_3d()
    # centre (1, 0, 0), radius 1.25 × 1: the chord is the x axis from -0.25 to 2.25
    assert np.allclose(sorted(xs), [-0.25, 2.25]) and np.allclose(ys, 0) and np.allclose(zs, 0)


def test_wrench_diagram_errors(h4_diagram):
    from dataclasses import replace

    with pytest.raises(ScrewkitValueError, match=r"got none for a, b.*pose out of reach"):
        plot_wrench_diagram(replace(h4_diagram, coordinates={}, degenerate=("pose out of reach",)))
    with pytest.raises(ScrewkitValueError, match=r"`radius` > 0, got -1"):
        plot_wrench_diagram(h4_diagram, radius=-1.0)
    twin = dict(h4_diagram.coordinates, i=h4_diagram.coordinates["j"])
    with pytest.raises(DegenerateGeometryError, match=r"line ij .*the same direction"):
        plot_wrench_diagram(replace(h4_diagram, coordinates=twin))
    with pytest.raises(ScrewkitTypeError, match="3-D axes"):
        plot_wrench_diagram(h4_diagram, ax=plt.subplots()[1])


# the twist graph ----------------------------------------------------------------------------------
# singularity surfaces (paper 004, Figs. 14-16) ------------------------------------------------------
def _square(z, phi=0.5, robot="toy"):
    """Two triangles of the square |x|, |y| <= 100 at height z, in the box region +-200 x +-200 x +-200."""
    corners = np.array([[-100, -100, z], [100, -100, z], [100, 100, z], [-100, 100, z]], dtype=float)
    region = Region.box((-200, 200), (-200, 200), (-200, 200))
    return SimpleNamespace(triangles=corners[[[0, 1, 2], [0, 2, 3]]], fixed={"phi": phi}, mechanism=robot,
                           region=region)


def test_singularity_surfaces_artists(tmp_path):
    empty = SimpleNamespace(**{**vars(_square(0.0)), "triangles": np.zeros((0, 3, 3)), "fixed": {"phi": 0.0}})
    ax = plot_singularity_surfaces([_square(50.0, 1.3), _square(-50.0, -1.3), empty], wireframe=6)
    ax.figure.savefig(tmp_path / "surfaces.png")
    assert (tmp_path / "surfaces.png").stat().st_size > 1000
    polygons = [c for c in ax.collections if isinstance(c, Poly3DCollection)]
    assert [len(p.get_paths()) for p in polygons] == [2, 2]  # one per triangle; none for the empty one
    assert [p.get_label() for p in polygons] == ["φ = +74.48°", "φ = -74.48°"]
    # the first in SURFACE_COLOURS' first colour, shaded (never brighter than the colour)
    base = np.array(matplotlib.colors.to_rgb(SURFACE_COLOURS[0]))
    faces = polygons[0].get_facecolor()[:, :3]
    assert np.all(faces <= base + 1e-12) and np.all(faces >= 0.45 * base - 1e-12)
    wire = [c for c in ax.collections if isinstance(c, Line3DCollection)]
    assert len(wire) == 1 and matplotlib.colors.same_color(wire[0].get_color()[0][:3], "tab:blue")
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend == ["φ = +74.48°", "φ = -74.48°", "φ = +0°: none in the region", "workspace"]
    assert ax.get_xlim() == (-200, 200) and ax.get_zlim() == (-200, 200)
    assert ax.get_title() == "toy: actuation singularity loci"


def test_singularity_surfaces_of_paper_004_robot(tmp_path):
    quattro = load_mechanism("quattro")
    pair = [actuation_singularity_surface(quattro, a, TABLE_4_CONE, grid=10) for a in (np.pi / 2, -np.pi / 2)]
    ax = plot_singularity_surfaces(pair, wireframe=0)
    ax.figure.savefig(tmp_path / "fig14b.png")
    polygons = [c for c in ax.collections if isinstance(c, Poly3DCollection)]
    assert [len(p.get_paths()) for p in polygons] == [len(s.triangles) for s in pair]
    assert not [c for c in ax.collections if isinstance(c, Line3DCollection)]  # no wireframe asked
    low, high = ax.get_zlim()
    assert (low, high) == (TABLE_4_CONE.lower[2], TABLE_4_CONE.upper[2])
    assert ax.get_title() == "Quattro: actuation singularity loci"
    # one surface on its own is one surface (a SingularSurface was once a tuple; a new user's trial got
    # "got ndarray" from iterating its fields)
    single = plot_singularity_surfaces(pair[0], wireframe=0)
    single.figure.savefig(tmp_path / "fig14b_plus.png")  # 3-D collections get their paths when drawn
    assert [len(p.get_paths()) for p in single.collections if isinstance(p, Poly3DCollection)] == [len(pair[0].triangles)]


def test_singularity_surfaces_errors():
    with pytest.raises(ScrewkitValueError, match="Expected at least one surface to draw, got none"):
        plot_singularity_surfaces([])
    with pytest.raises(ScrewkitTypeError, match=r"Expected each surface to have triangles, fixed \(with phi\), mechanism and region"):
        plot_singularity_surfaces([SimpleNamespace(triangles=np.zeros((0, 3, 3)))])
    bad = SimpleNamespace(**{**vars(_square(0.0)), "triangles": np.zeros((2, 3))})
    with pytest.raises(ScrewkitValueError, match=r"surfaces\[0\]\.triangles of shape \(m, 3, 3\), got \(2, 3\)"):
        plot_singularity_surfaces([bad])
    with pytest.raises(ScrewkitTypeError, match="Expected `ax` to be 3-D axes"):
        plot_singularity_surfaces([_square(0.0)], ax=plt.subplots()[1])


def test_twist_graph_artists_h4(tmp_path):
    graph = load_mechanism("h4").twist_graph()
    ax = plot_twist_graph(graph)
    ax.figure.savefig(tmp_path / "graph.png")
    arrows = [p for p in ax.patches if isinstance(p, FancyArrowPatch)]
    assert len(arrows) == graph.number_of_edges() == 22
    texts = [t.get_text() for t in ax.texts]
    assert set(texts[:16]) == set(graph.nodes)
    assert sorted(texts[16:]) == sorted(k for _, _, k in graph.edges(keys=True))
    bold = [a for a in arrows if a.get_linewidth() > 2]
    assert len(bold) == 4  # the four actuated revolute joints A1..A4
    # layers: the base at the bottom, the end effector at the top, four arms one level up
    position = {t.get_text(): t.get_position() for t in ax.texts[:16]}
    assert position["base"][1] == 0 and position["end_effector"][1] == 4
    assert {position[f"arm{i}"][1] for i in range(1, 5)} == {1.0}


def test_twist_graph_virtual_joints_dashed():
    graph = equivalent_twist_graph(load_mechanism("h4").twist_graph())
    ax = plot_twist_graph(graph, edge_labels="type")
    virtual = sum(bool(j.virtual) for _, _, j in graph.edges(data="joint"))
    dashed = [p for p in ax.patches if p.get_linestyle() == "--"]
    assert len(dashed) == virtual == 16
    assert sorted(t.get_text() for t in ax.texts[graph.number_of_nodes():]) == sorted(
        j.type for _, _, j in graph.edges(data="joint")
    )


def test_twist_graph_parallel_joints_are_separate_arcs():
    graph = twist_graph("base", "platform", [
        ("base", "platform", prismatic("P1", [1, 0, 0], actuated=True)),
        ("base", "platform", prismatic("P2", [0, 1, 0], actuated=True)),
    ], dof=2)
    ax = plot_twist_graph(graph, edge_labels=None)
    first, second = ax.patches
    assert first.get_connectionstyle().rad == -second.get_connectionstyle().rad != 0
    assert [t.get_text() for t in ax.texts] == ["base", "platform"]


def test_twist_graph_errors():
    graph = twist_graph("g", "s", [("g", "s", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True))])
    with pytest.raises(ScrewkitValueError, match="`edge_labels` to be 'name', 'type' or None, got 'joint'"):
        plot_twist_graph(graph, edge_labels="joint")
    bare = graph.copy()
    del bare.graph["platform"]
    with pytest.raises(TwistGraphError, match="platform"):
        plot_twist_graph(bare)


# without matplotlib ---------------------------------------------------------------------------------
@pytest.mark.parametrize("module", ["screwkit.interface.plot", "screwkit.interface.plot_diagrams"])
def test_import_without_matplotlib_names_the_extra(module):
    # a fresh interpreter in which importing matplotlib fails
    code = (
        "import sys\nsys.modules['matplotlib'] = None\n"
        "from screwkit.exceptions import MissingDependencyError\n"
        f"try:\n    import {module}\nexcept MissingDependencyError as err:\n    print(err)\n"
        "import screwkit\nprint(screwkit.classify.__name__)"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    message, after = result.stdout.strip().splitlines()
    assert "need matplotlib" in message and "optional extra `plot`" in message and 'screwkit[plot]' in message
    assert after == "classify"  # the rest of screwkit works


def test_import_screwkit_does_not_import_matplotlib():
    code = "import screwkit\nimport sys\nprint('matplotlib' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert result.stdout.strip() == "False"
