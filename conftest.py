"""Root conftest: makes the source tree importable the same way for tests and doctests."""
