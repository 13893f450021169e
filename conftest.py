"""Root conftest: source tree importable the same way for tests and doctests; deterministic hypothesis."""

from hypothesis import settings

# Derandomized property tests: the same examples on every run, no timing deadlines,
# so the suite cannot fail by chance on a loaded machine.
settings.register_profile("strapdown", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", deadline=None, max_examples=2000)
settings.load_profile("strapdown")
