"""Image comparison of a few key figures: regressions in what a reader sees are caught.

Each figure is drawn with the Agg backend under a fixed style (:data:`STYLE`) at a fixed size and dpi,
and compared with a stored PNG in ``tests/interface/baseline_images/`` by the root-mean-square
difference of the pixels (0-255 per channel); up to :data:`TOLERANCE` passes (font rasterising
differs slightly between FreeType versions; a moved line, label or colour does not pass).

The baselines were drawn by the figure code itself at a state whose figures were looked at (the
maps' symbols, units, diverging colours and zero level; the schematic wrench diagram of the H4 at
its default pose, read against paper 002's Fig. 4c). To redraw them after an intended change, look
at the new figures, then run::

    SCREWKIT_UPDATE_BASELINES=1 python -m pytest tests/interface/test_figure_images.py

and commit the PNGs with the change.
"""

import os
from pathlib import Path
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.image import imread

from screwkit import load_mechanism
from screwkit.interface.plot import plot_map, plot_verdicts
from screwkit.interface.plot_diagrams import plot_wrench_diagram_schematic

BASELINES = Path(__file__).parent / "baseline_images"
#: The style every compared figure is drawn in (matplotlib's defaults, one font, no hinting surprises).
STYLE = {
    "font.family": "DejaVu Sans",
    "text.hinting": "none",
    "axes.unicode_minus": True,
}
SIZE, DPI = (7.0, 5.0), 70
#: Largest accepted RMS difference, in 0-255 grey levels.
TOLERANCE = 3.0


def _grid_map(quantity, values, units):
    x, y = np.linspace(-300.0, 300.0, 41), np.linspace(-200.0, 200.0, 31)
    return SimpleNamespace(
        quantity=quantity,
        x_name="x",
        x_values=x,
        y_name="y",
        y_values=y,
        values=values(*np.meshgrid(x, y)),
        reachable=np.ones((31, 41), bool),
        fixed={"z": -750.0, "phi": 0.0},
        units=units,
    )


UNITS = {"x": "mm", "y": "mm", "z": "mm", "phi": "deg"}


def _signed_map(ax):
    # a signed quantity crossing zero along the circle x² + y² = 150²: diverging colours, zero level bold
    plot_map(_grid_map("det_A", lambda x, y: (np.hypot(x, y) - 150.0) / 10.0, UNITS), ax=ax)


def _lti_map(ax):
    plot_map(_grid_map("lti", lambda x, y: 0.9 - np.hypot(x / 600, y / 400), UNITS), ax=ax, levels=8)


def _one_verdict(ax):
    plot_verdicts(_grid_map("verdict", lambda x, y: np.zeros(x.shape, int), UNITS), ax=ax)


def _h4_schematic(ax):
    diagram, _ = load_mechanism("h4").wrench_diagram()
    plot_wrench_diagram_schematic(diagram, ax=ax)


FIGURES = {
    "signed_map": _signed_map,
    "lti_map": _lti_map,
    "one_verdict": _one_verdict,
    "h4_schematic": _h4_schematic,
}


def _render(draw, path):
    with matplotlib.rc_context(STYLE):
        figure, ax = plt.subplots(figsize=SIZE, layout="constrained")
        draw(ax)
        figure.savefig(path, dpi=DPI)  # no bbox_inches="tight": the canvas size is fixed
        plt.close(figure)


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_figure_matches_its_baseline(name, tmp_path):
    baseline = BASELINES / f"{name}.png"
    if os.environ.get("SCREWKIT_UPDATE_BASELINES"):
        _render(FIGURES[name], baseline)
        pytest.skip(f"baseline {baseline.name} redrawn: look at it before committing")
    drawn = tmp_path / f"{name}.png"
    _render(FIGURES[name], drawn)
    expected, actual = imread(baseline), imread(drawn)
    assert actual.shape == expected.shape, (actual.shape, expected.shape)
    rms = float(np.sqrt(np.mean((255.0 * (actual.astype(float) - expected.astype(float))) ** 2)))
    assert rms <= TOLERANCE, f"{name}: RMS {rms:.2f} > {TOLERANCE} (drawn: {drawn})"


def test_the_comparison_catches_a_changed_figure(tmp_path):
    # the check itself can fail: the signed map drawn with a sequential colour map is far from its baseline
    drawn = tmp_path / "changed.png"
    _render(
        lambda ax: plot_map(
            _grid_map("det_A", lambda x, y: (np.hypot(x, y) - 150.0) / 10.0, UNITS), ax=ax, cmap="viridis"
        ),
        drawn,
    )
    expected, actual = imread(BASELINES / "signed_map.png"), imread(drawn)
    rms = float(np.sqrt(np.mean((255.0 * (actual.astype(float) - expected.astype(float))) ** 2)))
    assert rms > 10 * TOLERANCE
