"""screwkit: singularities of parallel robots with screw theory and Grassmann–Cayley algebra."""

__version__ = "0.1.0"
