"""A module beside sibling_import.py: the coefficient it imports."""

TWO_SAMPLE = 2.0 / 3.0
