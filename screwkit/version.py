"""The version of screwkit: the bottom of the layers, imported by the package and by the command line.

The build reads it from here without importing the package (pyproject.toml's dynamic version).

Examples
--------
>>> from screwkit.version import __version__
>>> __version__.count(".")
2
"""

__all__ = ["__version__"]

__version__ = "0.2.0"
