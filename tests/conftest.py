"""Shared fixtures: a seeded random generator and hypothesis profiles."""

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

# derandomized: every run (CI's included) draws the same examples, so a failure is repeatable and a
# green run means the same thing each time; new examples come from changing the tests, not from luck
settings.register_profile(
    "screwkit",
    max_examples=40,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("screwkit")


@pytest.fixture
def rng():
    """A seeded generator: tests are repeatable."""
    return np.random.default_rng(20261121)


@pytest.fixture(scope="session")
def executed_notebooks(tmp_path_factory):
    """The folder where ``tests/test_notebooks.py`` leaves each notebook as it ran; the docs build
    (``tests/test_site.py``) renders these copies instead of executing the notebooks again."""
    return tmp_path_factory.mktemp("executed_notebooks", numbered=False)
