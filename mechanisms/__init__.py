"""The catalog: one TOML file per robot (see :mod:`screwkit.catalog`), shipped as package data."""
