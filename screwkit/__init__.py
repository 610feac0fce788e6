"""screwkit: singularities of parallel robots with screw theory and Grassmann–Cayley algebra.

The public API, along the data flow of the design (screws → screw systems → projective geometry →
twist graphs → wrench systems → labels and conditions). Conventions: :mod:`screwkit.algebra.screw`.

Examples
--------
>>> import screwkit as sk
>>> wrenches = sk.ScrewSystem.span([sk.Screw.force([1, 0, 0], [0, 0, 0]), sk.Screw.couple([0, 0, 1])])
>>> wrenches.reciprocal().order
4
"""

import functools
from pkgutil import extend_path
from typing import Any

from .algebra.motion_type import motion_type
from .algebra.screw import reciprocal_product
from .algebra.screwsystem import ScrewSystem
from .algebra.screwvalue import Screw
from .analysis.quantities import CONTRIBUTED as _CONTRIBUTED
from .analysis.quantities import register_quantity
from .core.singularity import classify, classify_poses, classify_table
from .core.verdicts import SingularityReport
from .core.wrench_systems import WrenchAnalysis, analyze_table
from .core.wrenches import wrench_analysis
from .exceptions import (
    CatalogError,
    DegenerateGeometryError,
    ScrewkitError,
    ScrewkitIndexError,
    ScrewkitTypeError,
    ScrewkitValueError,
    TwistGraphError,
    UnreachablePoseError,
)
from .graphs.joints import (
    Joint,
    cylindrical,
    helical,
    parallelogram,
    prismatic,
    revolute,
    spherical,
    universal,
    virtual,
)
from .graphs.jointtable import JointTable
from .graphs.loops import fundamental_loops, loop_closure_matrix
from .graphs.reduction import equivalent_twist_graph, platform_twist_system, series_parallel_tree
from .graphs.twistgraph import twist_graph
from .robots.report_composer import register_report_composer
from .version import __version__

#: Names loaded on first use (the catalog and its families, the generic analysis, the projective
#: helpers, the Jacobians, the composer and its report are not a cost of ``import screwkit``; PEP 562).
_LAZY = {
    "Mechanism": "robots.mechanism",
    "list_mechanisms": "robots.catalog",
    "load_mechanism": "robots.catalog",
    "load_snapshot": "robots.snapshot",
    "Family": "robots.families",
    "register": "robots.families",
    "GenericAnalysis": "core.generic",
    "generic_analysis": "core.generic",
    **dict.fromkeys(
        (
            "bracket",
    "check_path",
            "finite_point",
            "infinite_point",
            "join",
            "line_points",
            "meet_line_plane",
            "meet_planes",
            "plane",
            "plane_through",
        ),
        "algebra.projective",
    ),
    **dict.fromkeys(
        ("are_collinear", "are_coplanar", "is_at_infinity", "lines_intersect", "point_on_line"),
        "algebra.incidence",
    ),
    "Jacobians": "core.jacobian_matrices",
    "jacobians_from_wrenches": "core.jacobians",
    "schoenflies_basis": "core.jacobians",
    "PosedMechanism": "robots.posed",
    "AnalysisReport": "interface.analysis_report",
    "analyze": "interface.report",
    "graph_dot": "interface.export",
    "graph_json": "interface.export",
    "save_snapshot": "interface.export",
    "snapshot_text": "interface.export",
    "WrenchDiagram": "gca.diagram",
    "wrench_diagram": "gca.diagram_recipes",
    "diagram_at": "gca.diagram_placement",
    "graph_diagram": "gca.diagram_placement",
    "graph_sampler": "gca.diagram_placement",
    "diagram_points": "gca.diagram_points",
    "SuperbracketAnalysis": "gca.superbracket_analysis",
    "superbracket_analysis": "gca.superbracket_analysis",
    "GrassmannClass": "gca.grassmann",
    "grassmann_class": "gca.grassmann",
    "Transmission": "robots.transmission",
    "transmission": "papers.paper_004",
    "index_extremes": "papers.paper_004_table4",
    "wrench_transmission": "robots.transmission",
    "actuation_singularity_surface": "papers.paper_004_surfaces",
    "loci": "analysis.loci",
    "surfaces": "analysis.loci",
    "check_path": "analysis.paths",
    "grid_map": "analysis.workspace",
    "mechanism": "robots.graph_mechanism",
    "OperationMode": "core.operation_modes",
    "OperationModes": "core.mode_search",
    "find_operation_modes": "core.mode_search",
    "ModesAtPose": "core.mode_transitions",
    "modes_at": "core.mode_transitions",
    "certify": "analysis.certify",
}


