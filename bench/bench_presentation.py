"""Cost of presentation: reprs, notebook HTML and LaTeX of a report, the angle conversion of a batch
of poses, and drawing the key figures (run as ``python bench/bench_presentation.py``)."""

import time

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
from _timing import best_of

import screwkit as sk
from screwkit.interface.plot_diagrams import plot_wrench_diagram, plot_wrench_diagram_schematic
from screwkit.robots.angles import poses_in_radians

h4 = sk.load_mechanism("h4")
report = sk.analyze("h4", [30, -20, -750, 17], angles="deg")
posed = h4.at(h4.random_poses(np.random.default_rng(0), 1000))
names, angles = h4.pose_names, h4.angle_names
poses = np.asarray(posed.poses) * [1, 1, 1, 180 / np.pi]
print(f"repr(AnalysisReport): {len(repr(report))} chars, {best_of(20, lambda: repr(report)) * 1e3:.2f} ms")
print(f"str(AnalysisReport): {len(str(report))} chars, {best_of(5, lambda: str(report)) * 1e3:.2f} ms")
print(f"AnalysisReport._repr_html_: {best_of(5, report._repr_html_) * 1e3:.1f} ms")
latex = best_of(5, report.superbracket._repr_latex_)
print(f"SuperbracketAnalysis._repr_latex_: {latex * 1e6:.0f} µs")
timed = {
    "repr(PosedMechanism of 1000 poses)": best_of(20, lambda: repr(posed)),
    "PosedMechanism._repr_html_ (1000 poses, verdicts computed)": best_of(3, posed._repr_html_),
    "poses_in_radians, 1000 poses in degrees": best_of(
        50, lambda: poses_in_radians(poses, names, angles, "deg")
    ),
    "poses_in_radians, 1000 poses in radians (the turn check only)": best_of(
        50, lambda: poses_in_radians(poses / [1, 1, 1, 57.3], names, angles)
    ),
}
for what, seconds in timed.items():
    print(f"{what}: {seconds * 1e6:.1f} µs")
diagram, _ = h4.wrench_diagram()


def draw(plot):
    start = time.perf_counter()
    figure = plot(diagram).figure
    figure.savefig("/dev/null", format="png", dpi=100)
    plt.close(figure)
    return time.perf_counter() - start


for plot in (plot_wrench_diagram, plot_wrench_diagram_schematic):
    print(f"{plot.__name__}, drawn and saved at 100 dpi: {min(draw(plot) for _ in range(3)) * 1e3:.0f} ms")
