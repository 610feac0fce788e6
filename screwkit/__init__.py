"""screwkit: singularities of parallel robots with screw theory and Grassmann–Cayley algebra.

The public API, along the data flow of the design (screws → screw systems → projective geometry →
twist graphs → wrench systems → labels and conditions). Conventions: :mod:`screwkit.screw`.

Examples
--------
>>> import screwkit as sk
>>> wrenches = sk.ScrewSystem.span([sk.Screw.force([1, 0, 0], [0, 0, 0]), sk.Screw.couple([0, 0, 1])])
>>> wrenches.reciprocal().order
4
"""

from .exceptions import (
    CatalogError,
    DegenerateGeometryError,
    ScrewkitError,
    ScrewkitTypeError,
    ScrewkitValueError,
    TwistGraphError,
    UnreachablePoseError,
)
from .projective import (
    are_collinear,
    are_coplanar,
    bracket,
    finite_point,
    infinite_point,
    is_at_infinity,
    join,
    line_points,
    lines_intersect,
    meet_line_plane,
    meet_planes,
    plane,
    plane_through,
    point_on_line,
)
from .screw import Screw, reciprocal_product
from .screwsystem import ScrewSystem

__version__ = "0.1.0"

__all__ = [
    "CatalogError",
    "DegenerateGeometryError",
    "Screw",
    "ScrewSystem",
    "ScrewkitError",
    "ScrewkitTypeError",
    "ScrewkitValueError",
    "TwistGraphError",
    "UnreachablePoseError",
    "__version__",
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
    "reciprocal_product",
]
