"""Shared fixtures: a seeded random generator and hypothesis profiles."""

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "screwkit", max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.load_profile("screwkit")


@pytest.fixture
def rng():
    """A seeded generator: tests are repeatable."""
    return np.random.default_rng(20261121)
