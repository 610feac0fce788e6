"""The catalog: one TOML file per robot (see :mod:`screwkit.robots.catalog`), shipped as package data."""

__all__: list[str] = []
