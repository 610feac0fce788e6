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

from pkgutil import extend_path
from typing import Any

from .algebra.screw import Screw, reciprocal_product
from .algebra.screwsystem import ScrewSystem, motion_type
from .core.singularity import SingularityReport, classify, classify_poses, classify_table
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
    JointTable,
    cylindrical,
    helical,
    parallelogram,
    prismatic,
    revolute,
    spherical,
    universal,
    virtual,
)
from .graphs.twistgraph import (
    equivalent_twist_graph,
    fundamental_loops,
    loop_closure_matrix,
    platform_twist_system,
    series_parallel_tree,
    twist_graph,
)

#: Names loaded on first use (the catalog and its families, the generic analysis, the projective
#: helpers, the Jacobians, the composer and its report are not a cost of ``import screwkit``; PEP 562).
_LAZY = {
    "Mechanism": "robots.catalog",
    "list_mechanisms": "robots.catalog",
    "load_mechanism": "robots.catalog",
    "load_snapshot": "robots.catalog",
    "Family": "robots.families",
    "register": "robots.families",
    "GenericAnalysis": "core.generic",
    "generic_analysis": "core.generic",
    **dict.fromkeys(
        (
            "are_collinear",
            "are_coplanar",
            "bracket",
            "finite_point",
            "infinite_point",
            "is_at_infinity",
            "join",
            "line_points",
            "lines_intersect",
            "meet_line_plane",
            "meet_planes",
            "plane",
            "plane_through",
            "point_on_line",
        ),
        "algebra.projective",
    ),
    "WrenchJacobians": "core.jacobians",
    "jacobians_from_wrenches": "core.jacobians",
    "schoenflies_basis": "core.jacobians",
    "Pose": "robots.posed",
    "PosedMechanism": "robots.posed",
    "AnalysisReport": "interface.report",
    "analyze": "interface.report",
    "graph_dot": "interface.export",
    "graph_json": "interface.export",
    "save_snapshot": "interface.export",
    "snapshot_text": "interface.export",
    "WrenchDiagram": "gca.diagram",
    "wrench_diagram": "gca.diagram_recipes",
    "diagram_at": "gca.diagram_placement",
    "SuperbracketAnalysis": "gca.superbracket_analysis",
    "superbracket_analysis": "gca.superbracket_analysis",
    "TransmissionIndices": "analysis.indices",
    "transmission": "analysis.indices",
    "index_extremes": "analysis.indices",
    "wrench_transmission": "analysis.indices",
    "actuation_singularity_surface": "analysis.indices",
}


#: Submodules loaded on first use (``sk.workspace.grid_map``).
_LAZY_MODULES = {"workspace": "analysis.workspace"}


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

__version__ = "0.1.0"

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
    "Joint",
    "JointTable",
    "Mechanism",
    "Pose",
    "PosedMechanism",
    "Screw",
    "ScrewSystem",
    "ScrewkitError",
    "ScrewkitIndexError",
    "ScrewkitTypeError",
    "ScrewkitValueError",
    "SingularityReport",
    "SuperbracketAnalysis",
    "TransmissionIndices",
    "TwistGraphError",
    "UnreachablePoseError",
    "WrenchAnalysis",
    "WrenchDiagram",
    "WrenchJacobians",
    "__version__",
    "actuation_singularity_surface",
    "analyze",
    "analyze_table",
    "are_collinear",
    "are_coplanar",
    "bracket",
    "classify",
    "classify_poses",
    "classify_table",
    "cylindrical",
    "diagram_at",
    "equivalent_twist_graph",
    "finite_point",
    "fundamental_loops",
    "generic_analysis",
    "graph_dot",
    "graph_json",
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
    "loop_closure_matrix",
    "meet_line_plane",
    "meet_planes",
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
    "transmission",
    "twist_graph",
    "universal",
    "virtual",
    "wrench_analysis",
    "wrench_diagram",
    "wrench_transmission",
]
