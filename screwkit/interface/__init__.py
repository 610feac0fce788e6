"""The interfaces: the analysis report (text, JSON, LaTeX), exports (DOT, JSON, snapshot TOML), the
command line and the plots.

Layer 8, the top of the data flow (docs/architecture.md): it composes public functions only.
"""

__all__: list[str] = []
