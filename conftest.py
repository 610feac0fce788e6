"""Shared doctest setup: every docstring example of the package runs with ``np`` (numpy), ``sk``
(screwkit) and ``load_mechanism`` already imported, the names the examples assume
(docs/architecture.md §7)."""

import numpy as np
import pytest

import screwkit as sk


@pytest.fixture(autouse=True)
def _doctest_names(doctest_namespace):
    doctest_namespace.update(np=np, sk=sk, load_mechanism=sk.load_mechanism)
