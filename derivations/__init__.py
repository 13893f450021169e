"""Symbolic derivations (SymPy only) behind :mod:`strapdown.analysis`.

This package never imports :mod:`strapdown.analysis`; the dependency runs the other way.
The conventions (quaternion order, frames E and I, rotation vectors, dual
numbers, local errors exact minus algorithm) are those stated in the
:mod:`strapdown.analysis` package docstring.

SymPy symbols are module constants, in capitals, listed in the module's
``__all__`` and created once (``EPS, THETA = sp.symbols(...)``), so that every
expression a module returns uses the same objects and callers substitute
through them (``expr.subs(drift.EPS, -1)``); see
:mod:`strapdown.derivations.coning.drift`.
"""
