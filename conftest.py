"""Root conftest: source tree importable the same way for tests and doctests; deterministic hypothesis."""

import atexit
import os
import shutil
import tempfile

import pytest
from hypothesis import settings

from strapdown.derivations.reproducible import reproducible

# Generated code of derived expressions goes to a cache of the test run's own (the
# subprocesses of CLI tests inherit it), never to the user's cache directory.
if "STRAPDOWN_CACHE_DIR" not in os.environ:
    os.environ["STRAPDOWN_CACHE_DIR"] = tempfile.mkdtemp(prefix="strapdown-test-cache-")
    atexit.register(shutil.rmtree, os.environ["STRAPDOWN_CACHE_DIR"], ignore_errors=True)

# Derandomized property tests: the same examples on every run, no timing deadlines,
# so the suite cannot fail by chance on a loaded machine.
settings.register_profile("strapdown", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", deadline=None, max_examples=2000)
settings.load_profile("strapdown")


@pytest.fixture(autouse=True)
def _sympy_seeded():
    """Each test runs with SymPy's internal random choices seeded (factorisation time is then fixed)."""
    with reproducible():
        yield
