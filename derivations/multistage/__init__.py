"""Symbolic derivations for corrected attitude stages (Plotnikov 1999).

Modules
-------
lyapunov_function
    The Lyapunov function V, its derivative V′ = −lk|z|², and a strict Lyapunov function.
schuler
    The linearised stage and its Schuler tuning (acceleration → tilt transfer function).
"""
