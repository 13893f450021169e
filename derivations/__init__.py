"""Symbolic derivations (SymPy only) behind :mod:`analysis`.

This package never imports :mod:`analysis`; the dependency runs the other way.
The conventions (quaternion order, frames E and I, rotation vectors, dual
numbers) are those stated in the :mod:`analysis` package docstring.
"""