#: Submodules loaded on first use (``sk.workspace.grid_map``).
_LAZY_MODULES = {"workspace": "analysis.workspace"}


def _paper_004_map_values(posed: Any, quantity: str) -> Any:
    """Paper 004's indices over a posed batch, for the maps (imported on first use)."""
    from .papers.paper_004_summary import map_values

    return map_values(posed, quantity)


# the maps (screwkit.analysis) read paper 004's indices by name: the papers stand above them
for _name in _CONTRIBUTED:
    register_quantity(_name, functools.partial(_paper_004_map_values, quantity=_name))


def _pose_report(posed: Any, **options: Any) -> Any:
    """One pose's report, for ``posed[i].report()``: ``analyze(posed, ...)`` (imported on first use)."""
    from .interface.report import analyze

    return analyze(posed, **options)


# the posed mechanism (screwkit.robots) reports through the interface, which stands above it
register_report_composer(_pose_report)


def __getattr__(name: str) -> Any:
    if name in _LAZY_MODULES:
        import importlib

        return importlib.import_module(f".{_LAZY_MODULES[name]}", __name__)
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'screwkit' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY) | set(_LAZY_MODULES))

# The catalog (top-level ``mechanisms/``) is installed as ``screwkit.mechanisms`` by a setuptools
# package-dir mapping; when this source tree shadows a non-editable install (``python -m pytest`` from the
# repository root), the installed ``screwkit/`` folder is searched for it too.
__path__ = extend_path(__path__, __name__)

__all__ = [
    "AnalysisReport",
    "CatalogError",
    "DegenerateGeometryError",
    "Family",
    "GenericAnalysis",
    "GrassmannClass",
    "Jacobians",
    "Joint",
    "JointTable",
    "Mechanism",
    "ModesAtPose",
    "OperationMode",
    "OperationModes",
    "PosedMechanism",
    "Screw",
    "ScrewSystem",
    "ScrewkitError",
    "ScrewkitIndexError",
    "ScrewkitTypeError",
    "ScrewkitValueError",
    "SingularityReport",
    "SuperbracketAnalysis",
    "Transmission",
    "TwistGraphError",
    "UnreachablePoseError",
    "WrenchAnalysis",
    "WrenchDiagram",
    "__version__",
    "actuation_singularity_surface",
    "analyze",
    "analyze_table",
    "are_collinear",
    "are_coplanar",
    "bracket",
    "certify",
    "check_path",
    "classify",
    "classify_poses",
    "classify_table",
    "cylindrical",
    "diagram_at",
    "diagram_points",
    "equivalent_twist_graph",
    "find_operation_modes",
    "finite_point",
    "fundamental_loops",
    "generic_analysis",
    "graph_diagram",
    "graph_dot",
    "graph_json",
    "graph_sampler",
    "grassmann_class",
    "grid_map",
    "helical",
    "index_extremes",
    "infinite_point",
    "is_at_infinity",
    "jacobians_from_wrenches",
    "join",
    "line_points",
    "lines_intersect",
    "list_mechanisms",
    "load_mechanism",
    "load_snapshot",
    "loci",
    "loop_closure_matrix",
    "mechanism",
    "meet_line_plane",
    "meet_planes",
    "modes_at",
    "motion_type",
    "parallelogram",
    "plane",
    "plane_through",
    "platform_twist_system",
    "point_on_line",
    "prismatic",
    "reciprocal_product",
    "register",
    "revolute",
    "save_snapshot",
    "schoenflies_basis",
    "series_parallel_tree",
    "snapshot_text",
    "spherical",
    "superbracket_analysis",
    "surfaces",
    "transmission",
    "twist_graph",
    "universal",
    "virtual",
    "wrench_analysis",
    "wrench_diagram",
    "wrench_transmission",
]
